#!/usr/bin/env bash
# pbrt_hostile.sh RIMU RIMU_CONVERT WORKDIR: hostile pbrt inputs (issue 24) through both tools: exit 1 with the
# file (and line) and what was expected, quickly, and nothing written. A top-level .pbrt that is a FIFO, a link to
# /dev/zero or a folder; an include bomb (41 files, each including the next twice: 2^40 reads); an instance bomb
# (10^7 ObjectInstances from eight small files); a Latin-1 byte in a material name; an ObjectBegin never closed.
set -u
rimu=$1; convert=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Both tools on one scene: exit 1 within 120 s, the message matches, no output. A hang is killed by timeout (124).
expect_refused() {  # scene pattern
  local scene=$1 pattern=$2 output code tool
  for tool in rimu convert; do
    rm -f out.exr out.json
    if [ $tool = rimu ]; then
      output=$(timeout 120 "$rimu" "$scene" -o out.exr -q 2>&1); code=$?
    else
      output=$(timeout 120 "$convert" "$scene" -o out.json 2>&1); code=$?
    fi
    [ "$code" = 1 ] || fail "$tool $scene: exit $code, expected 1: $output"
    grep -Eq -- "$pattern" <<<"$output" || fail "$tool $scene: '$output' does not match /$pattern/"
    [ ! -e out.exr ] && [ ! -e out.json ] || fail "$tool $scene wrote an output"
  done
}

camera='LookAt 0 0 -3  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin'

mkfifo fifo.pbrt
expect_refused fifo.pbrt "fifo.pbrt: is a FIFO \(named pipe\); Rimu reads its inputs only from regular files"
ln -s /dev/zero zero.pbrt
expect_refused zero.pbrt "zero.pbrt: is a character device"
mkdir folder.pbrt
expect_refused folder.pbrt "folder.pbrt: is a directory; expected a file"

mkdir bomb
printf '%s\nInclude "f1.pbrt"\nInclude "f1.pbrt"\n' "$camera" >bomb/main.pbrt
for i in $(seq 1 40); do printf 'Include "f%d.pbrt"\nInclude "f%d.pbrt"\n' $((i + 1)) $((i + 1)) >bomb/f$i.pbrt; done
echo 'Shape "sphere"' >bomb/f41.pbrt
expect_refused bomb/main.pbrt "bomb/f[0-9]+\.pbrt:[12]: Include: the scene reads more than 65,536 included files"

mkdir instances  # eight small files: main and i1-i6 include the next ten times, i7 places an instance: 10^7
{ echo "$camera"; echo 'ObjectBegin "o"'; echo 'Shape "sphere" "float radius" 0.01'; echo 'ObjectEnd'
  for _ in $(seq 1 10); do echo 'Include "i1.pbrt"'; done; } >instances/main.pbrt
for level in 1 2 3 4 5 6; do for _ in $(seq 1 10); do echo "Include \"i$((level + 1)).pbrt\""; done >instances/i$level.pbrt; done
echo 'ObjectInstance "o"' >instances/i7.pbrt
# Stopped by the bound on included files, after ~59,000 instances (instances have their own bound, 2^20, tested in
# tests/render/pbrt_include_graph_test.cpp with a small value: reaching 2^20 here would take ~5 s of CPU per tool).
expect_refused instances/main.pbrt "instances/i[0-9]\.pbrt:[0-9]+: Include: the scene reads more than 65,536 included files"

printf '%s\nMakeNamedMaterial "caf\xe9" "string type" "diffuse"\nShape "sphere"\n' "$camera" >latin1.pbrt
expect_refused latin1.pbrt 'latin1.pbrt:5: the quoted string "caf\\xE9" is not UTF-8'

printf '%s\nObjectBegin "tree"\nShape "sphere"\n' "$camera" >unclosed.pbrt
expect_refused unclosed.pbrt 'unclosed.pbrt:5: ObjectBegin "tree" has no ObjectEnd'

[ $failures = 0 ] || exit 1
echo "hostile pbrt inputs: FIFO, /dev/zero, folder, include and instance bombs, Latin-1, unclosed ObjectBegin refused"
