#!/usr/bin/env bash
# Installs what is missing, builds Rimu, fuzzes each file reader briefly and runs the whole test suite through CTest.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   ASan+UBSan build in build-sanitize/
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
cmake_args=(-DCMAKE_BUILD_TYPE=Release -DRIMU_BUILD_TESTS=ON -DRIMU_BUILD_BENCHMARKS=ON -DRIMU_PYTHON=ON)
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-sanitize
  # The Python module is left out: a sanitized extension cannot load into an uninstrumented interpreter.
  cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DRIMU_SANITIZE=ON -DRIMU_BUILD_TESTS=ON -DRIMU_BUILD_BENCHMARKS=OFF -DRIMU_PYTHON=OFF)
fi

scripts/install-deps.sh --test
cmake -S . -B "$build_dir" "${cmake_args[@]}" >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
# The readers' fuzz targets, briefly (docs/fuzzing.md): a crash, sanitizer report or unexpected exception fails.
# They run before CTest so that CTest's summary is the run's closing line.
scripts/fuzz.sh "${RIMU_CI_FUZZ_SECONDS:-12}"
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)"
