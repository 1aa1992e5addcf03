#!/usr/bin/env bash
# scene_files_hash.sh RIMU SCENE_DIR WORKDIR: the scene hash covers the files a scene names. A CSV spectrum edited
# between two partial renders makes `rimu merge` refuse them, `rimu --resume` refuse to continue, and a farm task's
# --expect-scene-hash fail; nothing is written. An untouched copy merges.
set -u
rimu=$1; scene_dir=$2; dir=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
cp -r "$scene_dir" scene
opts=(scene/scene.json --resolution 16x12 --spp 4 --float --threads 1 -q)

hash0=$("$rimu" "${opts[@]}" --print-scene-hash) || fail "--print-scene-hash"
"$rimu" "${opts[@]}" --samples 0:2 -o a.exr || fail "first partial"
"$rimu" "${opts[@]}" --samples 2:4 -o b.exr || fail "second partial"
"$rimu" merge a.exr b.exr -o same.exr 2>same.log || fail "unchanged scene: the merge failed: $(cat same.log)"
# A checkpoint to resume later: a long render killed after its first checkpoint.
"$rimu" scene/scene.json --resolution 16x12 --spp 100000 --threads 1 --checkpoint 0.2s -o ck.exr 2>ck.log &
pid=$!
for _ in $(seq 1 600); do
  grep -q 'rimu: checkpoint' ck.log && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.05
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
grep -q 'rimu: checkpoint' ck.log && [ -f ck.exr ] || fail "no checkpoint to resume: $(cat ck.log)"

# The light's emission spectrum changes between the partials (the scene file itself does not).
sed -i 's/^600,15.6$/600,15.7/' scene/light_emission.csv
grep -q '^600,15.7$' scene/light_emission.csv || fail "the test could not edit the CSV"
hash1=$("$rimu" "${opts[@]}" --print-scene-hash) || fail "--print-scene-hash after the edit"
[ "$hash0" != "$hash1" ] || fail "the scene hash ($hash0) ignores an edit of light_emission.csv"
"$rimu" "${opts[@]}" --samples 2:4 -o c.exr || fail "partial after the edit"

"$rimu" merge a.exr c.exr -o never.exr 2>merge.log; code=$?
[ $code = 1 ] || fail "merge of partials from before and after the edit: exit $code, expected 1: $(cat merge.log)"
grep -q "the files it names.*differs: scene hash" merge.log || fail "merge: unclear message: $(cat merge.log)"
[ ! -e never.exr ] || fail "merge wrote an image although it refused"
cat merge.log

cp ck.exr ck.before.exr
"$rimu" --resume ck.exr -q 2>resume.log; code=$?
[ $code = 1 ] || fail "resume after the edit: exit $code, expected 1: $(cat resume.log)"
grep -q "resuming would mix two scenes" resume.log || fail "resume: unclear message: $(cat resume.log)"
cmp -s ck.exr ck.before.exr || fail "the refused resume changed the checkpoint"
cat resume.log

"$rimu" "${opts[@]}" --samples 0:2 --expect-scene-hash "$hash0" -o never.exr 2>task.log; code=$?
[ $code = 1 ] || fail "a farm task after the edit: exit $code, expected 1: $(cat task.log)"
grep -q "changed after the render was submitted" task.log || fail "farm task: unclear message: $(cat task.log)"
[ ! -e never.exr ] || fail "the farm task wrote an image although the scene changed"
echo "scene files: an edited CSV spectrum changes the hash; merge, resume and a farm task refuse"
