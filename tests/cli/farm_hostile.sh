#!/usr/bin/env bash
# farm_hostile.sh RIMU_FARM SCENE WORKDIR: rimu-farm refuses (exit 1, naming the option) every value that would reach
# a job script holding a control character — a newline there would end an #SBATCH line and start a command — and
# writes no script, so nothing can run; it refuses an --spp beyond the renderer's limit and a --frames range too long
# to submit, at once. NUL cannot be tested: no argument vector can hold it (execve ends every argument at the first).
set -u
farm=$1; scene=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
nl=$'\n'; cr=$'\r'; tab=$'\t'; esc=$'\e'
inject="${nl}touch INJECTED${nl}#"   # relative: a file name cannot hold a slash

# expect_refused LABEL PATTERN -- rimu-farm arguments...: exit 1, the message matches, no script, nothing ran.
expect_refused() {
  local label=$1 pattern=$2; shift 3
  local output code
  output=$(timeout 60 "$farm" "$@" 2>&1); code=$?
  [ "$code" = 1 ] || fail "$label: exit $code (expected 1): $output"
  grep -Eq -- "$pattern" <<<"$output" || fail "$label: the message does not match /$pattern/: $output"
  [ -z "$(find . -name '*.sbatch')" ] || fail "$label: a job script was written: $(find . -name '*.sbatch')"
  [ ! -e INJECTED ] || fail "$label: the injected command ran"
}

cp "$scene" "card${inject}.json"
expect_refused "scene name with a newline" "^rimu-farm: scene: .*control character '\\\\n'" -- \
  submit "card${inject}.json" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/a"
cp "$scene" "card${cr}x.json"
expect_refused "scene name with a carriage return" "scene: .*control character '\\\\r'" -- \
  submit "card${cr}x.json" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/b"
mkdir "sub${tab}dir" && cp "$scene" "sub${tab}dir/card.json"
expect_refused "a folder of the scene with a tab" "scene: .*control character '\\\\t'" -- \
  submit "sub${tab}dir/card.json" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/c"
expect_refused "--out with a newline" "--out: .*control character '\\\\n'" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/out${inject}"
expect_refused "--partition with a newline" "--partition: .*control character '\\\\n'" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/d" --partition "debug${inject}"
expect_refused "--time with a carriage return and a newline" "--time: .*control character '\\\\r'" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/e" --time "1:00:00${cr}${inject}"
expect_refused "--checkpoint with an escape" "--checkpoint: .*control character '\\\\x1b'" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/f" --checkpoint "10m${esc}"
expect_refused "a rimu option after -- with a newline" "rimu option after --: .*control character" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/g" -- --film "xyz${inject}"
expect_refused "--rimu with a newline" "--rimu: .*control character" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/h" --rimu "/bin/true${inject}"

# Limits: refused before any frame is hashed (the old code took minutes hashing 10^6 frames, then wrote tasks that
# all fail).
expect_refused "--spp beyond the renderer's limit" "--spp 99999999999: expected 1-16777216" -- \
  submit "$scene" --spp 99999999999 --tasks 2 --no-submit --out "$dir/i"
start=$(date +%s)
expect_refused "a million frames" "--frames 1-1000000: 1000000 frames; at most 10000" -- \
  submit "$scene" --spp 8 --tasks 2 --frames 1-1000000 --no-submit --out "$dir/j"
[ $(( $(date +%s) - start )) -lt 20 ] || fail "refusing a million frames took $(( $(date +%s) - start )) s"

# Quotes, spaces, $(...) and backquotes are not control characters: accepted, quoted in the body, nothing runs.
odd="it's \$(touch INJECTED) \`touch INJECTED\`; x"
cp "$scene" "$odd.json"
"$farm" submit "$odd.json" --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/ok" >/dev/null 2>&1 \
  || fail "a scene name with quotes and \$(...): refused"
bash -n ok/render.sbatch && bash -n ok/merge.sbatch || fail "the scripts do not parse"
[ "$(grep -c '^#SBATCH --array=0-1$' ok/render.sbatch)" = 1 ] || fail "render.sbatch lost its --array line"
[ ! -e INJECTED ] || fail "writing the scripts ran a command"
echo "rimu-farm: control characters refused in every script value; --spp and --frames bounded"
