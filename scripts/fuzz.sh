#!/usr/bin/env bash
# Builds the libFuzzer targets (build-fuzz/: clang, ASan + UBSan, see docs/fuzzing.md) and fuzzes each reader for a
# bounded time. Fails (exit 1) if any target finds a crash, a sanitizer report, an unexpected exception, a timeout
# or an out-of-memory; the input is written to fuzz/crashes/<target>/.
#   scripts/fuzz.sh [seconds-per-target] [target...]     targets (all by default): scene pbrt csv ies ply obj rvol image merge
# Inputs that add coverage accumulate in build-fuzz/corpus/<target>/ (reused by the next run; not committed).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(scene pbrt csv ies ply obj rvol image merge); fi

scripts/install-deps.sh --test
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# -O1 and line tables only: the usual fuzzing build (fast to compile, readable stack traces). No NDEBUG, so
# Rimu's assertions are checked too.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DRIMU_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" "${launcher[@]}" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

# The longest input per target: large enough for every seed and for what the readers parse, small enough that one
# input runs in milliseconds under the sanitizers.
declare -A max_len=([scene]=8192 [pbrt]=8192 [csv]=4096 [ies]=4096 [ply]=4096 [obj]=4096 [rvol]=1024 [image]=4096
                   [merge]=8192)

mkdir -p build-fuzz/logs
# One target: its log and exit status in build-fuzz/logs/<target>.{log,status}.
fuzz_target() {
  local t=$1 log="build-fuzz/logs/$1.log" status=0
  local dict=()
  mkdir -p "build-fuzz/corpus/$t" "fuzz/crashes/$t"
  if [ -f "fuzz/$t.dict" ]; then dict=(-dict="fuzz/$t.dict"); fi
  # One worker per target: -timeout is per input; -rss_limit_mb also bounds any one malloc. Leaks are checked
  # afterwards (below), not here: LeakSanitizer's exit check after a fuzzing loop has itself crashed on CI
  # ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error", the pbrt target, twice in ~30 runs;
  # the input it blamed was the empty one, which runs clean), and a tool's crash is not a finding about Rimu.
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
    "build-fuzz/bin/fuzz_$t" -max_total_time="$seconds" -max_len="${max_len[$t]}" -timeout=20 -rss_limit_mb=2048 \
    -detect_leaks=0 -print_final_stats=1 -artifact_prefix="fuzz/crashes/$t/" "${dict[@]}" \
    "build-fuzz/corpus/$t" "fuzz/corpus/$t" "fuzz/regressions/$t" >"$log" 2>&1 || status=$?
  # Leaks: every input of the corpus (the new ones included) once more, with libFuzzer's per-input leak check and
  # LeakSanitizer's at exit. A leak fails as before; only LeakSanitizer's own fatal error is retried, once.
  if [ "$status" -eq 0 ]; then
    local leaks="build-fuzz/logs/$t.leaks.log" attempt
    for attempt in 1 2; do
      status=0
      "build-fuzz/bin/fuzz_$t" -runs=0 -max_len="${max_len[$t]}" -timeout=20 -rss_limit_mb=2048 -detect_leaks=1 \
        -artifact_prefix="fuzz/crashes/$t/" "build-fuzz/corpus/$t" "fuzz/corpus/$t" "fuzz/regressions/$t" \
        >"$leaks" 2>&1 || status=$?
      if [ "$status" -ne 0 ] && grep -q "LeakSanitizer has encountered a fatal error" "$leaks" &&
         ! grep -q "ERROR: LeakSanitizer: detected memory leaks" "$leaks"; then
        echo "fuzz: $t: LeakSanitizer's own fatal error in the leak replay (attempt $attempt)" >>"$log"
        continue
      fi
      break
    done
    if [ "$status" -ne 0 ]; then
      echo "---- the leak replay (build-fuzz/logs/$t.leaks.log):" >>"$log"
      grep -v '^#[0-9]' "$leaks" | tail -30 >>"$log"
    fi
  fi
  echo "$status" >"build-fuzz/logs/$t.status"
}
# As many targets at once as there are cores (RIMU_FUZZ_JOBS overrides): on CI's two cores the nine targets take
# half the wall time they took one after another.
jobs=${RIMU_FUZZ_JOBS:-$(nproc)}
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  rm -f "build-fuzz/logs/$t.status"
  fuzz_target "$t" &
done
wait

failed=()
printf '%-6s %10s %8s %8s %8s  %s\n' target execs exec/s cov ft result
for t in "${targets[@]}"; do
  log="build-fuzz/logs/$t.log"
  status=$(cat "build-fuzz/logs/$t.status" 2>/dev/null || echo 125)
  # The statistics of the log (absent if the target died early: then "-").
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2 || true)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2 || true)
  if [ "$status" -eq 0 ]; then result=ok; else result="FAILED (exit $status; log $log; inputs in fuzz/crashes/$t/)"; failed+=("$t"); fi
  printf '%-6s %10s %8s %8s %8s  %s\n' "$t" "${execs:--}" "${rate:--}" "${cov:--}" "${ft:--}" "$result"
done

if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: ${failed[*]} crashed. The end of each log:" >&2
  for t in "${failed[@]}"; do
    echo "---- build-fuzz/logs/$t.log" >&2
    grep -v '^#[0-9]' "build-fuzz/logs/$t.log" | tail -40 >&2
  done
  echo "fuzz: reproduce with build-fuzz/bin/fuzz_<target> <crash file> (docs/fuzzing.md)" >&2
  exit 1
fi
echo "fuzz: every target ran ${seconds} s without a crash"
