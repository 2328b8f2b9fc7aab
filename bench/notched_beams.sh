#!/usr/bin/env bash
# Paper 001 §5.2, notched clamped beams (Tables 2 and 3): the seven cases of the
# two tables from examples/notched-beam-links.json (virtual links, the link
# plastic-strain criterion 0.17; spacing H/12 = 0.529 mm), 1 thread each, one
# row per run of the tables in docs/virtual-links.md (bench/notched_beams.py).
# usage: bench/notched_beams.sh [BUILD_DIR [OUT_DIR]]
#   CASES="I:mid:14.2 ..." (type:where:velocity), TREATMENTS="virtual_links damage_aware pseudo_spring"
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=${2:-$(mktemp -d "${TMPDIR:-/tmp}/notched.XXXXXX")}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
mkdir -p "$out"
echo "| treatment | notch | velocity (m/s) | permanent deflection | peak deflection | outcome per notch | broken links (failed particles) | particles | steps | wall time | max balance / impact energy |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for t in ${TREATMENTS:-virtual_links}; do
  for c in ${CASES:-I:mid:14.2 I:mid:18.2 II:mid:19.2 II:mid:27.1 III:supports:18.5 I:supports:17.7 I:supports:31.6}; do
    IFS=: read -r kind where v <<<"$c"
    run=$out/$t-$kind-$where-$v
    "$python" "$here/notched_scene.py" "$here/../examples/notched-beam-links.json" "$kind" "$where" "$v" "$t" "$run.json"
    "$build/tlsph-run" "$run.json" -o "$run" --threads 1 >"$run.log" 2>&1 || true
    printf '| %s | %s %s ' "$t" "$kind" "$where"
    "$python" "$here/notched_beams.py" "$run" "$run.json" "$run.log"
  done
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
