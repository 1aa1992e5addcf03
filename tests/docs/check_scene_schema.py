#!/usr/bin/env python3
"""Scene documents validate against docs/scene.schema.json (JSON Schema 2020-12).

The schema is what editors check scene files with; the loader (src/render/scene/) is what Rimu accepts. A scene the
loader renders but the schema refuses means the schema fell behind: this check keeps the two together on the
scenes the project ships, and on what the pbrt importer writes (the documents users see most).

Usage:
  check_scene_schema.py SCHEMA SCENES_DIR
      every *.json with a "camera" below SCENES_DIR.
  check_scene_schema.py SCHEMA --pbrt RIMU_CONVERT PBRT_DIR
      every PBRT_DIR/*.pbrt that is a scene (has a WorldBegin; not an Include fragment) and is not named bad_*,
      converted by RIMU_CONVERT into a temporary directory; a file it cannot convert is a failure too.
Exit 1 naming each file, path and message; 77 (skipped) without python3-jsonschema.
"""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:  # ctest reports the check as skipped (SKIP_RETURN_CODE), not passed
    print("python3-jsonschema is not installed (scripts/install-deps.sh installs it): schema check skipped")
    sys.exit(77)


def load_validator(schema_path: str) -> "jsonschema.Draft202012Validator":
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def schema_errors(validator, path: str, name: str) -> int:
    """Prints each schema error of the scene at `path` (named `name`); returns how many."""
    with open(path, encoding="utf-8") as f:
        document = json.load(f)
    failures = 0
    for error in validator.iter_errors(document):
        failures += 1
        where = "/".join(str(p) for p in error.absolute_path)
        # For a oneOf/anyOf, the deepest sub-error says which key is wrong.
        detail = max(error.context or [error], key=lambda e: len(list(e.absolute_path)))
        print(f"{name}: /{where}: {error.message[:160]}; {detail.message[:160]}")
    return failures


def check_scenes(validator, root: str) -> int:
    failures, checked = 0, 0
    for path in sorted(glob.glob(os.path.join(root, "**", "*.json"), recursive=True)):
        with open(path, encoding="utf-8") as f:
            document = json.load(f)
        if not isinstance(document, dict) or "camera" not in document:
            continue  # light definitions and other JSON beside the scenes
        checked += 1
        failures += schema_errors(validator, path, os.path.relpath(path, root))
    print(f"{checked} scenes checked, {failures} schema errors")
    return 1 if failures or checked == 0 else 0


def is_pbrt_scene(path: str) -> bool:
    """A whole scene, not a fragment read through Include (those have no WorldBegin and do not convert alone)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        return any(re.match(r"\s*WorldBegin\b", line) for line in f)


def check_pbrt_imports(validator, converter: str, pbrt_dir: str) -> int:
    failures, checked = 0, 0
    with tempfile.TemporaryDirectory(prefix="rimu_schema_pbrt_") as out_dir:
        for path in sorted(glob.glob(os.path.join(pbrt_dir, "*.pbrt"))):
            name = os.path.basename(path)
            if name.startswith("bad_") or not is_pbrt_scene(path):
                continue
            checked += 1
            output = os.path.join(out_dir, name[: -len(".pbrt")] + ".json")
            try:
                run = subprocess.run([converter, path, "-o", output], capture_output=True, text=True)
            except OSError as e:
                print(f"cannot run {converter}: {e}")
                return 1
            if run.returncode != 0:
                failures += 1
                print(f"{name}: rimu-convert exited {run.returncode}: {run.stderr.strip()[:300]}")
                continue
            failures += schema_errors(validator, output, f"{name} (converted)")
    print(f"{checked} pbrt scenes converted and checked, {failures} failures")
    return 1 if failures or checked == 0 else 0


def main(argv: list) -> int:
    validator = load_validator(argv[1])
    if len(argv) == 5 and argv[2] == "--pbrt":
        return check_pbrt_imports(validator, argv[3], argv[4])
    if len(argv) == 3:
        return check_scenes(validator, argv[2])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
