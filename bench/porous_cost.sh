#!/usr/bin/env bash
# Cost of plasticity with and without a porous model (docs/damage.md, "Cost"):
# whole-process wall and CPU time of tlsph-run on 1 thread for the cases of
# bench/porous_cost.py, this tree's engine against a base engine (BASE, e.g.
# the build of the commit before a change) on the same scenes, runs
# interleaved (case by case, engine by engine, REPEATS rounds) so that the
# load of a shared machine hits all of them alike; the report takes medians.
#
# usage: BASE=/path/to/base/tlsph-run bench/porous_cost.sh [OUTDIR]
#        REPEATS=N (default 5)  SPACING=H (default 0.0008 m)
# About 1-2 CPU-minutes per round.
set -euo pipefail
. "$(dirname "$0")/common.sh"
out=${1:-$here/out/porous_cost}
base=${BASE:?set BASE to the tlsph-run of the base engine}
repeats=${REPEATS:-5}
h=${SPACING:-0.0008}
cases="plastic jc000 jc003 gtn gtn_aravas sm_gurson"
mkdir -p "$out"
: >"$out/times.txt"
for c in $cases; do "$py" "$here/porous_cost.py" scene "$c" "$h" >"$out/$c.json"; done
uptime >"$out/load.txt"
for r in $(seq "$repeats"); do
  for c in $cases; do
    for engine in base new; do
      exe=$run
      [ "$engine" = base ] && exe=$base
      # the base engine knows no johnson_cook_accumulated
      [ "$engine" = base ] && [ "$c" = jc003 ] && continue
      rm -rf "${out:?}/run"
      # wall and CPU (user + system) seconds of the whole process: on a loaded
      # machine the CPU time is the steadier measure of the work done
      /usr/bin/time -f "%e %U %S" -o "$out/time.txt" env OMP_NUM_THREADS=1 \
        "$exe" "$out/$c.json" -o "$out/run" --threads 1 --quiet >/dev/null 2>&1
      read -r steps n share < <("$py" -c "
import h5py, sys
c = h5py.File('$out/run/result.h5', 'r')['cost'].attrs
print(int(c['steps']), int(c['particles']), float(c.get('material_phase_share', float('nan'))))")
      read -r wall user sys <"$out/time.txt"
      echo "$engine $c $r $wall $(echo "$user + $sys" | bc) $steps $n $share" >>"$out/times.txt"
    done
  done
  uptime >>"$out/load.txt"
done
rm -rf "${out:?}/run" "$out/time.txt"
"$py" "$here/porous_cost.py" report "$out"
