#!/usr/bin/env bash
# Sweep pbrt-v4 scenes written for pbrt, not for Rimu: import and render each at a tiny resolution under a time
# limit and print one markdown row per scene (docs/pbrt-import.md, "Scenes of pbrt-v4-scenes", was made with it).
#
#   bench/pbrt_scene_sweep.sh SCENE.pbrt ...
#
# Environment (defaults in brackets): BUILD [build] (with bin/rimu), OUT [/tmp/pbrt_scene_sweep], RESOLUTION
# [32x32], SPP [4], LIMIT [300] (seconds per rimu run, under `timeout`), THREADS [2], STANDINS [1].
#
# Each scene is first run as it is. Scenes copied from a repository snapshot often lack their big files (PLY
# meshes, textures, environment maps, included geometry: over the snapshot's size limit, or Git LFS pointers).
# With STANDINS=1 the scene's folder is then copied to $OUT/standins/ and every file Rimu reports missing is
# replaced there by a stand-in, one at a time, until the scene loads or nothing more can be stood in for:
#   *.ply, *.ply.gz  a unit quad with uv (ASCII PLY, gzip-compressed for .gz)
#   *.png            a 4×4 grey ramp, 8-bit sRGB (written here: no image library needed)
#   *.exr            an 8×8 render of Rimu's built-in Cornell box (square, so also a valid equal-area sky)
#   *.pbrt           one unit quad per material the scene's .pbrt files name with MakeNamedMaterial
#   *.spd            a constant spectrum of 1 (two "wavelength value" lines)
#   *.bsdf           a rough gold written in the measured-BRDF form by bin/rimu-make-measured-bsdf (when built)
# Anything else (a .nvdb, ...) is left missing. The stand-ins test what the importer makes of every
# statement of the real files; the pictures are of course not the scenes'. Rows say which files were stood in.
#
# Columns: the first run's outcome (ok, or the error's first line); with stand-ins: the outcome, the number of
# stand-ins, the render wall time, and the distinct "ignored:" lines (what Rimu lists as unsupported or
# approximated). Exit statuses: 1 = input error (expected for a missing file), 2 = library/machine failure,
# 124 = the time limit (a hang), 128+ = a crash: the last two are bugs.
set -uo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(realpath "${BUILD:-$ROOT/build}")
RIMU="$BUILD/bin/rimu"
[[ -x "$RIMU" ]] || { echo "$0: $RIMU missing: cmake --build $BUILD --target rimu" >&2; exit 1; }
OUT=${OUT:-/tmp/pbrt_scene_sweep}
RESOLUTION=${RESOLUTION:-32x32}
SPP=${SPP:-4}
LIMIT=${LIMIT:-300}
THREADS=${THREADS:-2}
STANDINS=${STANDINS:-1}
mkdir -p "$OUT/standins" "$OUT/logs"

# run_rimu SCENE TAG: renders SCENE, leaves its stderr in $OUT/logs/TAG.log; prints "STATUS SECONDS"
run_rimu() {
  local scene=$1 tag=$2 start end status
  start=$(date +%s.%N)
  timeout "$LIMIT" nice -n 19 "$RIMU" "$scene" --resolution "$RESOLUTION" --spp "$SPP" --threads "$THREADS" \
    -o "$OUT/logs/$tag.exr" >"$OUT/logs/$tag.out" 2>"$OUT/logs/$tag.log"
  status=$?
  end=$(date +%s.%N)
  awk -v s="$status" -v a="$start" -v b="$end" 'BEGIN { printf "%s %.1f\n", s, b - a }'
}

# outcome TAG STATUS: a short text for the table
outcome() {
  local tag=$1 status=$2 first
  case $status in
    0) echo "ok" ;;
    124) echo "**hang** (over ${LIMIT} s)" ;;
    1 | 2)
      first=$(grep -m1 -i 'error' "$OUT/logs/$tag.log" || head -1 "$OUT/logs/$tag.log")
      echo "exit $status: \`${first//|/\\|}\`" ;;
    *) echo "**crash** (exit $status)" ;;
  esac
}

write_png() { # write_png FILE: a 4×4 8-bit RGB grey ramp
  python3 - "$1" <<'PY'
import struct, sys, zlib
w = h = 4
rows = b''.join(b'\0' + bytes(v for x in range(w) for v in (40 + 50 * x, 40 + 50 * y, 120) ) for y in range(h))
def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
png += chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b'')
open(sys.argv[1], 'wb').write(png)
PY
}

write_ply() { # write_ply FILE: a unit quad with uv
  cat >"$1" <<'PLY'
ply
format ascii 1.0
comment stand-in written by bench/pbrt_scene_sweep.sh
element vertex 4
property float x
property float y
property float z
property float u
property float v
element face 1
property list uchar int vertex_indices
end_header
0 0 0 0 0
1 0 0 1 0
1 1 0 1 1
0 1 0 0 1
4 0 1 2 3
PLY
}

write_geometry() { # write_geometry FILE SCENE_FOLDER: a quad per named material
  {
    echo "# stand-in written by bench/pbrt_scene_sweep.sh: one quad per named material"
    grep -rhoE '^[[:space:]]*MakeNamedMaterial[[:space:]]+"[^"]*"' --include='*.pbrt' "$2" |
      sed -E 's/^[[:space:]]*MakeNamedMaterial[[:space:]]+//' | sort -u | while read -r name; do
        echo "NamedMaterial $name"
        echo 'Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point3 P" [ 0 0 0 1 0 0 1 1 0 0 1 0 ]'
        echo '    "point2 uv" [ 0 0 1 0 1 1 0 1 ]'
      done
  } >"$1"
}

# missing_file TAG FOLDER: the first file the log names that does not exist under FOLDER
missing_file() {
  local tag=$1 folder=$2 path
  while read -r path; do
    [[ -n "$path" && "$path" == "$folder"* && ! -e "$path" ]] && { echo "$path"; return; }
  done < <(grep -oE "'[^']+'|/[^ :']+\.(ply|ply\.gz|png|exr|pbrt|pfm|hdr|tga|jpg|spd|bsdf)" "$OUT/logs/$tag.log" | tr -d "'")
}

echo "| scene | as it is | with stand-ins | stood in | render s | listed as ignored |"
echo "|---|---|---|---|---|---|"
for scene in "$@"; do
  scene=$(realpath "$scene")
  dir=$(dirname "$scene")
  name="$(basename "$dir")/$(basename "$scene" .pbrt)"
  tag=${name//\//_}
  read -r status seconds < <(run_rimu "$scene" "$tag")
  first=$(outcome "$tag" "$status")
  second="—"; stood=0; secs=$seconds; ignored=""
  log="$OUT/logs/$tag.log"
  if [[ $status == 1 && $STANDINS == 1 ]]; then
    copy="$OUT/standins/$(basename "$dir")"
    rm -rf "$copy"; cp -r "$dir" "$copy"
    copy=$(realpath "$copy")
    target="$copy/$(basename "$scene")"
    : >"$OUT/logs/$tag.standins"
    while true; do
      read -r status secs < <(run_rimu "$target" "$tag.standin")
      [[ $status == 1 ]] || break
      file=$(missing_file "$tag.standin" "$copy")
      [[ -n "$file" ]] || break
      mkdir -p "$(dirname "$file")"
      case "$file" in
        *.ply.gz) write_ply "${file%.gz}" && gzip -f "${file%.gz}" ;;
        *.ply) write_ply "$file" ;;
        *.png) write_png "$file" ;;
        *.exr) nice -n 19 "$RIMU" --resolution 8x8 --spp 1 --threads "$THREADS" -o "$file" >/dev/null 2>&1 ;;
        *.pbrt) write_geometry "$file" "$copy" ;;
        *.spd) printf '360 1\n830 1\n' >"$file" ;;
        *.bsdf) "$BUILD/bin/rimu-make-measured-bsdf" "$file" >/dev/null 2>&1 ;;
        *) break ;;
      esac
      [[ -e "$file" ]] || break
      echo "${file#$copy/}" >>"$OUT/logs/$tag.standins"
      stood=$((stood + 1))
    done
    second=$(outcome "$tag.standin" "$status")
    log="$OUT/logs/$tag.standin.log"
  fi
  ignored=$(grep -oE '^ignored: [^(]*' "$log" | sed -E 's/^ignored: //; s/ +$//' | sort -u | paste -sd ';' - |
    sed 's/;/; /g; s/|/\\|/g')
  echo "| $name | $first | $second | $stood | $secs | ${ignored:-none} |"
done
