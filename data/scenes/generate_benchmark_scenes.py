#!/usr/bin/env python3
"""Writes the benchmark scenes of issue 7 (docs/benchmarks.md, "Speed against error") and the textured scene's PNG.

Run from anywhere:  python3 data/scenes/generate_benchmark_scenes.py
The outputs are committed; this script is how they were made (standard library only).
"""
import json
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
CHART_CSV = "../../spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv"
# Column names of the BabelColor average file, in chart order (row 1 left to right, ..., row 4).
PATCHES = ["dark_skin", "light_skin", "blue_sky", "foliage", "blue_flower", "bluish_green", "orange",
           "purplish_blue", "moderate_red", "purple", "yellow_green", "orange_yellow", "blue", "green", "red",
           "yellow", "magenta", "cyan", "white_9.5_(.05_D)", "neutral_8_(.23_D)", "neutral_6.5_(.44_D)",
           "neutral_5_(.70_D)", "neutral_3.5_(1.05_D)", "black_2_(1.5_D)"]
FILM = {"resolution": [160, 120], "response": "xyz", "filter": {"type": "gaussian", "radius": 1.5, "sigma": 0.5}}
INTEGRATOR = {"spp": 64, "max_depth": 12, "russian_roulette_depth": 3, "seed": 1}


def quad(name, material, v, **extra):
    shape = {"type": "quad", "name": name, "material": material, "vertices": v}
    shape.update(extra)
    return shape


def box_room(x0, x1, y0, y1, z0, z1, floor, ceiling, left, right, back, front):
    """Six inward-facing walls (diffuse materials are two-sided, so the winding only matters for lights)."""
    return [
        quad("floor", floor, [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]]),
        quad("ceiling", ceiling, [[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]]),
        quad("left wall", left, [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]]),
        quad("right wall", right, [[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]]),
        quad("back wall", back, [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]),
        quad("front wall", front, [[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]]),
    ]


def ceiling_light(cx, y, cz, half, emission):
    # (v1 − v0) × (v2 − v0) points down (−y): a one-sided area light emits along that normal.
    return quad("light", "white", [[cx + half, y, cz - half], [cx + half, y, cz + half], [cx - half, y, cz + half],
                                   [cx - half, y, cz - half]], emission=emission)


def patch_material(name):
    return {"type": "diffuse", "reflectance": {"csv": CHART_CSV, "column": name}}


def colorchecker_room(illuminant, description):
    materials = {"white": {"type": "diffuse", "reflectance": 0.8}, "chart backing": {"type": "diffuse", "reflectance": 0.03}}
    shapes = box_room(-1.5, 1.5, 0.0, 2.5, -1.0, 2.0, "white", "white", "white", "white", "white", "white")
    shapes.append(quad("chart backing", "chart backing", [[0.8, 0.55, 1.99], [-0.8, 0.55, 1.99], [-0.8, 1.65, 1.99],
                                                          [0.8, 1.65, 1.99]]))
    for i, name in enumerate(PATCHES):
        row, column = divmod(i, 6)
        material = "patch %02d %s" % (i + 1, name.split("_(")[0])
        materials[material] = patch_material(name)
        x_left = 0.735 - 0.25 * column       # chart seen from the camera (−z): patch 1 on the viewer's left (+x)
        y_top = 1.585 - 0.25 * row
        shapes.append(quad(material, material, [[x_left, y_top - 0.22, 1.985], [x_left - 0.22, y_top - 0.22, 1.985],
                                                [x_left - 0.22, y_top, 1.985], [x_left, y_top, 1.985]]))
    shapes.append(ceiling_light(0.0, 2.49, 0.9, 0.5, {"illuminant": illuminant, "scale": 0.05}))
    return {
        "description": description,
        "camera": {"type": "pinhole", "from": [0.0, 1.1, -0.9], "to": [0.0, 1.1, 2.0], "up": [0, 1, 0],
                   "vertical_fov_deg": 30},
        "film": FILM, "integrator": INTEGRATOR, "materials": materials, "shapes": shapes}


def colour_bleeding():
    materials = {
        "white": {"type": "diffuse", "reflectance": 0.8},
        "red": patch_material("red"), "green": patch_material("green"), "blue": patch_material("blue"),
        "orange": patch_material("orange"),
    }
    shapes = box_room(-1.0, 1.0, 0.0, 2.0, -0.5, 2.0, "white", "orange", "red", "green", "blue", "white")
    shapes.append(quad("white panel", "white", [[0.25, 0.0, 1.0], [0.25, 0.5, 1.0], [-0.25, 0.5, 1.0],
                                                          [-0.25, 0.0, 1.0]]))
    shapes.append({"type": "sphere", "name": "white sphere", "material": "white", "center": [0.45, 0.3, 1.3],
                   "radius": 0.3})
    # A light facing UP (towards the orange ceiling) above everything the camera sees: the scene is lit only
    # through the coloured ceiling and walls.
    shapes.append(quad("light", "white", [[-0.5, 1.7, 0.8], [-0.5, 1.7, 1.8], [0.5, 1.7, 1.8], [0.5, 1.7, 0.8]],
                       emission={"illuminant": "D65", "scale": 0.5}))
    return {
        "description": "Indirect-only colour bleeding: a D65 light faces an orange ceiling; red, green and blue "
                       "walls (ColorChecker patches) light a white sphere and a white panel. Issue 7.",
        "camera": {"type": "pinhole", "from": [0.0, 0.8, -0.4], "to": [0.0, 0.6, 2.0], "up": [0, 1, 0],
                   "vertical_fov_deg": 50},
        "film": FILM, "integrator": INTEGRATOR, "materials": materials, "shapes": shapes}


def dispersion():
    materials = {"white": {"type": "diffuse", "reflectance": 0.8}, "dark": {"type": "diffuse", "reflectance": 0.1},
                 "flint": {"type": "dielectric", "glass": "sf11"}}
    shapes = [
        quad("table", "white", [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]),
        quad("back wall", "dark", [[-2, 0, 1.5], [2, 0, 1.5], [2, 2, 1.5], [-2, 2, 1.5]]),
        {"type": "sphere", "name": "flint glass sphere", "material": "flint", "center": [0.0, 0.25, 0.3], "radius": 0.25},
        ceiling_light(-0.45, 1.2, 0.0, 0.1, {"illuminant": "D65", "scale": 2.0}),
    ]
    return {
        "description": "Dispersion: an N-SF11 flint glass sphere on a white table under a small D65 light; the caustic "
                       "on the table splits into colours. Issue 7.",
        "camera": {"type": "pinhole", "from": [0.9, 1.0, -1.2], "to": [0.1, 0.1, 0.4], "up": [0, 1, 0],
                   "vertical_fov_deg": 35},
        "film": FILM, "integrator": INTEGRATOR, "materials": materials, "shapes": shapes}


def mean_linear_colour():
    """The mean linear sRGB of colour_bars.png (IEC 61966-2-1 decoding), rounded to 3 decimals."""
    decode = lambda c: c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
    pixels = [colour_bars(x, y) for y in range(64) for x in range(64)]
    return [round(sum(decode(p[k] / 255) for p in pixels) / len(pixels), 3) for k in range(3)]


def textured(constant=False):
    # constant: the same scene with the texture replaced by its mean colour, the untextured reference for the
    # cost of texture lookups (docs/benchmarks.md, "RGB → spectrum upsampler").
    poster = {"rgb": mean_linear_colour()} if constant else {"texture": "colour_bars.png"}
    materials = {"white": {"type": "diffuse", "reflectance": 0.8},
                 "poster": {"type": "diffuse", "reflectance": poster}}
    shapes = box_room(-1.5, 1.5, 0.0, 2.5, -1.0, 2.0, "white", "white", "white", "white", "white", "white")
    shapes.append({"type": "triangles", "name": "poster", "material": "poster",
                   "positions": [[0.9, 0.5, 1.98], [-0.9, 0.5, 1.98], [-0.9, 1.7, 1.98], [0.9, 1.7, 1.98]],
                   "indices": [0, 1, 2, 0, 2, 3], "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]]})
    shapes.append(ceiling_light(0.0, 2.49, 0.9, 0.5, {"illuminant": "F11", "scale": 0.05}))
    return {
        "description": ("The textured scene (scene.json) with the poster's texture replaced by its mean linear sRGB "
                        "colour: the untextured reference for the cost of texture lookups." if constant else
                        "An sRGB image texture (colour_bars.png, made by generate_benchmark_scenes.py) on the back "
                        "wall of a white room under CIE F11; converted to spectra per texel at load in spectral "
                        "modes. Issue 7."),
        "camera": {"type": "pinhole", "from": [0.0, 1.1, -0.9], "to": [0.0, 1.1, 2.0], "up": [0, 1, 0],
                   "vertical_fov_deg": 30},
        "film": FILM, "integrator": INTEGRATOR, "materials": materials, "shapes": shapes}


def write_png(path, width, height, pixel):
    """An 8-bit sRGB-encoded RGB PNG (PNG spec: IHDR, one IDAT, IEND; filter type 0 per row)."""
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.write_bytes(png)


def colour_bars(x, y):
    # Top half: eight saturated bars (sRGB-encoded); bottom half: a grey ramp and a skin/sky/foliage row.
    bars = [(255, 255, 255), (255, 255, 0), (0, 255, 255), (0, 255, 0), (255, 0, 255), (255, 0, 0), (0, 0, 255),
            (0, 0, 0)]
    if y < 32:
        return bars[x // 8]
    if y < 48:
        g = int(255 * (x // 8) / 7)
        return (g, g, g)
    naturals = [(115, 82, 68), (194, 150, 130), (98, 122, 157), (87, 108, 67), (133, 128, 177), (103, 189, 170),
                (214, 126, 44), (80, 91, 166)]
    return naturals[x // 8]


if __name__ == "__main__":
    for illuminant, stem, words in [("D65", "colorchecker_d65", "CIE D65"), ("F11", "colorchecker_f11", "CIE F11 (narrow-band fluorescent)"),
                                    ("A", "colorchecker_a", "CIE illuminant A")]:
        scene = colorchecker_room(illuminant, "A ColorChecker Classic (BabelColor average reflectances) in a white "
                                  "room lit by a ceiling light of " + words + ". Issue 7.")
        (HERE / "colorchecker_room" / (stem + ".json")).write_text(json.dumps(scene, indent=1) + "\n")
    (HERE / "colour_bleeding" / "scene.json").write_text(json.dumps(colour_bleeding(), indent=1) + "\n")
    (HERE / "dispersion" / "scene.json").write_text(json.dumps(dispersion(), indent=1) + "\n")
    (HERE / "textured" / "scene.json").write_text(json.dumps(textured(), indent=1) + "\n")
    (HERE / "textured" / "constant_colour.json").write_text(json.dumps(textured(constant=True), indent=1) + "\n")
    write_png(HERE / "textured" / "colour_bars.png", 64, 64, colour_bars)
