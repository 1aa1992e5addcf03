#!/usr/bin/env bash
# denoise_bench.sh BUILD [SPPS] [REFERENCE_SPP] [RESOLUTION] [PNG_FOLDER]
# The denoiser against the noisy image (docs/benchmarks.md, "Denoising"): for each scene a reference of
# REFERENCE_SPP samples (seed 99), then for each spp in SPPS one render with every feature layer (`rimu --aov all`,
# seed 1, 2 threads) denoised by `rimu denoise`; prints relMSE against the reference (rimu-pbrt-image-compare relmse)
# of the noisy and the denoised image, their ratio, the mean shift (the denoised image's mean minus the noisy one's,
# over the reference's: linear sRGB, channels summed; the noisy image is unbiased, so this is what the denoiser adds
# or removes) and the denoiser's time per megapixel: wall-clock (its log line) and CPU (user + system, over both
# threads). A second reference of the same spp (seed 98) gives the "floor" row: the relMSE between two references,
# about twice what the reference's own noise adds to every figure.
# BASELINE=OTHER_BUILD also denoises every render with OTHER_BUILD's rimu (its own row, "base"), for a before/after
# comparison on the same renders.
# Scenes, lights ×1000 (bench/scaled_scene.py) so the relMSE floor of 0.01 is negligible: the Cornell box, the
# ColorChecker room under D65, the daylit room with an open window, and the textured scene. BENCH_SCENES="cornell"
# (say) runs only those. With PNG_FOLDER, writes per scene the 16-spp noisy, denoised and reference images side by
# side (<scene>_16spp.png: noisy | denoised, <scene>_reference.png: denoised | reference).
set -eu
build=$1; spps=${2:-"4 16 64"}; ref_spp=${3:-2048}; resolution=${4:-160x90}; pngs=${5:-}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-denoise.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
declare -A sources=([cornell]=$root/data/scenes/cornell_box/scene.json
                    [colorchecker_d65]=$root/data/scenes/colorchecker_room/colorchecker_d65.json
                    [daylit_open]=$root/data/scenes/interiors/daylit_room_open.json
                    [textured]=$root/data/scenes/textured/scene.json)
scenes=${BENCH_SCENES:-"cornell colorchecker_d65 daylit_open textured"}
denoisers="$rimu"; [ -n "${BASELINE:-}" ] && denoisers="$BASELINE/bin/rimu $rimu"
# The sum of an image's three channel means, as `compare` prints them (mean_a=R,G,B).
channel_sum() { "$compare" compare "$1" "$1" | sed -n 's/^mean_a=//p' | awk -F, '{ print $1 + $2 + $3 }'; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); spp ${spps} at $resolution, reference $ref_spp spp"
printf "%-17s %5s %5s %12s %12s %8s %8s %10s %10s\n" scene spp build relmse_noisy relmse_denoised gain shift "wall s/MP" "cpu s/MP"
for n in $scenes; do
  python3 "$root/bench/scaled_scene.py" "${sources[$n]}" "$scratch" "$n" 1000
  scene=$scratch/${n}_dir/$n.json
  "$rimu" -q "$scene" -o "$scratch/ref_$n.exr" --spp "$ref_spp" --seed 99 --threads 2 --resolution "$resolution"
  "$rimu" -q "$scene" -o "$scratch/ref2.exr" --spp "$ref_spp" --seed 98 --threads 2 --resolution "$resolution"
  floor=$("$compare" relmse "$scratch/ref2.exr" "$scratch/ref_$n.exr" | sed -n 's/^relmse=//p')
  printf "%-17s %5s %5s %12.4g\n" "$n" floor "" "$floor"
  megapixels=$(awk -v r="$resolution" 'BEGIN { split(r, d, "x"); print d[1] * d[2] / 1e6 }')
  reference_sum=$(channel_sum "$scratch/ref_$n.exr")
  for s in $spps; do
    "$rimu" -q "$scene" -o "$scratch/noisy.exr" --spp "$s" --seed 1 --threads 2 --resolution "$resolution" --aov all
    e_n=$("$compare" relmse "$scratch/noisy.exr" "$scratch/ref_$n.exr" | sed -n 's/^relmse=//p')
    noisy_sum=$(channel_sum "$scratch/noisy.exr")
    for denoiser in $denoisers; do
      label=new; [ "$denoiser" != "$rimu" ] && label=base
      TIMEFORMAT='%U %S'
      { time "$denoiser" denoise "$scratch/noisy.exr" -o "$scratch/denoised.exr" --threads 2 2>"$scratch/log"; } 2>"$scratch/cpu"
      per_mp=$(sed -n 's/.*(\([0-9.e+-]*\) s per megapixel).*/\1/p' "$scratch/log")
      cpu_mp=$(awk -v mp="$megapixels" '{ printf "%.3g", ($1 + $2) / mp }' "$scratch/cpu")
      e_d=$("$compare" relmse "$scratch/denoised.exr" "$scratch/ref_$n.exr" | sed -n 's/^relmse=//p')
      gain=$(awk -v a="$e_n" -v b="$e_d" 'BEGIN { printf "%.1f", a / b }')
      shift=$(awk -v d="$(channel_sum "$scratch/denoised.exr")" -v a="$noisy_sum" -v r="$reference_sum" \
                  'BEGIN { printf "%+.1f%%", 100 * (d - a) / r }')
      printf "%-17s %5s %5s %12.4g %12.4g %8s %8s %10.3g %10s\n" "$n" "$s" "$label" "$e_n" "$e_d" "$gain" "$shift" "$per_mp" "$cpu_mp"
    done
    if [ -n "$pngs" ] && [ "$s" = 16 ]; then
      mkdir -p "$pngs"
      "$compare" png "$scratch/noisy.exr" "$scratch/denoised.exr" "$pngs/denoise_${n}_16spp.png" >/dev/null
      "$compare" png "$scratch/denoised.exr" "$scratch/ref_$n.exr" "$pngs/denoise_${n}_reference.png" >/dev/null
    fi
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
