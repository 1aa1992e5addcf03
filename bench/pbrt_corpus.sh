#!/usr/bin/env bash
# Rimu against pbrt-v4 on a corpus of real third-party pbrt scenes (bench/pbrt_corpus.txt): runs
# bench/pbrt_side_by_side.sh on each scene alone, so that a scene Rimu or pbrt cannot load is a row of the summary
# rather than the end of the run, and prints one summary table (docs/benchmarks.md, "Real-scene corpus", was made
# with it). Every image, log and per-scene side-by-side table stays in $OUT.
#
#   bench/pbrt_corpus.sh PBRT_BINARY SCENES [NAME ...]
#
# PBRT_BINARY is a CPU build of pbrt-v4 (never part of this repository). SCENES is the folder that holds the
# repositories' files as SCENES/OWNER+REPO/PATH (the columns of bench/pbrt_corpus.txt). NAMEs pick scenes of the
# list (default: all). Scenes of FORMAT v3 are first rewritten by `PBRT_BINARY --upgrade` into
# corpus_NAME.pbrt next to the original, with the files they Include inlined first (bench/pbrt_v3_upgrade.py: the
# upgrader leaves included files pbrt-v3), and v4 scenes copied to corpus_NAME.pbrt there (unique names: the side
# by side names its work folders after the file). FORMAT v3-standins: upgraded so, then given stand-ins as below.
# FORMAT v4-standins: a v4 scene some of whose files are absent from
# the snapshot, copied by bench/pbrt_corpus_standins.py with those statements replaced (its header says how; the
# format cell counts the replacements, listed in $OUT/NAME.standins.log). Environment: as bench/pbrt_side_by_side.sh (BUILD, OUT
# [/tmp/pbrt_corpus], SPP, REF_SPP, THREADS, RESOLUTION, SPACE), plus NICE [19]: both renderers run under
# `nice -n NICE` (the script's own process is reniced, and the renderers inherit it).
#
# Summary columns: whether each renderer loaded the scene (else the first error line; where pbrt refuses a scene,
# Rimu is tried with one 1-spp render of the same copy); the per-channel mean ratio
# Rimu/pbrt of the two REF_SPP references; the share of 8×8 tiles × channels beyond 3σ between the references and,
# as the test's control, between the two SPP seeds of pbrt and of Rimu; Rimu's time to pbrt's relMSE over pbrt's
# (below 1: Rimu is faster), in render CPU time (the side by side's CPU table) and, in brackets, in the renderers'
# own wall-clock render times; peak RSS of each renderer's SPP render; the number of lines Rimu lists as ignored.
set -uo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 PBRT_BINARY SCENES [NAME ...]" >&2
  exit 1
fi
PBRT=$(realpath "$1")
SCENES=$(realpath "$2")
shift 2
[[ -x "$PBRT" ]] || { echo "$0: $PBRT is not an executable" >&2; exit 1; }
[[ -d "$SCENES" ]] || { echo "$0: $SCENES is not a folder" >&2; exit 1; }
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=$(realpath "${BUILD:-$ROOT/build}")
LIST="$ROOT/bench/pbrt_corpus.txt"
OUT=${OUT:-/tmp/pbrt_corpus}
export OUT
# pbrt-v4's imgtool beside the binary converts pbrt-v3's equirectangular maps for pbrt (bench/pbrt_corpus_standins.py).
if [[ -z "${PBRT_IMGTOOL:-}" && -x "$(dirname "$PBRT")/imgtool" ]]; then export PBRT_IMGTOOL="$(dirname "$PBRT")/imgtool"; fi
renice -n "${NICE:-19}" $$ >/dev/null
mkdir -p "$OUT"

wanted=("$@")
is_wanted() {
  [[ ${#wanted[@]} -eq 0 ]] && return 0
  local w
  for w in "${wanted[@]}"; do [[ $w == "$1" ]] && return 0; done
  return 1
}

# field ROW N: the Nth cell of a markdown row "| a | b | ... |"
# (Split on every "|": a separator of spaces around "|" ran empty cells together, which left the CPU column empty.)
field() { awk -F'|' -v n="$2" '{v = $(n + 1); gsub(/^ +| +$/, "", v); print v}' <<<"$1"; }
# share TESTS BEYOND: "BEYOND/TESTS (P %)"
share() { awk -v t="$1" -v b="$2" 'BEGIN {if (t > 0) printf "%d/%d (%.1f %%)", b, t, 100 * b / t; else print "–"}'; }

echo "# pbrt_corpus: $(date -u '+%Y-%m-%d %H:%M UTC'), load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# SPP=${SPP:-64} REF_SPP=${REF_SPP:-1024} THREADS=${THREADS:-2} RESOLUTION=${RESOLUTION:-scene} NICE=${NICE:-19}"
rows=()
while read -r name repo _commit path format; do
  [[ -z "$name" || $name == \#* ]] && continue
  is_wanted "$name" || continue
  src="$SCENES/${repo/\//+}/$path"
  entry="$(dirname "$src")/corpus_$name.pbrt"
  log="$OUT/$name.side_by_side"
  if [[ ! -f "$src" ]]; then
    rows+=("| $name | $format | missing: $src | | | | | | | | |")
    continue
  fi
  standins_from="$src"
  if [[ $format == v3 || $format == v3-standins ]]; then
    # pbrt's upgrader leaves Included files as they are: bench/pbrt_v3_upgrade.py inlines them first.
    upgraded="$(dirname "$src")/corpus_$name.upgraded.pbrt"
    if ! python3 "$ROOT/bench/pbrt_v3_upgrade.py" "$PBRT" "$src" "$upgraded" 2>"$OUT/$name.upgrade.log"; then
      rows+=("| $name | $format | pbrt --upgrade failed: $(grep -m1 -i error "$OUT/$name.upgrade.log" | sed "s/\x1b\[[0-9;]*m//g" | cut -c1-160) | | | | | | | | |")
      rm -f "$upgraded"
      continue
    fi
    if [[ $format == v3 ]]; then
      mv "$upgraded" "$entry"
    else
      standins_from="$upgraded"
    fi
  fi
  if [[ $format == v4-standins || $format == v3-standins ]]; then
    # Files absent from the snapshot get stand-ins (bench/pbrt_corpus_standins.py); the cell counts them.
    if ! python3 "$ROOT/bench/pbrt_corpus_standins.py" "$standins_from" "$entry" >"$OUT/$name.standins.log" 2>&1; then
      rows+=("| $name | $format | stand-ins failed: $(tail -1 "$OUT/$name.standins.log" | cut -c1-160) | | | | | | | | |")
      continue
    fi
    format="$format ($(grep -c '^standin: ' "$OUT/$name.standins.log"))"
  elif [[ $format != v3 ]]; then
    cp "$src" "$entry"
  fi
  bash "$ROOT/bench/pbrt_side_by_side.sh" "$PBRT" "$entry" >"$log.md" 2>"$log.err"
  status=$?
  work="$OUT/corpus_$name"
  pbrt_ok=yes
  rimu_ok=yes
  if [[ $status -ne 0 ]]; then
    # The side by side stops at the first renderer that fails; pbrt runs first.
    for r in pbrt rimu; do
      if grep -q "^$r failed" "$log.err"; then
        msg=$(grep -v -e '^\s*$' -e '^ignored: ' "$work/$r-s1.log" 2>/dev/null | grep -m1 -i -e error -e cannot -e refus -e unknown -e fail ||
          tail -1 "$work/$r-s1.log" 2>/dev/null)
        msg=$(sed "s/\x1b\[[0-9;]*m//g" <<<"${msg//|/\\|}" | cut -c1-200)
        if [[ $r == rimu ]]; then
          rimu_ok="no: $msg"
          break
        fi
        pbrt_ok="no: $msg"
        # Rimu was not run by the side by side: whether it loads the scene is still worth a row, so one 1-spp
        # render of the copy the side by side prepared (RESOLUTION applied) says so.
        res=()
        [[ -n "${RESOLUTION:-}" ]] && res=(--resolution "$RESOLUTION")
        if "$BUILD_DIR/bin/rimu" "$work/scene/corpus_$name.pbrt" -o "$work/rimu-probe.exr" -q --spp 1 \
          --threads "${THREADS:-2}" "${res[@]}" >"$work/rimu-s1.log" 2>&1; then
          rimu_ok="yes (1-spp probe)"
        else
          msg=$(grep -v -e '^\s*$' -e '^ignored: ' "$work/rimu-s1.log" | head -1)
          rimu_ok="no: $(cut -c1-200 <<<"${msg//|/\\|}")"
        fi
        break
      fi
    done
    [[ $pbrt_ok == yes && $rimu_ok == yes ]] && rimu_ok="side by side failed: $(tail -1 "$log.err" | cut -c1-160)"
    ignored=–
    [[ -f "$work/rimu-s1.log" ]] && ignored=$(grep -c '^ignored: ' "$work/rimu-s1.log")
    rows+=("| $name | $format | $pbrt_ok | $rimu_ok | | | | | | | $ignored |")
    continue
  fi
  refrow=$(grep -m1 "| corpus_$name | rimu-ref / pbrt-ref |" "$log.md")
  pctl=$(grep -m1 "| corpus_$name | pbrt-s2 / pbrt-s1 |" "$log.md")
  rctl=$(grep -m1 "| corpus_$name | rimu-s2 / rimu-s1 |" "$log.md")
  prow=$(grep -m1 "| corpus_$name | pbrt |" "$log.md")
  rrow=$(grep -m1 "| corpus_$name | rimu |" "$log.md")
  eq=$(grep -m1 "| corpus_$name | time to pbrt's relMSE |" "$log.md" | sed -n 's/.*Rimu\/pbrt \([0-9.e+-]*\)).*/\1/p')
  eq_cpu=$(field "$(grep -m1 "| corpus_$name | Rimu/pbrt |" "$log.md")" 10)
  ratio=$(field "$refrow" 5)
  rows+=("| $name | $format | yes | yes | ${ratio//,/, } | $(share "$(field "$refrow" 6)" "$(field "$refrow" 7)") | $(share "$(field "$pctl" 6)" "$(field "$pctl" 7)") | $(share "$(field "$rctl" 6)" "$(field "$rctl" 7)") | $eq_cpu ($eq) | $(field "$prow" 7) / $(field "$rrow" 7) | $(field "$rrow" 9) |")
done <"$LIST"

echo
echo "| scene | format | loads in pbrt | loads in Rimu | mean ratio Rimu/pbrt (R, G, B) | tiles >3σ refs | >3σ pbrt seeds | >3σ Rimu seeds | time to equal error Rimu/pbrt: render CPU (wall) | peak RSS MiB pbrt / Rimu | ignored |"
echo "|---|---|---|---|---|---|---|---|--:|---|--:|"
printf '%s\n' "${rows[@]}"
