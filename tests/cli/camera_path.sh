#!/usr/bin/env bash
# camera_path.sh RIMU COMPARE CAMERA_PATH_JSON WORKDIR: a camera path keyed by frame renders, at frame 6 (half way
# between keys at frames 1 and 11), the image of a fixed camera at the interpolated position and field of view, bit
# for bit; after the last key it holds the last key's camera; frames 1 and 11 differ.
set -u
rimu=$1; compare=$2; scene=$3; dir=$4
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
opts=(--float --threads 1 -q)

# The same scene with the camera frame 6 must have: from z = 6 + (3 - 6)/2 = 4.5, fov 20 + (30 - 20)/2 = 25.
python3 - "$scene" fixed.json <<'PY' || fail "could not write the fixed-camera scene"
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"] = {"up": [0, 1, 0], "vertical_fov_deg": 25, "from": [0, 0, 4.5], "to": [0, 0, 0]}
json.dump(scene, open(sys.argv[2], "w"))
PY
"$rimu" "$scene" --frame 6 "${opts[@]}" -o 'path.${frame:4}.exr' || fail "render of frame 6"
[ -f path.0006.exr ] || fail "no path.0006.exr"
"$rimu" fixed.json "${opts[@]}" -o fixed.exr || fail "render of the fixed camera"
"$compare" path.0006.exr fixed.exr --image-only || fail "frame 6 is not the interpolated camera's image"

"$rimu" "$scene" --frame 11 "${opts[@]}" -o last.exr || fail "render of frame 11"
"$rimu" "$scene" --frame 40 "${opts[@]}" -o held.exr || fail "render of frame 40"
"$compare" last.exr held.exr --image-only || fail "after the last key the camera is not held"
"$rimu" "$scene" --frame 1 "${opts[@]}" -o first.exr || fail "render of frame 1"
if "$compare" first.exr last.exr --image-only >/dev/null; then fail "frames 1 and 11 render the same image"; fi
echo "camera path: frame 6 = the interpolated camera; held after the last key; frames differ"
