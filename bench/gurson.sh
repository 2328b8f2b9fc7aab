#!/usr/bin/env bash
# The Gurson-family comparison of paper 003 §6.1 on two specimens, the notched
# round bar R = 2 mm of the Weldox bench (mode I, high triaxiality) and a block
# in simple shear: the five variants (Gurson, GTN, SM-Gurson, M-Gurson with the
# critical void fraction 0.0135, and GTN with the critical plastic strain
# 0.35), Table 1's Normal Strength steel (bench/gurson_scene.py); and the
# Johnson-Cook accumulated damage of paper 003 §5 on the same matrix (jc).  Each run is
# one tlsph-run on 1 thread, JOBS at a time; then the tables and
# docs/gurson-r2.svg, docs/gurson-shear.svg (bench/gurson_report.py).
#
# usage: bench/gurson.sh [OUTDIR]   (default bench/out/gurson)   JOBS=N (default 2)
#        VARIANTS="jc ..." runs only those (the report reads every run in OUTDIR)
# About 15 CPU-minutes at the bench spacings (0.5 mm bar, 0.4 mm block).
set -euo pipefail
. "$(dirname "$0")/common.sh"
out=${1:-$here/out/gurson}
jobs=${JOBS:-2}
mkdir -p "$out"
one() { # SPECIMEN-VARIANT
  local specimen=${1%%-*} variant=${1#*-} rc=0
  "$py" "$here/gurson_scene.py" "$specimen" "$variant" >"$out/$1.json"
  rm -rf "${out:?}/$1"
  OMP_NUM_THREADS=1 "$run" "$out/$1.json" -o "$out/$1" --threads 1 --quiet \
    >"$out/$1.log" 2>&1 || rc=$?
  echo "$1 exit $rc" >&2
}
export -f one
export here out run py
for specimen in r2 shear; do
  for variant in ${VARIANTS:-gurson gtn sm_gurson m_gurson gtn_strain jc}; do echo "$specimen-$variant"; done
done | xargs -P "$jobs" -I{} bash -c 'one {}'
"$py" "$here/gurson_report.py" "$out" "$top/docs/gurson-r2.svg" "$top/docs/gurson-shear.svg"
