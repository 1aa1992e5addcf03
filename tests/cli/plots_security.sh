#!/usr/bin/env bash
# plots_security.sh CASE RIMU_LIGHT RIMU_COLOUR
# The plot options with hostile paths and file names (docs: src/spectral/io/gnuplot_process.h). Every case runs in a
# fresh folder with a private $TMPDIR and checks that
#   - no injected command ran: names carry `touch P` (relative, as a user would type it) and `touch $MARK` (an
#     absolute marker set below, found wherever the command would have run: a shell, or gnuplot's backquotes);
#   - the tool either wrote a PNG at exactly the path it was given, or refused with exit 1 and a message;
#   - no .gp, .dat or .log file is left in the folder, and nothing at all in $TMPDIR.
set -u
case_name=$1 light=$2 colour=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/private_folder.sh"
private_folder rimu-plots-test

# run EXPECTED_PNG COMMAND...: runs COMMAND, then checks the rules above for EXPECTED_PNG.
run() {
  local png=$1; shift
  local output code
  output=$("$@" 2>&1 >/dev/null); code=$?
  if [ "$code" = 0 ]; then
    if [ ! -f "$png" ]; then fail "exit 0 but no PNG at [$png] from: $*"
    elif [ "$(head -c 4 "$png" | od -An -c | tr -d ' ')" != '211PNG' ]; then fail "[$png] is not a PNG"; fi
  elif [ "$code" = 1 ]; then
    [ -n "$output" ] || fail "exit 1 without a message from: $*"
  else
    fail "exit $code from: $*"; echo "$output"
  fi
  if [ -e "$MARK" ] || [ -n "$(find "$work" -name P -o -name Q -o -name R)" ]; then
    fail "an injected command ran: $*"; rm -f "$MARK"; find "$work" \( -name P -o -name Q -o -name R \) -delete
  fi
  local left
  left=$(find "$work" \( -name '*.gp' -o -name '*.dat' -o -name '*.log' \) -print)
  [ -z "$left" ] || fail "left behind by '$*': $left"
  left=$(find "$TMPDIR" -mindepth 1 -print)
  [ -z "$left" ] || fail "left in \$TMPDIR by '$*': $left"
}

case "$case_name" in
  light)
    run "x';touch P;'.png" "$light" --type point --lumens 100 --plot "x';touch P;'.png"
    run "y';touch \$MARK;'\`touch \$MARK\`.png" "$light" --type point --lumens 100 --cct 3000 \
        --plot "y';touch \$MARK;'\`touch \$MARK\`.png"
    ;;
  upsample)
    run "u';touch P;'.png" "$colour" upsample 0.8 0.2 0.1 --plot "u';touch P;'.png"
    run "v\";touch \$MARK;\"'\`touch \$MARK\`'.png" "$colour" upsample 0.8 0.2 0.1 --emission \
        --plot "v\";touch \$MARK;\"'\`touch \$MARK\`'.png"
    ;;
  gamut)
    run "g';touch \$MARK;'\`touch \$MARK\`.png" "$colour" gamut --out "g';touch \$MARK;'\`touch \$MARK\`.png"
    # Only the PNG (the CSV only when asked for).
    [ "$(find "$work" -mindepth 1 -maxdepth 1 ! -name tmp | wc -l)" = 1 ] || fail "gamut left: $(ls -A "$work")"
    ;;
  inspect)
    # Someone else's light file whose spectrum CSV has backquotes and $(...) in its name.
    csv="lamp\`touch \$MARK\`\$(touch \$MARK)_[x].csv"
    printf 'wavelength_nm,power\n380,1\n500,2\n780,1\n' > "$csv"
    printf '{"type": "point", "luminous_power_lm": 100, "spectrum": {"csv": "%s"}}\n' "$csv" > lamp.json
    run p.png "$light" inspect lamp.json --plot p.png
    run q.png "$light" inspect "$csv" --plot q.png
    # An IES file with such a name: its name is the polar plot's title.
    ies="down\`touch \$MARK\`'\$(touch \$MARK)'.ies"
    cp "$here/downlight.ies" "$ies"
    run polar.png "$light" inspect "$ies" --plot-polar polar.png
    ;;
  bad-folder)
    # A plot that cannot be written is refused before anything else is: no light file, exit 1, the folder named.
    output=$("$light" -o l.json --type point --lumens 100 --plot bad/x.png 2>&1); code=$?
    [ "$code" = 1 ] || fail "rimu-light --plot bad/x.png: exit $code"
    grep -q "folder 'bad' does not exist" <<<"$output" || fail "rimu-light message: $output"
    [ ! -e l.json ] || fail "rimu-light wrote l.json before refusing the plot"
    output=$("$colour" upsample 0.5 0.5 0.5 --plot bad/x.png 2>&1); code=$?
    [ "$code" = 1 ] || fail "rimu-colour upsample --plot bad/x.png: exit $code"
    ! grep -q "round trip" <<<"$output" || fail "rimu-colour upsample printed the report before refusing the plot"
    output=$("$colour" gamut --out bad/g.png --csv g.csv 2>&1); code=$?
    [ "$code" = 1 ] || fail "rimu-colour gamut --out bad/g.png: exit $code"
    [ ! -e g.csv ] || fail "rimu-colour gamut wrote g.csv before refusing the plot"
    output=$(RIMU_GNUPLOT="$work/no-gnuplot" "$light" -o l.json --type point --lumens 100 --plot x.png 2>&1); code=$?
    [ "$code" = 2 ] || fail "rimu-light without gnuplot: exit $code"
    grep -q "gnuplot not found at $work/no-gnuplot" <<<"$output" || fail "rimu-light message: $output"
    [ ! -e l.json ] || fail "rimu-light wrote l.json without gnuplot"
    ;;
  *) echo "unknown case $case_name"; exit 2 ;;
esac
[ "$failures" = 0 ] || exit 1
echo "ok: $case_name"
