#!/usr/bin/env bash
# Paper 001 §5.3, Kalthoff-Winkler: examples/kalthoff-links.json at several
# spacings and crack treatments, 1 thread each; one row per run of the tables in
# docs/virtual-links.md (crack angle by bench/kalthoff_angle.py, PNG of the
# crack paths by bench/kalthoff_plot.py when matplotlib is there).
# usage: bench/kalthoff.sh [BUILD_DIR [OUT_DIR]]
#   SPACINGS="0.002 0.001 0.0005" (m), TREATMENTS="virtual_links damage_aware pseudo_spring"
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=${2:-$(mktemp -d "${TMPDIR:-/tmp}/kalthoff.XXXXXX")}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
mkdir -p "$out"
echo "| treatment | spacing | crack angle (fit) | vs 70° | chord | first 10 mm | length | crack particles | particles | steps | wall time | max balance / external work |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for t in ${TREATMENTS:-virtual_links damage_aware pseudo_spring}; do
  for s in ${SPACINGS:-0.002 0.001 0.0005}; do
    run=$out/$t-$s
    "$python" "$here/kalthoff_scene.py" "$here/../examples/kalthoff-links.json" "$s" "$t" "$run.json"
    "$build/tlsph-run" "$run.json" -o "$run" --threads 1 >"$run.log" 2>&1 || true
    printf '| %s ' "$t"
    "$python" "$here/kalthoff_angle.py" "$run" "$run.log" --row
  done
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
