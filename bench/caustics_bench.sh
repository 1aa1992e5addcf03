#!/usr/bin/env bash
# Caustics by light tracing (docs/transport.md, "Caustics by light tracing"; docs/benchmarks.md, "Caustics by light
# tracing"): integrator.caustics "path_tracing" against "light_tracing" (bench/integrator_key_bench.sh, which says
# what is measured and how; the reference is light-traced, seed 99).
#
#   bench/caustics_bench.sh BUILD [OUT_DIR]
#
# Environment as bench/integrator_key_bench.sh's; defaults here: SCENES [dispersion/scene
# examples/spot_glass_caustic], SPPS ["16 64"], REF_SPP [2048], RESOLUTION [160x120]. Where a caustic comes from a
# light at a point (a spot), the path tracer never renders it: its relMSE then holds that bias, which more samples
# do not remove.
set -euo pipefail
KEY=caustics MODES="path_tracing light_tracing" LABELS="path tracing|light tracing" NAME=caustics \
  SCENES=${SCENES:-"dispersion/scene examples/spot_glass_caustic"} REF_SPP=${REF_SPP:-2048} \
  RESOLUTION=${RESOLUTION:-160x120} exec "$(dirname "$0")/integrator_key_bench.sh" "$1" "${2:-/tmp/caustics_bench}"
