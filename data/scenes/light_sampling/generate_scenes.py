#!/usr/bin/env python3
"""Writes the light-sampling benchmark scenes (docs/benchmarks.md, "Light sampling"): a spot + D65 environment over
a 3 m and a 100 m floor, a room lit by 32 x 32 ceiling panels and a sky window (also with the window as the sky's
portal), and a street of 200 lamps; for wavelength-aware light choice, three scenes of coloured lights: a red and a
blue lamp, a wall of RGB LED panels, and a square under low-/high-pressure sodium and mercury lamps; for the
resampled light choice at glossy vertices, 25 lamps over a lacquered copper and a lacquered plastic floor, and the LED
wall over a gold floor and a copper ball.

Run from anywhere:  python3 data/scenes/light_sampling/generate_scenes.py
The outputs are committed; this script is how they were made (standard library only). rimu renders each file as it
is; rimu-light-sampler-bench loads the same files and only overrides the film's resolution and filter and the
integrator's light_sampler.
"""
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
FILM = {"resolution": [320, 240], "response": "xyz", "filter": {"type": "box"}}


def spot_scene(floor_m):
    """The glass and copper spheres on a grey floor of floor_m x floor_m, an 800 lm 2700 K spot 2 m above the
    floor and a D65 environment."""
    h = floor_m / 2
    return {
        "description": "Light sampling: an 800 lm 2700 K spot and a D65 environment over a %g m floor with a glass "
                       "and a copper sphere. The environment's share of light samples must not grow with the floor."
                       % floor_m,
        "camera": {"from": [0, 3.5, 4.5], "to": [0, 0.3, 0], "vertical_fov_deg": 50},
        "film": FILM,
        "integrator": {"spp": 64, "max_depth": 6, "seed": 1},
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.5},
                      "glass": {"type": "dielectric", "ior": 1.5},
                      "copper": {"type": "conductor", "metal": "copper", "roughness": 0.15}},
        "lights": [
            {"type": "spot", "name": "spot", "position": [0, 2, 0], "direction": [0, -1, 0], "cone_angle_deg": 40,
             "falloff_start_deg": 30, "luminous_power_lm": 800, "power_convention": "cone",
             "spectrum": {"blackbody": 2700}},
            {"type": "environment", "name": "sky", "radiance": {"illuminant": "D65", "scale": 0.0001}},
        ],
        "shapes": [
            {"type": "sphere", "material": "glass", "center": [-0.35, 0.3, 0.1], "radius": 0.3},
            {"type": "sphere", "material": "copper", "center": [0.4, 0.3, -0.2], "radius": 0.3},
            {"type": "quad", "name": "floor", "material": "grey",
             "vertices": [[-h, 0, h], [h, 0, h], [h, 0, -h], [-h, 0, -h]]},
        ],
    }


def ceiling_grid_room(portal=False):
    """An 8 m x 8 m x 3 m room; 32 x 32 emissive 8 cm squares on the ceiling (blackbodies 2700-6500 K); a 2 m x 1 m
    window in the +x wall onto a D65 sky. portal: the sky is given the window as its portal (the same image)."""
    def wall(v):
        return {"type": "quad", "material": "wall", "vertices": v}
    shapes = [
        {"type": "quad", "material": "floor", "vertices": [[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]]},
        wall([[-4, 3, -4], [4, 3, -4], [4, 3, 4], [-4, 3, 4]]),
        wall([[-4, 0, -4], [4, 0, -4], [4, 3, -4], [-4, 3, -4]]),
        wall([[4, 0, 4], [-4, 0, 4], [-4, 3, 4], [4, 3, 4]]),
        wall([[-4, 0, 4], [-4, 0, -4], [-4, 3, -4], [-4, 3, 4]]),
        wall([[4, 0, -4], [4, 0, 4], [4, 1, 4], [4, 1, -4]]),
        wall([[4, 2, -4], [4, 2, 4], [4, 3, 4], [4, 3, -4]]),
        wall([[4, 1, -4], [4, 1, -1], [4, 2, -1], [4, 2, -4]]),
        wall([[4, 1, 1], [4, 1, 4], [4, 2, 4], [4, 2, 1]]),
    ]
    for i in range(32):
        for j in range(32):
            x, z, s, y = -4 + 0.25 * (i + 0.5), -4 + 0.25 * (j + 0.5), 0.04, 2.99
            cct = 2700.0 + (6500.0 - 2700.0) * ((i * 7 + j * 3) % 8) / 7.0
            # Counter-clockwise seen from below: faces down.
            shapes.append({"type": "quad", "material": "black",
                           "vertices": [[x - s, y, z - s], [x + s, y, z - s], [x + s, y, z + s], [x - s, y, z + s]],
                           "emission": {"blackbody": round(cct, 6), "scale": 30.0}})
    sky = {"type": "environment", "name": "sky", "radiance": {"illuminant": "D65", "scale": 0.01}}
    if portal:
        sky["portals"] = [[[4, 1, -1], [4, 1, 1], [4, 2, 1], [4, 2, -1]]]
    return {
        "description": "Light sampling: an 8 m x 8 m x 3 m room lit by 32 x 32 emissive 8 cm ceiling panels of "
                       "2700-6500 K and a 2 m x 1 m window onto a D65 sky"
                       + (", given to the sky as its portal." if portal else "."),
        "camera": {"from": [-3.5, 1.6, -3.0], "to": [4, 1.2, 1.0], "vertical_fov_deg": 70},
        "film": FILM,
        "integrator": {"spp": 64, "max_depth": 5, "seed": 1},
        "materials": {"wall": {"type": "diffuse", "reflectance": 0.6}, "floor": {"type": "diffuse", "reflectance": 0.3},
                      "black": {"type": "diffuse", "reflectance": 0}},
        "lights": [sky],
        "shapes": shapes,
    }


def street():
    """A 500 m road with 200 lamps 8 m up on both sides: LED spots, high-pressure sodium points (CIE HP1),
    low-pressure sodium spots (the D doublet); a dim night sky."""
    lights = [{"type": "environment", "name": "night sky", "radiance": {"daylight": 12000, "scale": 0.00002}}]
    for k in range(200):
        x, z = -250 + 2.5 * (k + 0.5), 7.0 if k % 2 else -7.0
        if k % 3 == 1:
            light = {"type": "point", "position": [x, 8, z], "luminous_power_lm": 9000,
                     "spectrum": {"illuminant": "HP1"}}
        else:
            light = {"type": "spot", "position": [x, 8, z], "direction": [0, -1, -z * 0.05], "cone_angle_deg": 130,
                     "falloff_start_deg": 90, "luminous_power_lm": 8000, "power_convention": "cone",
                     "spectrum": {"illuminant": "LED-B3"} if k % 3 == 0 else {"csv": "low_pressure_sodium.csv"}}
        light["name"] = "lamp %d" % k
        lights.append(light)
    return {
        "description": "Light sampling: a 500 m road under 200 lamps 8 m up (LED spots, high-pressure sodium points, "
                       "low-pressure sodium spots) and a dim night sky.",
        "camera": {"from": [-200, 1.7, -2], "to": [-150, 1.0, 1], "vertical_fov_deg": 45},
        "film": FILM,
        "integrator": {"spp": 64, "max_depth": 4, "seed": 1},
        "materials": {"asphalt": {"type": "diffuse", "reflectance": 0.12},
                      "kerb": {"type": "diffuse", "reflectance": 0.4}},
        "lights": lights,
        "shapes": [
            {"type": "quad", "material": "asphalt", "vertices": [[-250, 0, 6], [250, 0, 6], [250, 0, -6], [-250, 0, -6]]},
            {"type": "quad", "material": "kerb",
             "vertices": [[-250, 0.15, 10], [250, 0.15, 10], [250, 0.15, 6], [-250, 0.15, 6]]},
            {"type": "quad", "material": "kerb",
             "vertices": [[-250, 0.15, -6], [250, 0.15, -6], [250, 0.15, -10], [-250, 0.15, -10]]},
        ],
    }


def narrow_line(peak_nm, fwhm_nm):
    """An LED-like emission band: a Gaussian of the given full width at half maximum, tabulated every 2 nm over
    +-2 FWHM (relative units)."""
    import math
    sigma = fwhm_nm / (2.0 * math.sqrt(2.0 * math.log(2.0)))
    lo = int(round(peak_nm - 2 * fwhm_nm))
    wavelengths = list(range(lo - lo % 2, int(peak_nm + 2 * fwhm_nm) + 2, 2))
    values = [round(math.exp(-0.5 * ((w - peak_nm) / sigma) ** 2), 6) for w in wavelengths]
    values[0] = values[-1] = 0.0
    return {"wavelengths_nm": wavelengths, "values": values}


# Typical LED primaries: royal blue 460 nm (FWHM 20 nm), green 530 nm (30 nm), red 630 nm (18 nm).
RED, GREEN, BLUE = narrow_line(630, 18), narrow_line(530, 30), narrow_line(460, 20)


def coloured_floor_scene(description, lights, extra_shapes=(), camera=None):
    shapes = [
        {"type": "quad", "material": "white", "vertices": [[-6, 0, 6], [6, 0, 6], [6, 0, -6], [-6, 0, -6]]},
        {"type": "sphere", "material": "grey", "center": [-0.6, 0.4, 0.3], "radius": 0.4},
        {"type": "sphere", "material": "white", "center": [0.7, 0.3, -0.2], "radius": 0.3},
        {"type": "quad", "material": "white", "vertices": [[-6, 0, -3], [6, 0, -3], [6, 3, -3], [-6, 3, -3]]},
    ] + list(extra_shapes)
    return {
        "description": description,
        "camera": camera or {"from": [0, 2.2, 4.5], "to": [0, 0.5, -0.5], "vertical_fov_deg": 55},
        "film": FILM,
        "integrator": {"spp": 64, "max_depth": 4, "seed": 1},
        "materials": {"white": {"type": "diffuse", "reflectance": 0.8}, "grey": {"type": "diffuse", "reflectance": 0.4},
                      "black": {"type": "diffuse", "reflectance": 0}},
        "lights": lights,
        "shapes": shapes,
    }


def red_blue():
    """A red and a blue LED lamp (630 and 460 nm) either side of two spheres on a white floor by a white wall."""
    return coloured_floor_scene(
        "Light sampling, coloured lights: a red (630 nm) and a blue (460 nm) LED lamp of 5 W each either side of two "
        "spheres on a white floor; choosing the lamp that emits at the path's wavelengths cuts colour noise.",
        [{"type": "point", "name": "red", "position": [-1.5, 1.5, 0.5], "radiant_power_w": 5, "spectrum": RED},
         {"type": "point", "name": "blue", "position": [1.5, 1.5, 0.5], "radiant_power_w": 5, "spectrum": BLUE}])


def rgb_led_panels():
    """A wall of 12 x 6 small emissive panels, each a red, green or blue LED primary, facing the scene."""
    panels = []
    for i in range(12):
        for j in range(6):
            x, y, s = -2.75 + 0.5 * i, 0.5 + 0.4 * j, 0.08
            spectrum = (RED, GREEN, BLUE)[(i + 2 * j) % 3]
            # Counter-clockwise seen from +z: faces the scene.
            panels.append({"type": "quad", "material": "black",
                           "vertices": [[x - s, y - s, -2.99], [x + s, y - s, -2.99], [x + s, y + s, -2.99],
                                        [x - s, y + s, -2.99]],
                           "emission": dict(spectrum, scale=3.0)})
    return coloured_floor_scene(
        "Light sampling, coloured lights: a wall of 12 x 6 RGB LED panels (each one primary: 630, 530 or 460 nm) "
        "lighting two spheres on a white floor.", [], panels)


def rgb_led_panels_metal():
    """The RGB LED wall over a gold floor (roughness 0.3) with a copper ball (0.2) in place of the grey one: 72 area
    lights and glossy vertices, where the MIS weights of resampled lights count (docs/transport.md, "Glossy
    vertices and many lights")."""
    scene = rgb_led_panels()
    scene["description"] = ("Glossy vertices and many area lights: the wall of 12 x 6 RGB LED panels over a gold "
                            "floor of roughness 0.3 and a copper ball of roughness 0.2.")
    scene["materials"]["gold"] = {"type": "conductor", "metal": "gold", "roughness": 0.3}
    scene["materials"]["copper"] = {"type": "conductor", "metal": "copper", "roughness": 0.2}
    scene["shapes"][0]["material"] = "gold"
    scene["shapes"][1]["material"] = "copper"
    return scene


def sodium_mercury():
    """A 30 m square under nine lamps 6 m up: low-pressure sodium (the D doublet), high-pressure sodium (CIE HP1)
    and mercury (its four visible line groups), with a dim night sky."""
    lights = [{"type": "environment", "name": "night sky", "radiance": {"daylight": 12000, "scale": 0.00002}}]
    kinds = [{"csv": "low_pressure_sodium.csv"}, {"illuminant": "HP1"}, {"csv": "mercury_lines.csv"}]
    for i in range(3):
        for j in range(3):
            lights.append({"type": "point", "name": "lamp %d%d" % (i, j), "position": [-10 + 10 * i, 6, -10 + 10 * j],
                           "luminous_power_lm": 6000, "spectrum": kinds[(i + j) % 3]})
    return {
        "description": "Light sampling, coloured lights: a 30 m square under nine lamps 6 m up, low-pressure sodium, "
                       "high-pressure sodium (CIE HP1) and mercury, and a dim night sky.",
        "camera": {"from": [-14, 1.7, -14], "to": [5, 0.5, 5], "vertical_fov_deg": 60},
        "film": FILM,
        "integrator": {"spp": 64, "max_depth": 4, "seed": 1},
        "materials": {"paving": {"type": "diffuse", "reflectance": 0.35},
                      "wall": {"type": "diffuse", "reflectance": 0.6}},
        "lights": lights,
        "shapes": [
            {"type": "quad", "material": "paving", "vertices": [[-15, 0, 15], [15, 0, 15], [15, 0, -15], [-15, 0, -15]]},
            {"type": "sphere", "material": "wall", "center": [0, 1, 0], "radius": 1},
            {"type": "quad", "material": "wall", "vertices": [[15, 0, -15], [15, 0, 15], [15, 4, 15], [15, 4, -15]]},
        ],
    }


def lacquered_floor(metal):
    """A 5 x 5 grid of 800 lm 3000 K lamps 1.2 m over a lacquered floor (a smooth coat over copper of roughness
    0.1, or a coat of roughness 0.1 over a diffuse base) and a grey back wall: glints of a coated surface under many
    lamps, for the resampled light choice (docs/transport.md, "Glossy vertices and many lights")."""
    floor = ({"type": "coated_conductor", "metal": "copper", "conductor_roughness": 0.1, "coat_ior": 1.5} if metal
             else {"type": "coated_diffuse", "reflectance": {"rgb": [0.5, 0.3, 0.2]}, "roughness": 0.1, "coat_ior": 1.5})
    return {
        "description": "Glossy vertices: 25 lamps over %s." % ("copper under a smooth clear coat" if metal
                                                              else "a brown base under a coat of roughness 0.1"),
        "camera": {"from": [0, 1.0, -3], "to": [0, 0, 0.5], "vertical_fov_deg": 40},
        "film": {"resolution": [96, 96], "response": "xyz"},
        "integrator": {"spp": 64, "max_depth": 4, "seed": 1},
        "materials": {"floor": floor, "wall": {"type": "diffuse", "reflectance": 0.6}},
        "lights": [{"type": "point", "position": [round(-1.6 + 0.8 * i, 2), 1.2, round(-0.5 + 0.8 * k, 2)],
                    "luminous_power_lm": 800, "spectrum": {"blackbody": 3000}} for i in range(5) for k in range(5)],
        "shapes": [
            {"type": "quad", "material": "floor", "vertices": [[-4, 0, -4], [-4, 0, 6], [4, 0, 6], [4, 0, -4]]},
            {"type": "quad", "material": "wall", "vertices": [[-4, 0, 6], [-4, 3, 6], [4, 3, 6], [4, 0, 6]]},
        ],
    }


def write(name, scene):
    # One setting, shape or light per line: readable, and a diff shows which one changed.
    lines = []
    for key, value in scene.items():
        if key in ("lights", "shapes"):
            items = ",\n".join("  " + json.dumps(item) for item in value)
            lines.append(' "%s": [\n%s\n ]' % (key, items))
        else:
            lines.append(" %s: %s" % (json.dumps(key), json.dumps(value)))
    (HERE / name).write_text("{\n" + ",\n".join(lines) + "\n}\n")
    json.loads((HERE / name).read_text())  # still JSON


if __name__ == "__main__":
    write("spot_3m_floor.json", spot_scene(3.0))
    write("spot_100m_floor.json", spot_scene(100.0))
    write("ceiling_grid_room.json", ceiling_grid_room())
    write("ceiling_grid_room_portal.json", ceiling_grid_room(portal=True))
    write("street.json", street())
    write("red_blue_lamps.json", red_blue())
    write("rgb_led_panels.json", rgb_led_panels())
    write("rgb_led_panels_metal.json", rgb_led_panels_metal())
    write("sodium_mercury_square.json", sodium_mercury())
    write("lacquered_copper_lamps.json", lacquered_floor(metal=True))
    write("lacquered_plastic_lamps.json", lacquered_floor(metal=False))
