#!/usr/bin/env bash
# plot_outputs.sh RIMU_LIGHT RIMU_COLOUR IES: every plot goes through the renderer's output-file code
# (src/spectral/io/output_file.h):
#   - a plot's format follows its name: a .jpg (or any name not ending in .png, a device named without one) is
#     refused with exit 1 and nothing is written, instead of PNG bytes under a JPEG name;
#   - a destination that is a device (a character device with the numbers of /dev/full, made here with mknod so
#     the machine's own /dev/full is never at risk) or a link to one is written by a checked copy: "No space left on
#     device" is exit 2 naming the path, as for the renderer's images, and the device stays a device (the old code
#     renamed a PNG over it). mknod needs root: without it the device cases are skipped, the rest still runs.
set -u
light=$1 colour=$2 ies=$3
here=$(cd "$(dirname "$0")" && pwd)
. "$here/private_folder.sh"
private_folder rimu-plot-outputs

# expect CODE PATTERN COMMAND...: the exit code and a message matching PATTERN.
expect() {
  local want=$1 pattern=$2; shift 2
  local output code
  output=$("$@" 2>&1 >/dev/null); code=$?
  [ "$code" = "$want" ] || { fail "exit $code (expected $want) from: $* : $output"; return; }
  grep -Eq -- "$pattern" <<<"$output" || fail "message of '$*' does not match /$pattern/: $output"
}

plot_commands() {  # plot_commands NAME: one command line per plot option, each drawing to NAME
  echo "$colour fidelity F2 --graphic $1"
  echo "$colour gamut --out $1"
  echo "$colour upsample 0.8 0.2 0.1 --plot $1"
  echo "$light --type point --lumens 100 --plot $1"
  echo "$light inspect $ies --plot-polar $1"
}

while read -r -a command; do
  expect 1 "plot.jpg.*plots are PNG images, so the name must end in .png \(got '.jpg'\)" "${command[@]}"
  [ ! -e plot.jpg ] || fail "a plot.jpg was written by: ${command[*]}"
done < <(plot_commands plot.jpg)

if mknod full c 1 7 2>/dev/null && mknod full.png c 1 7; then
  ln -s full.png link.png
  while read -r -a command; do
    expect 1 "plots are PNG images, so the name must end in .png \(got ''\)" "${command[@]}"
    [ -c full ] || fail "the device 'full' is no longer a character device after: ${command[*]}"
  done < <(plot_commands full)
  for target in full.png link.png; do
    while read -r -a command; do
      expect 2 "cannot write '$target': No space left on device" "${command[@]}"
      [ -c full.png ] || fail "the device 'full.png' is no longer a character device after: ${command[*]}"
      [ -L link.png ] || fail "the link 'link.png' was replaced after: ${command[*]}"
    done < <(plot_commands $target)
  done
else
  echo "SKIP (device cases): mknod needs root"
fi
left=$(find "$TMPDIR" -mindepth 1 -print)
[ -z "$left" ] || fail "left in \$TMPDIR: $left"
left=$(find . -name '.*rimu-*' -print)
[ -z "$left" ] || fail "temporaries left: $left"
[ "$failures" = 0 ] && echo "plots: format by name, devices written by a checked copy and kept"
exit $((failures > 0))
