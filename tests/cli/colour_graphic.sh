#!/usr/bin/env bash
# colour_graphic.sh RIMU_COLOUR
# `rimu-colour fidelity --graphic`: writes a PNG (checked by its magic bytes) at the path given; a spectrum file
# name with backquotes and $(...) becomes a title without running anything; a destination in a missing folder is
# refused with exit 1 before the fidelity report is printed, and nothing is written.
set -u
colour=$1
. "$(dirname "$0")/private_folder.sh"
private_folder rimu-cvg-test
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }

"$colour" fidelity F2 --graphic cvg.png > report.txt || fail "fidelity F2 --graphic cvg.png: exit $?"
[ -f cvg.png ] && is_png cvg.png || fail "cvg.png is missing or not a PNG"
grep -q "Rf (CIE 224:2017)" report.txt || fail "the report was not printed with the graphic"

# A measured light with a hostile file name: it reaches the title only through the plot runner's text helper.
csv="lamp\`touch \$MARK\`\$(touch \$MARK).csv"
"$colour" report F11 --json > /dev/null  # the binary works at all
awk 'BEGIN { print "wavelength_nm,power"; for (nm = 380; nm <= 780; nm += 5) print nm "," 50 + nm / 10 }' > "$csv"
"$colour" fidelity --csv "$csv" --graphic lamp.png > /dev/null || fail "fidelity --csv (hostile name): exit $?"
[ -f lamp.png ] && is_png lamp.png || fail "lamp.png is missing or not a PNG"
[ ! -e "$MARK" ] || fail "a command in the spectrum's file name ran"

output=$("$colour" fidelity F2 --graphic bad/cvg.png 2>&1); code=$?
[ "$code" = 1 ] || fail "fidelity F2 --graphic bad/cvg.png: exit $code (expected 1)"
grep -q "folder 'bad' does not exist" <<<"$output" || fail "message does not name the missing folder: $output"
! grep -q "Rf (CIE" <<<"$output" || fail "the report was printed before the graphic was refused"
[ ! -e bad ] || fail "the missing folder was created"
left=$(find "$work" -mindepth 1 ! -path "$work/tmp" ! -name cvg.png ! -name lamp.png ! -name report.txt ! -name "$csv" -print)
[ -z "$left" ] || fail "left behind: $left"

[ "$failures" = 0 ] || exit 1
echo "ok"
