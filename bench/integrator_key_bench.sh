#!/usr/bin/env bash
# Two settings of one integrator key against each other (what bench/caustics_bench.sh and
# bench/bidirectional_bench.sh run): the same scenes rendered with integrator.KEY = MODE_A and MODE_B at several spp,
# against a long MODE_B reference (seed 99); relMSE and CPU time per run, the equal-time gain of MODE_B, and a plot of
# relMSE against CPU time per scene.
#
#   KEY=caustics MODES="path_tracing light_tracing" LABELS="path tracing|light tracing" NAME=caustics \
#     bench/integrator_key_bench.sh BUILD OUT_DIR
#
# Environment (defaults in brackets): SCENES (under data/scenes, without .json, or a path ending in .json or .pbrt:
# a pbrt scene is converted by rimu-convert first), SPPS ["16 64"], REF_SPP [2048], SEEDS ["1 2 3"], RESOLUTION
# [160x120], THREADS [2], CROP [none: the whole image; "X0 Y0 X1 Y1": relMSE over those pixels only], FACTORS
# [none: "SCENE=F ..." light factors per scene name, e.g. "interiors-door_ajar=1000000"], REF_MODES [none: "SCENE=MODE
# ..." the reference's KEY per scene name instead of MODE_B, e.g. an unbiased method's where MODE_B is consistent only]. Lights ×1000 otherwise
# (bench/scaled_scene.py: relMSE's +0.01 floor then negligible). CPU seconds are user + system of the whole
# process under nice 19. Gain at equal time = (relMSE·CPU)_A / (relMSE·CPU)_B over the seeds' means at the same
# spp. Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and OUT_DIR/NAME_SCENE.png.
set -euo pipefail
build=$(realpath "$1"); out=$2
key=$KEY; read -r mode_a mode_b <<<"$MODES"; label_a=${LABELS%%|*}; label_b=${LABELS#*|}; bench=$NAME
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare; convert=$build/bin/rimu-convert
for tool in "$rimu" "$compare" "$convert"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare rimu-convert" >&2; exit 1; }
done
scenes=$SCENES
spps=${SPPS:-"16 64"}; ref_spp=${REF_SPP:-2048}; seeds=${SEEDS:-"1 2 3"}
resolution=${RESOLUTION:-160x120}; threads=${THREADS:-2}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"
# shellcheck source=bench/bench_common.sh
source "$root/bench/bench_common.sh"

echo "# ${bench}_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); SPPS=\"$spps\" REF_SPP=$ref_spp SEEDS=\"$seeds\" RESOLUTION=$resolution THREADS=$threads CROP=\"${CROP:-}\""
printf "scene\t$key\tspp\tseed\tcpu_s\trelmse\tbody\n" >"$out/runs.tsv"
for scene in $scenes; do
  if [[ $scene == *.json || $scene == *.pbrt ]]; then source=$scene; else source=$root/data/scenes/$scene.json; fi
  name=$(basename "$(dirname "$source")")-$(basename "${source%.*}"); work=$out/$name; rm -rf "$work"; mkdir -p "$work"
  if [[ $source == *.pbrt ]]; then
    "$convert" "$source" -o "$work/converted.json" 2>"$work/convert.log"
    source=$work/converted.json
  fi
  factor=1000
  for pair in ${FACTORS:-}; do [[ ${pair%%=*} == "$name" ]] && factor=${pair#*=}; done
  python3 "$root/bench/scaled_scene.py" "$source" "$work" scaled "$factor"
  ref_mode=$mode_b
  for pair in ${REF_MODES:-}; do [[ ${pair%%=*} == "$name" ]] && ref_mode=${pair#*=}; done
  for mode in $mode_a $mode_b $ref_mode; do with_integrator_key "$work/scaled_dir/scaled.json" "$work/scaled_dir/$mode.json" "$key" "$mode"; done
  t=$(render "$work/scaled_dir/$ref_mode.json" "$ref_spp" 99 "$work/ref.exr")
  echo "$name: reference $ref_mode, $ref_spp spp, $t CPU s" >&2
  for spp in $spps; do
    for mode in $mode_a $mode_b; do
      for seed in $seeds; do
        t=$(render "$work/scaled_dir/$mode.json" "$spp" "$seed" "$work/$mode-$spp-$seed.exr")
        r=$("$compare" relmse "$work/$mode-$spp-$seed.exr" "$work/ref.exr" ${CROP:+--crop $CROP})
        e=$(sed -n 's/^relmse=//p' <<<"$r"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$r")
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
        printf "%-34s %-13s %5s spp seed %-3s %7s CPU s relMSE %-10s body %s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >&2
      done
    done
  done
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/${bench}_$name.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE'; set key top right; set title '$name, $resolution, spp $spps: $key'"
    echo "plot '$out/runs.tsv' using (strcol(1) eq '$name' && strcol(2) eq '$mode_a' ? \$5 : 1/0):6 with points pt 7 title '$label_a', \\"
    echo "     '$out/runs.tsv' using (strcol(1) eq '$name' && strcol(2) eq '$mode_b' ? \$5 : 1/0):6 with points pt 5 title '$label_b'"
  } | gnuplot
done

awk -F'\t' -v A="$mode_a" -v B="$mode_b" -v LA="$label_a" -v LB="$label_b" 'NR > 1 {
  k = $1 SUBSEP $3 SUBSEP $2; n[k]++; t[k] += $5; e[k] += $6; b[k] += $7
  if (!(($1, $3) in seen)) { seen[$1, $3] = 1; order[++ns] = $1 SUBSEP $3 }
}
END {
  print "| scene | spp | relMSE " LA " | relMSE " LB " | body " LA " | body " LB " | CPU s " LA " | CPU s " LB " | equal-time gain (relMSE) | (body) |"
  print "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
  for (i = 1; i <= ns; i++) {
    split(order[i], p, SUBSEP); a = order[i] SUBSEP A; c = order[i] SUBSEP B
    gain = (e[a] * t[a]) / (e[c] * t[c]) * (n[c] * n[c]) / (n[a] * n[a])
    gain_b = (b[a] * t[a]) / (b[c] * t[c]) * (n[c] * n[c]) / (n[a] * n[a])
    printf "| %s | %s | %.4g | %.4g | %.4g | %.4g | %.2f | %.2f | %.2f | %.2f |\n", p[1], p[2], e[a] / n[a], e[c] / n[c], b[a] / n[a], b[c] / n[c], t[a] / n[a], t[c] / n[c], gain, gain_b
  }
}' "$out/runs.tsv" | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
