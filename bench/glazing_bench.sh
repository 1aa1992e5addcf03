#!/usr/bin/env bash
# glazing_bench.sh BUILD [SPP] [REFERENCE_SPP] [SEEDS]
# The glazed daylit room against the open one (docs/benchmarks.md, "Glazing"). Three versions of
# data/scenes/interiors/daylit_room_*.json, their lights ×1000 so that the relMSE's absolute floor (0.01 in
# rimu-pbrt-image-compare) is negligible against pixel values (the image only scales):
#   open        the open window
#   glazed      two thin_dielectric panes: shadow rays pass them
#   glazed_old  the same panes as a 50/50 "mix" of the pane with itself, which shadow rays do not pass: the
#               behaviour before glazing was passed (NEE blocked at the pane, the pane a specular vertex)
# Prints relMSE at SPP (per seed) against a REFERENCE_SPP render of each (glazed_old against glazed's: both
# converge to the same image), and instructions per camera sample under callgrind (80×45, 1 thread; the difference
# of a 16- and a 4-spp run, so loading cancels). Renders run at nice 19.
set -eu
build=$1; spp=${2:-16}; ref_spp=${3:-256}; seeds=${4:-"1 2 3"}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-glazing.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
python3 - "$root/data/scenes/interiors" "$scratch" <<'PY'
import json, sys
source, out = sys.argv[1], sys.argv[2]
for name in ["open", "glazed"]:
    s = json.load(open(f"{source}/daylit_room_{name}.json"))
    for light in s["lights"]:
        for key in ("illuminance_lx", "luminance_nt"):
            if key in light: light[key] *= 1000
    json.dump(s, open(f"{out}/{name}.json", "w"))
    if name == "glazed":
        s["materials"]["clear"] = s["materials"]["glass"]
        s["materials"]["glass"] = {"type": "mix", "materials": ["clear", "clear"], "amount": 0.5}
        json.dump(s, open(f"{out}/glazed_old.json", "w"))
PY
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for n in open glazed; do nice -n 19 "$rimu" -q "$scratch/$n.json" -o "$scratch/ref_$n.exr" --spp "$ref_spp" --seed 99 --threads 2; done
for n in open glazed glazed_old; do
  ref=$scratch/ref_$n.exr; [ "$n" = glazed_old ] && ref=$scratch/ref_glazed.exr
  for seed in $seeds; do
    nice -n 19 "$rimu" -q "$scratch/$n.json" -o "$scratch/$n.exr" --spp "$spp" --seed "$seed" --threads 2
    echo "$n seed $seed spp $spp: $("$compare" relmse "$scratch/$n.exr" "$ref")"
  done
  count() { nice -n 19 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$rimu" -q "$scratch/$n.json" \
              -o "$scratch/cg.exr" --spp "$1" --resolution 80x45 --threads 1 2>&1 | sed -n 's/.*Collected : //p'; }
  i16=$(count 16); i4=$(count 4)
  echo "$n: $(( (i16 - i4) / (80 * 45 * 12) )) instructions per camera sample"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
