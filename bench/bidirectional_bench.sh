#!/usr/bin/env bash
# Bidirectional path tracing (docs/transport.md, "Bidirectional path tracing"; docs/benchmarks.md, "Bidirectional
# path tracing"): integrator.method "path_tracing" (the default path tracer, with whatever caustics and daylit-point
# settings the scene has) against "bidirectional" (bench/integrator_key_bench.sh, which says what is measured and
# how; the reference is bidirectional, seed 99).
#
#   bench/bidirectional_bench.sh BUILD [OUT_DIR]
#
# Environment as bench/integrator_key_bench.sh's; defaults here: SCENES [interiors/door_ajar cornell_box/scene
# examples/spot_glass_caustic interiors/daylit_room_open interiors/night_room_downlights], SPPS ["16 64"], REF_SPP
# [1024], RESOLUTION [160x90]; the door-ajar room's lights ×10⁶ (its image is dim), the others' ×1000.
set -euo pipefail
KEY=method MODES="path_tracing bidirectional" LABELS="path tracing|bidirectional" NAME=bidirectional \
  SCENES=${SCENES:-"interiors/door_ajar cornell_box/scene examples/spot_glass_caustic interiors/daylit_room_open interiors/night_room_downlights"} \
  REF_SPP=${REF_SPP:-1024} RESOLUTION=${RESOLUTION:-160x90} FACTORS=${FACTORS:-"interiors-door_ajar=1000000"} \
  exec "$(dirname "$0")/integrator_key_bench.sh" "$1" "${2:-/tmp/bidirectional_bench}"
