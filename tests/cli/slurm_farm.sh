#!/usr/bin/env bash
# slurm_farm.sh REPO RIMU RIMU_FARM COMPARE WORKDIR: a real Slurm (scripts/slurm-local.sh: munged, slurmctld, slurmd
# on this machine) runs rimu-farm's 4-task job array and its dependent merge; the merged image equals a
# single-process render within the merge's bound (1 float32 ULP). If the daemons cannot start, prints a loud SKIP
# and exits 77 (CTest SKIP_RETURN_CODE): a skipped test shows as "Skipped" in CTest's summary, never as passed.
set -u
repo=$1; rimu=$2; farm=$3; compare=$4; dir=$5
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

if ! started=$(RIMU_SLURM_DIR="$dir/slurm" "$repo/scripts/slurm-local.sh" start 2>&1); then
  echo "################################################################################"
  echo "SKIP: the single-node Slurm cluster could not start, so the farm test did not run:"
  echo "$started"
  echo "################################################################################"
  exit 77
fi
eval "$(grep '^export SLURM_CONF=' <<<"$started")"
trap 'RIMU_SLURM_DIR="$dir/slurm" "$repo/scripts/slurm-local.sh" stop' EXIT
scene=$repo/data/scenes/cornell_box/scene.json
options=(--resolution 32x24 --float --threads 1)

"$farm" submit "$scene" --spp 16 --tasks 4 --out "$dir/run" -- "${options[@]}" || fail "rimu-farm submit"
merge_job=$(python3 -c "import json; print(json.load(open('$dir/run/farm.json'))['merge_job'])")
for _ in $(seq 1 300); do   # bounded: 5 minutes
  [ -z "$(squeue -h -j "$merge_job" 2>/dev/null)" ] && break
  sleep 1
done
[ -z "$(squeue -h -j "$merge_job" 2>/dev/null)" ] || { squeue; fail "the merge job is still queued after 5 minutes"; }
# status works without an accounting database (this cluster has none): scontrol's record of the finished jobs.
"$farm" status "$dir/run" >status.txt 2>&1 || fail "rimu-farm status: $(cat status.txt)"
cat status.txt
grep -Eq "^ *${merge_job} +COMPLETED +0:0" status.txt || fail "rimu-farm status does not show the merge job $merge_job COMPLETED"
[ "$(grep -Ec '^ *[0-9]+_[0-3] +COMPLETED +0:0' status.txt)" = 4 ] || fail "rimu-farm status does not show 4 COMPLETED tasks"
cat "$dir"/run/logs/merge-*.out
[ -f run/final.exr ] || fail "no merged image; logs: $(cat "$dir"/run/logs/*)"
ls run/parts
"$rimu" "$scene" --spp 16 -q -o single.exr "${options[@]}" 2>/dev/null || fail "single render"
"$compare" single.exr run/final.exr --image-only --max-ulps 1 || fail "the farm's image differs from the single render"
echo "slurm farm: 4 tasks on Slurm merged to the single-process image"
