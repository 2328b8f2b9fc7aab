#!/usr/bin/env bash
# Graded vs uniform spacing on the R = 0.4 mm notched Weldox 700E bar with
# Johnson-Cook damage (issue 18 item 2, docs/damage.md#graded-spacing-on-the-r--04-mm-notch):
# the engineering strain at first failure against the cost of the run.
#  uniform  u060, u045, u030, u020: the whole bar at 0.6, 0.45, 0.3, 0.2 mm;
#  graded   g030 (0.6 mm, the notch section at 0.3 mm), g015 (0.6 -> 0.15 mm),
#           g020 (0.8 -> 0.2 mm), grading 2 (weldox_scene.py --refine).
# Runs stop at 26 us (engineering strain 0.093), the two coarsest at 36 us
# (0.14): past every first failure of the ladder.  Each run is one tlsph-run process on 1 OpenMP thread, JOBS at a
# time; one row per run from bench/weldox_metrics.py (particles, steps, wall).
#
# usage: bench/weldox_graded.sh [OUTDIR]   (default bench/out/weldox_graded)
#        JOBS=N (default 1)  CASES="u030 g030 ..." to run a subset
# The full ladder takes about 1.5 CPU-hours (u020 and g015 most of it).
set -euo pipefail
. "$(dirname "$0")/common.sh"
out=${1:-$here/out/weldox_graded}
jobs=${JOBS:-1}
mkdir -p "$out"
CASES=${CASES:-"u060 u045 u030 g030 g020 g015 u020"}

args_of() { # case -> weldox_scene.py spacing arguments
  case $1 in
    u060) echo "--end 3.6e-5 --spacing 0.0006" ;;
    u045) echo "--end 3.6e-5 --spacing 0.00045" ;;
    u030) echo "--end 2.6e-5 --spacing 0.0003" ;;
    u020) echo "--end 2.6e-5 --spacing 0.0002" ;;
    g030) echo "--end 2.6e-5 --spacing 0.0006 --refine 0.0003 --grading 2" ;;
    g015) echo "--end 2.6e-5 --spacing 0.0006 --refine 0.00015 --grading 2" ;;
    g020) echo "--end 2.6e-5 --spacing 0.0008 --refine 0.0002 --grading 2" ;;
    *) echo "unknown case $1" >&2; return 1 ;;
  esac
}

one() {
  # shellcheck disable=SC2046
  "$py" "$here/weldox_scene.py" 700e r04 jc $(args_of "$1") >"$out/$1.json"
  run_scene "$out" "$1"
}
export -f one args_of
export here out run py
# shellcheck disable=SC2086
run_parallel one "$jobs" $CASES

"$py" "$here/weldox_metrics.py" --header
for c in $CASES; do
  "$py" "$here/weldox_metrics.py" "$out/$c/result.h5" "$c" ||
    echo "| $c | no result: see $out/$c.log |"
done
