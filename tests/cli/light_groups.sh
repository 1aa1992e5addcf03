#!/usr/bin/env bash
# light_groups.sh RIMU WORKDIR SOURCE_DIR: light groups from the command line (docs/rendering.md, "Light groups").
# 1. The shipped example renders with a layer per group; `rimu display` rebalances it: every group at 1 is the
#    image as rendered (byte for byte), `--group lamps=0` changes it, --white-balance runs, also on an image
#    white-balanced when rendered.
# 2. The docs' commands run as written (from the source folder, with build/bin/rimu pointing at this build).
# 3. Errors: an unknown group lists the file's groups; --group on an image without groups; malformed options.
set -u
rimu=$1; dir=$2; source=$3
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
scene=$source/data/scenes/examples/light_groups.json

# 1. Render and rebalance.
"$rimu" "$scene" --resolution 40x30 --spp 4 --threads 2 -q -o groups.exr --png groups.png || fail "render"
"$rimu" display groups.exr --png ones.png --group sky=1,sun=1,lamps=1,ungrouped=1 2>ones.log || fail "display: $(cat ones.log)"
cmp -s ones.png groups.png || fail "every group at 1 is not the image as rendered"
"$rimu" display groups.exr --png no_lamps.png --group lamps=0 2>no_lamps.log || fail "display: $(cat no_lamps.log)"
cmp -s no_lamps.png groups.png && fail "--group lamps=0 left the image unchanged"
"$rimu" display groups.exr --png warm.png --white-balance 3200K 2>warm.log || fail "white balance: $(cat warm.log)"
cmp -s warm.png groups.png && fail "--white-balance 3200K left the image unchanged"
# An image white-balanced when rendered: display undoes its balance first (the equality to the unbalanced render's
# display is asserted in tests/render/light_groups_relight_test.cpp, where float rounding can be bounded).
"$rimu" "$scene" --resolution 40x30 --spp 4 --threads 2 -q -o balanced.exr --white-balance A || fail "render balanced"
"$rimu" display balanced.exr --png rebalanced.png --white-balance D65 --group sun=0 2>rebalanced.log ||
  fail "--white-balance on a white-balanced render: $(cat rebalanced.log)"
echo "rebalanced and white-balanced"

# 2. The commands docs/rendering.md shows for light groups, run as written in a copy of the layout they expect.
mkdir -p docs_run/build/bin docs_run/data/scenes/examples
ln -s "$rimu" docs_run/build/bin/rimu
cp "$scene" docs_run/data/scenes/examples/
# The render is made small (its options appended; the display commands take the render's EXR as it is).
sed -n '/^## Light groups/,/^### /p' "$source/docs/rendering.md" | sed -n '/^```sh$/,/^```$/p' | grep '^build/bin/rimu' |
  awk '/^build\/bin\/rimu display/ {print; next} {print $0 " --resolution 40x30 --spp 4 -q"}' > docs_run/commands.sh
[ "$(wc -l <docs_run/commands.sh)" -ge 4 ] || fail "found too few commands in docs/rendering.md: $(cat docs_run/commands.sh)"
(cd docs_run && bash -e commands.sh 2>commands.log) || fail "a docs command failed: $(cat docs_run/commands.log)"
echo "docs commands: $(wc -l <docs_run/commands.sh) ran"

# 3. Errors: exit 1, a message, no image.
"$rimu" display groups.exr --png bad.png --group lamp=0 2>bad.log; code=$?
[ $code = 1 ] || fail "unknown group: exit $code"
grep -q "no light group 'lamp'; its groups are: sky,sun,lamps,ungrouped" bad.log || fail "unknown group: $(cat bad.log)"
[ -e bad.png ] && fail "an image was written for an unknown group"
"$rimu" --resolution 16x12 --spp 2 -q -o plain.exr || fail "plain render"
"$rimu" display plain.exr --png bad.png --group sun=2 2>plain.log; code=$?
[ $code = 1 ] || fail "--group without groups: exit $code"
grep -q -- "--group.*has no light groups" plain.log || fail "--group without groups: $(cat plain.log)"
"$rimu" display groups.exr --png bad.png --group sun 2>malformed.log; code=$?
[ $code = 1 ] && grep -q -- "--group: expected group=scale" malformed.log || fail "malformed --group: $(cat malformed.log)"
"$rimu" display groups.exr --png bad.png --white-balance 0.8,0.5 2>white.log; code=$?
[ $code = 1 ] && grep -q -- "--white-balance: .*x + y < 1" white.log || fail "bad --white-balance: $(cat white.log)"
[ -e bad.png ] && fail "an image was written for a bad option"
echo "errors: unknown group, no groups, malformed options"
