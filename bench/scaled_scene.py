#!/usr/bin/env python3
"""scaled_scene.py SCENE.json OUT_FOLDER NAME FACTOR: SCENE written as OUT_FOLDER/NAME_dir/NAME.json with every
light and emitter amount multiplied by FACTOR and "guiding" taken out of its integrator.

The benchmarks' relMSE (rimu-pbrt-image-compare relmse) divides by r² + 0.01: scaling the lights by 1000 (the image
only scales) makes that floor negligible for scenes whose film values are far below 1. Relative paths in the scene
(spectra, meshes, includes) are written out as absolute paths, so the copy renders from anywhere.
"""
import json
import os
import sys

AMOUNT_KEYS = ("illuminance_lx", "luminance_nt", "power_w", "scale", "radiance", "luminous_power_lm",
               "luminous_intensity_cd", "candela_scale")


def scale_amounts(scene, factor):
    for light in scene.get("lights", []):
        for key in AMOUNT_KEYS:
            if isinstance(light.get(key), (int, float)):
                light[key] *= factor
    for shape in scene.get("shapes", []):
        emission = shape.get("emission")
        if isinstance(emission, dict) and any(k in emission for k in ("scale", "luminous_power_lm")):
            for key in ("scale", "luminous_power_lm"):
                if isinstance(emission.get(key), (int, float)):
                    emission[key] *= factor
        elif "emission_scale" in shape:
            shape["emission_scale"] *= factor


def absolute_paths(value, folder):
    """Every string naming a file that exists relative to the scene's folder, made absolute (a scene may reach
    outside its folder, e.g. ../../spectra/, which a copy of the folder alone would lose)."""
    if isinstance(value, dict):
        return {k: absolute_paths(v, folder) for k, v in value.items()}
    if isinstance(value, list):
        return [absolute_paths(v, folder) for v in value]
    if isinstance(value, str) and value and not os.path.isabs(value):
        candidate = os.path.normpath(os.path.join(folder, value))
        if os.path.isfile(candidate):
            return candidate
    return value


def main(source, out, name, factor):
    with open(source) as f:
        scene = json.load(f)
    scale_amounts(scene, factor)
    scene.get("integrator", {}).pop("guiding", None)
    scene = absolute_paths(scene, os.path.dirname(os.path.abspath(source)))
    folder = os.path.join(out, f"{name}_dir")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, f"{name}.json"), "w") as f:
        json.dump(scene, f)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]))
