#!/usr/bin/env python3
"""Writes a JSON scene of four hanging hair swatches (Rimu's `curves` shape and `hair` material) in sunlight and
skylight: black, red, brown and blond by eumelanin concentration as in Bitterli's hair-curl scene (8, 2, 0.8, 0.2).

    python3 bench/hair/make_hair_swatches.py OUT.json [STRANDS_PER_SWATCH] [CURVE_TYPE] [WIDTH_M]

Each strand is a wavy cubic Bezier curve of 3 segments, 0.5 m long, 0.2 mm wide (widths grow with the scene's
scale: real hair is 50-100 um, which needs far more strands per pixel than a small test render affords).
Deterministic (seeded), so renders are comparable between builds.
"""
import json
import math
import random
import sys


def strand(rng, x0, z0):
    # A strand hanging from y = 1.6 with a gentle wave in x and z; 10 control points = 3 cubic Bezier segments.
    phase, amplitude, period = rng.uniform(0, 2 * math.pi), rng.uniform(0.004, 0.012), rng.uniform(0.12, 0.2)
    length = 0.5 * rng.uniform(0.9, 1.0)
    points = []
    for i in range(10):
        t = i / 9
        y = 1.6 - length * t
        x = x0 + amplitude * math.sin(phase + 2 * math.pi * length * t / period) * t
        z = z0 + 0.3 * amplitude * math.cos(phase + 2 * math.pi * length * t / period) * t
        points += [round(x, 5), round(y, 5), round(z, 5)]
    return points


def main():
    out = sys.argv[1]
    strands = int(sys.argv[2]) if len(sys.argv) > 2 else 1500
    curve_type = sys.argv[3] if len(sys.argv) > 3 else "flat"
    rng = random.Random(7)
    colours = {"black": 8.0, "red": 2.0, "brown": 0.8, "blond": 0.2}
    materials = {name: {"type": "hair", "eumelanin": e} for name, e in colours.items()}
    materials["backdrop"] = {"type": "diffuse", "reflectance": 0.18}
    shapes = [{"type": "quad", "name": "backdrop", "material": "backdrop",
               "vertices": [[-2, 0, 0.4], [2, 0, 0.4], [2, 3, 0.4], [-2, 3, 0.4]]}]
    for k, name in enumerate(colours):
        centre = -0.45 + 0.3 * k
        points = []
        for _ in range(strands):
            points += strand(rng, centre + rng.uniform(-0.1, 0.1), rng.uniform(-0.03, 0.03))
        shapes.append({"type": "curves", "name": name + " swatch", "material": name, "curve_type": curve_type,
                       "points": points, "counts": [10] * strands, "width": float(sys.argv[4]) if len(sys.argv) > 4 else 0.0002})
    scene = {
        "description": "Four hanging hair swatches (eumelanin 8, 2, 0.8, 0.2) in sun and sky; written by "
                       "bench/hair/make_hair_swatches.py.",
        "camera": {"type": "pinhole", "from": [0.0, 1.35, -1.6], "to": [0.0, 1.35, 0.0], "up": [0, 1, 0],
                   "vertical_fov_deg": 24},
        "film": {"resolution": [320, 180]},
        "integrator": {"spp": 16, "max_depth": 16, "seed": 1},
        "materials": materials,
        "lights": [
            {"type": "distant", "name": "sun", "direction": [-0.5, 0.8, -0.6],
             "irradiance": {"blackbody": 5778, "scale": 1.0}, "angular_diameter_deg": 0.53},
            {"type": "environment", "name": "sky", "radiance": {"daylight": 12000, "scale": 0.0008}},
        ],
        "shapes": shapes,
    }
    with open(out, "w") as f:
        json.dump(scene, f, separators=(",", ":"))


if __name__ == "__main__":
    main()
