#!/usr/bin/env bash
# output_files.sh RIMU SCENE SCRATCH: the rimu tool's outputs seen from the shell. Checks that options that cannot
# work leave no file behind (the EXR was written before a bad --view or --png was noticed), that a display image's
# format follows its name, and that a temporary left by a killed render is removed by the next run.
set -u
rimu=$1; scene=$2; scratch=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$scratch"; mkdir -p "$scratch"; cd "$scratch" || exit 1
tiny=(--spp 1 --resolution 8x8 -q)

# Refused before rendering: exit 1, and no out.exr.
for case in "--view bogus --png v.png" "--exposure nan --png v.png" "--png /proc/rimu-x.png" "--iso inf" \
            "--iso 1e-300 --shutter 1e-300 --f-number 1e-300" "--ev 2000" "--png out.exr" "--png v.bmp"; do
  # shellcheck disable=SC2086
  output=$("$rimu" "$scene" -o out.exr "${tiny[@]}" $case 2>&1); code=$?
  [ "$code" = 1 ] || fail "rimu $case: exit $code, expected 1: $output"
  [ ! -e out.exr ] || fail "rimu $case: out.exr was written before the option was refused"
  grep -q "rimu-incomplete\|rimu-tmp" <<<"$output" && fail "rimu $case: the message names a temporary: $output"
done

# -o of another format is refused; --png picks its format by the extension.
"$rimu" "$scene" -o out.png "${tiny[@]}" >/dev/null 2>&1 && fail "-o out.png was accepted"
[ ! -e out.png ] || fail "-o out.png wrote a file"
"$rimu" "$scene" -o out.exr --png v.jpg "${tiny[@]}" || fail "--png v.jpg failed"
[ "$(head -c 3 v.jpg | od -An -tx1 | tr -d ' ')" = "ffd8ff" ] || fail "v.jpg is not a JPEG"
"$rimu" "$scene" -o out.exr --png v.png "${tiny[@]}" || fail "--png v.png failed"
[ "$(head -c 4 v.png | tail -c 3)" = "PNG" ] || fail "v.png is not a PNG"
grep -q sRGB v.png || fail "v.png has no sRGB chunk"

# A render killed with SIGKILL leaves its temporary; the next run on the same output removes it.
sleep 30 & dead=$!; kill -9 $dead; wait $dead 2>/dev/null
echo partial > ".out.exr.rimu-incomplete-$dead-0.exr"
echo partial > ".out.rimu-tmp-$dead-0.exr"
echo mine > ".other.exr.rimu-incomplete-$dead-0.exr"
"$rimu" "$scene" -o out.exr "${tiny[@]}" || fail "rerun failed"
[ ! -e ".out.exr.rimu-incomplete-$dead-0.exr" ] || fail "the stale temporary was not removed"
[ ! -e ".out.rimu-tmp-$dead-0.exr" ] || fail "the stale temporary of the old name was not removed"
[ -e ".other.exr.rimu-incomplete-$dead-0.exr" ] || fail "another output's temporary was removed"
cd / && rm -rf "$scratch"
echo "ok"
