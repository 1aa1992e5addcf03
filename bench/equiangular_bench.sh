#!/usr/bin/env bash
# Equiangular sampling in homogeneous media (docs/media.md, "Equiangular sampling"; docs/benchmarks.md,
# "Equiangular sampling towards lights with extent"): the same scenes rendered with integrator.equiangular off and on
# at several spp, against a long reference (equiangular on, seed 99); relMSE and CPU time per run, the equal-time
# gain of turning it on, and a plot of relMSE against CPU time per scene.
#
#   bench/equiangular_bench.sh BUILD [OUT_DIR]
#
# Environment (defaults in brackets): SCENES [media/stage_haze hazy_cornell media/chromatic_slab] (under
# data/scenes, without .json, or a path ending in .json; `hazy_cornell` is data/scenes/cornell_box with a scene-wide
# haze of σ_a 0.1, σ_s 0.6 /m added here), SPPS ["16 64"], REF_SPP [1024], SEEDS ["1 2 3"], RESOLUTION [160x90],
# THREADS [2]. Lights ×1000 (bench/scaled_scene.py: relMSE's +0.01 floor then negligible). CPU seconds are user +
# system of the whole process under nice 19 (parsing and BVH included). Gain at equal time = (relMSE·CPU)_off /
# (relMSE·CPU)_on over the seeds' means at the same spp. Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and
# OUT_DIR/equiangular_SCENE.png.
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/equiangular_bench}
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
scenes=${SCENES:-"media/stage_haze hazy_cornell media/chromatic_slab"}
spps=${SPPS:-"16 64"}; ref_spp=${REF_SPP:-1024}; seeds=${SEEDS:-"1 2 3"}
resolution=${RESOLUTION:-160x90}; threads=${THREADS:-2}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"

# edit SOURCE.json OUT.json EQUIANGULAR [HAZE]: the scene with integrator.equiangular set (and a haze added)
edit() {
  python3 - "$@" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene.setdefault("integrator", {})["equiangular"] = sys.argv[3] == "on"
if len(sys.argv) > 4:
    scene.setdefault("media", {})["haze"] = {"type": "homogeneous", "sigma_a": 0.1, "sigma_s": 0.6,
                                            "contains_camera": True}
json.dump(scene, open(sys.argv[2], "w"))
PY
}
# render FILE SPP SEED OUT.exr: prints CPU seconds
render() {
  /usr/bin/time -f "%U %S" -o "$4.time" nice -n 19 "$rimu" -q "$1" -o "$4" --float --spp "$2" --seed "$3" \
    --threads "$threads" --resolution "$resolution" >"$4.log" 2>&1
  awk '{s = $1 + $2} END {printf "%.2f", s}' "$4.time"
}

echo "# equiangular_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); SPPS=\"$spps\" REF_SPP=$ref_spp SEEDS=\"$seeds\" RESOLUTION=$resolution THREADS=$threads"
printf "scene\tequiangular\tspp\tseed\tcpu_s\trelmse\tbody\n" >"$out/runs.tsv"
for scene in $scenes; do
  haze=()
  if [[ $scene == hazy_cornell ]]; then source=$root/data/scenes/cornell_box/scene.json; haze=(haze)
  elif [[ $scene == *.json ]]; then source=$scene
  else source=$root/data/scenes/$scene.json; fi
  name=${scene##*/}; name=${name%.json}; work=$out/$name; rm -rf "$work"; mkdir -p "$work"
  python3 "$root/bench/scaled_scene.py" "$source" "$work" scaled 1000
  for mode in on off; do edit "$work/scaled_dir/scaled.json" "$work/scaled_dir/$mode.json" "$mode" "${haze[@]}"; done
  t=$(render "$work/scaled_dir/on.json" "$ref_spp" 99 "$work/ref.exr")
  echo "$name: reference $ref_spp spp, $t CPU s" >&2
  for spp in $spps; do
    for mode in off on; do
      for seed in $seeds; do
        t=$(render "$work/scaled_dir/$mode.json" "$spp" "$seed" "$work/$mode-$spp-$seed.exr")
        r=$("$compare" relmse "$work/$mode-$spp-$seed.exr" "$work/ref.exr")
        e=$(sed -n 's/^relmse=//p' <<<"$r"); b=$(sed -n 's/^relmse_without_worst_0.1pct=//p' <<<"$r")
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >>"$out/runs.tsv"
        printf "%-16s %-3s %5s spp seed %-3s %7s CPU s relMSE %-10s body %s\n" "$name" "$mode" "$spp" "$seed" "$t" "$e" "$b" >&2
      done
    done
  done
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/equiangular_$name.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, $threads threads)'"
    echo "set ylabel 'relMSE'; set key top right; set title '$name, $resolution, spp $spps: equiangular sampling'"
    echo "plot '$out/runs.tsv' using (strcol(1) eq '$name' && strcol(2) eq 'off' ? \$5 : 1/0):6 with points pt 7 title 'off', \\"
    echo "     '$out/runs.tsv' using (strcol(1) eq '$name' && strcol(2) eq 'on' ? \$5 : 1/0):6 with points pt 5 title 'on'"
  } | gnuplot
done

# The table: per scene and spp, means over the seeds, and the equal-time gain of equiangular sampling.
awk -F'\t' 'NR > 1 {
  k = $1 SUBSEP $3 SUBSEP $2; n[k]++; t[k] += $5; e[k] += $6; b[k] += $7
  if (!(($1, $3) in seen)) { seen[$1, $3] = 1; order[++ns] = $1 SUBSEP $3 }
}
END {
  print "| scene | spp | relMSE off | relMSE on | body off | body on | CPU s off | CPU s on | equal-time gain (relMSE) | (body) |"
  print "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
  for (i = 1; i <= ns; i++) {
    split(order[i], p, SUBSEP); off = order[i] SUBSEP "off"; on = order[i] SUBSEP "on"
    gain = (e[off] * t[off]) / (e[on] * t[on]) * (n[on] * n[on]) / (n[off] * n[off])
    gain_b = (b[off] * t[off]) / (b[on] * t[on]) * (n[on] * n[on]) / (n[off] * n[off])
    printf "| %s | %s | %.4g | %.4g | %.4g | %.4g | %.2f | %.2f | %.2f | %.2f |\n", p[1], p[2], e[off] / n[off], e[on] / n[on], b[off] / n[off], b[on] / n[on], t[off] / n[off], t[on] / n[on], gain, gain_b
  }
}' "$out/runs.tsv" | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
