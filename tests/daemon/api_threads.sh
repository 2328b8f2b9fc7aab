#!/bin/bash
# The daemon's thread budget (server/thread_budget.h, docs/deployment.md
# "Threads and cores"): the OpenMP threads of the engines running at once
# never add up to more than `cores`.  The engine reports its thread count in
# its cost record (cost.threads).  Reference: the rules themselves, on a
# 2-core budget given with --cores, whatever the machine has:
#   - max_jobs 3, threads_per_job 2: a warning at start; two jobs run at once,
#     1 thread each, and the third waits until one of them ends;
#   - max_jobs 2, threads_per_job 2: lowered to 1 with a warning;
#   - max_jobs 1, threads_per_job 2: the lone job gets both;
#   - a run's inputs.threads: up to the cores (granted), above them 422.
# Every wait is on job states, never on time.
. "$(dirname "$0")/common.sh"

strip_scene 2e-4 2 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/tiny.json"
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
threads_of() { req GET "$1/jobs/$2"; jget "$BODY" "d.get('cost', {}).get('threads')"; }
running_stepped() { # URL ID: running and past its first step
    req GET "$1/jobs/$2"
    [ "$(jget "$BODY" "d['status'] == 'running' and d.get('simulation', {}).get('step', 0) > 0")" = True ]
}

# ---------------------------------------------------------- 3 jobs, 2 cores
start_daemon D "$TMP/d" --cores 2 --max-jobs 3 --threads-per-job 2 --kill-grace 1 || exit 1
check "max_jobs 3 > cores 2: warned at start" grep -q "warning: max_jobs 3 > cores 2: at most 2 engines run at once" "$D_LOG"
check "  the start line names the budget" grep -q "max-jobs 3, cores 2, threads-per-job 1" "$D_LOG"
A=$(submit "$D_URL" "$TMP/long.json")
B=$(submit "$D_URL" "$TMP/long.json")
C=$(submit "$D_URL" "$TMP/long.json")
check "three long jobs submitted" test -n "$A" -a -n "$B" -a -n "$C"
# the first two claimed run side by side; which two is the queue's order
n_running() { local n=0 j; for j in $A $B $C; do [ "$(job_status "$D_URL" "$j")" = running ] && n=$((n + 1)); done; echo $n; }
two_stepped() { local n=0 j; for j in $A $B $C; do running_stepped "$D_URL" "$j" && n=$((n + 1)); done; [ $n = 2 ]; }
check "two jobs run at once (and step)" wait_until two_stepped
WAITING=""; RUN=""
for j in $A $B $C; do
    case $(job_status "$D_URL" "$j") in accepted) WAITING=$j ;; running) RUN="$RUN $j" ;; esac
done
check "  the third waits for a core (accepted while two run)" test -n "$WAITING" -a "$(n_running)" = 2
set -- $RUN
req DELETE "$D_URL/jobs/$1"
wait_status "$D_URL" "$1" '^dismissed$'
check "one cancelled: the waiting job starts" wait_until running_stepped "$D_URL" "$WAITING"
for j in $2 $WAITING; do req DELETE "$D_URL/jobs/$j"; done
for j in $2 $WAITING; do wait_status "$D_URL" "$j" '^dismissed$'; done
for j in $A $B $C; do
    check "  job $j ran on 1 thread (cost.threads = $(threads_of "$D_URL" "$j"))" [ "$(threads_of "$D_URL" "$j")" = 1 ]
done
req GET "$D_URL/jobs/$A"
check "  statusInfo with cost.threads valid" valid job
stop_daemons

# ---------------------------------------------------------- 2 x 2 > 2: lowered
start_daemon E "$TMP/e" --cores 2 --max-jobs 2 --threads-per-job 2 || exit 1
check "threads_per_job 2 x max_jobs 2 > cores 2: lowered to 1, warned" \
    grep -q "warning: threads_per_job 2 x max_jobs 2 > cores 2: lowered threads_per_job to 1" "$E_LOG"
T=$(submit "$E_URL" "$TMP/tiny.json")
long_poll_final "$E_URL" "$T"
check "  a job runs on 1 thread ($(threads_of "$E_URL" "$T"))" [ "$(threads_of "$E_URL" "$T")" = 1 ]
# a run may ask for its threads: up to the cores, granted while they are free
with_threads() { "$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); d['inputs']['threads']=json.loads(sys.argv[2]); print(json.dumps(d))" "$TMP/tiny.json" "$1" >"$TMP/t.json"; }
with_threads 2
T=$(submit "$E_URL" "$TMP/t.json")
long_poll_final "$E_URL" "$T"
check "inputs.threads 2 (= cores): the lone job runs on 2 ($(threads_of "$E_URL" "$T"))" [ "$(threads_of "$E_URL" "$T")" = 2 ]
for bad in 3 0 1.5 '"2"'; do
    with_threads "$bad"
    req POST "$E_URL/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/t.json"
    check "inputs.threads $bad: 422 at #/inputs/threads naming the range ($(jget "$BODY" "[e['pointer'] for e in d.get('errors', [])]"))" \
        [ "$STATUS:$(jget "$BODY" "any(e['pointer'] == '#/inputs/threads' and 'from 1 to 2' in e['detail'] for e in d['errors'])")" = 422:True ]
done
check "  problem valid" valid error
stop_daemons

# ---------------------------------------------------------- one job: all cores
start_daemon F "$TMP/f" --cores 2 --max-jobs 1 --threads-per-job 2 || exit 1
check "threads_per_job 2 x max_jobs 1 <= cores 2: no warning" bash -c "! grep -q 'warning: .*cores' '$F_LOG'"
T=$(submit "$F_URL" "$TMP/tiny.json")
long_poll_final "$F_URL" "$T"
check "  the lone job runs on 2 threads ($(threads_of "$F_URL" "$T"))" [ "$(threads_of "$F_URL" "$T")" = 2 ]
check "  and says so in its log" bash -c "curl -s '$F_URL/jobs/$T/log' | grep -q '(2 threads)'"
finish
