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
failed=0
while IFS= read -r command; do
  output=$(bash -c "$command" 2>&1 </dev/null); code=$?
  if [ "$code" != 0 ]; then
    echo "FAILED (exit $code): $command"; echo "$output" | tail -20; failed=$((failed + 1))
  else
    echo "ok: $command"
  fi
done <<<"$commands"
echo "$((count - failed)) of $count README commands ran"
[ "$failed" = 0 ]
