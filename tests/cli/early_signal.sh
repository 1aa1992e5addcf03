#!/usr/bin/env bash
# early_signal.sh RIMU WORKDIR: SIGTERM sent as soon as rimu has started — while it is still loading the scene, long
# before its first sample — stops it as documented (docs/farm.md): exit 0 and the output written (0 samples;
# with --checkpoint a partial that --resume continues), instead of the default action (exit 143, nothing written),
# which is what happened when the handler was installed only after the scene had loaded.
# The scene is a 2-million-triangle PLY (about a second to read and build the BVH for). The signal goes the moment
# the process catches SIGTERM (its SigCgt in /proc) or, at the latest, 0.3 s after the start, still during loading.
set -u
rimu=$1; dir=$2
. "$(dirname "$0")/private_folder.sh"
work_folder "$dir"

python3 - <<'PY'
import struct
n = 1000  # n x n vertices, 2 (n-1)^2 triangles
with open("grid.ply", "wb") as f:
    triangles = 2 * (n - 1) ** 2
    f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
             "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
             % (n * n, triangles)).encode())
    f.write(b"".join(struct.pack("<fff", x / n - 0.5, y / n - 0.5, 0.0) for y in range(n) for x in range(n)))
    faces = bytearray()
    for y in range(n - 1):
        for x in range(n - 1):
            v = y * n + x
            faces += struct.pack("<Biii", 3, v, v + 1, v + n) + struct.pack("<Biii", 3, v + 1, v + n + 1, v + n)
    f.write(faces)
PY
cat > grid.json <<'JSON'
{
  "camera": {"from": [0, 0, -3], "to": [0, 0, 0]},
  "film": {"resolution": [16, 16]},
  "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
  "lights": [{"type": "environment", "radiance": 1}],
  "shapes": [{"type": "mesh", "file": "grid.ply", "material": "grey"}]
}
JSON

# signal_early OUTPUT [OPTIONS]: starts rimu, sends SIGTERM as described above; prints the exit code.
signal_early() {
  local output=$1; shift
  "$rimu" grid.json --spp 64 --threads 1 -q -o "$output" "$@" 2>"$output.log" &
  local pid=$! start
  start=$(date +%s%N)
  while [ $(( ($(date +%s%N) - start) / 1000000 )) -lt 300 ]; do
    caught=$(awk '/^SigCgt:/ {print $2}' /proc/$pid/status 2>/dev/null)
    [ -n "$caught" ] && (( 0x$caught & 0x4000 )) && break
    sleep 0.005
  done
  kill -TERM $pid
  wait $pid
  echo $?
}

code=$(signal_early plain.exr)
[ "$code" = 0 ] || fail "SIGTERM while loading: exit $code (expected 0): $(cat plain.exr.log)"
[ -f plain.exr ] || fail "SIGTERM while loading: no plain.exr written"
code=$(signal_early part.exr --checkpoint 10m)
[ "$code" = 0 ] || fail "SIGTERM while loading, --checkpoint: exit $code: $(cat part.exr.log)"
[ -f part.exr ] || fail "SIGTERM while loading, --checkpoint: no partial written"
"$rimu" --resume part.exr --spp 2 >/dev/null 2>&1 && fail "--resume with --spp was accepted"
"$rimu" --resume part.exr -q 2>resume.log || fail "--resume of the 0-sample partial: $(cat resume.log)"
[ "$failures" = 0 ] && echo "SIGTERM while the scene loads: exit 0, the output written, the partial resumable"
exit $((failures > 0))
