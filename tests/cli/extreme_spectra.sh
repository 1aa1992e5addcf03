#!/usr/bin/env bash
# extreme_spectra.sh RIMU_COLOUR RIMU_LIGHT
# Spectral values at the edges of double precision, through every rimu-colour and rimu-light subcommand that reads a
# spectrum: each run exits 0 or 1 (never 2 or a signal), and no output, of a success or an error, holds NaN or
# infinity. Values outside the accepted range (0, or 1e-30 to 1e30) are refused by name and line; the edges work.
set -u
colour=$1
light=$2
. "$(dirname "$0")/private_folder.sh"
private_folder rimu-extreme-spectra

# flat VALUE FILE: a 5 nm table of VALUE over 380-780 nm.
flat() { awk -v v="$1" 'BEGIN { print "wavelength_nm,power"; for (nm = 380; nm <= 780; nm += 5) print nm "," v }' > "$2"; }
for v in 1e-310 1e-308 1e-300 1e-31 1e-30 1e30 1e31 1e300 1.7e308 1e-400 1e400; do flat "$v" "flat_$v.csv"; done
# A single line at 550 nm, light only beyond the eye's range, a huge dynamic range, a spike at each end.
awk 'BEGIN { print "wavelength_nm,power"; for (nm = 380; nm <= 780; nm += 5) print nm "," (nm == 550 ? 1 : 0) }' > line.csv
awk 'BEGIN { print "wavelength_nm,power"; for (nm = 380; nm <= 780; nm += 5) print nm "," (nm >= 780 ? 1 : 0) }' > edge.csv
awk 'BEGIN { print "wavelength_nm,power"; for (nm = 380; nm <= 780; nm += 5) print nm "," (nm == 600 ? 1e30 : 1e-30) }' > range.csv
awk 'BEGIN { print "wavelength_nm,r"; for (nm = 380; nm <= 780; nm += 10) print nm "," (nm == 550 ? -0.5 : 0.5) }' > negative_reflectance.csv
awk 'BEGIN { print "wavelength_nm,r"; for (nm = 380; nm <= 780; nm += 10) print nm ",1e-31" }' > tiny_reflectance.csv
awk 'BEGIN { print "wavelength_nm,r"; for (nm = 380; nm <= 780; nm += 10) print nm ",0" }' > black_reflectance.csv

# run EXPECTED_CODES PATTERN COMMAND...: exit code among EXPECTED_CODES ("0", "1" or "01"), output matching the
# regex PATTERN (empty: anything), and never nan or inf in the output.
run() {
  local codes=$1 pattern=$2
  shift 2
  local output code
  output=$("$@" 2>&1)
  code=$?
  [[ "$codes" == *"$code"* ]] || { fail "exit $code (expected $codes): $*"; echo "$output" | head -5; }
  if grep -Eiq '(^|[^a-z])-?(nan|inf|infinity)([^a-z]|$)' <<<"$output"; then
    fail "NaN or Inf in the output of: $*"
    grep -Ei '(^|[^a-z])-?(nan|inf|infinity)([^a-z]|$)' <<<"$output" | head -3
  fi
  if [ -n "$pattern" ] && ! grep -Eq -- "$pattern" <<<"$output"; then
    fail "output of '$*' does not match /$pattern/"
    echo "$output" | head -5
  fi
}

# The reported cases: refused with the reason and the line.
run 1 "flat_1e-310.csv:2.*1e-310 is nonzero but smaller in magnitude than Rimu accepts" "$colour" report --csv flat_1e-310.csv
run 1 "flat_1e-310.csv:2.*smaller in magnitude" "$colour" fidelity --csv flat_1e-310.csv
run 1 "flat_1.7e308.csv:2.*1.7e\+308 is larger in magnitude" "$colour" report --csv flat_1.7e308.csv
run 1 "flat_1.7e308.csv:2.*larger in magnitude" "$colour" fidelity --csv flat_1.7e308.csv
run 1 "flat_1e-400.csv:2.*beyond the range of double-precision numbers" "$colour" report --csv flat_1e-400.csv
run 1 "flat_1e400.csv:2.*beyond the range of double-precision numbers" "$colour" report --csv flat_1e400.csv
run 1 "negative_reflectance.csv:19.*reflectance factor -0.5 is negative" \
  "$colour" reflectance --csv negative_reflectance.csv
run 1 "negative_reflectance.csv:19.*negative" \
  "$colour" reflectance --patch "dark skin" --reference negative_reflectance.csv
# The edges of the range work, with the same colour as any other flat light (equal energy: x = y = 1/3).
run 0 "xy  \(2°\) +0\.3333[0-9] 0\.3333[0-9]" "$colour" report --csv flat_1e-30.csv
run 0 "xy  \(2°\) +0\.3333[0-9] 0\.3333[0-9]" "$colour" report --csv flat_1e30.csv
run 0 "Rf \(CIE 224:2017\) +[0-9]" "$colour" fidelity --csv flat_1e-30.csv
run 0 "Rf \(CIE 224:2017\) +[0-9]" "$colour" fidelity --csv flat_1e30.csv

# The sweep: every subcommand that reads a spectrum or a number, on every file; exit 0 or 1, never NaN or Inf.
for f in flat_*.csv line.csv edge.csv range.csv; do
  run 01 "" "$colour" report --csv "$f"
  run 01 "" "$colour" report --csv "$f" --json
  run 01 "" "$colour" report --csv "$f" --method 1nm
  run 01 "" "$colour" fidelity --csv "$f"
  run 01 "" "$colour" fidelity --csv "$f" --json
  run 01 "" "$light" inspect "$f"
  run 01 "" "$light" inspect "$f" --json
  run 01 "" "$light" --type point --lumens 800 --csv "$f"
  run 01 "" "$light" --type environment --nits 1000 --csv "$f"
  run 01 "" "$light" --type spot --watts 1e-300 --csv "$f"
done
for f in negative_reflectance.csv tiny_reflectance.csv black_reflectance.csv flat_1e-30.csv; do
  run 01 "" "$colour" reflectance --csv "$f"
  run 01 "" "$colour" reflectance --csv "$f" --json --observer 10
done
for rgb in "1e-310 0 0" "1e-30 1e-30 1e-30" "1e30 1e30 1e30" "1.7e308 0 0" "-1e30 1 1" "1e-400 0 0"; do
  # shellcheck disable=SC2086
  run 01 "" "$colour" upsample $rgb
  # shellcheck disable=SC2086
  run 01 "" "$colour" upsample $rgb --emission --csv
done
for amount in 1e-310 1e-30 1e30 1e31 1.7e308 1e-400; do
  run 01 "" "$light" --type point --lumens "$amount" --cct 3000
  run 01 "" "$light" --type distant --lux "$amount" --daylight 6500
  run 01 "" "$light" convert --from "$amount lm" --to cd --type point
  run 01 "" "$light" convert --from "$amount lx" --to EV --type distant
  run 01 "" "$light" convert --from "$amount nt" --to W/m2/sr --type environment
done
# A temperature that underflows to 0 is named as the --blackbody it was (before: "--daylight ... got 0 K").
run 1 "--blackbody: blackbody temperature must be a finite number in \(0, 1e6\] K, got 0" \
  "$colour" report --blackbody 1e-400
for t in 1e-310 0.5 1 1e6 1e7; do
  run 01 "" "$colour" report --blackbody "$t"
  run 01 "" "$light" --type point --lumens 800 --cct "$t"
done
run 01 "" "$light" convert --from "-30 EV" --to lx --type distant
run 01 "" "$light" convert --from "60 EV" --to nt --type environment
exit $((failures > 0))
