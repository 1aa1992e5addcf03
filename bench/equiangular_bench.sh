#!/usr/bin/env bash
# Equiangular sampling in homogeneous media (docs/media.md, "Equiangular sampling"; docs/benchmarks.md,
# "Equiangular sampling towards lights with extent"): the same scenes rendered with integrator.equiangular "off",
# "points" (the default: lights at a point) and "all" (every light not at infinity) at several spp, against a long
# reference ("all", seed 99); relMSE and CPU time per run, the equal-time gain of each setting over "off", and a plot
# of relMSE against CPU time per scene.
#
#   bench/equiangular_bench.sh BUILD [OUT_DIR]
#
# Environment (defaults in brackets): SCENES [media/stage_haze hazy_cornell hazy_night_room media/chromatic_slab]
# (under data/scenes, without .json, or a path ending in .json; `hazy_cornell` is data/scenes/cornell_box with a
# scene-wide haze of σ_a 0.1, σ_s 0.6 /m added here, `hazy_night_room` interiors/night_room_downlights (50 IES
# downlights) with σ_a 0.01, σ_s 0.08 /m, g 0.6, the stage's haze), SPPS ["16 64"], REF_SPP [1024], SEEDS ["1 2 3"], RESOLUTION [160x90],
# THREADS [2], MODES ["off points all"] (the first is the baseline of the gains). Lights ×1000 (bench/scaled_scene.py: relMSE's +0.01 floor then negligible). CPU seconds are user +
# system of the whole process under nice 19 (parsing and BVH included). Gain at equal time = (relMSE·CPU)_base /
# (relMSE·CPU)_mode over the seeds' means at the same spp. Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and
# OUT_DIR/equiangular_SCENE.png.
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/equiangular_bench}
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
scenes=${SCENES:-"media/stage_haze hazy_cornell hazy_night_room media/chromatic_slab"}
spps=${SPPS:-"16 64"}; ref_spp=${REF_SPP:-1024}; seeds=${SEEDS:-"1 2 3"}
resolution=${RESOLUTION:-160x90}; threads=${THREADS:-2}; modes=${MODES:-"off points all"}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"
# shellcheck source=bench/bench_common.sh
source "$root/bench/bench_common.sh"

# edit SOURCE.json OUT.json EQUIANGULAR [SIGMA_A SIGMA_S G]: the scene with integrator.equiangular set (and a
# scene-wide haze of these coefficients, per metre, added)
edit() {
  python3 - "$@" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene.setdefault("integrator", {})["equiangular"] = sys.argv[3]
if len(sys.argv) > 4:
    sigma_a, sigma_s, g = (float(v) for v in sys.argv[4:7])
    scene.setdefault("media", {})["haze"] = {"type": "homogeneous", "sigma_a": sigma_a, "sigma_s": sigma_s, "g": g,
                                            "contains_camera": True}
json.dump(scene, open(sys.argv[2], "w"))
PY
}

echo "# equiangular_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); SPPS=\"$spps\" REF_SPP=$ref_spp SEEDS=\"$seeds\" MODES=\"$modes\" RESOLUTION=$resolution THREADS=$threads"
printf "scene\tequiangular\tspp\tseed\tcpu_s\trelmse\tbody\n" >"$out/runs.tsv"
for scene in $scenes; do
  haze=()
  if [[ $scene == hazy_cornell ]]; then source=$root/data/scenes/cornell_box/scene.json; haze=(0.1 0.6 0)
  elif [[ $scene == hazy_night_room ]]; then
    source=$root/data/scenes/interiors/night_room_downlights.json; haze=(0.01 0.08 0.6)
  elif [[ $scene == *.json ]]; then source=$scene
  else source=$root/data/scenes/$scene.json; fi
  name=${scene##*/}; name=${name%.json}; work=$out/$name; rm -rf "$work"; mkdir -p "$work"
  python3 "$root/bench/scaled_scene.py" "$source" "$work" scaled 1000
  for mode in $modes all; do edit "$work/scaled_dir/scaled.json" "$work/scaled_dir/$mode.json" "$mode" "${haze[@]}"; done
  t=$(render "$work/scaled_dir/all.json" "$ref_spp" 99 "$work/ref.exr")
  echo "$name: reference $ref_spp spp, $t CPU s" >&2
  for spp in $spps; do
    for mode in $modes; do
      for seed in $seeds; do
        t=$(render "$work/scaled_dir/$mode.json" "$spp" "$seed" "$work/$mode-$spp-$seed.exr")
        r=$("$compare" relmse "$work/$mode-$spp-$seed.exr" "$work/ref.exr")
        e=$(sed -n 's/^relmse=//p' <<<"$r"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$r")
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
        printf "%-16s %-6s %5s spp seed %-3s %7s CPU s relMSE %-10s body %s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >&2
      done
    done
  done
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/equiangular_$name.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE'; set key top right; set title '$name, $resolution, spp $spps: equiangular sampling'"
    plot="plot"; pt=7
    for mode in $modes; do
      plot+=" '$out/runs.tsv' using (strcol(1) eq '$name' && strcol(2) eq '$mode' ? \$5 : 1/0):6 with points pt $pt title '$mode',"
      pt=$((pt - 2))
    done
    echo "${plot%,}"
  } | gnuplot
done

# The table: per scene, spp and setting, means over the seeds, and the equal-time gain over the first setting.
awk -F'\t' -v base="${modes%% *}" 'NR > 1 {
  k = $1 SUBSEP $3 SUBSEP $2; n[k]++; t[k] += $5; e[k] += $6; b[k] += $7
  if (!(($1, $3) in seen)) { seen[$1, $3] = 1; order[++ns] = $1 SUBSEP $3 }
  if (!($2 in mseen)) { mseen[$2] = 1; ms[++nm] = $2 }
}
END {
  print "| scene | spp | equiangular | relMSE | body relMSE | CPU s | equal-time gain over " base " (relMSE) | (body) |"
  print "|---|--:|---|--:|--:|--:|--:|--:|"
  for (i = 1; i <= ns; i++) {
    split(order[i], p, SUBSEP); k0 = order[i] SUBSEP base
    for (j = 1; j <= nm; j++) {
      k = order[i] SUBSEP ms[j]
      gain = (e[k0] / n[k0]) * (t[k0] / n[k0]) / ((e[k] / n[k]) * (t[k] / n[k]))
      gain_b = (b[k0] / n[k0]) * (t[k0] / n[k0]) / ((b[k] / n[k]) * (t[k] / n[k]))
      printf "| %s | %s | %s | %.4g | %.4g | %.2f | %.2f | %.2f |\n", p[1], p[2], ms[j], e[k] / n[k], b[k] / n[k], t[k] / n[k], gain, gain_b
    }
  }
}' "$out/runs.tsv" | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
