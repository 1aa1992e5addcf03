#!/usr/bin/env bash
# pic_bench.sh PIC_BUILD NOPIC_BUILD [PAIRS] [SPP]
# Does building the libraries position-independent (needed for the Python module, -DRIMU_PYTHON=ON) slow the
# renderer? Renders the embedded Cornell box with each build's `rimu`, alternating PIC and non-PIC runs so that
# changes in machine load hit both alike, and prints each run's user CPU seconds, the median of each and the
# median of the per-pair ratios (PIC / non-PIC). Single-threaded (--threads 1) so that CPU time is the work done.
#   cmake -S . -B build-nopic -DCMAKE_BUILD_TYPE=Release -DRIMU_PYTHON=OFF && cmake --build build-nopic --target rimu
#   bench/pic_bench.sh build build-nopic 7 16
set -eu
pic=$1/bin/rimu; nopic=$2/bin/rimu; pairs=${3:-7}; spp=${4:-16}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-pic.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
cpu_seconds() {  # user CPU seconds of one render
  /usr/bin/time -f %U "$1" -q --threads 1 --spp "$spp" --resolution 128x128 -o "$scratch/out.exr" 2>&1 >/dev/null | tail -1
}
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "command: $pic|$nopic -q --threads 1 --spp $spp --resolution 128x128 (embedded Cornell box), $pairs alternating pairs"
ratios=(); a=(); b=()
for i in $(seq "$pairs"); do
  if [ $((i % 2)) = 1 ]; then t_pic=$(cpu_seconds "$pic"); t_nopic=$(cpu_seconds "$nopic")
  else t_nopic=$(cpu_seconds "$nopic"); t_pic=$(cpu_seconds "$pic"); fi
  a+=("$t_pic"); b+=("$t_nopic"); ratios+=("$(echo "$t_pic / $t_nopic" | bc -l)")
  printf 'pair %d: PIC %s s, non-PIC %s s, ratio %.3f\n' "$i" "$t_pic" "$t_nopic" "${ratios[-1]}"
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }
printf 'median user CPU: PIC %s s, non-PIC %s s; median ratio %.3f (min %.3f, max %.3f)\n' "$(median "${a[@]}")" \
  "$(median "${b[@]}")" "$(median "${ratios[@]}")" "$(printf '%s\n' "${ratios[@]}" | sort -g | head -1)" \
  "$(printf '%s\n' "${ratios[@]}" | sort -g | tail -1)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
