#!/usr/bin/env bash
# Do 2 OpenMP threads beat 1, on an idle machine and beside other work?
#
# The copper Taylor bar (examples/taylor-bar.json: Johnson-Cook with rate and
# thermal terms, a wall) at two spacings, ~5e3 particles (0.6 mm) and ~4e4
# (0.3 mm), the first STEPS steps, with 1 and 2 threads, each
#   idle:     nothing else started by this script, and
#   busy:     beside one CPU-bound process (`yes > /dev/null`), the daemon's
#             normal condition when a second job or a study runs.
# The runs are interleaved (1, 2, 1, 2, ...) so that a change in the
# machine's load hits both thread counts alike; three rounds, medians.
# Engines wait at barriers passively (OMP_WAIT_POLICY=passive, as tlsphd
# starts them; set WAIT_POLICY to compare).  Particle-steps per second are
# the engine's own (/cost particle_steps_per_second: the run loop, output
# and stability checks included).  Prints the load average before and after:
# numbers taken on a shared machine say so.
#
# usage: bench/threads.sh [STEPS_5K] [STEPS_40K]   (default 600 and 150 steps)
# About 4 min on the project's 2-core machine when idle.
set -euo pipefail
. "$(dirname "$0")/common.sh"
steps5=${1:-600}
steps40=${2:-150}
rounds=${ROUNDS:-3}
export OMP_WAIT_POLICY=${WAIT_POLICY:-passive}
scratch_dir
hog=""
stop_hog() { if [ -n "$hog" ]; then kill "$hog" 2>/dev/null || true; wait "$hog" 2>/dev/null || true; hog=""; fi; }
trap 'stop_hog; rm -rf "$out"' EXIT

# scene SPACING STEPS > the Taylor bar at that spacing, STEPS steps, one frame
scene() {
  "$py" - "$top/examples/taylor-bar.json" "$@" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["bodies"][0]["spacing"] = float(sys.argv[2])
s["time"]["max_steps"] = int(sys.argv[3])
s["output"]["frames"] = 1
s.setdefault("limits", {})["max_particles"] = 2000000
print(json.dumps(s))
PY
}

# one SCENE THREADS: prints the run's particle-steps/s and its particles
one() {
  rm -rf "$out/r"
  "$run" "$1" -o "$out/r" --threads "$2" --quiet
  "$py" -c "
import h5py, sys
c = h5py.File(sys.argv[1], 'r')['cost'].attrs
print('%.6g %d' % (float(c['particle_steps_per_second']), int(c['particles'])))" "$out/r/result.h5"
}

median() { printf '%s\n' "$@" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs, OMP_WAIT_POLICY=$OMP_WAIT_POLICY, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| scene | particles | steps | machine | 1 thread (p-steps/s) | 2 threads (p-steps/s) | 2 / 1 |"
echo "|---|---:|---:|---|---:|---:|---:|"
for size in 5k 40k; do
  case $size in
    5k) h=0.0006 steps=$steps5 ;;
    40k) h=0.0003 steps=$steps40 ;;
  esac
  scene "$h" "$steps" >"$out/s.json"
  for machine in idle busy; do
    [ "$machine" = busy ] && { yes >/dev/null & hog=$!; }
    r1=() r2=() n=0
    for _ in $(seq "$rounds"); do
      read -r v n < <(one "$out/s.json" 1); r1+=("$v")
      read -r v n < <(one "$out/s.json" 2); r2+=("$v")
    done
    stop_hog
    m1=$(median "${r1[@]}") m2=$(median "${r2[@]}")
    awk -v s="$size" -v h="$h" -v n="$n" -v k="$steps" -v m="$machine" -v a="$m1" -v b="$m2" -v l1="${r1[*]}" -v l2="${r2[*]}" \
      'BEGIN {printf "| taylor-bar h = %.1f mm | %d | %d | %s | %.3g (%s) | %.3g (%s) | %.2f |\n", h * 1000, n, k, m, a, l1, b, l2, b / a}'
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
