#!/bin/bash
# tlsphd crash recovery:
#   - kill -9 the daemon while two jobs run: the engines die with it
#     (PR_SET_PDEATHSIG); a new daemon on the same data directory requeues and
#     completes both, without duplicate rows;
#   - kill -9 one engine: its job fails with a reason naming the signal, and
#     the daemon keeps answering /jobs.
. "$(dirname "$0")/common.sh"

DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 2 --kill-grace 1 || exit 1
strip_scene 1.5e-3 10 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/mid.json"
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
engine_pids() { pgrep -f "$DATA/jobs/$1/" || true; }
sql() {
    if command -v sqlite3 >/dev/null; then sqlite3 "$DATA/tlsphd.sqlite" "$1"; else
        "$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); [print('|'.join(map(str,r))) for r in c.execute(sys.argv[2])]" "$DATA/tlsphd.sqlite" "$1"; fi
}

J1=$(submit "$D_URL" "$TMP/mid.json")
J2=$(submit "$D_URL" "$TMP/mid.json")
check "two jobs submitted" [ -n "$J1" -a -n "$J2" ]
wait_status "$D_URL" "$J1" '^running$' && wait_status "$D_URL" "$J2" '^running$'
check "both running" [ "$(job_status "$D_URL" "$J1")$(job_status "$D_URL" "$J2")" = runningrunning ]
engines_of() { for j in "$@"; do [ -n "$(engine_pids "$j")" ] || return 1; done; }
wait_until engines_of "$J1" "$J2"
check "two engine processes" [ -n "$(engine_pids "$J1")" -a -n "$(engine_pids "$J2")" ]
sleep 0.5
kill -KILL "$D_PID"
wait "$D_PID" 2>/dev/null
no_engines_of() { [ -z "$(engine_pids "$1")$(engine_pids "$2")" ]; }
gone=0
wait_until no_engines_of "$J1" "$J2" && gone=1
check "kill -9 daemon: its engines die too (no orphans)" [ "$gone" = 1 ]
check "rows left running in the database" [ "$(sql "SELECT COUNT(*) FROM jobs WHERE status='running'")" = 2 ]

start_daemon E "$DATA" --max-jobs 2 --kill-grace 1 || exit 1
check "restart: recovery logged" grep -q 'recovered 2 job' "$E_LOG"
s1=$(job_status "$E_URL" "$J1")
check "restart: job 1 requeued (accepted/running, got $s1)" bash -c "[[ '$s1' =~ ^(accepted|running)$ ]]"
wait_status "$E_URL" "$J1" '^(successful|failed)$'
wait_status "$E_URL" "$J2" '^(successful|failed)$'
check "job 1 completed after restart" [ "$(job_status "$E_URL" "$J1")" = successful ]
check "job 2 completed after restart" [ "$(job_status "$E_URL" "$J2")" = successful ]
check "attempts = 2 for both" [ "$(sql "SELECT attempts FROM jobs WHERE id IN ('$J1','$J2')" | sort -u)" = 2 ]
check "no duplicate rows (2 rows)" [ "$(sql "SELECT COUNT(*) FROM jobs")" = 2 ]
req GET "$E_URL/jobs/$J1"
check "statusInfo valid" valid job
req GET "$E_URL/jobs/$J1/results/result.h5"
check "result of the rerun downloadable" cmp -s "$BODY" "$DATA/jobs/$J1/result.h5"

# kill -9 one engine
J3=$(submit "$E_URL" "$TMP/long.json")
wait_status "$E_URL" "$J3" '^running$'
wait_until engines_of "$J3"
P3=$(engine_pids "$J3" | head -1)
check "engine of job 3 found" [ -n "$P3" ]
kill -KILL $P3
answered=0
for _ in $(seq 20); do
    req GET "$E_URL/jobs"
    [ "$STATUS" = 200 ] && answered=$((answered + 1))
    sleep 0.1
done
check "daemon answers /jobs meanwhile (20/20)" [ "$answered" = 20 ]
wait_status "$E_URL" "$J3" '^failed$'
req GET "$E_URL/jobs/$J3"
check "killed engine: failed" [ "$(jget "$BODY" "d['status']")" = failed ]
check "  outcome crashed" [ "$(jget "$BODY" "d.get('outcome')")" = crashed ]
check "  message names the signal ($(jget "$BODY" "d.get('message')"))" bash -c "'$PY' -c \"import json,sys; m=json.load(open(sys.argv[1])).get('message',''); sys.exit(not ('signal' in m.lower() or 'SIGKILL' in m))\" '$BODY'"
check "  statusInfo valid" valid job
req GET "$E_URL/healthz"
check "daemon healthy" [ "$STATUS" = 200 ]
finish
