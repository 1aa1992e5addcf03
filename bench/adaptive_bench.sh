#!/usr/bin/env bash
# adaptive_bench.sh BUILD [BUDGETS_S] [REFERENCE_SPP] [RESOLUTION] [THRESHOLD] [OUT.png]
# Adaptive sampling against uniform sampling at equal time (issue #26 §1; docs/benchmarks.md, "Adaptive sampling"):
# for each scene a uniform reference of REFERENCE_SPP samples (seed 99), then for each render-time budget
# (`rimu --time T`, whole passes; the render time is what the EXR records) one uniform render and one with
# `--noise-threshold THRESHOLD`, both with seed 1 and 2 threads. THRESHOLD is set low enough that the budget, not the
# threshold, ends the adaptive render, so the two spend the same time and differ only in where the samples go.
# Prints relMSE (rimu-pbrt-image-compare relmse, against the reference) and the spp reached, and the equal-time gain
#   relMSE_uniform / relMSE_adaptive,
# and draws relMSE against render time, one panel per scene, to OUT.png (gnuplot; default adaptive_sampling.png).
# Scenes, lights ×1000 (bench/scaled_scene.py) so the relMSE floor of 0.01 is negligible: the Cornell box (difficulty
# fairly even), the ColorChecker room under F11, and the daylit room with an open window (a bright sun patch and
# dark corners). BENCH_SCENES="cornell daylit_open" (say) runs only those. The machine should be otherwise idle:
# the budgets are wall-clock render time.
set -eu
build=$1; budgets=${2:-"2 4 8 16"}; ref_spp=${3:-4096}; resolution=${4:-160x90}; threshold=${5:-0.002}
plot=${6:-adaptive_sampling.png}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-adaptive.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
declare -A sources=([cornell]=$root/data/scenes/cornell_box/scene.json
                    [colorchecker_f11]=$root/data/scenes/colorchecker_room/colorchecker_f11.json
                    [daylit_open]=$root/data/scenes/interiors/daylit_room_open.json)
scenes=${BENCH_SCENES:-"cornell colorchecker_f11 daylit_open"}
# Renders and prints the spp reached (from rimu's summary line: "rimu: SCENE: N spp ...").
render_spp() { "$rimu" "$@" 2>&1 >/dev/null | sed -n 's/^rimu: .*: \([0-9]*\) spp.*/\1/p' | head -1; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); budgets ${budgets} s at $resolution, reference $ref_spp spp, threshold $threshold"
printf "%-17s %6s %12s %12s %8s %8s %6s\n" scene budget relmse_unif relmse_adapt spp_unif spp_adapt gain | tee "$scratch/table"
for n in $scenes; do
  python3 "$root/bench/scaled_scene.py" "${sources[$n]}" "$scratch" "$n" 1000
  scene=$scratch/${n}_dir/$n.json
  "$rimu" -q "$scene" -o "$scratch/ref_$n.exr" --spp "$ref_spp" --seed 99 --threads 2 --resolution "$resolution"
  for t in $budgets; do
    common=("$scene" --seed 1 --threads 2 --resolution "$resolution" --time "${t}s")
    s_u=$(render_spp "${common[@]}" -o "$scratch/uniform.exr")
    s_a=$(render_spp "${common[@]}" --noise-threshold "$threshold" -o "$scratch/adaptive.exr")
    e_u=$("$compare" relmse "$scratch/uniform.exr" "$scratch/ref_$n.exr" | sed 's/.*=//')
    e_a=$("$compare" relmse "$scratch/adaptive.exr" "$scratch/ref_$n.exr" | sed 's/.*=//')
    gain=$(awk -v a="$e_u" -v b="$e_a" 'BEGIN { printf "%.2f", a / b }')
    printf "%-17s %6s %12.4g %12.4g %8s %8s %6s\n" "$n" "$t" "$e_u" "$e_a" "$s_u" "$s_a" "$gain" | tee -a "$scratch/table"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
# One panel per scene: relMSE against the budget, log-log, uniform and adaptive.
{
  echo "set terminal pngcairo size 1200,400 font ',10'; set output '$plot'"
  echo "set multiplot layout 1,$(wc -w <<<"$scenes"); set logscale xy; set xlabel 'render time (s)'; set ylabel 'relMSE'; set key top right"
  for n in $scenes; do
    echo "set title '$n' noenhanced"
    echo "plot '$scratch/table' using (strcol(1) eq '$n' ? \$2 : 1/0):3 with linespoints title 'uniform', '' using (strcol(1) eq '$n' ? \$2 : 1/0):4 with linespoints title 'adaptive'"
  done
  echo "unset multiplot"
} | gnuplot
echo "plot: $plot"
