#!/usr/bin/env bash
# Single-core throughput against the machine's bound (docs/performance.md,
# "Single-core throughput and the machine's bound").
#
# Four scenes, one thread, at about 5e3 and 4e4 particles (and 4e5 with
# SIZES="5k 40k 400k"), STEPS steps each, one frame:
#   elastic          the steel block of bench/elastic_block.sh (hourglass on)
#   plastic          the copper Taylor bar (examples/taylor-bar.json) without
#                    its thermal block: Johnson-Cook with the rate term
#   plastic+thermal  the example itself: JC with rate and thermal softening,
#                    adiabatic heating
#   damage           the example with Johnson-Cook damage (d1..d3 of OFHC
#                    copper, Johnson & Cook 1985), damage-aware treatment
# Particle-steps per second: the engine's own (/cost: per wall second of the
# run loop, output and stability checks included; setup excluded), and per CPU
# second of the whole process (setup included), which a busy machine disturbs
# less (a run that waits for a core is not charged for it).  With BEFORE=<tlsph-run of
# another build> the two engines run interleaved (before, after, before, ...)
# so that a change in the machine's load hits both alike; ROUNDS rounds
# (default 3), medians.  Prints the load average before and after.
#
# usage: bench/throughput.sh [STEPS_5K] [STEPS_40K] [STEPS_400K]  (default 400 100 20)
set -euo pipefail
. "$(dirname "$0")/common.sh"
steps5=${1:-400}
steps40=${2:-100}
steps400=${3:-20}
rounds=${ROUNDS:-3}
sizes=${SIZES:-5k 40k}
before=${BEFORE:-}
scratch_dir

# scene KIND SIZE STEPS > the scene
scene() {
  "$py" - "$top/examples/taylor-bar.json" "$@" <<'PY'
import json, sys
kind, size, steps = sys.argv[2], sys.argv[3], int(sys.argv[4])
if kind == "elastic":
    k = {"5k": 17, "40k": 34, "400k": 74}[size]
    L = k * 0.001
    s = {"name": "throughput-block", "dimension": 3,
         "time": {"end": 1.0, "cfl": 0.3},
         "discretization": {"kernel": "wendland_c2", "support_factor": 2.01,
                            "hourglass": {"enabled": True, "coefficient": 1.0}},
         "materials": {"steel": {"density": 7850, "youngs_modulus": 2.1e11, "poisson_ratio": 0.3}},
         "bodies": [{"name": "block", "material": "steel", "spacing": 0.001,
                     "geometry": {"box": {"min": [0, 0, 0], "max": [L, L, L]}},
                     "initial_velocity": ["2*sin(3.14159*y/%g)" % L, "2*sin(3.14159*z/%g)" % L,
                                          "2*sin(3.14159*x/%g)" % L]}]}
else:
    s = json.load(open(sys.argv[1]))
    s["bodies"][0]["spacing"] = {"5k": 0.0006, "40k": 0.0003, "400k": 0.00014}[size]
    mat = s["materials"]["ofhc_copper"]
    if kind == "plastic":
        del mat["thermal"]
        for key in ("thermal_exponent", "reference_temperature", "melting_temperature"):
            del mat["strength"][key]
    elif kind == "damage":
        mat["damage"] = {"type": "johnson_cook", "d1": 0.54, "d2": 4.89, "d3": -3.03}
        s["discretization"]["damage"] = {"treatment": "damage_aware"}
s["time"]["max_steps"] = steps
s["output"] = {"frames": 1, "series_every": 50}
s.setdefault("limits", {})["max_particles"] = 2000000
print(json.dumps(s))
PY
}

# one ENGINE SCENE: prints the run's particle-steps per wall second (the
# engine's own) and per CPU second of the process (setup included), and its
# particles
one() {
  rm -rf "$out/r"
  OMP_NUM_THREADS=1 /usr/bin/time -f "%U %S" -o "$out/time" "$1" "$2" -o "$out/r" --threads 1 --quiet
  "$py" -c "
import h5py, sys
c = h5py.File(sys.argv[1], 'r')['cost'].attrs
u, s = (float(x) for x in open(sys.argv[2]).read().split()[-2:])
n, k = int(c['particles']), int(c['steps'])
print('%.6g %.6g %d' % (float(c['particle_steps_per_second']), n * k / (u + s), n))" "$out/r/result.h5" "$out/time"
}

median() { printf '%s\n' "$@" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs, 1 thread, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# p-steps/s: per wall second of the run loop (the engine's /cost) | per CPU second of the whole process"
if [ -n "$before" ]; then
  echo "| scene | particles | steps | before, wall | after, wall | before, CPU | after, CPU | after / before (CPU) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
else
  echo "| scene | particles | steps | p-steps/s, wall | p-steps/s, CPU |"
  echo "|---|---:|---:|---:|---:|"
fi
for size in $sizes; do
  case $size in
    5k) steps=$steps5 ;;
    40k) steps=$steps40 ;;
    400k) steps=$steps400 ;;
  esac
  for kind in elastic plastic plastic+thermal damage; do
    scene "$kind" "$size" "$steps" >"$out/s.json"
    wa=() ca=() wb=() cb=() n=0
    for _ in $(seq "$rounds"); do
      if [ -n "$before" ]; then read -r w c n < <(one "$before" "$out/s.json"); wb+=("$w"); cb+=("$c"); fi
      read -r w c n < <(one "$run" "$out/s.json"); wa+=("$w"); ca+=("$c")
    done
    if [ -n "$before" ]; then
      awk -v s="$kind" -v n="$n" -v k="$steps" -v wa="$(median "${wa[@]}")" -v wb="$(median "${wb[@]}")" \
        -v ca="$(median "${ca[@]}")" -v cb="$(median "${cb[@]}")" -v lb="${cb[*]}" -v la="${ca[*]}" \
        'BEGIN {printf "| %s | %d | %d | %.3g | %.3g | %.3g (%s) | %.3g (%s) | %.2f |\n", s, n, k, wb, wa, cb, lb, ca, la, ca / cb}'
    else
      awk -v s="$kind" -v n="$n" -v k="$steps" -v wa="$(median "${wa[@]}")" -v ca="$(median "${ca[@]}")" -v la="${ca[*]}" \
        'BEGIN {printf "| %s | %d | %d | %.3g | %.3g (%s) |\n", s, n, k, wa, ca, la}'
    fi
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
