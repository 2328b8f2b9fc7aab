#!/usr/bin/env bash
# The Gurson-family comparison of paper 003 §6.1 on the notched round bar
# R = 2 mm of the Weldox bench: the five variants (Gurson, GTN, SM-Gurson,
# M-Gurson with the critical void fraction 0.0135, and GTN with the critical
# plastic strain 0.35), Table 1's Normal Strength steel (bench/gurson_scene.py).
# Each run is one tlsph-run on 1 thread, JOBS at a time; then a Markdown table
# (bench/weldox_metrics.py's columns) and docs/gurson-r2.svg, the engineering
# stress-strain curves (bench/gurson_report.py).
#
# usage: bench/gurson.sh [OUTDIR]   (default bench/out/gurson)   JOBS=N (default 2)
# About 10 CPU-minutes at the bench spacing of 0.5 mm.
set -euo pipefail
. "$(dirname "$0")/common.sh"
out=${1:-$here/out/gurson}
jobs=${JOBS:-2}
mkdir -p "$out"
one() {
  "$py" "$here/gurson_scene.py" r2 "$1" >"$out/r2-$1.json"
  rm -rf "${out:?}/r2-$1"
  local rc=0
  OMP_NUM_THREADS=1 "$run" "$out/r2-$1.json" -o "$out/r2-$1" --threads 1 --quiet \
    >"$out/r2-$1.log" 2>&1 || rc=$?
  echo "r2-$1 exit $rc" >&2
}
export -f one
export here out run py
printf '%s\n' gurson gtn sm_gurson m_gurson gtn_strain | xargs -P "$jobs" -I{} bash -c 'one {}'
"$py" "$here/gurson_report.py" "$out" "$top/docs/gurson-r2.svg"
