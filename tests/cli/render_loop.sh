#!/usr/bin/env bash
# render_loop.sh RIMU COMPARE WORKDIR: the lighter's loop from the command line (docs/rendering.md).
# 1. Progress to a file (not a terminal): a render log of lines with the percentage, samples/s, elapsed and left.
# 2. A time budget stopped by SIGTERM, then --resume: it continues to the rest of its budget, ends on a pass
#    boundary, and its image is bit-identical to a fixed-spp render of the samples it reached.
# 3. --preview: after the render it equals the --png of the same samples.
set -u
rimu=$1; compare=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
tiny=(--resolution 32x24 --threads 2 --seed 5)

# 1. The render log.
"$rimu" "${tiny[@]}" --spp 64 -o log.exr 2>log.txt || fail "render: $(cat log.txt)"
lines=$(grep -cE '^rendering: [0-9]+\.[0-9]%, [0-9.e+]+ samples/s, [0-9:]+ elapsed, [0-9:-]+ left$' log.txt)
[ "$lines" -ge 5 ] || fail "expected a log line per 10 % (at least 5), found $lines: $(cat log.txt)"
grep -qE '^rendering: 100\.0% in ' log.txt || fail "no final progress line: $(cat log.txt)"
if grep -q $'\r' log.txt; then fail "carriage returns in a log file"; fi
echo "render log: $lines progress lines"

# 2. A time budget, SIGTERM, resume.
"$rimu" "${tiny[@]}" --time 3s --checkpoint 1h -o timed.exr 2>timed.log &
pid=$!
caught() { local mask; mask=$(awk '/^SigCgt:/ {print $2}' /proc/$pid/status 2>/dev/null) || return 1
           [ -n "$mask" ] && (( (16#$mask >> 14) & 1 )); }
for _ in $(seq 1 600); do caught && break; kill -0 $pid 2>/dev/null || break; sleep 0.05; done
caught || fail "rimu never installed a SIGTERM handler: $(cat timed.log)"
sleep 1
kill -TERM $pid
wait $pid; code=$?
[ $code = 0 ] || fail "SIGTERM: exit code $code: $(cat timed.log)"
grep -q 'interrupted before the time budget of 3 s' timed.log || fail "not interrupted before the budget: $(cat timed.log)"
"$rimu" --resume timed.exr --threads 2 2>resumed.log || fail "resume: $(cat resumed.log)"
grep -q 'the time budget of 3 s was spent' resumed.log || fail "the resumed render did not end on its budget: $(cat resumed.log)"
spp=$(sed -nE 's/^rimu: .*: ([0-9]+) spp.*/\1/p' resumed.log | tail -1)
[ -n "$spp" ] || fail "no spp in the summary: $(cat resumed.log)"
echo "time budget: $spp spp after SIGTERM and resume"
"$rimu" --resume timed.exr 2>again.log || fail "a second resume: $(cat again.log)"
grep -q 'nothing to resume' again.log || fail "a render that spent its budget resumed again: $(cat again.log)"
"$rimu" "${tiny[@]}" --spp "$spp" --samples "0:$spp" -q -o fixed.exr || fail "fixed render"
"$compare" fixed.exr timed.exr --image-only || fail "the time-budget render differs from a fixed $spp-spp render"

# 3. The preview.
"$rimu" "${tiny[@]}" --spp 24 --preview preview.png --preview-interval 0.01s --png final.png -q -o preview.exr ||
  fail "preview render"
[ -f preview.png ] || fail "no preview written"
cmp preview.png final.png || fail "the preview differs from the final PNG of the same samples"
ls -a | grep -q 'rimu-incomplete' && fail "a temporary file was left behind: $(ls -a)"
echo "render loop: log, time budget with resume, preview: ok"
