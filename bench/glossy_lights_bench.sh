#!/usr/bin/env bash
# Resampled light choice at glossy vertices (docs/transport.md, "Glossy vertices and many lights";
# docs/benchmarks.md, "Glossy vertices: resampled light choice"): the same scenes rendered with
# integrator.glossy_light_candidates = 1 (the light sampler's own choice) and more, at equal spp, against a long
# reference; relMSE and CPU time per setting, and the equal-time gain over one candidate.
#
#   bench/glossy_lights_bench.sh BUILD [OUT_DIR]
#
# Environment (defaults in brackets): SCENES [interiors/night_room_downlights interiors/day_room_downlights
# light_sampling/spot_3m_floor examples/metal_sphere_environment] (under data/scenes, without .json; or a path
# ending in .json, e.g. a bench/lamp_subset.py copy of a room with fewer lamps),
# CANDIDATES ["1 2 4 8 16"], SPP [64], REF_SPP [1024], SEEDS ["1 2 3 4 5 6"], RESOLUTION [160x90], THREADS [2].
# Each scene is copied with its lights ×1000 (bench/scaled_scene.py: relMSE's +0.01 floor then negligible); the
# reference uses 8 candidates, seed 99. relMSE is rimu-pbrt-image-compare's; "body" is its relMSE without the worst
# 0.1 % of pixels (the fireflies the method is for are in those). CPU seconds are user + system of the whole
# process under nice 19 (parsing and BVH included). Gain at equal time = (relMSE·CPU)₁ / (relMSE·CPU)_M over the
# seeds' means. Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and OUT_DIR/glossy_SCENE.png (relMSE against CPU time).
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/glossy_lights_bench}
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
scenes=${SCENES:-"interiors/night_room_downlights interiors/day_room_downlights light_sampling/spot_3m_floor examples/metal_sphere_environment"}
candidates=${CANDIDATES:-"1 2 4 8 16"}; spp=${SPP:-64}; ref_spp=${REF_SPP:-1024}; seeds=${SEEDS:-"1 2 3 4 5 6"}
resolution=${RESOLUTION:-160x90}; threads=${THREADS:-2}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"
# shellcheck source=bench/bench_common.sh
source "$root/bench/bench_common.sh"

echo "# glossy_lights_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); SPP=$spp REF_SPP=$ref_spp SEEDS=\"$seeds\" CANDIDATES=\"$candidates\" RESOLUTION=$resolution THREADS=$threads"
printf "scene\tcandidates\tseed\tcpu_s\trelmse\tbody\n" >"$out/runs.tsv"
for scene in $scenes; do
  source=$root/data/scenes/$scene.json
  [[ $scene == *.json ]] && source=$scene && scene=${scene%.json}
  name=${scene##*/}; work=$out/$name; rm -rf "$work"; mkdir -p "$work"
  python3 "$root/bench/scaled_scene.py" "$source" "$work" scaled 1000
  with_integrator_key "$work/scaled_dir/scaled.json" "$work/scaled_dir/ref.json" glossy_light_candidates 8
  t=$(render "$work/scaled_dir/ref.json" "$ref_spp" 99 "$work/ref.exr")
  echo "$name: reference $ref_spp spp, $t CPU s" >&2
  for m in $candidates; do
    with_integrator_key "$work/scaled_dir/scaled.json" "$work/scaled_dir/m$m.json" glossy_light_candidates "$m"
    for seed in $seeds; do
      t=$(render "$work/scaled_dir/m$m.json" "$spp" "$seed" "$work/m$m-$seed.exr")
      r=$("$compare" relmse "$work/m$m-$seed.exr" "$work/ref.exr")
      e=$(sed -n 's/^relmse=//p' <<<"$r"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$r")
      printf "%s\t%s\t%s\t%s\t%s\t%s\n" "$name" "$m" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
      printf "%-28s M=%-3s seed %-3s %6s CPU s relMSE %-10s body %s\n" "$name" "$m" "$seed" "$t" "$e" "$b" >&2
    done
  done
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/glossy_$name.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE at $spp spp'; set key top right; set title '$name, $resolution, $spp spp: glossy_light_candidates'"
    plot="plot"
    for m in $candidates; do
      plot+=" '$out/runs.tsv' using (strcol(1) eq '$name' && \$2 == $m ? \$4 : 1/0):5 with points pt 7 title 'M = $m',"
    done
    echo "${plot%,}"
  } | gnuplot
done

# The table: per scene and M, means over the seeds, and the equal-time gain over M = 1.
awk -F'\t' 'NR > 1 {
  k = $1 SUBSEP $2; n[k]++; t[k] += $4; e[k] += $5; b[k] += $6
  if (!($1 in seen)) { seen[$1] = 1; order[++ns] = $1 }
  if (!(($1, $2) in mseen)) { mseen[$1, $2] = 1; ms[$1, ++nm[$1]] = $2 }
  if (e_max[k] == "" || $5 > e_max[k]) e_max[k] = $5
  if (e_min[k] == "" || $5 < e_min[k]) e_min[k] = $5
}
END {
  print "| scene | candidates | relMSE mean (min–max over seeds) | body relMSE mean | CPU s mean | equal-time gain over 1 (relMSE) | (body) |"
  print "|---|--:|--:|--:|--:|--:|--:|"
  for (i = 1; i <= ns; i++) {
    s = order[i]; k1 = s SUBSEP ms[s, 1]
    for (j = 1; j <= nm[s]; j++) {
      k = s SUBSEP ms[s, j]
      gain = (e[k1] / n[k1]) * (t[k1] / n[k1]) / ((e[k] / n[k]) * (t[k] / n[k]))
      gain_b = (b[k1] / n[k1]) * (t[k1] / n[k1]) / ((b[k] / n[k]) * (t[k] / n[k]))
      printf "| %s | %s | %.3g (%.3g–%.3g) | %.3g | %.2f | %.2f | %.2f |\n", s, ms[s, j], e[k] / n[k], e_min[k], e_max[k], b[k] / n[k], t[k] / n[k], gain, gain_b
    }
  }
}' "$out/runs.tsv" | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
