#!/usr/bin/env bash
# adaptive_bench.sh BUILD [BUDGETS_S] [REFERENCE_SPP] [RESOLUTION] [THRESHOLD] [OUT.png]
# Adaptive sampling against uniform sampling (docs/benchmarks.md, "Adaptive sampling"). For each scene two uniform
# references of REFERENCE_SPP samples (seeds 98 and 99; relMSE between them over 2 is the reference's own share of
# every figure, the "floor"), then for each render-time budget T (`rimu --time T`) and seed (BENCH_SEEDS, default
# 1; 2 threads):
#   adaptive   --time T --noise-threshold THRESHOLD: the budget, not the threshold, ends it; mean spp m reached;
#   uniform    --spp round(m): the same camera samples (within half a sample per pixel);
#   uniform    --time T: the same wall-clock budget (BENCH_WALL=0 leaves it out).
# Prints relMSE against the seed-99 reference (rimu-pbrt-image-compare relmse) and three gains:
#   samples  relMSE(uniform, same samples) / relMSE(adaptive)        the allocation alone, immune to load;
#   cpu      relMSE·CPU s (uniform, same samples) / relMSE·CPU s (adaptive)   equal CPU time, the bookkeeping
#            included (relMSE ∝ 1/time for either: both are unbiased Monte Carlo);
#   wall     relMSE(uniform, --time T) / relMSE(adaptive)           equal wall time, noisy on a loaded machine;
# and samples_fc and cpu_fc, the samples and CPU gains with the floor taken off both relMSEs (n/a when the adaptive
# relMSE is under it): at long budgets the references' own noise is most of every relMSE and hides the gains.
# Then a summary per scene and budget over the seeds: the geometric mean of the CPU gains, and the CPU gain of the
# means (mean relMSE·CPU s of the uniform renders over the adaptive ones'), without and with the floor taken off,
# and draws relMSE against the camera samples per pixel, one panel per scene, to OUT.png (gnuplot; default
# adaptive_sampling.png). Scenes, lights ×1000 (bench/scaled_scene.py) so relMSE's floor of 0.01 is negligible: the
# Cornell box, the ColorChecker room under F11, the daylit room with an open window (its difficulty is even: the
# sky lights every corner directly), the night room (50 downlights; light through a glass tumbler and off a copper
# ball: rare caustic paths) and the window-and-corridor room (a bright window and sun patch, a dark corridor lit only
# indirectly). BENCH_SCENES="cornell daylit_open" (say) runs only those.
set -eu
build=$1; budgets=${2:-"4 16"}; ref_spp=${3:-8192}; resolution=${4:-120x68}; threshold=${5:-0.001}
plot=${6:-adaptive_sampling.png}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-adaptive.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
declare -A sources=([cornell]=$root/data/scenes/cornell_box/scene.json
                    [colorchecker_f11]=$root/data/scenes/colorchecker_room/colorchecker_f11.json
                    [daylit_open]=$root/data/scenes/interiors/daylit_room_open.json
                    [night_room]=$root/data/scenes/interiors/night_room_downlights.json
                    [window_corridor]=$root/data/scenes/interiors/window_corridor.json)
# The night room's 800 lm downlights give film values near 0.002: ×1e5 to bring them, as ×1000 does the others,
# far above relMSE's floor.
declare -A factors=([cornell]=1000 [colorchecker_f11]=1000 [daylit_open]=1000 [night_room]=100000 [window_corridor]=1000)
scenes=${BENCH_SCENES:-"cornell colorchecker_f11 daylit_open night_room window_corridor"}
pixels=$(awk -F'x' '{ print $1 * $2 }' <<<"$resolution")
# BENCH_SEEDS="1 2 3" repeats each budget with those seeds (default 1); BENCH_WALL=0 skips the uniform --time render
# (the wall column reads n/a); BENCH_REFS=DIR keeps the references there and reuses them (named by scene, spp and
# resolution), so a second run with another build renders only the adaptive and uniform images.
# BENCH_REF_SPP="window_corridor=16384" gives those scenes longer references than REFERENCE_SPP.
declare -A ref_spps=(); for kv in ${BENCH_REF_SPP:-}; do ref_spps[${kv%%=*}]=${kv#*=}; done
seeds=${BENCH_SEEDS:-1}; wall=${BENCH_WALL:-1}; refs=${BENCH_REFS:-$scratch}; mkdir -p "$refs"
# Renders; sets cpu_s (user + system CPU seconds of the whole process) and mean_spp (rimu's summary: the adaptive
# line's mean, else the spp line's count).
render() {
  /usr/bin/time -f "%U %S" -o "$scratch/time" "$rimu" "$@" 2>"$scratch/log" >/dev/null
  cpu_s=$(awk '{ print $1 + $2 }' "$scratch/time")
  mean_spp=$(sed -n 's/^rimu: adaptive sampling: .*; mean \([0-9.e+]*\) spp$/\1/p' "$scratch/log")
  [ -n "$mean_spp" ] || mean_spp=$(sed -n 's/^rimu: .*: \([0-9]*\) spp.*/\1/p' "$scratch/log" | head -1)
}
relmse() { "$compare" relmse "$1" "$2" | sed -n 's/^relmse=//p'; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); budgets ${budgets} s at $resolution, references $ref_spp spp, threshold $threshold"
printf "%-17s %4s %6s %7s %9s %11s %11s %11s %6s %6s %6s %9s %7s %7s %7s\n" scene seed budget floor spp_mean relmse_adapt relmse_same \
  relmse_wall samples cpu wall samples_fc cpu_fc cpu_s_a cpu_s_u | tee "$scratch/table"
for n in $scenes; do
  python3 "$root/bench/scaled_scene.py" "${sources[$n]}" "$scratch" "$n" "${factors[$n]}"
  scene=$scratch/${n}_dir/$n.json
  spp_ref=${ref_spps[$n]:-$ref_spp}
  for seed in 98 99; do
    ref=$refs/ref${seed}_${n}_${spp_ref}_$resolution.exr
    [ -f "$ref" ] || "$rimu" -q "$scene" -o "$ref" --spp "$spp_ref" --seed $seed --threads 2 --resolution "$resolution"
  done
  ref98=$refs/ref98_${n}_${spp_ref}_$resolution.exr; ref99=$refs/ref99_${n}_${spp_ref}_$resolution.exr
  floor=$(awk -v e="$(relmse "$ref98" "$ref99")" 'BEGIN { printf "%.3g", e / 2 }')
  for seed in $seeds; do
  for t in $budgets; do
    common=("$scene" --seed "$seed" --threads 2 --resolution "$resolution")
    render "${common[@]}" --time "${t}s" --noise-threshold "$threshold" -o "$scratch/adaptive.exr"
    cpu_a=$cpu_s; spp_a=$mean_spp
    render "${common[@]}" --spp "$(printf '%.0f' "$spp_a")" -o "$scratch/same.exr"
    cpu_u=$cpu_s
    e_a=$(relmse "$scratch/adaptive.exr" "$ref99")
    e_s=$(relmse "$scratch/same.exr" "$ref99")
    e_w=nan
    if [ "$wall" != 0 ]; then
      render "${common[@]}" --time "${t}s" -o "$scratch/wall.exr"
      e_w=$(relmse "$scratch/wall.exr" "$ref99")
    fi
    awk -v n="$n" -v seed="$seed" -v t="$t" -v f="$floor" -v m="$spp_a" -v a="$e_a" -v s="$e_s" -v w="$e_w" -v ca="$cpu_a" -v cu="$cpu_u" \
      'BEGIN { fc = a + 0 > f + 0 ? sprintf("%.2f", (s - f) / (a - f)) : "n/a"; wg = w == "nan" ? "n/a" : sprintf("%.2f", w / a)
               cfc = a + 0 > f + 0 ? sprintf("%.2f", (s - f) * cu / ((a - f) * ca)) : "n/a"
               printf "%-17s %4s %6s %7s %9.1f %11.4g %11.4g %11s %6.2f %6.2f %6s %9s %7s %7.2f %7.2f\n", n, seed, t, f, m, a, s, w, s / a, s * cu / (a * ca), wg, fc, cfc, ca, cu }' |
      tee -a "$scratch/table"
  done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
# Per scene and budget over the seeds: the geometric mean of the seeds' CPU gains, and the gain of the means (mean
# relMSE·CPU s of the uniform renders over that of the adaptive ones, and the same with the floor taken off every
# relMSE). relMSE is an expectation: a few seeds' ratios are skewed by single rare paths, which the ratio of means
# weighs as the expectation does, while their geometric mean weighs the typical seed.
awk 'NR > 1 { k = $1 " " $3; n[k]++; lg[k] += log($10); u[k] += $7 * $15; a[k] += $6 * $14
              uf[k] += ($7 - $4) * $15; af[k] += ($6 - $4) * $14; if (!(k in order)) { order[k] = ++count; key[count] = k } }
     END { printf "%-17s %6s %5s %12s %12s %15s\n", "scene", "budget", "seeds", "cpu_geomean", "cpu_of_means", "cpu_of_means_fc"
           for (i = 1; i <= count; ++i) { k = key[i]; split(k, p, " ")
             printf "%-17s %6s %5d %12.3f %12.3f %15.3f\n", p[1], p[2], n[k], exp(lg[k] / n[k]), u[k] / a[k], uf[k] / af[k] } }' \
  "$scratch/table"
# One panel per scene: relMSE against the mean spp, log-log, adaptive and uniform at the same samples.
{
  echo "set terminal pngcairo size $((330 * $(wc -w <<<"$scenes"))),400 font ',10'; set output '$plot'"
  echo "set multiplot layout 1,$(wc -w <<<"$scenes"); set logscale xy; set xlabel 'camera samples per pixel (mean)'; set ylabel 'relMSE'; set key top right"
  for n in $scenes; do
    echo "set title '$n' noenhanced"
    echo "plot '$scratch/table' using (strcol(1) eq '$n' ? \$5 : 1/0):7 with points pt 7 title 'uniform', '' using (strcol(1) eq '$n' ? \$5 : 1/0):6 with points pt 5 title 'adaptive', '' using (strcol(1) eq '$n' ? \$5 : 1/0):(\$4 + 0) with lines dt 2 title 'reference floor'"
  done
  echo "unset multiplot"
} | gnuplot
echo "plot: $plot"
