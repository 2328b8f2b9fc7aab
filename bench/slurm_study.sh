#!/bin/bash
# The same 12-child study with tlsphd's local executor and with its Slurm
# executor on a private single-node Slurm on this machine (docs/deployment.md,
# "Local or Slurm: the cost of the scheduler").  Both run 2 children at once
# with 1 thread each (local: max_jobs 2; Slurm: a 2-CPU node and the study's
# max_parallel 2).  Prints, for each: the study's wall time (created to
# finished), the sum of the children's engine wall_seconds, and the overhead
# per child: (2 x wall - sum of engine seconds) / 12, the time a child's slot
# spent on anything but the engine (start-up, scheduling, polling).
# ORDER=slurm-first runs Slurm first.  Needs root, slurm-wlm and munge (deploy/install-deps.sh).  Run from the tree:
#   top_srcdir=$PWD top_builddir=$PWD/build bash bench/slurm_study.sh
. "$(dirname "$0")/../tests/daemon/common.sh"
. "$top_srcdir/tests/daemon/slurm_cluster.sh"
trap 'stop_daemons; stop_slurm; cleanup' EXIT
SLURM_CPUS=2 start_slurm "$TMP/slurm" || { echo "cannot start Slurm: $SLURM_SKIP"; exit 1; }
scontrol update PartitionName=test State=UP

study_request 1.5e-3 10 1e-5,2e-5,3e-5,4e-5 2 >"$TMP/study.json"

measure() { # label URL
    req POST "$2/processes/study/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/study.json"
    local sid; sid=$(jget "$BODY" "d['jobID']")
    long_poll_final "$2" "$sid"
    local job=$TMP/job.json; cp "$BODY" "$job"
    req GET "$2/jobs/$sid/results/summary"
    "$PY" - "$1" "$job" "$BODY" <<'PYEOF'
import json, sys
from datetime import datetime
label, job, summ = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
t = lambda s: datetime.fromisoformat(s.replace("Z", "+00:00")).timestamp()
wall = t(job["finished"]) - t(job["created"])
col = summ["columns"].index("wall_seconds")
engine = sum(r[col] for r in summ["rows"])
n = len(summ["rows"])
print(f"| {label} | {job['status']} | {n} | {wall:.1f} | {engine:.1f} | {(2 * wall - engine) / n:.2f} |")
PYEOF
}
local_run() {
    start_daemon L "$TMP/local" --max-jobs 2 || exit 1
    measure local "$L_URL"
    stop_daemons
}
echo "| executor | status | children | study wall s | sum of engine s | overhead per child s |"
echo "|---|---|---|---|---|---|"
# ORDER=slurm-first: Slurm first (the machine's other load changes with time)
[ "${ORDER:-local-first}" = local-first ] && local_run
cat >"$TMP/slurm.conf" <<EOC
executor = slurm
shared_dir = $TMP/shared
slurm_partition = test
slurm_poll = ${SLURM_POLL:-1}
slurm_mem_base_mb = 128
EOC
start_daemon S "$TMP/slurmdata" --config "$TMP/slurm.conf" || exit 1
measure "slurm (poll ${SLURM_POLL:-1} s)" "$S_URL"
stop_daemons
[ "${ORDER:-local-first}" = local-first ] || local_run
