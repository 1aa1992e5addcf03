#!/usr/bin/env python3
"""Writes a load-time scene for bench/pbrt_side_by_side.sh: a binary PLY height field of 2·N² triangles (a
wavy sheet, so that the BVH is not trivially flat) under a distant light, seen from above.

    make_mesh_scene.py FOLDER N       # FOLDER/mesh_<triangles>.pbrt and FOLDER/mesh_<triangles>.ply
"""
import math
import struct
import sys

folder, n = sys.argv[1], int(sys.argv[2])
triangles = 2 * n * n
name = f"mesh_{triangles}"
with open(f"{folder}/{name}.ply", "wb") as f:
    f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {(n + 1) ** 2}\n"
             "property float x\nproperty float y\nproperty float z\n"
             f"element face {triangles}\nproperty list uchar int vertex_indices\nend_header\n").encode())
    row = []
    for j in range(n + 1):
        y = -1 + 2 * j / n
        row.append(b"".join(struct.pack("<3f", -1 + 2 * i / n, y,
                                        0.05 * math.sin(9 * (-1 + 2 * i / n)) * math.cos(7 * y))
                            for i in range(n + 1)))
    f.write(b"".join(row))
    tri = struct.Struct("<B3i")
    for j in range(n):
        f.write(b"".join(tri.pack(3, j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1) +
                         tri.pack(3, j * (n + 1) + i, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i)
                         for i in range(n)))
with open(f"{folder}/{name}.pbrt", "w") as f:
    f.write(f"""# Load-time scene written by bench/pbrt_scenes/make_mesh_scene.py: {triangles} triangles in one binary PLY.
LookAt 0 -2.2 2.2   0 0 0   0 0 1
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 96 ] "integer yresolution" [ 72 ] "string filename" "{name}.exr"
Sampler "zsobol" "integer pixelsamples" [ 16 ]
Integrator "volpath" "integer maxdepth" [ 3 ]
PixelFilter "box"
WorldBegin
LightSource "distant" "point3 from" [ 1 -1 3 ] "point3 to" [ 0 0 0 ] "float illuminance" [ 2 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "plymesh" "string filename" "{name}.ply"
""")
print(f"{folder}/{name}.pbrt")
