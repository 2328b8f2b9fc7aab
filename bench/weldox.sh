#!/usr/bin/env bash
# The Weldox case study of paper 000 §6 at bench resolution: three alloys
# (460E, 700E, 900E) x three specimens (smooth, notched R = 2 mm, notched
# R = 0.4 mm) x three damage models (Johnson-Cook, Cockcroft-Latham, GTN), plus
# the pseudo-spring treatment on the 460E Johnson-Cook case of each specimen,
# to show the instability the damage-aware approximation removes.
#
# Scenes come from bench/weldox_scene.py (geometry, loading and resolution are
# stated there); each run is one whole tlsph-run process on 1 OpenMP thread,
# JOBS of them at a time.  One Markdown table row per run from
# bench/weldox_metrics.py: peak engineering stress and its strain, the strains
# at damage initiation, first failure and separation, the notch-section
# averages, the load rise between failure and separation, particle count,
# steps, wall time and the run's status.
#
# usage: bench/weldox.sh [OUTDIR]   (default bench/out/weldox; results are kept)
#        JOBS=N (default 2)  CASES="460e:r2:jc ..." to run a subset
# Takes about an hour on the project's 2-core machine (about 115 CPU-minutes,
# JOBS=2).
set -euo pipefail
. "$(dirname "$0")/common.sh"
out=${1:-$here/out/weldox}
jobs=${JOBS:-2}
mkdir -p "$out"

if [ -z "${CASES:-}" ]; then
  CASES=""
  # the R = 0.4 mm bars are the most expensive: start them first
  for geo in r04 r2 smooth; do
    for alloy in 460e 700e 900e; do
      for model in jc cl gtn; do CASES="$CASES $alloy:$geo:$model"; done
    done
  done
  for geo in r04 r2 smooth; do CASES="$CASES 460e:$geo:jc:pseudo_spring"; done
fi

# ALLOY:GEOMETRY:MODEL[:TREATMENT] -> alloy geo model treatment, and the run's name
parse_case() {
  IFS=: read -r alloy geo model treatment <<<"$1"
  treatment=${treatment:-damage_aware}
  name="$alloy-$geo-$model"
  if [ "$treatment" = pseudo_spring ]; then name="$name-pseudo-spring"; fi
}

one() { # ALLOY:GEOMETRY:MODEL[:TREATMENT] -> OUTDIR/<name>/
  parse_case "$1"
  "$py" "$here/weldox_scene.py" "$alloy" "$geo" "$model" --treatment "$treatment" \
    >"$out/$name.json"
  run_scene "$out" "$name"
}
export -f parse_case one
export here out run py
# shellcheck disable=SC2086
run_parallel one "$jobs" $CASES

"$py" "$here/weldox_metrics.py" --header
for c in $CASES; do
  parse_case "$c"
  "$py" "$here/weldox_metrics.py" "$out/$name/result.h5" "$name" ||
    echo "| $name | no result: see $out/$name.log |"
done
