#!/bin/sh
# The plate tearing test of paper 003 §6.1 with the five Gurson-family runs
# (docs/crack-growth.md "The tearing test"): one scene per variant from
# bench/tearing_scene.py, run one at a time on one thread under nice, then
# the table and the SVG of bench/tearing_report.py.
#
# usage: bench/tearing.sh BUILDDIR OUTDIR [SVG] [-- tearing_scene.py options]
#   e.g. bench/tearing.sh build /tmp/tearing docs/tearing.svg -- --spacing 0.01
set -eu
build=$1
out=$2
svg=${3:-$out/tearing.svg}
shift 2
[ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
for v in gurson gtn sm_gurson m_gurson gtn_strain; do
    python3 "$here/tearing_scene.py" "$v" "$@" >"$out/$v.json"
    echo "== $v: $(uptime)"
    nice -n 5 "$build/tlsph-run" "$out/$v.json" -o "$out/$v" --threads 1 >"$out/$v.log" 2>&1 || true
    grep -v "crack tip" "$out/$v.log" | tail -3
done
/usr/bin/python3 "$here/tearing_report.py" "$out" "$svg"
