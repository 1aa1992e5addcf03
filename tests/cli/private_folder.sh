# Sourced by the CLI tests that need a folder of their own and count failures (colour_graphic.sh, plots_security.sh, …).
# private_folder PREFIX: makes a fresh folder (removed on exit) with a private $TMPDIR inside it, exports $MARK (the
# absolute path an injected `touch $MARK` would create, wherever it ran) and changes into the folder ($work).
# work_folder DIR: the same for a folder the test names (under the build tree, kept for a look after a failure): made
# fresh and entered.
# fail MESSAGE: reports one failure and counts it in $failures; the script ends with `exit $((failures > 0))`.
private_folder() {
  work=$(mktemp -d "${TMPDIR:-/tmp}/$1-XXXXXX")
  trap 'rm -rf "$work"' EXIT
  mkdir "$work/tmp"
  export TMPDIR="$work/tmp" MARK="$work/INJECTED"
  cd "$work" || exit 1
}
work_folder() {
  rm -rf "$1"; mkdir -p "$1"; cd "$1" || exit 1
}
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
