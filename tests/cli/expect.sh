#!/usr/bin/env bash
# expect.sh EXIT_CODE PATTERN -- COMMAND...
# Runs COMMAND; passes if it exits with EXIT_CODE and its output (stdout+stderr) matches the regex PATTERN.
set -u
want_code=$1; pattern=$2; shift 3
output=$("$@" 2>&1); code=$?
if [ "$code" != "$want_code" ]; then
  echo "expected exit code $want_code, got $code from: $*"; echo "$output"; exit 1
fi
if ! grep -Eq -- "$pattern" <<<"$output"; then
  echo "output of '$*' does not match /$pattern/:"; echo "$output"; exit 1
fi
