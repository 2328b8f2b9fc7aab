#!/bin/sh
# The readings of paper 003's crack criterion in the tearing test
# (docs/crack-growth.md "Which quantity the criterion reads"): GTN, SM-Gurson
# and M-Gurson under each reading, one run at a time on one thread under nice,
# then the table of bench/tearing_readings.py.
#
#   sum     the paper's: the fibre's summed f (with SM/M-Gurson's shear part)
#           reaches D_c = 0.0135, the points fail by themselves at f_p = 0.0135
#   mean    D_c = 3 x 0.0135 (each particle's mean f at the paper's value)
#   sum-nopf, mean-nopf   the same without the points' own fracture at f_p
#           (fracture_void_fraction 1: a point fails only when its surface
#           collapses), as the paper's text has no failure of a point
#
# usage: bench/tearing_readings.sh BUILDDIR OUTDIR [tearing_scene.py options]
#   e.g. bench/tearing_readings.sh build /tmp/readings --spacing 0.01
set -eu
build=$1
out=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
args=""
for reading in sum mean sum-nopf mean-nopf; do
    case $reading in
    sum) opt="" ;;
    mean) opt="--per-particle" ;;
    sum-nopf) opt="--point-fracture 1" ;;
    mean-nopf) opt="--per-particle --point-fracture 1" ;;
    esac
    mkdir -p "$out/$reading"
    for v in gtn sm_gurson m_gurson; do
        # shellcheck disable=SC2086
        python3 "$here/tearing_scene.py" "$v" $opt "$@" >"$out/$reading/$v.json"
        echo "== $reading $v: $(uptime)"
        nice -n 5 "$build/tlsph-run" "$out/$reading/$v.json" -o "$out/$reading/$v" --threads 1 \
            >"$out/$reading/$v.log" 2>&1 || true
        grep -v "crack tip" "$out/$reading/$v.log" | tail -1
    done
    args="$args $reading=$out/$reading"
done
# shellcheck disable=SC2086
/usr/bin/python3 "$here/tearing_readings.py" $args
