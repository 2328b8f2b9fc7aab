#!/usr/bin/env bash
# Throughput and memory of the elastic TLSPH core: a 3-D steel block with a
# smooth initial velocity field, free (no boundary conditions), hourglass
# control on, at about 1e4, 1e5 and 4e5 particles, with 1 and 2 OpenMP threads.
# Support radius 2.01 spacings: 32 neighbours in the bulk (~30 on average).
#
# Prints particle-steps per second (whole process: the run loop's own wall
# clock, which excludes scene parsing but includes neighbour search and output)
# and memory per particle (engine arrays, and the process's peak RSS / N).
#
# usage: bench/elastic_block.sh [STEPS] [SIZES...]    (default 200 steps; 22 47 74)
set -euo pipefail
. "$(dirname "$0")/common.sh"
steps=${1:-200}; shift || true
sizes=("$@"); [ ${#sizes[@]} -gt 0 ] || sizes=(22 47 74)
scratch_dir
printf "%10s %8s %8s %14s %12s %12s %10s\n" particles threads steps "p-steps/s" "B/particle" "RSS B/part" "wall s"
for k in "${sizes[@]}"; do
  L=$(awk -v k="$k" 'BEGIN { printf "%.6f", k * 0.001 }')
  cat > "$out/block.json" <<JSON
{"name": "bench-block-$k", "dimension": 3,
 "time": {"end": 1.0, "max_steps": $steps, "cfl": 0.3},
 "discretization": {"kernel": "wendland_c2", "support_factor": 2.01,
                    "hourglass": {"enabled": true, "coefficient": 1.0}},
 "stability": {"check_every": 50},
 "output": {"frames": 1, "series_every": 50},
 "limits": {"max_particles": 2000000},
 "materials": {"steel": {"density": 7850, "youngs_modulus": 2.1e11, "poisson_ratio": 0.3}},
 "bodies": [{"name": "block", "material": "steel", "spacing": 0.001,
             "geometry": {"box": {"min": [0, 0, 0], "max": [$L, $L, $L]}},
             "initial_velocity": ["2*sin(3.14159*y/$L)", "2*sin(3.14159*z/$L)", "2*sin(3.14159*x/$L)"]}]}
JSON
  for threads in 1 2; do
    rm -rf "$out/r"
    "$run" "$out/block.json" -o "$out/r" --threads "$threads" --progress-fd 3 --quiet 3>"$out/progress.jsonl"
    "$py" - "$out/progress.jsonl" "$threads" <<'PY'
import json, sys
last = [json.loads(l) for l in open(sys.argv[1]) if l.strip()][-1]
c = last["cost"]
print("%10d %8s %8d %14.4g %12.0f %12.0f %10.2f" % (c["particles"], sys.argv[2], c["steps"],
      c["particle_steps_per_second"], c["bytes_per_particle"],
      c["peak_memory_bytes"] / c["particles"], c["wall_seconds"]))
PY
  done
done
