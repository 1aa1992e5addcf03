#!/usr/bin/env bash
# Metropolis light transport (docs/transport.md, "Metropolis light transport"; docs/benchmarks.md, "Metropolis light
# transport"): integrator.method "path_tracing" (the default path tracer with the scene's own settings) against
# "metropolis" (bench/integrator_key_bench.sh, which says what is measured and how). Metropolis is consistent, not
# unbiased, so every reference is the path tracer's (seed 99).
#
#   bench/metropolis_bench.sh BUILD [OUT_DIR]
#
# Environment as bench/integrator_key_bench.sh's; defaults here: SCENES [interiors/door_ajar cornell_box/scene
# interiors/daylit_room_open], SPPS ["64 256"], REF_SPP [4096], RESOLUTION [160x90]; the door-ajar room's lights
# ×10⁶ (its image is dim), the others' ×1000.
set -euo pipefail
scenes=${SCENES:-"interiors/door_ajar cornell_box/scene interiors/daylit_room_open"}
ref_modes=""
for scene in $scenes; do ref_modes+="$(basename "$(dirname "$scene")")-$(basename "${scene%.*}")=path_tracing "; done
KEY=method MODES="path_tracing metropolis" LABELS="path tracing|Metropolis" NAME=metropolis SCENES=$scenes \
  SPPS=${SPPS:-"64 256"} REF_SPP=${REF_SPP:-4096} RESOLUTION=${RESOLUTION:-160x90} REF_MODES=$ref_modes \
  FACTORS=${FACTORS:-"interiors-door_ajar=1000000"} \
  exec "$(dirname "$0")/integrator_key_bench.sh" "$1" "${2:-/tmp/metropolis_bench}"
