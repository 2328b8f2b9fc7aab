#!/bin/bash
# tlsphd with the Slurm executor (executor = slurm; server/executor_slurm.h)
# on a private single-node Slurm started here (slurm_cluster.sh; SKIP, exit
# 77, where Slurm is not installed or cannot start):
#   - a run waits PENDING (its partition is down), then RUNNING once the
#     partition opens, then ends successful, its result downloadable by id;
#   - a 6-child study is one job array (one Slurm job id, %2 from its
#     max_parallel) and its summary table is complete;
#   - cancel reaches scancel: the Slurm job ends CANCELLED, the run dismissed;
#   - a run over its Slurm time limit (wall_limit 60 s: --time=1) ends failed,
#     outcome timed_out, with TIMEOUT in its message;
#   - kill -9 of the daemon mid-array, and a restart: every child ends
#     successful after one attempt, Slurm saw each task once (nothing lost,
#     nothing submitted twice);
#   - a node that fails under a run (scontrol ... State=DOWN: NODE_FAIL): the
#     run is requeued, submitted again, and ends successful at attempt 2.
# Waits are event-driven (states polled), never fixed sleeps.
. "$(dirname "$0")/common.sh"
. "$here/slurm_cluster.sh"

trap 'stop_daemons; stop_slurm; cleanup' EXIT
if ! start_slurm "$TMP/slurm"; then
    echo "SKIP: cannot start a private Slurm: $SLURM_SKIP"
    exit 77
fi
echo "# Slurm up: $SLURM_CONF"

DATA=$TMP/data
SHARED=$TMP/shared
cat >"$TMP/tlsphd.conf" <<EOF
executor = slurm
shared_dir = $SHARED
slurm_partition = test
slurm_poll = 0.3
slurm_mem_base_mb = 128
wall_limit = 60
max_attempts = 3
EOF
start_daemon D "$DATA" --config "$TMP/tlsphd.conf" || exit 1
check "daemon says executor slurm" grep -q 'executor slurm' "$D_LOG"

wrap() { "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))"; }
strip_scene 1e-3 5 | wrap >"$TMP/mid.json"
strip_scene 1.0 10 | wrap >"$TMP/long.json"
message() { curl -s "$1/jobs/$2" | "$PY" -c "import json,sys; print(json.load(sys.stdin).get('message',''))" 2>/dev/null; }
message_has() { message "$1" "$2" | grep -q "$3"; }
slurm_id() { awk '{print $3}' "$SHARED/$1/slurm_job" 2>/dev/null; }
slurm_state() { squeue -h -t all -j "$1" -o %T 2>/dev/null; }

# ------------------------------------------------------------ PENDING -> RUNNING -> successful
J1=$(submit "$D_URL" "$TMP/mid.json")
JT=$(submit "$D_URL" "$TMP/long.json")
check "runs submitted" [ -n "$J1" -a -n "$JT" ]
check "run 1: PENDING in Slurm (partition down), message says so" wait_until message_has "$D_URL" "$J1" 'PENDING (PartitionDown)'
check "  API status running while Slurm queues it" [ "$(job_status "$D_URL" "$J1")" = running ]
check "  one Slurm job per run" [ -n "$(slurm_id "$J1")" -a "$(slurm_id "$J1")" != "$(slurm_id "$JT")" ]
scontrol update PartitionName=test State=UP
check "run 1: RUNNING once the partition is up" wait_until message_has "$D_URL" "$J1" 'RUNNING on'
wait_status "$D_URL" "$J1" '^(successful|failed|dismissed)$'
req GET "$D_URL/jobs/$J1"
check "run 1: successful ($(jget "$BODY" "d.get('message')"))" [ "$(jget "$BODY" "d['status']")" = successful ]
check "  progress 100" [ "$(jget "$BODY" "d.get('progress')")" = 100 ]
check "  statusInfo valid" valid job
req GET "$D_URL/jobs/$J1/results/result.h5"
check "  result.h5 downloadable by id" bash -c "[ '$STATUS' = 200 ] && cmp -s '$BODY' '$SHARED/$J1/result.h5'"
check "  progress stream file kept in the job directory" grep -q '"event":"finished"' "$SHARED/$J1/progress.jsonl"
check "  exit status 0 written by the batch script" [ "$(cat "$SHARED/$J1/exit_status")" = 0 ]
check "  Slurm says COMPLETED" [ "$(slurm_state "$(slurm_id "$J1")")" = COMPLETED ]

# ------------------------------------------------------------ cancel
JC=$(submit "$D_URL" "$TMP/long.json")
check "run to cancel: RUNNING" wait_until message_has "$D_URL" "$JC" 'RUNNING on'
req DELETE "$D_URL/jobs/$JC"
check "DELETE: 200" [ "$STATUS" = 200 ]
wait_status "$D_URL" "$JC" '^(successful|failed|dismissed)$'
req GET "$D_URL/jobs/$JC"
check "cancelled run dismissed ($(jget "$BODY" "d.get('message')"))" [ "$(jget "$BODY" "d['status'] + '/' + d.get('outcome', '')")" = dismissed/cancelled ]
check "  scancel reached Slurm (logged)" grep -q "job $JC: scancel $(slurm_id "$JC")" "$D_LOG"
check "  Slurm says CANCELLED" [ "$(slurm_state "$(slurm_id "$JC")")" = CANCELLED ]
no_engine() { ! pgrep -f "$SHARED/$1/" >/dev/null; }
check "  its engine is gone" wait_until no_engine "$JC"

# ------------------------------------------------------------ a study as one array; kill -9 mid-array
study_request 5e-4 4 1e-5,2e-5 2 >"$TMP/study.json"
check "study request valid (execute schema)" bash -c "'$PY' '$here/validate.py' execute <'$TMP/study.json'"
req POST "$D_URL/processes/study/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/study.json"
check "study submitted: 201" [ "$STATUS" = 201 ]
SID=$(jget "$BODY" "d['jobID']")
children() { curl -s "$D_URL/jobs?study=$SID&limit=100" | "$PY" -c "import json,sys; print(' '.join(j['jobID'] for j in json.load(sys.stdin)['jobs']))"; }
# each child's slurm_job record holds its Slurm id once sbatch has answered ("-" before)
all_recorded() { for c in $(children); do case "$(slurm_id "$c")" in "" | -) return 1 ;; esac; done; }
wait_until all_recorded
KIDS=$(children)
check "6 children" [ "$(echo $KIDS | wc -w)" = 6 ]
ARRAYS=$(for c in $KIDS; do slurm_id "$c" | cut -d_ -f1; done | sort -u)
check "one job array for the 6 children (Slurm job $ARRAYS)" [ "$(echo $ARRAYS | wc -w)" = 1 ]
check "  tasks 0..5" [ "$(for c in $KIDS; do slurm_id "$c" | cut -d_ -f2; done | sort -n | tr '\n' ' ')" = "0 1 2 3 4 5 " ]
check "  array limit %2 from max_parallel" bash -c "scontrol show job '$ARRAYS' | grep -q 'ArrayTaskThrottle=2'"
# kill -9 once the array is under way but not done
some_done() { [ "$(curl -s "$D_URL/jobs?study=$SID&status=successful&limit=100" | "$PY" -c "import json,sys; print(len(json.load(sys.stdin)['jobs']))")" -ge 1 ]; }
check "array under way: a child successful" wait_until some_done
kill -KILL "$D_PID"
wait "$D_PID" 2>/dev/null
left=$(for c in $KIDS; do [ -e "$SHARED/$c/exit_status" ] || echo "$c"; done | wc -l)
check "daemon killed mid-array ($left of 6 children not yet ended)" [ "$left" -ge 1 ]
start_daemon E "$DATA" --config "$TMP/tlsphd.conf" || exit 1
adopted() { grep -q 'adopted [1-9][0-9]* run(s) from Slurm, requeued 0' "$E_LOG"; }
check "restart: runs adopted from Slurm, none requeued (logged)" wait_until adopted
long_poll_final "$E_URL" "$SID"
check "study successful after the restart ($(jget "$BODY" "d.get('message')"))" [ "$(jget "$BODY" "d['status']")" = successful ]
req GET "$E_URL/jobs?study=$SID&limit=100"
check "  every child successful after one attempt" [ "$(jget "$BODY" "all(j['status'] == 'successful' for j in d['jobs']) and len(d['jobs']) == 6")" = True ]
sql() { "$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); [print('|'.join(map(str,r))) for r in c.execute(sys.argv[2])]" "$DATA/tlsphd.sqlite" "$1"; }
check "  attempts 1 for each child (none run twice)" [ "$(sql "SELECT DISTINCT attempts FROM jobs WHERE study_id='$SID'")" = 1 ]
check "  Slurm saw each task once (6 tasks of one array, all COMPLETED)" \
    [ "$(squeue -h -r -t all -o '%i %T' | grep -c "^${ARRAYS}_[0-5] COMPLETED$")" = 6 ]
check "  4 Slurm submissions in all (3 runs, 1 array): nothing submitted twice" \
    [ "$(squeue -h -r -t all -o '%F %j' | grep ' tlsph-' | cut -d' ' -f1 | sort -u | wc -l)" = 4 ]
req GET "$E_URL/jobs/$SID/results/summary"
check "summary: 200, valid" bash -c "[ '$STATUS' = 200 ] && '$PY' '$here/validate.py' 'study#/\$defs/summary' <'$BODY'"
check "summary: 6 complete rows" [ "$(jget "$BODY" "len(d['rows']) == 6 and all(r[d['columns'].index('peak_force')] is not None and r[d['columns'].index('status')] == 'successful' for r in d['rows'])")" = True ]

# ------------------------------------------------------------ TIMEOUT
wait_status "$E_URL" "$JT" '^(successful|failed|dismissed)$'
req GET "$E_URL/jobs/$JT"
check "run over its time limit: failed/timed_out ($(jget "$BODY" "d.get('message')"))" [ "$(jget "$BODY" "d['status'] + '/' + d.get('outcome', '')")" = failed/timed_out ]
check "  message names TIMEOUT" [ "$(jget "$BODY" "'TIMEOUT' in d.get('message', '')")" = True ]
check "  Slurm says TIMEOUT" [ "$(slurm_state "$(slurm_id "$JT")")" = TIMEOUT ]

# ------------------------------------------------------------ NODE_FAIL (last: it stops every job on the node)
JN=$(submit "$E_URL" "$TMP/mid.json")
check "run on a node about to fail: RUNNING" wait_until message_has "$E_URL" "$JN" 'RUNNING on'
FIRST=$(slurm_id "$JN")
scontrol update NodeName="$SLURM_NODE" State=DOWN Reason=tlsph-test
requeued() { grep -q "job $JN: Slurm job $FIRST: NODE_FAIL: its node failed; requeued (attempt 1 of 3)" "$E_LOG"; }
check "  Slurm's NODE_FAIL requeues the run (logged)" wait_until requeued
resubmitted() { local s; s=$(slurm_id "$JN"); [ -n "$s" ] && [ "$s" != - ] && [ "$s" != "$FIRST" ]; }
check "  submitted again as a new Slurm job" wait_until resubmitted
# (ReturnToService=2 may have brought the node back already: then RESUME is refused)
scontrol update NodeName="$SLURM_NODE" State=RESUME 2>/dev/null
wait_status "$E_URL" "$JN" '^(successful|failed|dismissed)$'
check "  successful once the node is back" [ "$(job_status "$E_URL" "$JN")" = successful ]
check "  attempts 2" [ "$(sql "SELECT attempts FROM jobs WHERE id='$JN'")" = 2 ]
finish
