#!/usr/bin/env bash
# Diffuse entry against a refracting boundary (docs/benchmarks.md, "Subsurface: diffuse entry"): skin_ball.pbrt's
# Skin1 ball lit (a) by its grey environment alone and (b) by that environment and a small spherical lamp (r = 5 cm)
# in place of the distant light, which a refracting boundary lets in only through exits that hit it. Both models are
# imported by rimu-convert (pbrt's subsurface gets "diffuse_entry": true); the refracting variant is the same JSON
# without it. Each variant is measured against its own reference: the two are different models, not two estimators
# of one image.
#
#   bench/subsurface/diffuse_entry_bench.sh BUILD [OUT_DIR]
#
# Environment: SPPS ["16 64"], SEEDS ["1 2 3"], REF_SPP [2048]. relMSE is rimu-pbrt-image-compare's over the ball
# (crop 70 20 130 110 of the 200 × 150 image); time is CPU seconds (user + system) under nice 19, 2 threads.
# Writes OUT_DIR/runs.tsv, OUT_DIR/table.md and OUT_DIR/diffuse_entry.png (relMSE against CPU time).
set -euo pipefail
build=$(realpath "$1"); out=${2:-/tmp/diffuse_entry_bench}
here=$(cd "$(dirname "$0")" && pwd); root=$(cd "$here/../.." && pwd)
bin=$build/bin
for tool in rimu rimu-convert rimu-pbrt-image-compare; do
  [[ -x $bin/$tool ]] || { echo "$0: $bin/$tool missing: cmake --build $build --target $tool" >&2; exit 1; }
done
spps=${SPPS:-"16 64"}; seeds=${SEEDS:-"1 2 3"}; ref_spp=${REF_SPP:-2048}
export RIMU_DATA=${RIMU_DATA:-$root/data}
mkdir -p "$out"; cd "$out"
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg), $(git -C "$root" rev-parse --short HEAD)"

# The two lightings, from the bench scene.
sed '/LightSource "distant"/d' "$here/skin_ball.pbrt" > environment.pbrt
awk '/LightSource "distant"/ {print "  Translate 0.8 -0.8 1.2"; print "  AreaLightSource \"diffuse\" \"rgb L\" [300 300 300]";
     print "  Shape \"sphere\" \"float radius\" 0.05"; next} {print}' "$here/skin_ball.pbrt" > lamp.pbrt
for lighting in environment lamp; do
  "$bin/rimu-convert" $lighting.pbrt -o ${lighting}_entry.json 2> /dev/null
  python3 - ${lighting}_entry.json ${lighting}_refract.json <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
for m in d["materials"].values():
    m.pop("diffuse_entry", None)
json.dump(d, open(sys.argv[2], "w"), indent=1)
EOF
done

cpu() { awk '{printf "%.2f", $1 + $2}' "$1"; }
relmse() { "$bin/rimu-pbrt-image-compare" relmse "$1" "$2" --crop 70 20 130 110 | sed -n 's/^relmse=//p'; }
printf 'variant\tspp\tseed\tcpu_s\trelmse\n' > runs.tsv
for variant in environment_refract environment_entry lamp_refract lamp_entry; do
  /usr/bin/time -f "%U %S" -o ref.time nice -n 19 "$bin/rimu" $variant.json -o ref_$variant.exr --spp $ref_spp --seed 99 > /dev/null 2>&1
  for spp in $spps; do for seed in $seeds; do
    /usr/bin/time -f "%U %S" -o run.time nice -n 19 "$bin/rimu" $variant.json -o run.exr --spp $spp --seed $seed > /dev/null 2>&1
    printf '%s\t%s\t%s\t%s\t%s\n' $variant $spp $seed "$(cpu run.time)" "$(relmse run.exr ref_$variant.exr)" | tee -a runs.tsv
  done; done
done

# Table: per variant and budget, the mean CPU time and the median relMSE over the seeds (fireflies make means of
# the refracting lamp runs meaningless).
python3 - <<'EOF' | tee table.md
import csv, statistics
rows = list(csv.DictReader(open("runs.tsv"), delimiter="\t"))
print("| variant | spp | CPU s (mean) | relMSE (median over seeds; all seeds) |")
print("|---|--:|--:|--:|")
for variant in dict.fromkeys(r["variant"] for r in rows):
    for spp in dict.fromkeys(r["spp"] for r in rows):
        runs = [r for r in rows if r["variant"] == variant and r["spp"] == spp]
        errors = [float(r["relmse"]) for r in runs]
        cpu = statistics.mean(float(r["cpu_s"]) for r in runs)
        print(f"| {variant} | {spp} | {cpu:.2f} | {statistics.median(errors):.3g} ({', '.join(r['relmse'] for r in runs)}) |")
EOF
{
  echo "set terminal pngcairo size 560,400 font ',10' noenhanced; set output '$out/diffuse_entry.png'"
  echo "set datafile separator tab; set logscale xy; set xlabel 'CPU time (s, user + system, 2 threads)'; set ylabel 'relMSE (ball)'"
  echo "set key outside right; set title 'Skin1 ball: refracting boundary vs diffuse entry'"
  plot="plot"
  for variant in environment_refract environment_entry lamp_refract lamp_entry; do
    plot+=" '$out/runs.tsv' using (strcol(1) eq '$variant' ? \$4 : 1/0):5 with points title '$variant',"
  done
  echo "${plot%,}"
} | gnuplot
echo "wrote $out/table.md, $out/runs.tsv, $out/diffuse_entry.png"
