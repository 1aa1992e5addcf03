#!/usr/bin/env bash
# pbrt_scene_hash.sh RIMU WORKDIR: the scene hash covers every file a pbrt scene reads (issue 24), because it is
# made from the readers' own record of what they opened. Three files the old hash (a second parser of the scene's
# strings) missed: a PLY named inside an Include in a sub-folder (resolved against that sub-folder), a file named
# in single quotes, a file included under a name not ending in .pbrt. Editing any of them changes the hash, and
# partials rendered before and after the edit are refused by `rimu merge`, `rimu --resume` and
# `--expect-scene-hash`; nothing is written. An unchanged scene merges, and --print-scene-hash agrees with the
# hash a render computes from its own load.
set -u
rimu=$1; dir=$2
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

ply() {  # a triangle whose first corner's x is $1
  printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n'
  printf 'element face 1\nproperty list uchar int vertex_indices\nend_header\n%s 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' "$1"
}
make_scene() {
  rm -rf scene; mkdir -p scene/parts/meshes
  cat >scene/main.pbrt <<'PBRT'
LookAt 0.3 0.3 3  0.3 0.3 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 16 "integer yresolution" 12
Sampler "independent" "integer pixelsamples" 4
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Include "parts/room.pbrt"
PBRT
  printf 'Shape "plymesh" "string filename" "meshes/sub.ply"\n' >scene/parts/room.pbrt
  printf "Shape 'plymesh' 'string filename' 'quoted.ply'\nInclude \"extra.inc\"\n" >>scene/main.pbrt
  printf 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\nShape "sphere" "float radius" 0.1\n' >scene/extra.inc
  ply 0 >scene/parts/meshes/sub.ply
  ply 0 >scene/quoted.ply
}
opts=(scene/main.pbrt --spp 4 --float --threads 1 -q)

# edit_name edit-command: renders partials 0:2 and 2:4 before the edit and 2:4 after it, then checks.
check_edit() {
  local name=$1 edit=$2 hash0 hash1 code
  make_scene
  hash0=$("$rimu" "${opts[@]}" --print-scene-hash) || fail "$name: --print-scene-hash"
  "$rimu" "${opts[@]}" --samples 0:2 --expect-scene-hash "$hash0" -o a.exr ||
    fail "$name: a render of the unchanged scene does not hash to --print-scene-hash's $hash0"
  "$rimu" "${opts[@]}" --samples 2:4 -o b.exr || fail "$name: second partial"
  "$rimu" merge a.exr b.exr -o same.exr 2>same.log || fail "$name: unchanged scene: the merge failed: $(cat same.log)"
  # A checkpoint to resume: a long render killed after its first checkpoint.
  rm -f ck.exr
  "$rimu" scene/main.pbrt --spp 100000 --threads 1 --checkpoint 0.2s -o ck.exr 2>ck.log &
  local pid=$!
  for _ in $(seq 1 600); do
    grep -q 'rimu: checkpoint' ck.log && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.05
  done
  kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
  grep -q 'rimu: checkpoint' ck.log && [ -f ck.exr ] || fail "$name: no checkpoint to resume: $(cat ck.log)"
  eval "$edit"
  hash1=$("$rimu" "${opts[@]}" --print-scene-hash) || fail "$name: --print-scene-hash after the edit"
  [ "$hash0" != "$hash1" ] || fail "$name: the scene hash ($hash0) ignores the edit"
  "$rimu" "${opts[@]}" --samples 2:4 -o c.exr || fail "$name: partial after the edit"
  rm -f never.exr
  "$rimu" merge a.exr c.exr -o never.exr 2>merge.log; code=$?
  [ $code = 1 ] || fail "$name: merge of partials from before and after the edit: exit $code: $(cat merge.log)"
  grep -q "differs: scene hash" merge.log || fail "$name: merge: unclear message: $(cat merge.log)"
  [ ! -e never.exr ] || fail "$name: merge wrote an image although it refused"
  cp ck.exr ck.before.exr
  "$rimu" --resume ck.exr -q 2>resume.log; code=$?
  [ $code = 1 ] || fail "$name: resume after the edit: exit $code: $(cat resume.log)"
  grep -q "resuming would mix two scenes" resume.log || fail "$name: resume: unclear message: $(cat resume.log)"
  cmp -s ck.exr ck.before.exr || fail "$name: the refused resume changed the partial"
  "$rimu" "${opts[@]}" --samples 0:2 --expect-scene-hash "$hash0" -o never.exr 2>task.log; code=$?
  [ $code = 1 ] || fail "$name: a farm task after the edit: exit $code: $(cat task.log)"
  grep -q "changed after the render was submitted" task.log || fail "$name: farm task: unclear message: $(cat task.log)"
  [ ! -e never.exr ] || fail "$name: the farm task wrote an image although the scene changed"
  echo "$name: the hash changed ($hash0 -> $hash1); merge, resume and a farm task refuse"
}

check_edit "PLY named in a sub-folder's Include" "ply 0.01 >scene/parts/meshes/sub.ply"
check_edit "PLY named in single quotes" "ply 0.01 >scene/quoted.ply"
check_edit "Include of extra.inc" "sed -i 's/0.1$/0.11/' scene/extra.inc"

# A moved scene folder keeps its hash (files are named relative to the scene's folder).
make_scene
hash0=$("$rimu" "${opts[@]}" --print-scene-hash) || fail "--print-scene-hash"
mv scene moved
hash1=$("$rimu" moved/main.pbrt --spp 4 --float --threads 1 -q --print-scene-hash) || fail "--print-scene-hash, moved"
[ "$hash0" = "$hash1" ] || fail "moving the scene folder changed the hash ($hash0 -> $hash1)"
echo "a moved scene folder keeps its hash"
