#!/usr/bin/env bash
# sphere_lights_bench.sh BUILD [SPP] [REFERENCE_SPP] [SEEDS]
# Emissive spheres as analytic lights against the same spheres tessellated (docs/transport.md, "Emissive spheres"):
# bench/pbrt_scenes/sphere_lights_plates.pbrt (four spheres of 0.03-1 m over four glossy plates, after Veach's MIS
# scene) and sphere_lights_plates_mesh.pbrt, the same with each sphere squashed by 10⁻⁵, which the importer
# tessellates (9,024 triangles per sphere, one light tree leaf each). Prints, per version:
#   - relMSE at SPP (per seed) against that version's own REFERENCE_SPP render (2 threads), over the plates (rows
#     40-119: the glossy reflections) and over the whole image, whose relMSE the spheres seen directly dominate (a
#     0.03 m sphere of 555× the largest one's radiance covers part of a pixel: its edge pixels' errors against a
#     near-black reference outweigh everything else, in both versions alike);
#   - instructions per camera sample under callgrind (80×60, 1 thread; the difference of a 16- and a 4-spp run, so
#     loading cancels), and the instructions of loading (the 4-spp run less 4/12 of that difference);
#   - peak RSS and wall time of a 1-spp render (/usr/bin/time -v): what loading costs.
# Time to equal error (analytic over mesh) is then (relMSE_a · instructions_a) / (relMSE_m · instructions_m) per
# sample at equal spp. Renders run at nice 19.
set -eu
build=$1; spp=${2:-16}; ref_spp=${3:-512}; seeds=${4:-"1 2 3"}
rimu=$build/bin/rimu; compare=$build/bin/rimu-pbrt-image-compare
root=$(cd "$(dirname "$0")/.." && pwd); export RIMU_DATA=${RIMU_DATA:-$root/data}
scenes=$root/bench/pbrt_scenes
scratch=$(mktemp -d "${TMPDIR:-/tmp}/rimu-sphere-lights.XXXXXX"); trap 'rm -rf "$scratch"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for n in sphere_lights_plates sphere_lights_plates_mesh; do
  scene=$scenes/$n.pbrt
  nice -n 19 /usr/bin/time -v -o "$scratch/time.txt" "$rimu" -q "$scene" -o "$scratch/one.exr" --spp 1 --threads 2 >/dev/null 2>&1
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$scratch/time.txt")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + t[i]; print s}' "$scratch/time.txt")
  echo "$n: 1-spp render: peak RSS $rss MiB, wall $wall s"
  nice -n 19 "$rimu" -q "$scene" -o "$scratch/ref.exr" --spp "$ref_spp" --seed 99 --threads 2 >/dev/null
  for seed in $seeds; do
    nice -n 19 "$rimu" -q "$scene" -o "$scratch/run.exr" --spp "$spp" --seed "$seed" --threads 2 >/dev/null
    plates=$("$compare" relmse "$scratch/run.exr" "$scratch/ref.exr" --crop 0 40 160 120 | sed 's/relmse=//')
    whole=$("$compare" relmse "$scratch/run.exr" "$scratch/ref.exr" | sed 's/relmse=//')
    echo "$n seed $seed spp $spp: relMSE plates $plates, whole image $whole"
  done
  count() { nice -n 19 valgrind --tool=callgrind --callgrind-out-file=/dev/null "$rimu" -q "$scene" \
              -o "$scratch/cg.exr" --spp "$1" --resolution 80x60 --threads 1 2>&1 | sed -n 's/.*Collected : //p'; }
  i16=$(count 16); i4=$(count 4)
  per_sample=$(( (i16 - i4) / (80 * 60 * 12) ))
  echo "$n: $per_sample instructions per camera sample; loading $(( (i4 - per_sample * 80 * 60 * 4) / 1000000 )) M instructions"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
