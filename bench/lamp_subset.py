#!/usr/bin/env python3
"""lamp_subset.py SCENE.json OUT.json N: SCENE with N of its lights kept, spread over the list (every k-th), each
kept light's amount multiplied by (lights before) / N so that the room receives about the same light, and relative
paths made absolute (bench/scaled_scene.py's rule) so OUT renders from anywhere.

For the question of how many lights the resampled light choice needs before it pays (docs/benchmarks.md, "Glossy
vertices: resampled light choice"): the same room and materials, lit by 4, 8, 16 … of its downlights.
"""
import json
import os
import sys

from scaled_scene import absolute_paths, AMOUNT_KEYS


def main(source, out, count):
    with open(source) as f:
        scene = json.load(f)
    lights = scene.get("lights", [])
    if not 1 <= count <= len(lights):
        sys.exit(f"lamp_subset.py: {source} has {len(lights)} lights; N must be 1 to {len(lights)}")
    kept = [lights[(i * len(lights)) // count] for i in range(count)]
    for light in kept:
        for key in AMOUNT_KEYS:
            if isinstance(light.get(key), (int, float)):
                light[key] *= len(lights) / count
    scene["lights"] = kept
    scene = absolute_paths(scene, os.path.dirname(os.path.abspath(source)))
    with open(out, "w") as f:
        json.dump(scene, f)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
