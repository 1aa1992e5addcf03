#!/usr/bin/env python3
"""Every scene in data/scenes validates against docs/scene.schema.json (JSON Schema 2020-12).

The schema is what editors check scene files with; the loader (src/render/scene/) is what Rimu accepts. A scene the
loader renders but the schema refuses means the schema fell behind: this check keeps the two together on the
scenes the project ships. Usage: check_scene_schema.py SCHEMA SCENES_DIR (every *.json with a "camera" below
SCENES_DIR). Exit 1 naming each file, path and message.
"""
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:  # ctest reports the check as skipped (SKIP_RETURN_CODE), not passed
    print("python3-jsonschema is not installed (scripts/install-deps.sh installs it): schema check skipped")
    sys.exit(77)


def main(schema_path: str, root: str) -> int:
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    failures, checked = 0, 0
    for path in sorted(glob.glob(os.path.join(root, "**", "*.json"), recursive=True)):
        with open(path, encoding="utf-8") as f:
            document = json.load(f)
        if not isinstance(document, dict) or "camera" not in document:
            continue  # light definitions and other JSON beside the scenes
        checked += 1
        for error in validator.iter_errors(document):
            failures += 1
            where = "/".join(str(p) for p in error.absolute_path)
            # For a oneOf/anyOf, the deepest sub-error says which key is wrong.
            detail = max(error.context or [error], key=lambda e: len(list(e.absolute_path)))
            print(f"{os.path.relpath(path, root)}: /{where}: {error.message[:160]}; {detail.message[:160]}")
    print(f"{checked} scenes checked, {failures} schema errors")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
