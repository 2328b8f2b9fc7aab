#!/usr/bin/env bash
# Accuracy vs cost of the Taylor bar, and the throughput of the plastic engine.
#
#  1. Accuracy: each Taylor example (examples/taylor-bar.json: OFHC copper,
#     Johnson-Cook with rate and thermal terms, 190 m/s, against the Johnson &
#     Cook 1983 experiment; examples/taylor-bar-linear-hardening.json: the
#     Zienkiewicz/Foulk finite-element benchmark, 227 m/s) run to 80 us at three
#     spacings; one table row per run: final length, foot diameter, max plastic
#     strain, energy split (fractions of the impact energy), particles, steps,
#     wall time (bench/taylor_metrics.py defines every column).
#  2. Speed: the Johnson-Cook bar at spacing 0.3 mm (~4.3e4 particles), the
#     first STEPS steps (the impact is under way: plasticity, rate term and
#     heating active) with 1 and 2 OpenMP threads: particle-steps per second of
#     the run loop (whole process wall clock of tlsph-run's loop: output and
#     stability checks included, scene parsing excluded).
#
# The hourglass spring is the scene's default (tangent for plastic materials since
# 2026-11-26); HOURGLASS_STIFFNESS=elastic reproduces the tables measured before.
#
# usage: bench/taylor_bar.sh [accuracy|speed|all] [STEPS]   (default all, 1500 steps)
# Takes about 30 min on the project's 2-core machine for "all".
set -euo pipefail
. "$(dirname "$0")/common.sh"
what=${1:-all}
steps=${2:-1500}
scratch_dir

# scene FILE SPACING MAX_STEPS FRAMES > copy with the body's spacing (m) replaced
scene() {
  "$py" - "$@" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1]))
s["bodies"][0]["spacing"] = float(sys.argv[2])
if int(sys.argv[3]) > 0:
    s["time"]["max_steps"] = int(sys.argv[3])
s["output"]["frames"] = int(sys.argv[4])
s.setdefault("limits", {})["max_particles"] = 2000000
if os.environ.get("HOURGLASS_STIFFNESS"):
    hg = s.setdefault("discretization", {}).setdefault("hourglass", {})
    hg["stiffness"] = os.environ["HOURGLASS_STIFFNESS"]
print(json.dumps(s))
PY
}

if [ "$what" = accuracy ] || [ "$what" = all ]; then
  echo "| example | h (mm) | particles | steps | wall (s) | p-steps/s | L_f (mm) | D_foot (mm) | max eps_p | max T (K) | plastic | hourglass | wall loss | KE left | balance |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  for ex in taylor-bar taylor-bar-linear-hardening; do
    case $ex in
      taylor-bar) spacings="0.0006 0.00045 0.0003" ;;
      *) spacings="0.0006 0.0004 0.0003" ;;
    esac
    for h in $spacings; do
      scene "$top/examples/$ex.json" "$h" 0 4 >"$out/s.json"
      rm -rf "$out/r"
      OMP_NUM_THREADS=2 "$run" "$out/s.json" -o "$out/r" --quiet
      "$py" "$here/taylor_metrics.py" "$out/r" --json | "$py" -c "
import json, sys
m = json.load(sys.stdin)
print('| $ex | %.2f | %d | %d | %.0f | %.3g | %.2f | %.2f | %.2f | %.0f | %.3f | %.3f | %.3f | %.4f | %+.4f |' % (
    m['spacing_mm'], m['particles'], m['steps'], m['wall_seconds'], m['particle_steps_per_second'],
    m['length_mm'], m['foot_diameter_mm'], m['max_plastic_strain'], m['max_temperature_K'],
    m['plastic_work'], m['hourglass'], m['wall_loss'], m['kinetic_left'], m['balance']))"
    done
  done
fi

if [ "$what" = speed ] || [ "$what" = all ]; then
  echo
  echo "| scene | particles | threads | steps | p-steps/s | p-steps/s per thread | engine B/particle |"
  echo "|---|---:|---:|---:|---:|---:|---:|"
  scene "$top/examples/taylor-bar.json" 0.0003 "$steps" 1 >"$out/s.json"
  for threads in 1 2; do
    rm -rf "$out/r"
    "$run" "$out/s.json" -o "$out/r" --threads "$threads" --quiet
    "$py" "$here/taylor_metrics.py" "$out/r" --json | "$py" -c "
import json, sys
m = json.load(sys.stdin)
print('| taylor-bar (Johnson-Cook, rate + heating) h = 0.3 mm | %d | $threads | %d | %.3g | %.3g | %.0f |' % (
    m['particles'], m['steps'], m['particle_steps_per_second'],
    m['particle_steps_per_second'] / $threads, m['bytes_per_particle']))"
  done
fi
