#!/usr/bin/env python3
"""rimu-farm: render a scene (or a sequence) on a Slurm cluster as a job array of partial renders and a merge.

  rimu-farm submit SCENE --spp 4096 --tasks 16 [--frames 1-100] [--partition P] [--time 1:00:00]
                   [--out DIR] [--checkpoint 10m] [--no-submit] [-- RIMU OPTIONS, e.g. --film spectral:47]
  rimu-farm status DIR      squeue, and sacct (or scontrol without accounting) for the jobs submitted from DIR
  rimu-farm collect DIR     merge what the tasks wrote (as the merge job does), e.g. after fixing a failed task

Thin on purpose: every task runs `rimu --samples A:B`, the merge job runs `rimu merge`. The scripts it writes into
DIR (render.sbatch, merge.sbatch) are plain bash with #SBATCH lines: read them, or reuse their two commands in
another scheduler's wrapper (docs/farm.md). Exit codes: 0 ok, 1 bad input, 2 Slurm or rimu failed.
"""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys


# The renderer's own limits (tools/rimu/main.cpp --spp, render/output/partial_record.cpp --samples): a farm asking for more
# would submit tasks that all fail.
MAX_SPP = 1 << 24
# Frames per submission: each frame costs one `rimu --print-scene-hash` at submission and its tasks in the array.
MAX_FRAMES = 10000
# Slurm's largest possible MaxArraySize is 4000001 (array indices 0-4000000); most clusters allow far fewer (1001 by
# default), and sbatch then refuses the array itself.
MAX_ARRAY_TASKS = 4000001


def fail(message, code=1):
    print(f"rimu-farm: {message}", file=sys.stderr)
    sys.exit(code)


def check_script_value(option, value):
    """Refuses a value that reaches a job script if it holds a control character (a newline, carriage return, tab,
    NUL, escape...). In an #SBATCH header line nothing is quoted, so a newline there would end the line and start a
    command (and cut off the #SBATCH lines after it); in the body the values are quoted, but a script whose lines are
    exactly the lines it was meant to have is easier to read and to trust. Every such value goes through here."""
    for i, ch in enumerate(value):
        if ord(ch) < 32 or ord(ch) == 127 or 0x80 <= ord(ch) < 0xA0 or ch in "\u2028\u2029":
            fail(f"{option}: the value {value!r} holds the control character {ch!r} (at {i}); a job script line "
                 f"cannot hold it: rename or choose another value")
    return value


def find_rimu(explicit):
    if explicit:
        return os.path.abspath(explicit)
    beside = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rimu")
    if os.access(beside, os.X_OK):
        return beside
    found = shutil.which("rimu")
    if not found:
        fail("cannot find the rimu binary (next to rimu-farm or on PATH); give --rimu")
    return found


def parse_frames(text):
    if text is None:
        return None
    try:
        first, _, last = text.partition("-")
        first, last = int(first), int(last or first)
    except ValueError:
        fail(f"--frames: expected FIRST-LAST, e.g. 1-100; got '{text}'")
    if last < first:
        fail(f"--frames: the last frame {last} comes before the first {first}")
    return first, last


def sample_ranges(spp, tasks):
    """[0, spp) cut into `tasks` contiguous ranges whose sizes differ by at most one."""
    return [(spp * i // tasks, spp * (i + 1) // tasks) for i in range(tasks)]


def scene_hash(rimu, scene, frame, rimu_options):
    command = [rimu, scene, "--print-scene-hash", *rimu_options] + ([] if frame is None else ["--frame", str(frame)])
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write(result.stderr)
        fail(f"rimu could not hash the scene {scene}", result.returncode)
    return result.stdout.strip()


def sbatch_header(name, out, partition, time_limit, extra):
    lines = ["#!/bin/bash", f"#SBATCH --job-name={name}", f"#SBATCH --output={out}", "#SBATCH --ntasks=1"]
    if partition:
        lines.append(f"#SBATCH --partition={partition}")
    if time_limit:
        lines.append(f"#SBATCH --time={time_limit}")
    return "\n".join(lines + extra) + "\n"


def write_scripts(args, rimu, scene, frames, hashes, out):
    ranges = sample_ranges(args.spp, args.tasks)
    frame_list = list(range(frames[0], frames[1] + 1)) if frames else [None]
    tasks = len(ranges) * len(frame_list)
    rimu_options = " ".join(shlex.quote(o) for o in args.rimu_options)
    frame_words = " ".join("-" if f is None else str(f) for f in frame_list)
    hash_words = " ".join(hashes)
    range_words = " ".join(f"{a}:{b}" for a, b in ranges)
    checkpoint = f"--checkpoint {shlex.quote(args.checkpoint)}" if args.checkpoint else ""
    render = sbatch_header(f"rimu-{os.path.basename(scene)}", f"{out}/logs/render-%A_%a.out", args.partition,
                           args.time, [f"#SBATCH --array=0-{tasks - 1}", "#SBATCH --requeue",
                                       "#SBATCH --signal=TERM@60  # rimu writes a checkpoint on SIGTERM"])
    render += f"""
# One partial render per array task: task i renders sample range i % {len(ranges)} of frame i / {len(ranges)}.
# Each writes its own file, named after its range, so a requeued or rerun task replaces (or resumes) its own
# partial and nothing is counted twice; `rimu merge` refuses overlapping ranges anyway.
set -euo pipefail
rimu={shlex.quote(rimu)}
scene={shlex.quote(scene)}
ranges=({range_words})
frames=({frame_words})
hashes=({hash_words})   # the scene hash of each frame at submission: a task refuses a scene changed since
part=$((SLURM_ARRAY_TASK_ID % ${{#ranges[@]}}))
index=$((SLURM_ARRAY_TASK_ID / ${{#ranges[@]}}))
frame=${{frames[$index]}}
range=${{ranges[$part]}}
frame_options=()
dir={shlex.quote(out)}/parts
if [ "$frame" != "-" ]; then frame_options=(--frame "$frame"); dir="$dir/frame.$frame"; fi
mkdir -p "$dir"
output="$dir/samples.${{range/:/-}}.exr"
if [ -f "$output" ]; then
  # A checkpoint of an earlier run of this task (requeued after a node failure or a time limit): continue it.
  exec "$rimu" --resume "$output" -q
fi
exec "$rimu" "$scene" --spp {args.spp} --samples "$range" "${{frame_options[@]}}" \\
  --expect-scene-hash "${{hashes[$index]}}" {checkpoint} -q -o "$output" {rimu_options}
"""
    merge = sbatch_header(f"rimu-merge-{os.path.basename(scene)}", f"{out}/logs/merge-%j.out", args.partition,
                          args.time, [])
    merge += f"""
# Runs after every render task succeeded (submitted with --dependency=afterok:<render job>): one merge per frame.
# rimu merge checks that the partials belong to one render and cover all {args.spp} samples; it writes nothing
# otherwise and exits 1.
set -euo pipefail
rimu={shlex.quote(rimu)}
out={shlex.quote(out)}
for frame in {frame_words}; do
  if [ "$frame" = "-" ]; then
    "$rimu" merge "$out"/parts/samples.*.exr --final -o "$out/final.exr"
  else
    "$rimu" merge "$out/parts/frame.$frame"/samples.*.exr --final -o "$out/frame.$frame.exr"
  fi
done
"""
    os.makedirs(os.path.join(out, "logs"), exist_ok=True)
    for name, text in (("render.sbatch", render), ("merge.sbatch", merge)):
        with open(os.path.join(out, name), "w") as f:
            f.write(text)
        os.chmod(os.path.join(out, name), 0o755)
    return tasks


def sbatch(arguments):
    result = subprocess.run(["sbatch", "--parsable", *arguments], capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write(result.stderr)
        fail("sbatch failed: " + " ".join(arguments), 2)
    return result.stdout.strip().split(";")[0]


def check_submit_values(args, rimu=None, scene=None, out=None):
    """Every value that is written into render.sbatch or merge.sbatch, checked before anything runs or is written:
    first as given, then (rimu, scene, out) made absolute, since the current folder's name becomes part of them."""
    values = [("scene", args.scene), ("--out", args.out), ("--rimu", args.rimu), ("--partition", args.partition),
              ("--time", args.time), ("--checkpoint", args.checkpoint), ("scene", scene), ("--out", out),
              ("--rimu", rimu)] + [("a rimu option after --", value) for value in args.rimu_options]
    for option, value in values:
        if value:
            check_script_value(option, value)


def submit(args):
    check_submit_values(args)
    if not 1 <= args.spp <= MAX_SPP:
        fail(f"--spp {args.spp}: expected 1-{MAX_SPP}, the renderer's limit")
    if args.tasks < 1 or args.spp < args.tasks:
        fail(f"--tasks {args.tasks} must be in 1-{args.spp} (at least one sample per task)")
    frames = parse_frames(args.frames)
    frame_count = frames[1] - frames[0] + 1 if frames else 1
    if frame_count > MAX_FRAMES:
        fail(f"--frames {args.frames}: {frame_count} frames; at most {MAX_FRAMES} per submission (each is hashed "
             f"at submission and gets its own tasks): split the sequence into several submissions")
    if args.tasks * frame_count > MAX_ARRAY_TASKS:
        fail(f"--tasks {args.tasks} x {frame_count} frames = {args.tasks * frame_count} array tasks; Slurm allows "
             f"at most {MAX_ARRAY_TASKS} in one array")
    rimu = find_rimu(args.rimu)
    scene = os.path.abspath(args.scene)
    if not os.path.isfile(scene):
        fail(f"{args.scene}: no such scene file")
    out = os.path.abspath(args.out or os.path.splitext(os.path.basename(scene))[0] + ".farm")
    check_submit_values(args, rimu, scene, out)
    hashes = [scene_hash(rimu, scene, f, args.rimu_options)
              for f in (range(frames[0], frames[1] + 1) if frames else [None])]
    tasks = write_scripts(args, rimu, scene, frames, hashes, out)
    record = {"scene": scene, "spp": args.spp, "tasks": args.tasks, "frames": args.frames, "hashes": hashes}
    if args.no_submit:
        print(f"rimu-farm: wrote {out}/render.sbatch ({tasks} tasks) and {out}/merge.sbatch; submit with\n"
              f"  job=$(sbatch --parsable {out}/render.sbatch) && sbatch --dependency=afterok:$job {out}/merge.sbatch")
    else:
        if not shutil.which("sbatch"):
            fail("sbatch not found: is this a Slurm submit host? (--no-submit writes the scripts only)", 2)
        record["render_job"] = sbatch([os.path.join(out, "render.sbatch")])
        record["merge_job"] = sbatch([f"--dependency=afterok:{record['render_job']}", os.path.join(out, "merge.sbatch")])
        print(f"rimu-farm: submitted render job {record['render_job']} ({tasks} tasks) and merge job "
              f"{record['merge_job']}; `rimu-farm status {out}`")
    with open(os.path.join(out, "farm.json"), "w") as f:
        json.dump(record, f, indent=2)


def load_record(directory):
    try:
        with open(os.path.join(directory, "farm.json")) as f:
            return json.load(f)
    except OSError as e:
        fail(f"{directory}: not a rimu-farm folder ({e.strerror}: farm.json)")


def sacct_table(jobs):
    """sacct's table of the jobs, or None when Slurm keeps no accounting (a cluster without slurmdbd: sacct then
    fails or says that accounting storage is disabled)."""
    if not shutil.which("sacct"):
        return None
    result = subprocess.run(["sacct", "--jobs", ",".join(jobs), "--format=JobID%20,State,ExitCode,Elapsed"],
                            capture_output=True, text=True)
    if result.returncode != 0 or "disabled" in result.stderr or "disabled" in result.stdout:
        return None
    return result.stdout


def scontrol_rows(job):
    """One row per job (or array task) slurmctld still knows (finished jobs stay for MinJobAge, 300 s by default):
    (JobId_ArrayTaskId, JobState, ExitCode, RunTime), from `scontrol show job -o`; None if it no longer knows it."""
    result = subprocess.run(["scontrol", "show", "job", "-o", job], capture_output=True, text=True)
    if result.returncode != 0:
        return None
    rows = []
    for line in result.stdout.splitlines():
        fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
        name = fields.get("JobId", "?")
        if fields.get("ArrayTaskId"):
            name = f"{fields.get('ArrayJobId', name)}_{fields['ArrayTaskId']}"
        rows.append((name, fields.get("JobState", "?"), fields.get("ExitCode", "?"), fields.get("RunTime", "?")))
    return rows


def status(args):
    record = load_record(args.dir)
    jobs = [j for j in (record.get("render_job"), record.get("merge_job")) if j]
    if not jobs:
        fail(f"{args.dir}: its scripts were written with --no-submit; nothing to ask Slurm about")
    if not shutil.which("squeue"):
        fail("squeue is not on PATH: is this a Slurm login node?", 2)
    print("queued or running (squeue):")
    sys.stdout.flush()
    # squeue fails for a job id slurmctld has forgotten; the answer below may still hold it.
    answered = subprocess.run(["squeue", "--jobs", ",".join(jobs), "--array",
                               "--format=%.18i %.9T %.10M %.20R"]).returncode == 0
    table = sacct_table(jobs)
    if table is not None:
        print("accounting (sacct):")
        print(table, end="")
        answered = True
    else:
        # No accounting database: slurmctld's own memory of the jobs (finished ones for MinJobAge) is the record.
        print("all states (scontrol show job; this cluster keeps no accounting, so finished jobs are listed only "
              "for slurmctld's MinJobAge):")
        print(f"{'JOB':>20} {'STATE':>12} {'EXIT':>6} {'TIME':>10}")
        for job in jobs:
            rows = scontrol_rows(job)
            if rows is None:
                print(f"{job:>20} {'FORGOTTEN':>12}      -          -   (no longer known to slurmctld: see "
                      f"{os.path.join(args.dir, 'logs')} and the partials in {os.path.join(args.dir, 'parts')})")
                continue
            answered = True
            for name, state, exit_code, run_time in rows:
                print(f"{name:>20} {state:>12} {exit_code:>6} {run_time:>10}")
    sys.exit(0 if answered else 2)


def collect(args):
    load_record(args.dir)
    result = subprocess.run(["bash", os.path.join(args.dir, "merge.sbatch")])
    sys.exit(0 if result.returncode == 0 else (1 if result.returncode == 1 else 2))


def main():
    parser = argparse.ArgumentParser(prog="rimu-farm", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    s = commands.add_parser("submit", help="write and submit the job array and the merge job")
    s.add_argument("scene")
    s.add_argument("--spp", type=int, required=True, help="samples per pixel of the whole render")
    s.add_argument("--tasks", type=int, required=True, help="partial renders per frame (sample ranges)")
    s.add_argument("--frames", help="FIRST-LAST: a sequence (the scene uses ${frame}; docs/scene-format.md)")
    s.add_argument("--partition", help="Slurm partition")
    s.add_argument("--time", help="Slurm time limit per task, e.g. 1:00:00")
    s.add_argument("--checkpoint", default="10m", help="checkpoint interval of each task (default 10m; '' for none)")
    s.add_argument("--out", help="folder for scripts, logs, partials and images (default SCENE.farm)")
    s.add_argument("--rimu", help="the rimu binary the tasks run (default: next to rimu-farm, or on PATH)")
    s.add_argument("--no-submit", action="store_true", help="write the scripts, do not submit")
    st = commands.add_parser("status", help="squeue/sacct for a submitted folder")
    st.add_argument("dir")
    c = commands.add_parser("collect", help="merge what the tasks wrote (as the merge job does)")
    c.add_argument("dir")
    argv = sys.argv[1:]
    rimu_options = argv[argv.index("--") + 1:] if "--" in argv else []  # after --: more rimu options
    args = parser.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    args.rimu_options = rimu_options
    if args.command == "submit":
        submit(args)
    elif args.command == "status":
        status(args)
    else:
        collect(args)


if __name__ == "__main__":
    main()
