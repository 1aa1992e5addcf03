#!/usr/bin/env bash
# daylit_points_bench.sh BUILD [OUT] — daylit points off against on (docs/benchmarks.md, "Daylit points";
# docs/transport.md says what they are). Scenes: the rooms of data/scenes/interiors lit through a window portal,
# their lights scaled (bench/scaled_scene.py: ×1000, the door-ajar room ×10⁶, so that the relMSE's absolute floor
# of 0.01 in rimu-pbrt-image-compare is negligible; the image only scales). Per scene a reference of REF_SPP
# samples (daylit points on, seed 99), then per configuration, spp and seed one render, timed in CPU seconds (user +
# system of the whole process: loading included; nice 19, THREADS threads), and its relMSE against the reference.
# Prints a table of means over the seeds per spp with the gains
#   equal spp: relMSE_off / relMSE_on,    equal time: (relMSE_off · t_off) / (relMSE_on · t_on)
# (relMSE ∝ 1/time for an unbiased estimator), for relMSE and for the "body" relMSE without the worst 0.1 % of the
# pixels (rimu-pbrt-image-compare's second line: a room lit through a gap has rare fireflies that decide a single
# render's relMSE), and writes OUT/runs.tsv and a plot of relMSE against CPU time per
# scene (OUT/daylit_SCENE.png). Environment: SCENES, SPPS ("16 64 256"), SEEDS ("1 2 3"), REF_SPP (4096),
# RESOLUTION (160x90), THREADS (2).
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/daylit_points_bench}
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
scenes=${SCENES:-"daylit_room_open daylit_room_glazed door_ajar window_corridor day_room_downlights"}
spps=${SPPS:-"16 64 256"}; seeds=${SEEDS:-"1 2 3"}; ref_spp=${REF_SPP:-4096}; resolution=${RESOLUTION:-160x90}
threads=${THREADS:-2}
mkdir -p "$out"
cputime() { /usr/bin/time -f "%U %S" -o "$out/time" nice -n 19 "$@" >/dev/null 2>&1; awk '{printf "%.2f", $1 + $2}' "$out/time"; }
echo "# daylit_points_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# SPPS=\"$spps\" SEEDS=\"$seeds\" REF_SPP=$ref_spp RESOLUTION=$resolution THREADS=$threads"
printf "scene\tdaylit_points\tspp\tseed\tcpu_s\trelmse\trelmse_body\n" >"$out/runs.tsv"
for scene in $scenes; do
  factor=1000; [[ $scene == door_ajar ]] && factor=1e6
  python3 "$root/bench/scaled_scene.py" "$root/data/scenes/interiors/$scene.json" "$out" "$scene" "$factor"
  file=$out/${scene}_dir/$scene.json
  common=(--resolution "$resolution" --threads "$threads" -q --float)
  t=$(cputime "$rimu" "$file" -o "$out/$scene-ref.exr" --spp "$ref_spp" --seed 99 --daylit-points on "${common[@]}")
  echo "$scene: reference $ref_spp spp, $t CPU s" >&2
  for spp in $spps; do
    for seed in $seeds; do
      for mode in off on; do  # alternated, so that a change of load falls on both
        image=$out/$scene-$mode-$spp-$seed.exr
        t=$(cputime "$rimu" "$file" -o "$image" --spp "$spp" --seed "$seed" --daylit-points "$mode" "${common[@]}")
        c=$("$compare" relmse "$image" "$out/$scene-ref.exr")
        e=$(sed -n 's/^relmse=//p' <<<"$c"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$c")
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$scene" "$mode" "$spp" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
      done
    done
  done
  # Means over the seeds per configuration and spp, for the plot.
  awk -F'\t' -v s="$scene" 'NR > 1 && $1 == s {k = $2 "\t" $3; t[k] += $5; e[k] += $6; n[k]++}
    END {for (k in t) printf "%s\t%.4f\t%.6g\n", k, t[k] / n[k], e[k] / n[k]}' "$out/runs.tsv" | sort -k1,1 -k2,2n >"$out/$scene-means.tsv"
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/daylit_$scene.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE (mean of $(wc -w <<<"$seeds") seeds)'; set key top right; set title '$scene, $resolution, $spps spp'"
    echo "plot '$out/$scene-means.tsv' using (strcol(1) eq 'off' ? \$3 : 1/0):4 with linespoints title 'daylit points off', \\"
    echo "     '$out/$scene-means.tsv' using (strcol(1) eq 'on' ? \$3 : 1/0):4 with linespoints title 'daylit points on'"
  } | gnuplot
done
max_spp=${spps##* }
echo "| scene | spp | relMSE off (mean) | relMSE on (mean) | CPU s off | CPU s on | equal-spp gain | equal-time gain | body: equal-spp | body: equal-time |"
echo "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
for scene in $scenes; do
  for spp in $spps; do
    awk -F'\t' -v s="$scene" -v n="$spp" 'NR > 1 && $1 == s && $3 == n {t[$2] += $5; e[$2] += $6; b[$2] += $7; c[$2]++}
      END {eo = e["off"] / c["off"]; en = e["on"] / c["on"]; to = t["off"] / c["off"]; tn = t["on"] / c["on"];
           bo = b["off"] / c["off"]; bn = b["on"] / c["on"];
           printf "| %s | %s | %.4g | %.4g | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", s, n, eo, en, to, tn, eo / en,
                  (eo * to) / (en * tn), bo / bn, (bo * to) / (bn * tn)}' "$out/runs.tsv"
  done
done | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, runs.tsv and plots in $out"
