#!/usr/bin/env bash
# readme_commands.sh REPO_ROOT BUILD_DIR
# Runs every command of README.md that starts with build/bin/ inside a ```sh block, in order, as a user would from a
# fresh clone: in a scratch copy of the repository root (every top-level entry linked, build/ pointing at BUILD_DIR),
# so the files a command writes land in the scratch folder and a later command can read them. Each must exit 0.
set -u
repo=$(cd "$1" && pwd); build=$(cd "$2" && pwd)
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-readme.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
for entry in "$repo"/* "$repo"/.[!.]*; do
  [ -e "$entry" ] || continue
  name=$(basename "$entry")
  [ "$name" = build ] || [ "$name" = .git ] || ln -s "$entry" "$scratch/$name"
done
ln -s "$build" "$scratch/build"
cd "$scratch" || exit 1

commands=$(awk '/^```sh[[:space:]]*$/ { inside = 1; next } /^```/ { inside = 0 } inside && /^build\/bin\// { print }' \
           "$repo/README.md")
count=$(grep -c . <<<"$commands")
if [ "$count" -lt 10 ]; then
  echo "found only $count build/bin commands in README.md's sh blocks; the extraction is broken"; exit 1
fi
# A render with --checkpoint is the README's long render (1024 spp of the Cornell box: 2-10 minutes, the rest of the
# README takes about one). It runs as written and is stopped as its comment says, by SIGTERM (what Ctrl-C and
# schedulers send), once rimu handles the signal and has rendered for a moment: it must write its -o file and exit 0.
# Rendering it to the end would check nothing the shorter renders above do not.
stopped_by_sigterm() {
  local command=$1 output_file pid mask
  output_file=$(sed -E 's/.* -o ([^ ]+).*/\1/' <<<"$command")
  rm -f "$output_file"
  bash -c "exec $command" >stopped.log 2>&1 </dev/null &
  pid=$!
  # Bit 15 (SIGTERM) of SigCgt in /proc: a signal before the handler exists would kill rimu with status 143.
  for _ in $(seq 1 1200); do
    mask=$(awk '/^SigCgt:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
    [ -n "$mask" ] && (( (16#$mask >> 14) & 1 )) && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  sleep 2
  kill -TERM "$pid" 2>/dev/null
  wait "$pid"; code=$?
  output=$(cat stopped.log)
  [ "$code" = 0 ] || return
  grep -q interrupted stopped.log || { output="not stopped by SIGTERM (it ended first): $output"; code=1; return; }
  [ -s "$output_file" ] || { output="no $output_file after SIGTERM: $output"; code=1; }
}

failed=0
while IFS= read -r command; do
  note=""
  if [[ $command == *--checkpoint* ]]; then
    stopped_by_sigterm "$command"; note=" (stopped by SIGTERM after its first seconds)"
  else
    output=$(bash -c "$command" 2>&1 </dev/null); code=$?
  fi
  if [ "$code" != 0 ]; then
    echo "FAILED (exit $code): $command"; echo "$output" | tail -20; failed=$((failed + 1))
  else
    echo "ok: $command$note"
  fi
done <<<"$commands"
echo "$((count - failed)) of $count README commands ran"
[ "$failed" = 0 ]
