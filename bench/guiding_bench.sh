#!/usr/bin/env bash
# guiding_bench.sh BUILD [SPP] [REFERENCE_SPP] [SEEDS] [RESOLUTION]
# Path guiding on and off (docs/benchmarks.md, "Path guiding"): the daylit room (open window and glazed,
# data/scenes/interiors/, their lights ×1000 so that the relMSE's absolute floor of 0.01 in
# rimu-pbrt-image-compare is negligible; the image only scales), the door-ajar room (lights ×10⁶: it is ~200×
# darker) and the Cornell box (the scene guiding cannot help, lights ×1000 likewise). For each scene: a reference of REFERENCE_SPP samples (guiding off, seed 99), then
# per seed one render with guiding off and one with it on, alternated, each timed in CPU seconds (user + system
# of the whole process, 2 threads; the machine is shared, so CPU time is less disturbed than wall time but not
# immune: the table says the load). Prints relMSE at SPP, CPU seconds, and the equal-time gain
#   (relMSE_off · t_off) / (relMSE_on · t_on)
# (relMSE ∝ 1/time for an unbiased estimator: the ratio of the relMSE the two would reach in the same time).
# Renders run at nice 19. BENCH_SCENES="door_ajar cornell" (say) runs only those.
set -eu
build=$1; spp=${2:-64}; ref_spp=${3:-2048}; seeds=${4:-"1 2 3"}; resolution=${5:-160x90}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-guiding.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
declare -A sources=([daylit_open]=$root/data/scenes/interiors/daylit_room_open.json
                    [daylit_glazed]=$root/data/scenes/interiors/daylit_room_glazed.json
                    [door_ajar]=$root/data/scenes/interiors/door_ajar.json
                    [cornell]=$root/data/scenes/cornell_box/scene.json)
for n in "${!sources[@]}"; do
  factor=1000; if [ "$n" = door_ajar ]; then factor=1e6; fi
  python3 "$root/bench/scaled_scene.py" "${sources[$n]}" "$scratch" "$n" "$factor"
done
cputime() { /usr/bin/time -f "%U %S" -o "$scratch/time" nice -n 19 "$@" >/dev/null; awk '{print $1 + $2}' "$scratch/time"; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); $spp spp at $resolution, reference $ref_spp spp"
printf "%-14s %-5s %10s %10s %8s %8s %6s\n" scene seed relmse_off relmse_on cpu_off cpu_on gain
for n in ${BENCH_SCENES:-daylit_open daylit_glazed door_ajar cornell}; do
  scene=$scratch/${n}_dir/$n.json
  nice -n 19 "$rimu" -q "$scene" -o "$scratch/ref_$n.exr" --spp "$ref_spp" --seed 99 --threads 2 \
    --resolution "$resolution" --guiding off
  for seed in $seeds; do
    t_off=$(cputime "$rimu" -q "$scene" -o "$scratch/off.exr" --spp "$spp" --seed "$seed" --threads 2 --resolution "$resolution" --guiding off)
    t_on=$(cputime "$rimu" -q "$scene" -o "$scratch/on.exr" --spp "$spp" --seed "$seed" --threads 2 --resolution "$resolution" --guiding on)
    e_off=$("$compare" relmse "$scratch/off.exr" "$scratch/ref_$n.exr" | sed -n 's/^relmse=//p')
    e_on=$("$compare" relmse "$scratch/on.exr" "$scratch/ref_$n.exr" | sed -n 's/^relmse=//p')
    gain=$(awk -v a="$e_off" -v b="$e_on" -v ta="$t_off" -v tb="$t_on" 'BEGIN { printf "%.2f", a * ta / (b * tb) }')
    printf "%-14s %-5s %10.4g %10.4g %8.2f %8.2f %6s\n" "$n" "$seed" "$e_off" "$e_on" "$t_off" "$t_on" "$gain"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
