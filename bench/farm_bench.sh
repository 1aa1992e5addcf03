#!/usr/bin/env bash
# The cost of splitting a render into partials (docs/farm.md, "Benchmark"):
# 1. CPU time (user + system, every process) of one `rimu --spp 64` against 2, 4 and 8 `rimu --samples` partials
#    plus `rimu merge`, on the Cornell box at RESOLUTION (default 320x240), one thread per process so CPU time is
#    not blurred by idle workers.
# 2. Wall time, CPU time and peak memory (max RSS) of `rimu merge` of 8 partials of a spectral (47-bin) image at
#    MERGE_RESOLUTION (default 3840x2160; the partials take 8 x ~2 GB of disk in WORK_DIR).
# Usage: bench/farm_bench.sh BUILD_DIR [WORK_DIR]   (prints a Markdown table; not run by the tests)
#        RESOLUTION=640x480 MERGE_RESOLUTION=none bench/farm_bench.sh build   (part 1 only)
#        RESOLUTION=none bench/farm_bench.sh build                            (part 2 only)
set -euo pipefail
build=$(realpath "${1:?usage: bench/farm_bench.sh BUILD_DIR [WORK_DIR]}")
work=${2:-/tmp/rimu-farm-bench}
resolution=${RESOLUTION:-320x240}
merge_resolution=${MERGE_RESOLUTION:-3840x2160}
rimu=$build/bin/rimu
mkdir -p "$work"; cd "$work"
TIMEFORMAT='%U %S %R'
cpu() { # runs "$@", prints user+system seconds
  local t; t=$( { time "$@" >/dev/null 2>&1; } 2>&1 ); awk '{ printf "%.2f", $1 + $2 }' <<<"$t"
}
# runs "$@", prints "wall s, user+system s, peak RSS GB" (GNU time's %M is the largest resident set, in KB)
wall_cpu_memory() {
  /usr/bin/time -f '%e %U %S %M' -o time.txt "$@" >/dev/null 2>&1
  awk '{ printf "%.1f s wall, %.1f s CPU, peak memory %.2f GB", $1, $2 + $3, $4 / 1048576 }' time.txt
}

echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GB", $2/1048576}' /proc/meminfo); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ "$resolution" != none ]; then
common=(--resolution "$resolution" --spp 64 --threads 1 --float -q)
one=$(cpu "$rimu" "${common[@]}" --samples 0:64 -o one.exr)
echo
echo "| partials | CPU s (renders + merge) | merge CPU s | ratio to one process ($one s) |"
echo "|---|---|---|---|"
for n in 2 4 8; do
  total=0; parts=()
  for i in $(seq 0 $((n - 1))); do
    t=$(cpu "$rimu" "${common[@]}" --samples $((64 * i / n)):$((64 * (i + 1) / n)) -o part$n.$i.exr)
    total=$(awk -v a="$total" -v b="$t" 'BEGIN { print a + b }'); parts+=(part$n.$i.exr)
  done
  m=$(cpu "$rimu" merge "${parts[@]}" --final -o merged$n.exr)
  total=$(awk -v a="$total" -v b="$m" 'BEGIN { print a + b }')
  echo "| $n | $total | $m | $(awk -v a="$total" -v b="$one" 'BEGIN { printf "%.3f", a / b }') |"
done
fi

[ "$merge_resolution" = none ] && exit 0
echo
echo "merge of 8 partials at $merge_resolution, --film spectral:47 (1 spp each):"
parts=()
for i in $(seq 0 7); do
  "$rimu" --resolution "$merge_resolution" --film spectral:47 --spp 8 --samples $i:$((i + 1)) -q -o big.$i.exr 2>/dev/null
  parts+=(big.$i.exr)
done
echo "partial size: $(du -h big.0.exr | cut -f1) each"
echo "merge keeping the sums: $(wall_cpu_memory "$rimu" merge "${parts[@]}" -o big.merged.exr)"
rm -f big.merged.exr
echo "merge --final: $(wall_cpu_memory "$rimu" merge "${parts[@]}" --final -o big.final.exr)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
