#!/usr/bin/env bash
# Interiors against pbrt-v4 (docs/benchmarks.md, "Interiors against pbrt-v4"): the four rooms of
# data/scenes/interiors/ in pbrt-v4's format (daylit room with an open window, the same glazed, the night room with
# 50 downlights, the door-ajar room; written by data/scenes/interiors/write_pbrt_versions.py), rendered from the
# same .pbrt file by Rimu (guiding off/on × light sampler power/bvh) and, when its binary is given, by pbrt-v4.
#
#   bench/interior_bench.sh BUILD [PBRT_BINARY|-] [OUT_DIR]
#
# Environment (defaults in brackets): RESOLUTION [160x90], SPPS ["4 16 64"] (the budgets), REF_SPP [1024],
# THREADS [2], SCENES [daylit_room_open daylit_room_glazed night_room_downlights door_ajar].
# Per scene: a reference per renderer (Rimu: guiding on, power sampler, seed 99; pbrt: seed 99; each renderer is
# measured against its own reference, as bench/pbrt_side_by_side.sh does, because the two differ by their spectral
# upsampling, the sun's disc and — in the glazed room — by what reaches the room, see the docs), then one render per
# configuration and budget. Time is CPU seconds (user + system of the whole process, parsing and BVH included) under
# nice 19: the machine is shared, and the load is printed. relMSE is rimu-pbrt-image-compare's (linear sRGB,
# (x − r)²/(r² + 0.01)); it includes the reference's own error, about relMSE_ref = relMSE(64 spp)·64/REF_SPP.
# "time to pbrt's 64-spp error" takes relMSE ∝ 1/time from each configuration's largest budget:
#   t = t_max · relMSE(t_max) / relMSE_pbrt(64 spp).
# Writes OUT_DIR/table.md (the markdown table), OUT_DIR/runs.tsv and OUT_DIR/interior_SCENE.png (relMSE against CPU
# time, gnuplot), and keeps every image.
set -euo pipefail
build=$(realpath "$1"); pbrt=${2:--}; out=${3:-/tmp/interior_bench}
root=$(cd "$(dirname "$0")/.." && pwd)
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
for tool in "$rimu" "$compare"; do
  [[ -x $tool ]] || { echo "$0: $tool missing: cmake --build $build --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
if [[ $pbrt != - ]]; then pbrt=$(realpath "$pbrt"); [[ -x $pbrt ]] || { echo "$0: $pbrt is not executable" >&2; exit 1; }; fi
resolution=${RESOLUTION:-160x90}; spps=${SPPS:-"4 16 64"}; ref_spp=${REF_SPP:-1024}; threads=${THREADS:-2}
scenes=${SCENES:-"daylit_room_open daylit_room_glazed night_room_downlights door_ajar"}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"
configs=("rimu guiding off, power" "rimu guiding off, bvh" "rimu guiding on, power" "rimu guiding on, bvh")
[[ $pbrt != - ]] && configs+=("pbrt-v4")

# cpu_of LOG: user + system seconds of a /usr/bin/time -f "%U %S" log
cpu_of() { awk '{s = $1 + $2} END {printf "%.2f", s}' "$1"; }

# render CONFIG SCENE_FILE SPP SEED OUT.exr: one render; prints its CPU seconds
render() {
  local config=$1 file=$2 spp=$3 seed=$4 image=$5
  if [[ $config == pbrt-v4 ]]; then
    /usr/bin/time -f "%U %S" -o "$image.time" nice -n 19 "$pbrt" --quiet --spp "$spp" --seed "$seed" \
      --nthreads "$threads" --outfile "$image" "$file" >"$image.log" 2>&1
  else
    local guiding sampler
    guiding=$(sed -E 's/.*guiding (on|off).*/\1/' <<<"$config"); sampler=${config##*, }
    /usr/bin/time -f "%U %S" -o "$image.time" nice -n 19 "$rimu" -q "$file" -o "$image" --float --spp "$spp" \
      --seed "$seed" --threads "$threads" --guiding "$guiding" --light-sampler "$sampler" >"$image.log" 2>&1
  fi
  cpu_of "$image.time"
}

echo "# interior_bench: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# RESOLUTION=$resolution SPPS=\"$spps\" REF_SPP=$ref_spp THREADS=$threads pbrt=$pbrt"
printf "scene\tconfig\tspp\tcpu_s\trelmse\n" >"$out/runs.tsv"
table=()
for scene in $scenes; do
  work=$out/$scene; rm -rf "$work"; mkdir -p "$work/scene"
  cp "$root/data/scenes/interiors/$scene.pbrt" "$root/data/scenes/interiors/downlight_equal_area.pfm" "$work/scene/"
  file=$work/scene/$scene.pbrt
  sed -i -E "s/(\"integer xresolution\" )[0-9]+/\1${resolution%x*}/; s/(\"integer yresolution\" )[0-9]+/\1${resolution#*x}/" "$file"
  t_ref=$(render "rimu guiding on, power" "$file" "$ref_spp" 99 "$work/ref-rimu.exr")
  echo "$scene: Rimu reference $ref_spp spp, $t_ref CPU s" >&2
  if [[ $pbrt != - ]]; then
    t_ref=$(render pbrt-v4 "$file" "$ref_spp" 99 "$work/ref-pbrt.exr")
    echo "$scene: pbrt reference $ref_spp spp, $t_ref CPU s" >&2
    # The two references' means (linear sRGB), to list the differences between the renderers.
    c=$("$compare" compare "$work/ref-pbrt.exr" "$work/ref-rimu.exr")
    echo "$scene: mean Rimu/pbrt (R, G, B) $(sed -n 's/^ratio_b_over_a=//p' <<<"$c"), blocks beyond 4.5σ $(sed -n 's/^blocks_beyond_4.5sigma=//p' <<<"$c") of $(sed -n 's/^block_tests=//p' <<<"$c")"
    "$compare" png "$work/ref-pbrt.exr" "$work/ref-rimu.exr" "$work/pbrt_vs_rimu.png" >/dev/null
  fi
  declare -A last_t last_e
  for config in "${configs[@]}"; do
    for spp in $spps; do
      tag=$(tr ' ,' '_' <<<"$config" | tr -s _)-$spp
      t=$(render "$config" "$file" "$spp" 1 "$work/$tag.exr")
      ref=$work/ref-rimu.exr; [[ $config == pbrt-v4 ]] && ref=$work/ref-pbrt.exr
      e=$("$compare" relmse "$work/$tag.exr" "$ref" | sed -n 's/^relmse=//p')
      printf "%s\t%s\t%s\t%s\t%s\n" "$scene" "$config" "$spp" "$t" "$e" >>"$out/runs.tsv"
      printf "%-24s %-24s %5s spp %8s CPU s relMSE %s\n" "$scene" "$config" "$spp" "$t" "$e" >&2
      last_t[$config]=$t; last_e[$config]=$e
    done
  done
  max_spp=${spps##* }
  for config in "${configs[@]}"; do
    to_pbrt=–; ratio=–
    if [[ $pbrt != - ]]; then
      to_pbrt=$(awk -v t="${last_t[$config]}" -v e="${last_e[$config]}" -v target="${last_e[pbrt-v4]}" 'BEGIN {printf "%.3g", t * e / target}')
      ratio=$(awk -v a="$to_pbrt" -v b="${last_t[pbrt-v4]}" 'BEGIN {printf "%.2f", a / b}')
    fi
    row="| $scene | $config |"
    for spp in $spps; do
      row+=" $(awk -F'\t' -v s="$scene" -v c="$config" -v n="$spp" '$1 == s && $2 == c && $3 == n {printf "%.3g (%s s)", $5, $4}' "$out/runs.tsv") |"
    done
    table+=("$row $to_pbrt | $ratio |")
  done
  unset last_t last_e
  # relMSE against CPU time, one line per configuration
  {
    echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/interior_$scene.png'"
    echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, 2 threads)'; set ylabel 'relMSE'; set key bottom left; set title '$scene, $resolution'"
    plot="plot"
    for config in "${configs[@]}"; do
      plot+=" '$out/runs.tsv' using (strcol(1) eq '$scene' && strcol(2) eq '$config' ? \$4 : 1/0):5 with linespoints title '$config',"
    done
    echo "${plot%,}"
  } | gnuplot
done

header="| scene | configuration |"; rule="|---|---|"
for spp in $spps; do header+=" relMSE at $spp spp (CPU s) |"; rule+="--:|"; done
{
  echo "$header CPU s to pbrt's ${spps##* }-spp relMSE | ÷ pbrt's time |"
  echo "$rule--:|--:|"
  printf '%s\n' "${table[@]}"
} | tee "$out/table.md"
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg); images, logs and plots in $out"
