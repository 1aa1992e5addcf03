#!/usr/bin/env bash
# image_messages.sh RIMU WORKDIR: a broken PNG texture (a bad chunk CRC; a file cut short inside its image data) is
# reported in one message of Rimu's that names the file (exit 1). libpng's own lines ("libpng error: IHDR: CRC
# error", which name no file) no longer reach standard error on their own: every line there starts with "rimu:".
set -u
rimu=$1; dir=$2
. "$(dirname "$0")/private_folder.sh"
work_folder "$dir"

python3 - <<'PY'
import struct, zlib
def chunk(kind, data, crc=None):
    crc = zlib.crc32(kind + data) if crc is None else crc
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc & 0xffffffff)
width, height = 16, 16
ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
rows = b"".join(b"\0" + bytes([200, 100, 50]) * width for _ in range(height))
idat = zlib.compress(rows)
signature = b"\x89PNG\r\n\x1a\n"
good = signature + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")
open("good.png", "wb").write(good)
open("bad_crc.png", "wb").write(signature + chunk(b"IHDR", ihdr, crc=0xdeadbeef) + chunk(b"IDAT", idat) + chunk(b"IEND", b""))
open("truncated.png", "wb").write(signature + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat)[: 8 + len(idat) // 3])
PY

for png in good bad_crc truncated; do
  cat > $png.json <<JSON
{
  "camera": {"from": [0, 0, -3], "to": [0, 0, 0]},
  "film": {"resolution": [8, 8]},
  "materials": {"poster": {"type": "diffuse", "reflectance": {"texture": "$png.png"}}},
  "lights": [{"type": "environment", "radiance": 1}],
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "poster"}]
}
JSON
done
"$rimu" good.json --spp 1 -q -o good.exr 2>good.log || fail "the good PNG: $(cat good.log)"
[ ! -s good.log ] || fail "the good PNG printed: $(cat good.log)"
for png in bad_crc truncated; do
  "$rimu" $png.json --spp 1 -q -o $png.exr 2>$png.log; code=$?
  [ "$code" = 1 ] || fail "$png.png: exit $code (expected 1): $(cat $png.log)"
  grep -q "$png.png" $png.log || fail "$png.png: the message does not name the file: $(cat $png.log)"
  stray=$(grep -v '^rimu: ' $png.log)
  [ -z "$stray" ] || fail "$png.png: a line not from Rimu on stderr: $stray"
done
[ "$failures" = 0 ] && echo "broken PNGs: one message naming the file, nothing from libpng on its own"
exit $((failures > 0))
