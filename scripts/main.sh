#!/usr/bin/env bash
# Installs what is missing, builds Rimu, and runs its main job.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
# The main job: render the embedded default scene, the measured spectral Cornell box, to EXR (CIE XYZ) and PNG (sRGB).
mkdir -p out
build/bin/rimu -o out/cornell_box.exr --png out/cornell_box.png "$@"
