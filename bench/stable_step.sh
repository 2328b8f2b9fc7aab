#!/usr/bin/env bash
# The stable step of the discretisation against the estimates (docs/performance.md,
# "The stable step"):
#  1. bench/stable_step (built with the tree) on the FE Taylor bar
#     (examples/taylor-bar-linear-hardening.json) at SPACING: at 14 times of the
#     impact, the measured leapfrog limit dt_crit = 2/omega_max of the linearised
#     force evaluation, the run's step and both estimates (JSON lines);
#  2. the bar run to 80 us with each /time/step_estimate (1 thread): steps, length,
#     foot, energy balance (bench/taylor_metrics.py);
#  3. the SVG of dt over the impact (bench/stable_step_plot.py) to OUT_SVG.
#
# usage: bench/stable_step.sh [SPACING=0.0008] [OUT_SVG=docs/stable-step-taylor.svg]
# About 5 min of one core at 0.8 mm.
set -euo pipefail
. "$(dirname "$0")/common.sh"
spacing=${1:-0.0008}
svg=${2:-$top/docs/stable-step-taylor.svg}
tool="${BUILD_DIR:-$top/build}/bench/stable_step"
scratch_dir

for est in elastic tangent; do
  "$py" - "$top/examples/taylor-bar-linear-hardening.json" "$spacing" "$est" >"$out/$est.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["bodies"][0]["spacing"] = float(sys.argv[2])
s["time"]["step_estimate"] = sys.argv[3]
s["output"]["frames"] = 4
print(json.dumps(s))
PY
done
OMP_NUM_THREADS=1 "$tool" "$out/tangent.json" 5e-7 1e-6 2e-6 4e-6 7e-6 1e-5 1.5e-5 2e-5 3e-5 4e-5 \
  5e-5 6e-5 7e-5 8e-5 | tee "$out/crit.jsonl"
for est in elastic tangent; do
  OMP_NUM_THREADS=1 "$run" "$out/$est.json" -o "$out/r_$est" --quiet
  echo "$est: $("$py" "$here/taylor_metrics.py" "$out/r_$est" --json)"
done
"$py" "$here/stable_step_plot.py" "$svg" "Time step over the FE Taylor bar ($spacing m)" \
  "$out/r_elastic" "$out/r_tangent" "$out/crit.jsonl"
echo "wrote $svg"
