#!/usr/bin/env bash
# The image half of bench/pbrt_side_by_side.sh (bench/pbrt_image_compare.cpp) on two Rimu renders of the pbrt
# Cornell box. Usage: pbrt_image_compare.sh RIMU COMPARE DATA_DIR WORK_DIR
# An image against itself: ratio exactly 1, every tile's z 0, relMSE 0. Two seeds: no 8×8 tile beyond 4.5σ of 48
# (the standard error is right: a missing square root or a wrong divisor puts tiles far beyond it; false alarm for
# 48 N(0,1) tests ≈ 3e-4). The same box with its red and green walls swapped (the JSON twin of the file, edited) is
# caught. `allocation`: counts equal everywhere are worth exactly 1; an adaptive render's unequal counts are worth
# no more than the oracle's (n ∝ √q is the minimum of Σ q/n for the total), which is worth at least 1 (Cauchy–
# Schwarz); an image without an `spp` channel, and runs without noise between them, are refused. Bad input: exit 1
# with the file named.
set -u
rimu=$1; compare=$2; data=$3; work=$4
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
value() { sed -n "s/^$1=//p" <<<"$2"; }

for seed in 1 2; do
  "$rimu" "$data/cornell.pbrt" -o "$work/s$seed.exr" --float -q --spp 16 --seed $seed --threads 2 >/dev/null 2>&1 ||
    fail "rimu did not render cornell.pbrt"
done

out=$("$compare" compare "$work/s1.exr" "$work/s1.exr")
[ "$(value ratio_b_over_a "$out")" = "1,1,1" ] || fail "self ratio: $out"
[ "$(value block_tests "$out")" = 48 ] || fail "32x32 image: expected 48 tile tests: $out"
[ "$(value worst_z "$out")" = 0 ] || fail "self worst z: $out"
[ "$(value relmse "$("$compare" relmse "$work/s1.exr" "$work/s1.exr")")" = 0 ] || fail "self relMSE not 0"

out=$("$compare" compare "$work/s1.exr" "$work/s2.exr")
[ "$(value 'blocks_beyond_4.5sigma' "$out")" = 0 ] || fail "two seeds differ beyond noise: $out"
awk -v r="$(value rms_z "$out")" 'BEGIN {exit !(r > 0.5 && r < 2)}' || fail "two seeds: rms z not ≈ 1: $out"
relmse=$(value relmse "$("$compare" relmse "$work/s1.exr" "$work/s2.exr")")
awk -v e="$relmse" 'BEGIN {exit !(e > 0)}' || fail "two seeds: relMSE $relmse, expected > 0"
# Without the worst 0.1 % of the pixels (1 of 1,024 here) the relMSE can only fall, by their share of the sum:
# relmse·(1 − share)·1024/1023 = the rest's mean. With the image itself as --denominator, the relMSE is unchanged.
out=$("$compare" relmse "$work/s1.exr" "$work/s2.exr")
awk -v e="$relmse" -v w="$(value 'relmse_without_worst_0.1pct' "$out")" -v f="$(value 'worst_0.1pct_share' "$out")" \
  'BEGIN {rest = e * (1 - f) * 1024 / 1023; exit !(f > 0 && f < 1 && w <= e * 1024 / 1023 && w > 0.999 * rest && w < 1.001 * rest)}' ||
  fail "worst 0.1 %: $out"
[ "$(value relmse "$("$compare" relmse "$work/s1.exr" "$work/s2.exr" --denominator "$work/s2.exr")")" = "$relmse" ] ||
  fail "--denominator of the reference itself changed the relMSE"
d=$(value relmse "$("$compare" relmse "$work/s1.exr" "$work/s2.exr" --denominator "$work/s1.exr")")
awk -v d="$d" -v e="$relmse" 'BEGIN {exit !(d > 0 && d != e)}' || fail "--denominator ignored: $d vs $relmse"

# Counts: 48 spp everywhere (no pixel reaches the threshold of 10⁻⁶), and an adaptive render's unequal counts.
"$rimu" "$data/cornell.pbrt" -o "$work/even.exr" -q --spp 48 --noise-threshold 0.000001 --threads 2 >/dev/null 2>&1 ||
  fail "rimu did not render the even counts"
"$rimu" "$data/cornell.pbrt" -o "$work/uneven.exr" -q --spp 256 --noise-threshold 0.05 --threads 2 >/dev/null 2>&1 ||
  fail "rimu did not render the adaptive counts"
out=$("$compare" allocation "$work/even.exr" "$work/s1.exr" "$work/s2.exr" --run-spp 16)
[ "$(value allocation_gain "$out")" = 1.0000 ] && [ "$(value mean_spp "$out")" = 48 ] || fail "even counts: $out"
out=$("$compare" allocation "$work/uneven.exr" "$work/s1.exr" "$work/s2.exr" --run-spp 16)
awk -v a="$(value allocation_gain "$out")" -v o="$(value oracle_gain "$out")" 'BEGIN {exit !(a > 0 && a != 1 && a <= o && o >= 1)}' ||
  fail "adaptive counts: $out"
out=$("$compare" allocation "$work/s1.exr" "$work/s1.exr" "$work/s2.exr" --run-spp 16 2>&1); code=$?
[ $code = 1 ] && grep -q "spp" <<<"$out" || fail "counts without spp: exit $code: $out"
out=$("$compare" allocation "$work/uneven.exr" "$work/s1.exr" "$work/s1.exr" --run-spp 16 2>&1); code=$?
[ $code = 1 ] && grep -q "runs agree" <<<"$out" || fail "one run twice: exit $code: $out"

# The JSON twin has its geometry inline, so it renders from the work folder.
sed -e 's/"red": {/"tmp": {/; s/"green": {/"red": {/; s/"tmp": {/"green": {/' "$data/cornell_equivalent.json" >"$work/swapped.json"
"$rimu" "$work/swapped.json" -o "$work/swapped.exr" --float -q --spp 16 --seed 3 --threads 2 >/dev/null 2>&1 ||
  fail "rimu did not render the swapped JSON"
out=$("$compare" compare "$work/s1.exr" "$work/swapped.exr")
[ "$(value 'blocks_beyond_4.5sigma' "$out")" -gt 0 ] 2>/dev/null || fail "swapped walls not caught: $out"

t=$(value render_time_s "$("$compare" info "$work/s1.exr")")
awk -v t="$t" 'BEGIN {exit !(t > 0)}' || fail "info: render time '$t'"

out=$("$compare" compare "$work/s1.exr" "$work/missing.exr" 2>&1); code=$?
[ $code = 1 ] && grep -q "missing.exr" <<<"$out" || fail "missing file: exit $code: $out"
out=$("$compare" compare "$work/s1.exr" 2>&1); code=$?
[ $code = 1 ] && grep -q "usage" <<<"$out" || fail "usage: exit $code: $out"
out=$("$compare" compare "$work/s1.exr" "$work/s2.exr" --space nonsense 2>&1); code=$?
[ $code = 1 ] && grep -q -- "--space" <<<"$out" || fail "bad space: exit $code: $out"

[ $failures = 0 ] && echo "pbrt_image_compare: all checks passed"
exit $((failures > 0))
