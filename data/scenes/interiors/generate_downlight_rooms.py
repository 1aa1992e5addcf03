#!/usr/bin/env python3
"""Writes the downlight rooms (README.md in this folder): an 8 m x 6 m x 3 m room lit by 50 recessed IES downlights
of 800 lm at 3000 K on a 10 x 5 grid in the ceiling, with a table holding a glass tumbler, a copper ball and a red
box; at night (the downlights alone) and by day (the same downlights, plus an 80,000 lx sun and a daylight sky
entering through a 3 m x 1.5 m window that is the sky's portal).

Run from anywhere:  python3 data/scenes/interiors/generate_downlight_rooms.py
The outputs are committed; this script is how they were made (standard library only).
"""
import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent

# The room: x in [-4, 4], z in [-3, 3], floor y = 0, ceiling y = 3. The window is in the x = +4 wall.
X, Z, H = 4.0, 3.0, 3.0
WINDOW_Z, WINDOW_Y = (-1.5, 1.5), (0.9, 2.4)
TABLE_TOP_Y = 0.76


def quad(material, vertices, **extra):
    return {"type": "quad", "material": material, "vertices": vertices, **extra}


def box(material, lower, upper, name=None):
    """A closed box as one triangle mesh, faces counter-clockwise seen from outside."""
    (x0, y0, z0), (x1, y1, z1) = lower, upper
    positions = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                 [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 4, 7, 3), (1, 2, 6, 5), (0, 1, 5, 4), (3, 7, 6, 2)]
    indices = []
    for a, b, c, d in faces:
        indices += [a, b, c, a, c, d]
    shape = {"type": "triangles", "material": material, "positions": positions, "indices": indices}
    if name:
        shape["name"] = name
    return shape


def tumbler(material, base_centre, radius, height, wall, bottom, segments=32):
    """A drinking glass as one closed, outward-facing mesh: the solid of revolution of the profile
    (0, 0) -> (r, 0) -> (r, h) -> (r - wall, h) -> (r - wall, bottom) -> (0, bottom) about the y axis, so a
    dielectric sees glass inside it and air in the cup and around it."""
    profile = [(0.0, 0.0), (radius, 0.0), (radius, height), (radius - wall, height), (radius - wall, bottom),
               (0.0, bottom)]
    cx, cy, cz = base_centre
    positions, indices = [], []
    ring = []  # ring[i][k]: the index of profile point i at angle k (points on the axis are one vertex)
    for r, y in profile:
        if r == 0.0:
            ring.append([len(positions)] * segments)
            positions.append([cx, cy + y, cz])
            continue
        row = []
        for k in range(segments):
            phi = 2 * math.pi * k / segments
            row.append(len(positions))
            positions.append([round(cx + r * math.cos(phi), 6), round(cy + y, 6), round(cz + r * math.sin(phi), 6)])
        ring.append(row)
    # The profile runs clockwise in the (r, y) half-plane (out along the base, up the outside, down the inside), so
    # its outward normal is its direction turned by -90 degrees; each quad is wound to face that way.
    for i in range(len(profile) - 1):
        (r0, y0), (r1, y1) = profile[i], profile[i + 1]
        outward = (y1 - y0, -(r1 - r0))  # (radial, vertical)
        for k in range(segments):
            k1 = (k + 1) % segments
            a, b, c, d = ring[i][k], ring[i][k1], ring[i + 1][k1], ring[i + 1][k]
            # Winding (a, b, c): check against the outward normal at the quad's middle angle.
            phi = 2 * math.pi * (k + 0.5) / segments
            expected = (outward[0] * math.cos(phi), outward[1], outward[0] * math.sin(phi))
            tri = [t for t in ((a, b, c), (a, c, d)) if len({t[0], t[1], t[2]}) == 3]
            for t in tri:
                p = [positions[j] for j in t]
                u = [p[1][m] - p[0][m] for m in range(3)]
                v = [p[2][m] - p[0][m] for m in range(3)]
                n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
                if sum(n[m] * expected[m] for m in range(3)) < 0:
                    t = (t[0], t[2], t[1])
                indices += list(t)
    return {"type": "triangles", "name": "glass tumbler", "material": material, "positions": positions,
            "indices": indices}


def room_shapes(window):
    shapes = [
        quad("floor", [[-X, 0, Z], [X, 0, Z], [X, 0, -Z], [-X, 0, -Z]], name="floor"),
        quad("ceiling", [[-X, H, -Z], [X, H, -Z], [X, H, Z], [-X, H, Z]], name="ceiling"),
        quad("wall", [[-X, 0, -Z], [X, 0, -Z], [X, H, -Z], [-X, H, -Z]]),
        quad("wall", [[X, 0, Z], [-X, 0, Z], [-X, H, Z], [X, H, Z]]),
        quad("wall", [[-X, 0, Z], [-X, 0, -Z], [-X, H, -Z], [-X, H, Z]]),
    ]
    if not window:
        shapes.append(quad("wall", [[X, 0, -Z], [X, 0, Z], [X, H, Z], [X, H, -Z]]))
    else:
        (z0, z1), (y0, y1) = WINDOW_Z, WINDOW_Y
        shapes += [
            quad("wall", [[X, 0, -Z], [X, 0, Z], [X, y0, Z], [X, y0, -Z]]),
            quad("wall", [[X, y1, -Z], [X, y1, Z], [X, H, Z], [X, H, -Z]]),
            quad("wall", [[X, y0, -Z], [X, y0, z0], [X, y1, z0], [X, y1, -Z]]),
            quad("wall", [[X, y0, z1], [X, y0, Z], [X, y1, Z], [X, y1, z1]]),
        ]
    # The table: a 1.6 m x 0.9 m top 4 cm thick on four 6 cm legs, under the middle of the room.
    tx, tz = 0.4, 0.0
    shapes.append(box("wood", [tx - 0.8, TABLE_TOP_Y - 0.04, tz - 0.45], [tx + 0.8, TABLE_TOP_Y, tz + 0.45],
                      name="table top"))
    for sx in (-1, 1):
        for sz in (-1, 1):
            lx, lz = tx + sx * 0.72, tz + sz * 0.37
            shapes.append(box("wood", [lx - 0.03, 0, lz - 0.03], [lx + 0.03, TABLE_TOP_Y - 0.04, lz + 0.03]))
    shapes.append(tumbler("glass", [tx - 0.35, TABLE_TOP_Y, tz + 0.15], 0.04, 0.11, 0.003, 0.012))
    shapes.append({"type": "sphere", "name": "copper ball", "material": "copper",
                   "center": [tx + 0.1, TABLE_TOP_Y + 0.08, tz - 0.12], "radius": 0.08})
    shapes.append(box("red", [tx + 0.4, TABLE_TOP_Y, tz + 0.02], [tx + 0.62, TABLE_TOP_Y + 0.14, tz + 0.2],
                      name="red box"))
    return shapes


def downlights():
    """10 x 5 recessed downlights 1 cm below the ceiling, 0.8 m apart along x and 1.2 m along z."""
    lights = []
    for i in range(10):
        for k in range(5):
            x = round(-3.6 + 0.8 * i, 3)
            z = round(-2.4 + 1.2 * k, 3)
            lights.append({"type": "ies", "name": "downlight %d,%d" % (i, k), "file": "../../examples/downlight.ies",
                           "position": [x, 2.99, z], "direction": [0, -1, 0], "spectrum": {"blackbody": 3000},
                           "luminous_power_lm": 800})
    return lights


MATERIALS = {
    "floor": {"type": "diffuse", "reflectance": 0.3},
    "ceiling": {"type": "diffuse", "reflectance": 0.8},
    "wall": {"type": "diffuse", "reflectance": 0.7},
    "wood": {"type": "diffuse", "reflectance": {"rgb": [0.45, 0.3, 0.18]}},
    "red": {"type": "diffuse", "reflectance": {"rgb": [0.7, 0.08, 0.06]}},
    "glass": {"type": "dielectric", "glass": "bk7"},
    "copper": {"type": "conductor", "metal": "copper", "roughness": 0.1},
}


def room(day):
    lights = downlights()
    if day:
        (z0, z1), (y0, y1) = WINDOW_Z, WINDOW_Y
        lights += [
            {"type": "distant", "name": "sun", "direction": [0.75, 0.55, 0.3], "spectrum": {"daylight": 5500},
             "illuminance_lx": 80000, "angular_diameter_deg": 0.53},
            {"type": "environment", "name": "sky", "spectrum": {"daylight": 6500}, "luminance_nt": 4000,
             "portals": [[[X, y0, z1], [X, y0, z0], [X, y1, z0], [X, y1, z1]]]},
        ]
    what = ("by day: the 50 downlights, an 80,000 lx sun and a 4,000 nt daylight sky through a 3 m x 1.5 m window "
            "(the sky's portal)" if day else "at night: 50 downlights")
    return {
        "description": "An 8 m x 6 m x 3 m room with a table holding a glass, a copper ball and a red box, lit " + what +
                       " (recessed downlights of 800 lm at 3000 K, data/examples/downlight.ies, 10 x 5 in the ceiling).",
        "camera": {"from": [-1.5, 1.45, -1.8], "to": [0.6, 0.8, 0.1], "vertical_fov_deg": 50},
        "film": {"resolution": [320, 180]},
        "integrator": {"spp": 16, "max_depth": 5, "seed": 1},
        "materials": MATERIALS,
        "lights": lights,
        "shapes": room_shapes(window=day),
    }


def workplane_room():
    """The night room with a lighting designer's 20 x 20 illuminance grid 0.8 m above the floor (just above the
    0.75 m table top), kept 0.5 m from the walls, measuring upwards (docs/scene-format.md, "sensors")."""
    scene = room(False)
    scene["description"] += " A 20 x 20 lux grid 0.8 m above the floor."
    scene["sensors"] = {"samples": 256, "grids": [
        {"name": "workplane", "origin": [-X + 0.5, 0.8, -Z + 0.5], "u": [0, 0, 1], "v": [1, 0, 0],
         "size": [2 * Z - 1, 2 * X - 1], "counts": [20, 20]}]}
    return scene


def main():
    for name, day in (("night_room_downlights.json", False), ("day_room_downlights.json", True)):
        (HERE / name).write_text(json.dumps(room(day), indent=1) + "\n")
    (HERE / "night_room_workplane.json").write_text(json.dumps(workplane_room(), indent=1) + "\n")


if __name__ == "__main__":
    main()
