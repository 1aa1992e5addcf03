#!/usr/bin/env bash
# Rimu against pbrt-v4 on the same .pbrt files: load time, peak memory, time to a given spp, time to equal
# relMSE, and the image difference. Prints markdown tables (the "Rimu and pbrt-v4 side by side" section of
# docs/benchmarks.md was made with it) and leaves every image and log in $OUT.
#
#   bench/pbrt_side_by_side.sh PBRT_BINARY [SCENE.pbrt ...]
#
# PBRT_BINARY is a CPU build of pbrt-v4 (never part of this repository), or "-" for Rimu's figures alone. Without
# scene arguments: every .pbrt file in tests/data/pbrt/ that is a whole scene (has WorldBegin) and is not a bad_*
# error case, then those of bench/pbrt_scenes/.
# Environment (defaults in brackets): BUILD [build] (Rimu's build folder, with bin/rimu and
# bin/rimu-pbrt-image-compare), OUT [/tmp/pbrt_side_by_side], SPP [64], REF_SPP [1024], THREADS [2],
# RESOLUTION [the scene's; WIDTHxHEIGHT rewrites the copied scene's Film], SPACE [srgb-linear], MESH_N [0: none;
# N adds a generated binary-PLY scene of 2·N² triangles, bench/pbrt_scenes/make_mesh_scene.py, e.g. 708 ≈ 1 M].
#
# Per scene and renderer: two renders at SPP (seeds 1 and 2) and one reference at REF_SPP (seed 7), each under
# /usr/bin/time -v. Reported: wall and CPU (user + sys) seconds and peak RSS of the SPP render with seed 1; its
# render time (the renderer's own, from the EXR header) and load = wall − render (parsing, BVH, start-up and
# writing the image); relMSE of each SPP image against its own renderer's reference; the time each needs to reach
# the relMSE pbrt reaches at SPP, taking relMSE ∝ 1/spp (render time × relMSE / target); and, between the two
# references (and between the two SPP renders of each renderer as a control of the test itself), per-channel mean
# ratio Rimu/pbrt and the 8×8-block paired differences in units of their standard error; and $OUT/SCENE/
# pbrt_vs_rimu.png, the two references side by side (pbrt left) at one exposure.
#
# Time to equal error in CPU time (the table after the timing table): REPEATS [2] renders at SPP per renderer (seeds
# 1 … REPEATS) and REPEATS load probes at 1 spp (seeds 101 …), each under /usr/bin/time. CPU = user + sys, which a
# shared machine disturbs far less than wall time. Per renderer: the median CPU of the SPP renders; load CPU =
# the median of the probes less one sample's share, cpu(1) − (cpu(SPP) − cpu(1)) / (SPP − 1) (parsing, BVH,
# start-up, writing); render CPU = cpu(SPP) − load, and CPU per sample = render CPU / (SPP · pixels); relMSE =
# the mean over the REPEATS renders against the renderer's reference, over 1 + SPP/REF_SPP (the reference's own
# noise, the same factor for both renderers). Ratios Rimu/pbrt: relMSE at equal spp, CPU per sample, and their
# product, the render CPU each needs to the same relMSE (relMSE ∝ 1/spp); and the same with each renderer's load
# CPU added to the render CPU pbrt spends at SPP and Rimu at the spp it needs for pbrt's relMSE. TABULATE_ONLY=1
# renders nothing and prints the tables again from the images and logs already in $OUT (same settings).
set -euo pipefail

if [[ $# -lt 1 ]]; then
  echo "usage: $0 PBRT_BINARY [SCENE.pbrt ...]" >&2
  exit 1
fi
PBRT=$1
shift
if [[ $PBRT == - ]]; then
  renderers=(rimu)
else
  PBRT=$(realpath "$PBRT")
  [[ -x "$PBRT" ]] || { echo "$0: $PBRT is not an executable" >&2; exit 1; }
  renderers=(pbrt rimu)
fi
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(realpath "${BUILD:-$ROOT/build}")
RIMU="$BUILD/bin/rimu"
COMPARE="$BUILD/bin/rimu-pbrt-image-compare"
for tool in "$RIMU" "$COMPARE"; do
  [[ -x "$tool" ]] || { echo "$0: $tool missing: cmake --build $BUILD --target rimu rimu-pbrt-image-compare" >&2; exit 1; }
done
OUT=${OUT:-/tmp/pbrt_side_by_side}
SPP=${SPP:-64}
REF_SPP=${REF_SPP:-1024}
THREADS=${THREADS:-2}
SPACE=${SPACE:-srgb-linear}
RESOLUTION=${RESOLUTION:-}
MESH_N=${MESH_N:-0}
REPEATS=${REPEATS:-2}
TABULATE_ONLY=${TABULATE_ONLY:-0}
[[ $REPEATS -ge 2 ]] || { echo "$0: REPEATS must be 2 or more (the seed control compares seeds 1 and 2)" >&2; exit 1; }
mkdir -p "$OUT"

# fire_nanovdb.pbrt reads a generated NanoVDB file (not committed): made here once, with NanoVDB's headers.
if [[ ! -f "$ROOT/bench/pbrt_scenes/fire.nvdb" ]]; then
  g++ -std=c++17 -O1 "$ROOT/bench/pbrt_scenes/make_fire_nvdb.cpp" -o "$OUT/make_fire_nvdb" &&
    "$OUT/make_fire_nvdb" "$ROOT/bench/pbrt_scenes/fire.nvdb"
fi

scenes=("$@")
if [[ ${#scenes[@]} -eq 0 ]]; then
  for f in "$ROOT"/tests/data/pbrt/*.pbrt "$ROOT"/bench/pbrt_scenes/*.pbrt; do
    [[ -f "$f" && $(basename "$f") != bad_* ]] && grep -q '^[[:space:]]*WorldBegin' "$f" && scenes+=("$f")
  done
fi
if [[ $MESH_N -gt 0 ]]; then
  mkdir -p "$OUT/generated_mesh"
  scenes+=("$(python3 "$ROOT/bench/pbrt_scenes/make_mesh_scene.py" "$OUT/generated_mesh" "$MESH_N")")
fi

# key=value from the compare tool's output
value() { sed -n "s/^$1=//p" <<<"$2"; }
# /usr/bin/time -v fields
wall_s() { awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + t[i]; print s}' "$1"; }
cpu_s() { awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} END {printf "%.2f", u + s}' "$1"; }
# median of the numbers given as arguments
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# min–max of the numbers given as arguments
spread() { printf '%s\n' "$@" | sort -g | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%s–%s", lo, hi}'; }
rss_mib() { awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$1"; }

# run_renderer NAME SCENE SPP SEED OUTPUT.exr: one render under /usr/bin/time -v, its log next to the image.
run_renderer() {
  local name=$1 scene=$2 spp=$3 seed=$4 out=$5
  local log=${out%.exr}.log
  if [[ $name == rimu ]]; then
    local res=()
    [[ -n "$RESOLUTION" ]] && res=(--resolution "$RESOLUTION")
    /usr/bin/time -v -o "$log.time" "$RIMU" "$scene" -o "$out" --float -q --spp "$spp" --seed "$seed" \
      --threads "$THREADS" "${res[@]}" >"$log" 2>&1 || { echo "rimu failed on $scene: see $log" >&2; return 1; }
  else
    /usr/bin/time -v -o "$log.time" "$PBRT" --quiet --spp "$spp" --seed "$seed" --nthreads "$THREADS" \
      --outfile "$out" "$scene" >"$log" 2>&1 || { echo "pbrt failed on $scene: see $log" >&2; return 1; }
  fi
}

# compare_row A B: one row of the image table for $work/A.exr against $work/B.exr
compare_row() {
  local c
  c=$("$COMPARE" compare "$work/$1.exr" "$work/$2.exr" --space "$SPACE")
  image_rows+=("| $name | $2 / $1 | $(value mean_a "$c") | $(value mean_b "$c") | $(value ratio_b_over_a "$c") | $(value block_tests "$c") | $(value blocks_beyond_3sigma "$c") | $(value blocks_beyond_4.5sigma "$c") | $(value rms_z "$c") | $(value worst_z "$c") at $(value worst_at "$c") |")
}

echo "# pbrt_side_by_side: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)), load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# rimu: $("$RIMU" --version 2>/dev/null | head -1); pbrt: $PBRT; SPP=$SPP REF_SPP=$REF_SPP THREADS=$THREADS RESOLUTION=${RESOLUTION:-scene} SPACE=$SPACE"
timing_rows=()
cpu_rows=()
image_rows=()
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .pbrt)
  work="$OUT/$name"
  if [[ $TABULATE_ONLY != 0 ]]; then
    [[ -d "$work" ]] || { echo "$0: TABULATE_ONLY: $work missing" >&2; exit 1; }
  else
    rm -rf "$work"
    mkdir -p "$work/scene"
    # Both renderers read one copy of the scene's folder (its Includes and meshes), with RESOLUTION applied to it.
    cp -r "$(dirname "$scene")"/. "$work/scene/"
    file="$work/scene/$(basename "$scene")"
    # pbrt-v4 writes half floats unless told otherwise (Film "savefp16" defaults to true); Rimu writes 32-bit floats
    # here (--float). Half rounding is the same in every pixel of a flat region (a uniform sky), where it shows as a
    # difference of many standard errors, so pbrt writes 32-bit floats too. Rimu lists the parameter as ignored.
    grep -q savefp16 "$file" || sed -i -E 's/^([[:space:]]*Film[[:space:]]+"[a-z]+")/\1 "bool savefp16" false/' "$file"
    if [[ -n "$RESOLUTION" ]]; then
      # Lines that are comments are left alone (published scenes keep old resolutions commented out); a Film without
      # a resolution of its own (pbrt's default is 1280×720) is given RESOLUTION, so that pbrt renders it too.
      sed -i -E "/^[[:space:]]*#/! {s/(\"integer xresolution\"[[:space:]]*\[?[[:space:]]*)[0-9]+/\1${RESOLUTION%x*}/; s/(\"integer yresolution\"[[:space:]]*\[?[[:space:]]*)[0-9]+/\1${RESOLUTION#*x}/}" "$file"
      grep -q '^[^#]*"integer xresolution"' "$file" ||
        sed -i -E "s/^([[:space:]]*Film[[:space:]]+\"[a-z]+\")/\1 \"integer xresolution\" ${RESOLUTION%x*} \"integer yresolution\" ${RESOLUTION#*x}/" "$file"
    fi
    for r in "${renderers[@]}"; do
      for ((k = 1; k <= REPEATS; ++k)); do
        run_renderer $r "$file" "$SPP" $k "$work/$r-s$k.exr"
        run_renderer $r "$file" 1 $((100 + k)) "$work/$r-load$k.exr"
      done
      run_renderer $r "$file" "$REF_SPP" 7 "$work/$r-ref.exr"
    done
  fi
  # CPU-time figures (header comment): median CPU of the SPP renders and of the 1-spp probes, mean relMSE.
  declare -A load_cpu render_cpu per_sample rel
  pixels=$(value pixels "$("$COMPARE" info "$work/${renderers[0]}-ref.exr")")
  for r in "${renderers[@]}"; do
    cpus=() probes=() errs=()
    for ((k = 1; k <= REPEATS; ++k)); do
      cpus+=("$(cpu_s "$work/$r-s$k.log.time")")
      probes+=("$(cpu_s "$work/$r-load$k.log.time")")
      errs+=("$(value relmse "$("$COMPARE" relmse "$work/$r-s$k.exr" "$work/$r-ref.exr" --space "$SPACE")")")
    done
    c=$(median "${cpus[@]}")
    p=$(median "${probes[@]}")
    load_cpu[$r]=$(awk -v c="$c" -v p="$p" -v n="$SPP" 'BEGIN {l = p - (c - p) / (n - 1); printf "%.3f", (l > 0 ? l : 0)}')
    render_cpu[$r]=$(awk -v c="$c" -v l="${load_cpu[$r]}" 'BEGIN {printf "%.3f", c - l}')
    per_sample[$r]=$(awk -v t="${render_cpu[$r]}" -v n="$SPP" -v px="$pixels" 'BEGIN {printf "%.4g", 1e9 * t / (n * px)}')
    rel[$r]=$(printf '%s\n' "${errs[@]}" | awk -v n="$SPP" -v m="$REF_SPP" '{s += $1} END {printf "%.4g", s / NR / (1 + n / m)}')
    cpu_rows+=("| $name | $r | ${load_cpu[$r]} | ${render_cpu[$r]} | $c ($(spread "${cpus[@]}")) | ${per_sample[$r]} | ${rel[$r]} ($(spread "${errs[@]}")) | | | | |")
  done
  if [[ ${#renderers[@]} -eq 2 ]]; then
    cpu_rows+=("| $name | Rimu/pbrt | | | | | | $(awk -v a="${rel[rimu]}" -v b="${rel[pbrt]}" 'BEGIN {printf "%.3g", a / b}') | $(awk -v a="${per_sample[rimu]}" -v b="${per_sample[pbrt]}" 'BEGIN {printf "%.3g", a / b}') | $(awk -v ea="${rel[rimu]}" -v eb="${rel[pbrt]}" -v ta="${render_cpu[rimu]}" -v tb="${render_cpu[pbrt]}" 'BEGIN {printf "%.3g", ta * ea / (tb * eb)}') | $(awk -v ea="${rel[rimu]}" -v eb="${rel[pbrt]}" -v ta="${render_cpu[rimu]}" -v tb="${render_cpu[pbrt]}" -v la="${load_cpu[rimu]}" -v lb="${load_cpu[pbrt]}" 'BEGIN {printf "%.3g", (la + ta * ea / eb) / (lb + tb)}') |")
  fi
  unset load_cpu render_cpu per_sample rel
  declare -A render relmse
  for r in "${renderers[@]}"; do
    t="$work/$r-s1.log.time"
    render[$r]=$(value render_time_s "$("$COMPARE" info "$work/$r-s1.exr")")
    relmse[$r]=$(value relmse "$("$COMPARE" relmse "$work/$r-s1.exr" "$work/$r-ref.exr" --space "$SPACE")")
    wall=$(wall_s "$t")
    load=$(awk -v w="$wall" -v r="${render[$r]}" 'BEGIN {printf "%.3f", w - r}')
    ignored=""
    [[ $r == rimu ]] && ignored=$(grep -c '^ignored: ' "$work/rimu-s1.log" || true)
    timing_rows+=("| $name | $r | $load | ${render[$r]} | $wall | $(cpu_s "$t") | $(rss_mib "$t") | ${relmse[$r]} | ${ignored:-–} |")
  done
  if [[ ${#renderers[@]} -eq 1 ]]; then
    compare_row rimu-s1 rimu-s2
    unset render relmse
    continue
  fi
  # Time to the relMSE pbrt reaches at SPP (relMSE ∝ 1/spp): pbrt's is its render time; Rimu's is scaled.
  rimu_equal=$(awk -v t="${render[rimu]}" -v e="${relmse[rimu]}" -v target="${relmse[pbrt]}" 'BEGIN {printf "%.3g", t * e / target}')
  ratio=$(awk -v a="$rimu_equal" -v b="${render[pbrt]}" 'BEGIN {printf "%.2f", a / b}')
  timing_rows+=("| $name | time to pbrt's relMSE | | pbrt ${render[pbrt]} s, Rimu $rimu_equal s (Rimu/pbrt $ratio) | | | | | |")
  for pair in "pbrt-ref rimu-ref" "pbrt-s1 pbrt-s2" "rimu-s1 rimu-s2" "pbrt-s1 rimu-s1"; do
    compare_row $pair
  done
  "$COMPARE" png "$work/pbrt-ref.exr" "$work/rimu-ref.exr" "$work/pbrt_vs_rimu.png" --space "$SPACE"
  unset render relmse
done

echo
echo "Timing (the SPP render with seed 1; load = wall − the renderer's own render time; relMSE against the renderer's own REF_SPP reference; ignored = lines Rimu lists as ignored):"
echo
echo "| scene | renderer | load s | render s | wall s | CPU s | peak RSS MiB | relMSE at $SPP spp | ignored |"
echo "|---|---|--:|--:|--:|--:|--:|--:|--:|"
printf '%s\n' "${timing_rows[@]}"
echo
echo "CPU time (user + sys; $REPEATS renders at $SPP spp and $REPEATS 1-spp load probes per renderer; medians, min–max in brackets; relMSE over 1 + SPP/REF_SPP; per sample = render CPU / (spp × pixels); ratios Rimu/pbrt, below 1 = Rimu better):"
echo
echo "| scene | renderer | load CPU s | render CPU s | CPU s at $SPP spp | CPU ns / sample | relMSE at $SPP spp | relMSE ratio at equal spp | CPU / sample ratio | render CPU to equal error | with load |"
echo "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
printf '%s\n' "${cpu_rows[@]}"
echo
echo "Images in $SPACE (Rimu's XYZ converted with its xyz_to_rgb matrix); b / a: ratio = mean(b)/mean(a) per channel; blocks: 8×8 tiles × 3 channels, paired mean difference / standard error:"
echo
echo "| scene | b / a | mean a (R,G,B) | mean b (R,G,B) | ratio b/a | tests | >3σ | >4.5σ | rms z | worst z |"
echo "|---|---|---|---|---|--:|--:|--:|--:|---|"
printf '%s\n' "${image_rows[@]}"
