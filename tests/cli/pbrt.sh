#!/usr/bin/env bash
# pbrt-v4 scenes through the tools (docs/pbrt-import.md). Usage: pbrt.sh RIMU RIMU_CONVERT DATA_DIR WORK_DIR
# Bad input: exit 1, a message with the pbrt file and line, and no output file (rimu and rimu-convert alike).
# Good input: rimu-convert writes JSON whose relative mesh paths work from the output's folder, and rimu renders it.
set -u
rimu=$1; convert=$2; data=$3; work=$4
rm -rf "$work"; mkdir -p "$work/out"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect_bad() {  # file pattern [also-convert]
  local file=$1 pattern=$2 output code
  output=$("$rimu" "$data/$file" -o "$work/bad.exr" -q 2>&1); code=$?
  [ "$code" = 1 ] || fail "rimu $file: exit $code, expected 1: $output"
  grep -Eq -- "$pattern" <<<"$output" || fail "rimu $file: '$output' does not match /$pattern/"
  [ ! -e "$work/bad.exr" ] || fail "rimu $file wrote an image"
  [ "${3:-}" = convert ] || return 0  # each tool start costs ~0.5 s: rimu-convert on a few of them
  output=$("$convert" "$data/$file" -o "$work/bad.json" 2>&1); code=$?
  [ "$code" = 1 ] || fail "rimu-convert $file: exit $code, expected 1: $output"
  grep -Eq -- "$pattern" <<<"$output" || fail "rimu-convert $file: '$output' does not match /$pattern/"
  [ ! -e "$work/bad.json" ] || fail "rimu-convert $file wrote a file"
}

expect_bad bad_unknown_statement.pbrt "bad_unknown_statement.pbrt:4: unknown statement 'Shpe'" convert
expect_bad bad_wrong_type.pbrt "bad_wrong_type.pbrt:4: .*expected an integer, found '64.5'"
expect_bad bad_missing_include.pbrt "bad_missing_include.pbrt:4: Include: '.*no_such_file.pbrt': cannot open the file: it does not exist"
expect_bad bad_missing_ply.pbrt "bad_missing_ply.pbrt:5: .*cannot find the PLY file '.*no_such_mesh.ply'" convert
expect_bad bad_mismatched_end.pbrt "bad_mismatched_end.pbrt:6: AttributeEnd without a matching AttributeBegin"
expect_bad bad_nan_transform.pbrt "bad_nan_transform.pbrt:4: Translate: expected a finite number, found 'nan'"
expect_bad bad_truncated_ply.pbrt "bad_truncated_ply.pbrt:4: Shape \"plymesh\": .*truncated.ply:13: vertex 2: the file ends inside this record" convert

# --strict turns the report into an error, in both tools.
output=$("$rimu" "$data/unsupported.pbrt" --strict -o "$work/strict.exr" -q 2>&1)
[ $? = 1 ] && grep -q 'unsupported.pbrt:7: not supported (--strict): Material "fourier"' <<<"$output" || fail "rimu --strict: $output"
[ ! -e "$work/strict.exr" ] || fail "rimu --strict wrote an image"
output=$("$convert" "$data/unsupported.pbrt" --strict -o "$work/strict.json" 2>&1)
[ $? = 1 ] && [ ! -e "$work/strict.json" ] || fail "rimu-convert --strict: $output"

# Without --strict: the list, then the render.
output=$("$rimu" "$data/unsupported.pbrt" -o "$work/unsupported.exr" -q 2>&1)
[ $? = 0 ] && grep -q 'ignored: Material "fourier" (pbrt-v3.s tabulated BSDF, which pbrt-v4 no longer reads; a grey diffuse of reflectance 0.5 stands in) (2 times), first at .*unsupported.pbrt:7' <<<"$output" || fail "rimu unsupported.pbrt: $output"

# Convert into another folder, then render the JSON: the PLY path must be relative to the JSON.
cp "$data/quad.ply" "$work/quad.ply"
printf 'LookAt 0 0 -3  0 0 0  0 1 0\nCamera "perspective"\nFilm "rgb" "integer xresolution" 8 "integer yresolution" 8\nWorldBegin\nLightSource "infinite"\nShape "plymesh" "string filename" "quad.ply"\n' > "$work/quad.pbrt"
output=$("$convert" "$work/quad.pbrt" -o "$work/out/quad.json" 2>&1) || fail "rimu-convert quad.pbrt: $output"
grep -q '"file": "../quad.ply"' "$work/out/quad.json" || fail "the converted mesh path is not relative to the JSON: $(grep file "$work/out/quad.json")"
output=$("$rimu" "$work/out/quad.json" -o "$work/quad.exr" -q 2>&1) || fail "rimu on the converted JSON: $output"
output=$("$rimu" "$data/cornell.pbrt" -o "$work/cornell.exr" --spp 2 -q 2>&1) || fail "rimu cornell.pbrt: $output"
[ -e "$work/cornell.exr" ] || fail "rimu cornell.pbrt wrote no image"

[ "$failures" = 0 ] && echo "pbrt CLI checks passed"
exit $((failures > 0))
