# Sourced by the CLI tests that hand tools hostile file names (colour_graphic.sh, plots_security.sh).
# private_folder PREFIX: makes a fresh folder (removed on exit) with a private $TMPDIR inside it, exports $MARK (the
# absolute path an injected `touch $MARK` would create, wherever it ran) and changes into the folder ($work).
# fail MESSAGE: reports one failure and counts it in $failures; the script ends with `exit $((failures > 0))`.
private_folder() {
  work=$(mktemp -d "${TMPDIR:-/tmp}/$1-XXXXXX")
  trap 'rm -rf "$work"' EXIT
  mkdir "$work/tmp"
  export TMPDIR="$work/tmp" MARK="$work/INJECTED"
  cd "$work" || exit 1
}
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
