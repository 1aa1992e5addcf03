#!/usr/bin/env python3
"""Writes the memory-cost scenes of docs/pbrt-import.md ("Memory"): the difference of two sizes of one scene is the
cost of what differs between them.

    make_memory_scenes.py FOLDER

FOLDER/quad.pbrt           a quad under a uniform "infinite" light (start-up)
FOLDER/texture_256.pbrt    the quad with a 256 × 256 8-bit PNG reflectance texture (the first image)
FOLDER/texture_2048.pbrt   the same with 2048 × 2048 texels (per texel: against texture_256)
FOLDER/instances.pbrt      100,000 ObjectInstances of one sphere, placed at random (per instance)
Triangles: bench/pbrt_scenes/make_mesh_scene.py FOLDER 708 and 250.
"""
import random
import struct
import sys
import zlib

folder = sys.argv[1]
HEADER = """LookAt 0 0 3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 64 ]
Sampler "zsobol" "integer pixelsamples" [ 16 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
"""
QUAD = ('Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] "integer indices" [ 0 1 2  0 2 3 ] '
        '"point2 uv" [ 0 0  1 0  1 1  0 1 ]\n')


def write_png(path, n):
    """An n × n 8-bit RGB PNG of a pattern that does not compress to nothing."""
    raw = bytearray()
    for y in range(n):
        raw.append(0)  # no filter
        for x in range(n):
            v = ((x * 7 + y * 13) ^ (x * y)) & 255
            raw += bytes((v, (3 * v) & 255, 255 - v))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(raw), 6)) + chunk(b"IEND", b""))


with open(f"{folder}/quad.pbrt", "w") as f:
    f.write(HEADER + 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n' + QUAD)
for n in (256, 2048):
    write_png(f"{folder}/texture_{n}.png", n)
    with open(f"{folder}/texture_{n}.pbrt", "w") as f:
        f.write(HEADER + f'Texture "checks" "spectrum" "imagemap" "string filename" "texture_{n}.png"\n'
                'Material "diffuse" "texture reflectance" "checks"\n' + QUAD)
random.seed(1)
with open(f"{folder}/instances.pbrt", "w") as f:
    f.write(HEADER.replace("LookAt 0 0 3  0 0 0  0 1 0", "LookAt 0 -300 100  0 0 0  0 0 1") +
            'ObjectBegin "ball"\nShape "sphere" "float radius" 0.5\nObjectEnd\n')
    for _ in range(100000):
        f.write("AttributeBegin\nTranslate %.4f %.4f %.4f\nObjectInstance \"ball\"\nAttributeEnd\n" %
                (random.uniform(-100, 100), random.uniform(-100, 100), random.uniform(0, 10)))
print(folder)
