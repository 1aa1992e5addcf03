#!/usr/bin/env bash
# farm_scripts.sh RIMU RIMU_FARM COMPARE SCENE WORKDIR: the scripts rimu-farm writes, run without Slurm (each array
# task by hand, as any scheduler's wrapper could): a two-frame ${frame} sequence in 2 sample ranges per frame,
# merged, equals single-process renders of each frame (within the merge's 1-ULP bound); a task whose scene changed
# after submission refuses to render (exit 1).
set -u
rimu=$1; farm=$2; compare=$3; scene=$4; dir=$5
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

"$farm" submit "$scene" --spp 8 --tasks 2 --frames 1-2 --no-submit --out "$dir/seq" -- --float \
  || fail "rimu-farm submit --no-submit"
for task in 0 1 2 3; do
  SLURM_ARRAY_TASK_ID=$task bash seq/render.sbatch 2>>tasks.log || fail "task $task: $(cat tasks.log)"
done
"$farm" collect seq || fail "rimu-farm collect"
for frame in 1 2; do
  "$rimu" "$scene" --frame $frame --spp 8 --float -q -o single.$frame.exr 2>/dev/null || fail "single render of frame $frame"
  "$compare" single.$frame.exr seq/frame.$frame.exr --image-only --max-ulps 1 || fail "frame $frame: merged differs"
done
"$compare" seq/frame.1.exr seq/frame.2.exr --image-only --max-ulps 0 >/dev/null && fail "frames 1 and 2 are the same image"

cp "$scene" copy.json
"$farm" submit copy.json --spp 8 --tasks 2 --frames 1-1 --no-submit --out "$dir/changed" >/dev/null || fail "submit copy"
echo " " >> copy.json   # any change of the bytes changes the hash
output=$(SLURM_ARRAY_TASK_ID=0 bash changed/render.sbatch 2>&1); code=$?
[ $code = 1 ] || fail "a changed scene: exit code $code, expected 1: $output"
grep -q "changed after the render was submitted" <<<"$output" || fail "a changed scene: message: $output"
echo "farm scripts: 2 frames x 2 ranges merged as single renders; a changed scene refused"
