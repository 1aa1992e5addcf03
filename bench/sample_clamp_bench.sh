#!/usr/bin/env bash
# sample_clamp_bench.sh BUILD [OUT] — what the sample clamp (film "max_sample_value", `--max-sample-value`;
# docs/rendering.md, "Sample clamp") trades: variance for bias (docs/benchmarks.md, "Sample clamp").
# Scenes, lights scaled by bench/scaled_scene.py so that rimu-pbrt-image-compare's relMSE floor of 0.01 is negligible
# (the image only scales): the door-ajar room (×10⁶; light through an 11-cm gap, firefly-bound), the night room
# (×10⁵; 50 downlights, a glass and a copper ball) and the Cornell box (×1000; no fireflies: the clamp's bias alone).
# Per scene an unclamped reference of REF_SPP samples (seed 99); its mean luminance Y (from the linear sRGB means of
# `rimu-pbrt-image-compare compare`) sets the clamps, CLAMPS multiples of it ("none" = no clamp). Then per clamp,
# spp and seed one render, timed in CPU seconds (user + system of the whole process, nice 19, THREADS threads), and
# against the *unclamped* reference: relMSE (bias² and variance both), the body relMSE without the worst 0.1 % of the
# pixels, and the mean ratio image/reference (green, without the Cornell box's lamp; the clamp's darkening, plus
# noise). Prints per scene, clamp and spp the means over the seeds and the equal-time gain against no clamp,
# (relMSE_none · t_none) / (relMSE · t);
# writes OUT/runs.tsv, OUT/table.md and a plot of relMSE against CPU time per scene (OUT/clamp_SCENE.png).
# Environment: SCENES ("door_ajar night_room cornell"), CLAMPS ("none 1000 100 30 10"), SPPS ("16 64 256"), SEEDS
# ("1 2 3"), REF_SPP (4096), RESOLUTION (160x90), THREADS (2).
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/sample_clamp_bench}
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
scenes=${SCENES:-"door_ajar night_room cornell"}; clamps=${CLAMPS:-"none 1000 100 30 10"}
spps=${SPPS:-"16 64 256"}; seeds=${SEEDS:-"1 2 3"}; ref_spp=${REF_SPP:-4096}; resolution=${RESOLUTION:-160x90}
threads=${THREADS:-2}
declare -A sources=([door_ajar]=$root/data/scenes/interiors/door_ajar.json
                    [night_room]=$root/data/scenes/interiors/night_room_downlights.json
                    [cornell]=$root/data/scenes/cornell_box/scene.json)
declare -A factors=([door_ajar]=1e6 [night_room]=1e5 [cornell]=1000)
# The mean ratio leaves out what any clamp below its radiance must cut: the Cornell box's lamp, seen directly in the
# top fifth of the frame (the other rooms show no emitter).
width=${resolution%x*}; height=${resolution#*x}
declare -A ratio_crops=([cornell]="--crop 0 $((height / 5)) $width $height")
mkdir -p "$out"
# CPU seconds of a command; its log (rimu's summary names the clamped samples) in $out/log.
cputime() { /usr/bin/time -f "%U %S" -o "$out/time" nice -n 19 "$@" >/dev/null 2>"$out/log"; awk '{printf "%.2f", $1 + $2}' "$out/time"; }
echo "# sample_clamp_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# CLAMPS=\"$clamps\" SPPS=\"$spps\" SEEDS=\"$seeds\" REF_SPP=$ref_spp RESOLUTION=$resolution THREADS=$threads"
printf "scene\tclamp\tvalue\tspp\tseed\tcpu_s\trelmse\trelmse_body\tratio\tclamped\n" >"$out/runs.tsv"
for scene in $scenes; do
  python3 "$root/bench/scaled_scene.py" "${sources[$scene]}" "$out" "$scene" "${factors[$scene]}"
  file=$out/${scene}_dir/$scene.json
  common=(--resolution "$resolution" --threads "$threads" --float)
  ref=$out/$scene-ref.exr
  t=$(cputime "$rimu" "$file" -o "$ref" --spp "$ref_spp" --seed 99 "${common[@]}")
  # Mean luminance of the reference (linear sRGB → Y, Rec. 709 weights).
  y=$("$compare" compare "$ref" "$ref" | sed -n 's/^mean_a=//p' | awk -F, '{printf "%.6g", 0.2126 * $1 + 0.7152 * $2 + 0.0722 * $3}')
  echo "$scene: reference $ref_spp spp, $t CPU s, mean Y $y" >&2
  for spp in $spps; do
    for seed in $seeds; do
      for clamp in $clamps; do  # alternated, so that a change of load falls on every clamp
        image=$out/$scene-$clamp-$spp-$seed.exr
        option=(); value=inf
        if [[ $clamp != none ]]; then value=$(awk -v k="$clamp" -v y="$y" 'BEGIN {printf "%.6g", k * y}'); option=(--max-sample-value "$value"); fi
        t=$(cputime "$rimu" "$file" -o "$image" --spp "$spp" --seed "$seed" "${option[@]}" "${common[@]}")
        c=$("$compare" relmse "$image" "$ref")
        e=$(sed -n 's/^relmse=//p' <<<"$c"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$c")
        r=$("$compare" compare "$ref" "$image" ${ratio_crops[$scene]:-} | sed -n 's/^ratio_b_over_a=//p' | cut -d, -f2)
        n=$(sed -n 's/.*clamped samples: \([0-9]*\).*/\1/p' "$out/log"); n=${n:-0}
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$scene" "$clamp" "$value" "$spp" "$seed" "$t" "$e" "$b" "$r" "$n" >>"$out/runs.tsv"
      done
    done
  done
  awk -F'\t' -v s="$scene" 'NR > 1 && $1 == s {k = $2 "\t" $4; t[k] += $6; e[k] += $7; n[k]++}
    END {for (k in t) printf "%s\t%.4f\t%.6g\n", k, t[k] / n[k], e[k] / n[k]}' "$out/runs.tsv" | sort -k1,1 -k2,2n >"$out/$scene-means.tsv"
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/clamp_$scene.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE against the unclamped reference (mean of $(wc -w <<<"$seeds") seeds)'"
    echo "set key top right; set title '$scene, $resolution, $spps spp; clamp = k x mean Y'"
    printf "plot "
    first=1
    for clamp in $clamps; do
      [[ $first == 1 ]] || printf ", \\\\\n     "
      first=0
      title="k = $clamp"; [[ $clamp == none ]] && title="no clamp"
      printf "'%s' using (strcol(1) eq '%s' ? \$3 : 1/0):4 with linespoints title '%s'" "$out/$scene-means.tsv" "$clamp" "$title"
    done
    echo
  } | gnuplot
done
echo "| scene | clamp (× mean Y) | spp | relMSE (mean) | body relMSE | mean ratio to reference | CPU s | equal-time gain vs none |"
echo "|---|--:|--:|--:|--:|--:|--:|--:|"
for scene in $scenes; do
  for clamp in $clamps; do
    for spp in $spps; do
      awk -F'\t' -v s="$scene" -v k="$clamp" -v n="$spp" 'NR > 1 && $1 == s && $4 == n {t[$2] += $6; e[$2] += $7; b[$2] += $8; r[$2] += $9; c[$2]++}
        END {e0 = e["none"] / c["none"]; t0 = t["none"] / c["none"]; ek = e[k] / c[k]; tk = t[k] / c[k];
             printf "| %s | %s | %s | %.4g | %.4g | %.4f | %.2f | %.2f |\n", s, k, n, ek, b[k] / c[k], r[k] / c[k], tk,
                    (e0 * t0) / (ek * tk)}' "$out/runs.tsv"
    done
  done
done | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, runs.tsv and plots in $out"
