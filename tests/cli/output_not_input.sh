#!/usr/bin/env bash
# output_not_input.sh BUILD_BIN SOURCE_DIR WORKDIR: no tool writes an output over one of its inputs — the same name,
# a symbolic link or a hard link to it (compared by device and inode) — for every output option: rimu -o/--png
# against the scene and a file it names, rimu merge -o against a partial (with and without --final), rimu display --png against the EXR, rimu-convert
# -o against the pbrt file and a file it includes, rimu-colour --graphic against --csv, rimu-light -o/--plot against
# the definition, the inspected file and --csv. Each is exit 1 naming the output and the input, and the input is
# unchanged (the old tools replaced it with exit 0). `rimu --resume FILE` still writes FILE (it continues it).
set -u
bin=$1 src=$2 dir=$3
. "$(dirname "$0")/private_folder.sh"
work_folder "$dir"

# refused INPUT OUTPUT COMMAND...: exit 1, a message naming OUTPUT as an input, INPUT's bytes unchanged.
refused() {
  local input=$1 output=$2; shift 2
  local before after message code
  before=$(md5sum < "$input")
  message=$("$@" 2>&1 >/dev/null); code=$?
  after=$(md5sum < "$input")
  [ "$code" = 1 ] || fail "exit $code (expected 1) from: $* : $message"
  grep -q -- "$output.*the output is the input.*choose another output name" <<<"$message" ||
    fail "message of '$*': $message"
  [ "$before" = "$after" ] || fail "'$*' changed its input $input"
}

cp -r "$src/data/scenes/cornell_box" box
cp "$src/tests/data/pbrt/cornell.pbrt" "$src/tests/data/pbrt/cornell_walls.pbrt" .
quick=(--resolution 8x6 --threads 1 -q)

# rimu: the scene itself (a link and a hard link, as the names must end in .exr / .png) and a CSV it names.
ln -s box/scene.json scene_link.exr; ln box/scene.json scene_hard.png
refused box/scene.json scene_link.exr "$bin/rimu" box/scene.json "${quick[@]}" --spp 1 -o scene_link.exr
refused box/scene.json scene_hard.png "$bin/rimu" box/scene.json "${quick[@]}" --spp 1 -o ok.exr --png scene_hard.png
ln -s box/light_emission.csv csv_link.exr
refused box/light_emission.csv csv_link.exr "$bin/rimu" box/scene.json "${quick[@]}" --spp 1 -o csv_link.exr
ln -s cornell.pbrt pbrt_link.exr
refused cornell.pbrt pbrt_link.exr "$bin/rimu" cornell.pbrt "${quick[@]}" --spp 1 -o pbrt_link.exr
[ ! -e ok.exr ] || fail "rimu wrote -o although --png was refused"

# rimu merge: -o one of the partials, by its name and through a link, with and without --final.
"$bin/rimu" box/scene.json "${quick[@]}" --spp 2 --samples 0:1 -o q0.exr && \
  "$bin/rimu" box/scene.json "${quick[@]}" --spp 2 --samples 1:2 -o q1.exr || fail "partials"
refused q0.exr q0.exr "$bin/rimu" merge q0.exr q1.exr --final -o q0.exr
refused q1.exr q1.exr "$bin/rimu" merge q0.exr q1.exr -o q1.exr
ln -s q0.exr q0_link.exr
refused q0.exr q0_link.exr "$bin/rimu" merge q0.exr q1.exr --final -o q0_link.exr
"$bin/rimu" merge q0.exr q1.exr --final -o merged.exr 2>/dev/null || fail "a merge to a new file"

# rimu display: --png a link to the EXR it shows.
ln -s q0.exr q0_link.png
refused q0.exr q0_link.png "$bin/rimu" display q0.exr --png q0_link.png
"$bin/rimu" display merged.exr --png merged.png 2>/dev/null || fail "rimu display of a merge"

# rimu --resume: -o defaults to the resumed file, which is continued, not destroyed.
"$bin/rimu" box/scene.json "${quick[@]}" --spp 4 --samples 0:2 -o part.exr || fail "a partial to resume"
"$bin/rimu" --resume part.exr -q 2>/dev/null || fail "rimu --resume part.exr (its own output)"

# rimu-convert: the pbrt file by name, through a link and a hard link; a file it includes.
refused cornell.pbrt cornell.pbrt "$bin/rimu-convert" cornell.pbrt -o cornell.pbrt
ln -s cornell.pbrt convert_link.json; ln cornell.pbrt convert_hard.json
refused cornell.pbrt convert_link.json "$bin/rimu-convert" cornell.pbrt -o convert_link.json
refused cornell.pbrt convert_hard.json "$bin/rimu-convert" cornell.pbrt -o convert_hard.json
refused cornell_walls.pbrt cornell_walls.pbrt "$bin/rimu-convert" cornell.pbrt -o cornell_walls.pbrt

# rimu-colour: the fidelity graphic over its spectrum.
cp "$src/data/spectra/illuminants/cie_led_5nm.csv" led.csv; ln -s led.csv led_link.png
refused led.csv led_link.png "$bin/rimu-colour" fidelity --csv led.csv --column LED-B3 --graphic led_link.png

# rimu-light: recolor in place, a plot over the inspected CSV, a definition over --csv.
"$bin/rimu-light" --type point --lumens 100 -o lamp.json || fail "rimu-light -o lamp.json"
refused lamp.json lamp.json "$bin/rimu-light" recolor lamp.json --cct 3000 -o lamp.json
printf 'wavelength_nm,power\n380,1\n780,1\n' > flat.csv; ln -s flat.csv flat_link.png; ln flat.csv flat_hard.json
refused flat.csv flat_link.png "$bin/rimu-light" inspect flat.csv --plot flat_link.png
refused flat.csv flat_hard.json "$bin/rimu-light" --type point --lumens 100 --csv flat.csv -o flat_hard.json
refused flat.csv flat_link.png "$bin/rimu-light" --type point --lumens 100 --csv flat.csv --plot flat_link.png
refused flat.csv flat_hard.json "$bin/rimu-light" recolor lamp.json --csv flat.csv -o flat_hard.json

[ "$failures" = 0 ] && echo "outputs that are inputs: refused by every tool; --resume continues its own file"
exit $((failures > 0))
