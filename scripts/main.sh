#!/usr/bin/env bash
# Installs what is missing for rendering, builds the tools, and runs the main job.
# Only the tools are built (not the tests, benchmarks or the Python module: scripts/test.sh adds those).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
if [ ! -f build/CMakeCache.txt ]; then
  # A first configuration without the parts that need the test packages; scripts/test.sh turns them on in the same
  # build folder. An existing build folder keeps its settings.
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRIMU_BUILD_TESTS=OFF -DRIMU_BUILD_BENCHMARKS=OFF \
        -DRIMU_PYTHON=OFF >/dev/null
else
  cmake -S . -B build >/dev/null
fi
cmake --build build -j"$(nproc)" --target rimu-tools
# The main job: render the embedded default scene, the measured spectral Cornell box, to EXR (CIE XYZ) and PNG (sRGB).
mkdir -p out
build/bin/rimu -o out/cornell_box.exr --png out/cornell_box.png "$@"
