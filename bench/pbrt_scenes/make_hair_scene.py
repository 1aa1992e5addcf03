#!/usr/bin/env python3
"""Writes a load-time scene of N hair strands as pbrt's hair files are written: one `Shape "curve"` statement of
4 control points per strand (cubic Bézier, flat, width0 → width1 tapering), N statements in a row under one
material, over a wavy scalp patch, seen from the side. Deterministic (a fixed seed).

    make_hair_scene.py FOLDER N       # FOLDER/hair_<N>.pbrt
"""
import math
import random
import sys

folder, n = sys.argv[1], int(sys.argv[2])
rng = random.Random(7)
name = f"hair_{n}"
with open(f"{folder}/{name}.pbrt", "w") as f:
    f.write(f"""# Load-time scene written by bench/pbrt_scenes/make_hair_scene.py: {n} curves, one Shape "curve" each.
LookAt 0 -3 0.6   0 0 0.5   0 0 1
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 96 ] "integer yresolution" [ 72 ] "string filename" "{name}.exr"
Sampler "zsobol" "integer pixelsamples" [ 16 ]
Integrator "volpath" "integer maxdepth" [ 5 ]
PixelFilter "box"
WorldBegin
LightSource "infinite" "rgb L" [ 0.8 0.8 0.8 ]
Material "diffuse" "rgb reflectance" [ 0.3 0.2 0.1 ]
""")
    for _ in range(n):
        x, y = rng.uniform(-1, 1), rng.uniform(-1, 1)
        z = 0.05 * math.sin(5 * x) * math.cos(4 * y)
        lean = rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)
        p = [(x + lean[0] * t * t, y + lean[1] * t * t, z + t) for t in (0.0, 1 / 3, 2 / 3, 1.0)]
        points = "  ".join(f"{a:.5f} {b:.5f} {c:.5f}" for a, b, c in p)
        f.write(f'Shape "curve" "point3 P" [ {points} ] "string type" "flat" '
                f'"float width0" 0.004 "float width1" 0.001\n')
