#!/usr/bin/env bash
# Vertex connection and merging (docs/transport.md, "Vertex connection and merging"; docs/benchmarks.md, the section
# of that name): integrator.method "bidirectional" against "vcm" (bench/integrator_key_bench.sh, which says what is
# measured and how). Merging is consistent, not unbiased, so the reference is bidirectional where that converges in
# reasonable time (the Cornell box, the door-ajar room) and a long vcm render only where nothing else does (the pool
# seen through water: every path E S D S L).
#
#   bench/vertex_merging_bench.sh BUILD [OUT_DIR]
#
# Environment as bench/integrator_key_bench.sh's; defaults here: SCENES [examples/pool_through_water
# cornell_box/scene interiors/door_ajar], SPPS ["16 64"], REF_SPP [2048], RESOLUTION [160x90]; the door-ajar room's
# lights ×10⁶ (its image is dim), the others' ×1000.
set -euo pipefail
KEY=method MODES="bidirectional vcm" LABELS="bidirectional|vcm" NAME=vertex_merging \
  SCENES=${SCENES:-"examples/pool_through_water cornell_box/scene interiors/door_ajar"} \
  REF_SPP=${REF_SPP:-2048} RESOLUTION=${RESOLUTION:-160x90} FACTORS=${FACTORS:-"interiors-door_ajar=1000000"} \
  REF_MODES=${REF_MODES:-"cornell_box-scene=bidirectional interiors-door_ajar=bidirectional"} \
  exec "$(dirname "$0")/integrator_key_bench.sh" "$1" "${2:-/tmp/vertex_merging_bench}"
