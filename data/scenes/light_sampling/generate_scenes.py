#!/usr/bin/env python3
"""Writes the light-sampling benchmark scenes (docs/benchmarks.md, "Light sampling"): a spot + D65 environment over
a 3 m and a 100 m floor, a room lit by 32 x 32 ceiling panels and a sky window (also with the window as the sky's
portal), and a street of 200 lamps.

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
