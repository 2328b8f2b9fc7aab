#!/usr/bin/env bash
# Paper 001 §5.1 with virtual links: examples/projectile-beam-links.json at four
# beam spacings (5, 7, 10 and 15 particles through the depth; 15 is the paper's
# 0.423 mm), 1 thread each,
# one row per run of the table in docs/virtual-links.md (bench/links_beam.py).
# usage: bench/links_beam.sh [BUILD_DIR [OUT_DIR]]; SPACINGS="..." (m) to run others
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=${2:-$(mktemp -d "${TMPDIR:-/tmp}/links_beam.XXXXXX")}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
mkdir -p "$out"
echo "| spacing (particles through H) | beam particles | steps | peak deflection | permanent deflection | vs eq. 36 | broken links | max balance / impact energy | wall time |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in ${SPACINGS:-0.00127 0.000907143 0.000635 0.000423}; do
  sed "s/\"spacing\": 0.000635/\"spacing\": $s/" "$here/../examples/projectile-beam-links.json" \
    >"$out/beam-$s.json"
  "$build/tlsph-run" "$out/beam-$s.json" -o "$out/beam-$s" --threads 1 >"$out/beam-$s.log" 2>&1
  "$python" "$here/links_beam.py" "$out/beam-$s" "$out/beam-$s.log"
done
