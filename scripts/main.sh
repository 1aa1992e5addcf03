#!/usr/bin/env bash
# Installs what is missing, builds Rimu, and runs its main job.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
# Until the renderer lands (issue 4), the main job is the colour toolkit's report on CIE illuminant D65.
build/bin/rimu-colour report D65
