#!/usr/bin/env bash
# Paper 001 §5.1 with virtual links: examples/projectile-beam-links.json at four
# beam spacings (5, 7, 10 and 15 particles through the depth; 15 is the paper's
# 0.423 mm), 1 thread each,
# one row per run of the table in docs/virtual-links.md (bench/links_beam.py).
# usage: bench/links_beam.sh [BUILD_DIR [OUT_DIR]]; SPACINGS="..." (m) to run others,
#   VELOCITIES="..." (m/s, default 20) for the deflection against eq. 36 at other speeds
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=${2:-$(mktemp -d "${TMPDIR:-/tmp}/links_beam.XXXXXX")}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
mkdir -p "$out"
echo "| spacing (particles through H) | velocity | beam particles | steps | peak deflection | permanent deflection | eq. 36 | vs eq. 36 | broken links | max balance / impact energy | wall time |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for v in ${VELOCITIES:-20}; do
  for s in ${SPACINGS:-0.00127 0.000907143 0.000635 0.000423}; do
    run=$out/beam-$s-$v
    sed -e "s/\"spacing\": 0.000635/\"spacing\": $s/" -e "s/\"velocity\": \[0, -20, 0\]/\"velocity\": [0, -$v, 0]/" \
      "$here/../examples/projectile-beam-links.json" >"$run.json"
    "$build/tlsph-run" "$run.json" -o "$run" --threads 1 >"$run.log" 2>&1
    "$python" "$here/links_beam.py" "$run" "$run.log"
  done
done
