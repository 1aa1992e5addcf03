#!/usr/bin/env bash
# The door-ajar room (issue #25's last target; docs/benchmarks.md, "Metropolis light transport"): the path tracer
# (the scene's own settings: daylit points, the light tree), bidirectional path tracing, and Metropolis light transport
# over each, at equal samples and compared at equal CPU time, against a reference averaged from several long
# path-traced renders of different seeds (the room's light arrives by rare paths, so one render of a few thousand
# samples is itself too noisy to measure a 5× gain against).
#
#   bench/door_ajar_bench.sh BUILD [OUT_DIR]
#
# Environment (defaults in brackets): SPPS ["64 256 1024"], SEEDS ["1 2 3"], REF_SPP [4096], REF_SEEDS ["99 98 91 92
# 93 94 95 96"] (the reference is their mean: 32,768 samples per pixel), RESOLUTION [160x90], THREADS [2],
# CONFIGS [path_tracing bidirectional metropolis metropolis_over_path_tracing]. Lights ×10⁶ (bench/scaled_scene.py:
# relMSE's +0.01 floor then negligible). CPU seconds are user + system of the whole process under nice 19. relMSE
# is rimu-pbrt-image-compare's, "body" the same without the worst 0.1 % of the pixels. The equal-time gain of a
# configuration over the path tracer at the same spp is (relMSE·CPU)_path tracer / (relMSE·CPU)_configuration over
# the seeds' means. Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and OUT_DIR/door_ajar.png (relMSE against CPU time).
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/door_ajar_bench}
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
spps=${SPPS:-"64 256 1024"}; seeds=${SEEDS:-"1 2 3"}; ref_spp=${REF_SPP:-4096}
ref_seeds=${REF_SEEDS:-"99 98 91 92 93 94 95 96"}; resolution=${RESOLUTION:-160x90}; threads=${THREADS:-2}
configs=${CONFIGS:-"path_tracing bidirectional metropolis metropolis_over_path_tracing"}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"
# shellcheck source=bench/bench_common.sh
source "$root/bench/bench_common.sh"

echo "# door_ajar_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); SPPS=\"$spps\" SEEDS=\"$seeds\" REF_SPP=$ref_spp REF_SEEDS=\"$ref_seeds\" RESOLUTION=$resolution THREADS=$threads"
python3 "$root/bench/scaled_scene.py" "$root/data/scenes/interiors/door_ajar.json" "$out" scaled 1000000
scenes=$out/scaled_dir
with_integrator_key "$scenes/scaled.json" "$scenes/path_tracing.json" method path_tracing
with_integrator_key "$scenes/scaled.json" "$scenes/bidirectional.json" method bidirectional
with_integrator_key "$scenes/scaled.json" "$scenes/metropolis.json" method metropolis
with_integrator_key "$scenes/metropolis.json" "$scenes/metropolis_over_path_tracing.json" metropolis '{"bidirectional": false}'

references=()
for seed in $ref_seeds; do
  image=$out/reference-$seed.exr
  [[ -f $image ]] || { t=$(render "$scenes/path_tracing.json" "$ref_spp" "$seed" "$image"); echo "reference seed $seed: $ref_spp spp, $t CPU s" >&2; }
  references+=("$image")
done
"$compare" mean "$out/reference.exr" "${references[@]}"

printf "config\tspp\tseed\tcpu_s\trelmse\tbody\n" >"$out/runs.tsv"
for spp in $spps; do
  for config in $configs; do
    for seed in $seeds; do
      image=$out/$config-$spp-$seed.exr
      t=$(render "$scenes/$config.json" "$spp" "$seed" "$image")
      r=$("$compare" relmse "$image" "$out/reference.exr")
      e=$(sed -n 's/^relmse=//p' <<<"$r"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$r")
      printf "%s\t%s\t%s\t%s\t%s\t%s\n" "$config" "$spp" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
      printf "%-30s %5s spp seed %-3s %7s CPU s relMSE %-10s body %s\n" "$config" "$spp" "$seed" "$t" "$e" "$b" >&2
    done
  done
done

{
  echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/door_ajar.png'"
  echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
  echo "set ylabel 'relMSE'; set key top right; set title 'door ajar, $resolution, spp $spps'"
  printf "plot "
  n=0
  for config in $configs; do
    n=$((n + 1)); [[ $n -gt 1 ]] && printf ", \\\\\n     "
    printf "'%s' using (strcol(1) eq '%s' ? \$4 : 1/0):5 with points pt %d title '%s'" "$out/runs.tsv" "$config" "$((n + 4))" "${config//_/ }"
  done
  echo
} | gnuplot

awk -F'\t' 'NR > 1 {
  k = $2 SUBSEP $1; n[k]++; t[k] += $4; e[k] += $5; b[k] += $6
  if (!($1 in seen_c)) { seen_c[$1] = 1; configs[++nc] = $1 }
  if (!($2 in seen_s)) { seen_s[$2] = 1; spps[++ns] = $2 }
}
END {
  print "| spp | configuration | relMSE (mean of seeds) | body | CPU s | equal-time gain over the path tracer (relMSE) | (body) |"
  print "|--:|---|--:|--:|--:|--:|--:|"
  for (i = 1; i <= ns; i++) {
    base = spps[i] SUBSEP "path_tracing"
    for (j = 1; j <= nc; j++) {
      k = spps[i] SUBSEP configs[j]
      if (!(k in n)) continue
      gain = (base in n) ? (e[base] / n[base] * t[base] / n[base]) / (e[k] / n[k] * t[k] / n[k]) : 0
      gain_b = (base in n) ? (b[base] / n[base] * t[base] / n[base]) / (b[k] / n[k] * t[k] / n[k]) : 0
      printf "| %s | %s | %.4g | %.4g | %.2f | %.2f | %.2f |\n", spps[i], configs[j], e[k] / n[k], b[k] / n[k], t[k] / n[k], gain, gain_b
    }
  }
}' "$out/runs.tsv" | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
