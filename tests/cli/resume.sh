#!/usr/bin/env bash
# resume.sh RIMU COMPARE WORKDIR: checkpoints and --resume end to end.
# 1. kill -9 a render after its second checkpoint, resume it: the image (and its sums) equals an uninterrupted one's.
# 2. SIGTERM (what Slurm sends before SIGKILL) makes a render write a checkpoint and exit 0; resuming it gives the
#    same image again.
set -u
rimu=$1; compare=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
opts=(--resolution 128x96 --spp 256 --float --threads 1 --seed 3)
fail() { echo "FAIL: $*"; exit 1; }

"$rimu" "${opts[@]}" -q --samples 0:256 -o full.exr 2>full.log || fail "reference render: $(cat full.log)"

# 1. kill -9 after the second checkpoint.
"$rimu" "${opts[@]}" --checkpoint 0.3s -o killed.exr 2>killed.log &
pid=$!
for _ in $(seq 1 600); do
  [ "$(grep -c 'rimu: checkpoint' killed.log)" -ge 2 ] && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.05
done
[ "$(grep -c 'rimu: checkpoint' killed.log)" -ge 2 ] || fail "no second checkpoint before the render ended: $(cat killed.log)"
kill -9 $pid; wait $pid 2>/dev/null
grep 'rimu: checkpoint' killed.log | tail -1
[ -f killed.exr ] || fail "no checkpoint file after kill -9"
"$rimu" --resume killed.exr -q --threads 2 2>resume.log || fail "resume: $(cat resume.log)"
cat resume.log
"$compare" full.exr killed.exr || fail "the resumed render differs from the uninterrupted one"

# 2. SIGTERM: a checkpoint and exit 0 (the interval is long: only the signal writes).
"$rimu" "${opts[@]}" --checkpoint 1h -o term.exr 2>term.log &
pid=$!
# Signal only once rimu has installed its SIGTERM handler (bit 15 of SigCgt in /proc): on a loaded machine start-up
# can take longer than any fixed sleep, and a signal before the handler exists kills the process with status 143.
caught() { local mask; mask=$(awk '/^SigCgt:/ {print $2}' /proc/$pid/status 2>/dev/null) || return 1
           [ -n "$mask" ] && (( (16#$mask >> 14) & 1 )); }
for _ in $(seq 1 600); do caught && break; kill -0 $pid 2>/dev/null || break; sleep 0.05; done
caught || fail "SIGTERM: rimu never installed a SIGTERM handler (or ended early): $(cat term.log)"
sleep 0.5
kill -TERM $pid
wait $pid; code=$?
[ $code = 0 ] || fail "SIGTERM: exit code $code, expected 0: $(cat term.log)"
grep -q 'interrupted' term.log || fail "SIGTERM: the render finished before the signal (machine too fast?): $(cat term.log)"
grep 'spp' term.log | tail -1
"$rimu" --resume term.exr -q 2>resume2.log || fail "resume after SIGTERM: $(cat resume2.log)"
"$compare" full.exr term.exr || fail "the render resumed after SIGTERM differs from the uninterrupted one"
echo "resume: bit-identical after kill -9 and after SIGTERM"
