# Helpers shared by the render benchmarks (sourced; bash). The caller sets rimu (the binary), threads and
# resolution before calling render.

# render FILE SPP SEED OUT.exr: renders FILE under nice 19 (32-bit floats; log in OUT.exr.log) and prints the CPU
# seconds (user + system) of the whole process.
render() {
  /usr/bin/time -f "%U %S" -o "$4.time" nice -n 19 "$rimu" -q "$1" -o "$4" --float --spp "$2" --seed "$3" \
    --threads "$threads" --resolution "$resolution" >"$4.log" 2>&1
  awk '{s = $1 + $2} END {printf "%.2f", s}' "$4.time"
}

# with_integrator_key SOURCE.json OUT.json KEY VALUE: the scene with integrator.KEY = VALUE (VALUE read as JSON
# where it parses, e.g. 8, else as a string, e.g. light_tracing).
with_integrator_key() {
  python3 - "$@" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
try:
    value = json.loads(sys.argv[4])
except ValueError:
    value = sys.argv[4]
scene.setdefault("integrator", {})[sys.argv[3]] = value
json.dump(scene, open(sys.argv[2], "w"))
PY
}
