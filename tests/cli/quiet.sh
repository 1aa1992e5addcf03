#!/usr/bin/env bash
# quiet.sh RIMU PHOTOMETRIC_SCENE WORKDIR: `rimu -q` prints nothing on stderr but warnings and errors: no progress line, no summary,
# no checkpoint notes, no note on how the display image was metered, no "nothing to resume". Without -q the summary
# is there (so the test sees the difference).
set -u
rimu=$1; photometric=$2; dir=$3
. "$(dirname "$0")/private_folder.sh"
work_folder "$dir"
quick=(--resolution 8x6 --spp 2 --threads 1)

"$rimu" "${quick[@]}" -o loud.exr 2>loud.log || fail "a render without -q"
grep -q "rimu: wrote loud.exr" loud.log || fail "without -q, no summary: $(cat loud.log)"
"$rimu" "${quick[@]}" -q -o quiet.exr --png quiet.png --checkpoint 0.001s 2>quiet.log || fail "rimu -q: $(cat quiet.log)"
[ ! -s quiet.log ] || fail "rimu -q printed: $(cat quiet.log)"
"$rimu" --resume quiet.exr -q 2>resume.log || fail "rimu --resume -q: $(cat resume.log)"
[ ! -s resume.log ] || fail "rimu --resume -q (nothing to resume) printed: $(cat resume.log)"
# A photometric scene without a camera exposure: its display image is metered, which is a note, not a warning.
"$rimu" "$photometric" "${quick[@]}" -o metered.exr --png metered.png 2>metered.log || fail "the photometric card"
grep -q "display image is metered" metered.log || fail "without -q, no metering note: $(cat metered.log)"
"$rimu" "$photometric" "${quick[@]}" -q -o metered.exr --png metered.png 2>metered_quiet.log || fail "-q photometric"
[ ! -s metered_quiet.log ] || fail "rimu -q (metered display image) printed: $(cat metered_quiet.log)"
[ "$failures" = 0 ] && echo "rimu -q: nothing on stderr"
exit $((failures > 0))
