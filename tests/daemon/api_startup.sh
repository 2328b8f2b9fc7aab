#!/bin/bash
# What tlsphd trusts at start (issue 13, items 12 and 13):
#   1. random bytes over three pages of tlsphd.sqlite: the start is refused
#      (exit 3, a log line naming PRAGMA integrity_check and --recover), where
#      it used to start and accept jobs into the damaged file; --recover moves
#      the file aside and rebuilds the rows from the job directories;
#   2. a 0-byte tlsphd.sqlite beside job directories: refused (exit 3, the
#      count and one directory named), where it used to start afresh with the
#      jobs orphaned; --recover gives every directory its row back (a
#      successful run stays successful, its result downloadable);
#   3. kill -9 while a large study is being submitted (the daemon is stopped
#      once its child directories appear, checked to be mid-submission, then
#      killed): the next start removes every directory of that submission.
# References: SQLite's own PRAGMA integrity_check; the directories on disk.
. "$(dirname "$0")/common.sh"

sql() { "$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); [print('|'.join(map(str,r))) for r in c.execute(sys.argv[2])]" "$1" "$2"; }
wrap() { "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))"; }
strip_scene 2e-4 2 tiny | wrap >"$TMP/tiny.json"
# study NUM [SERIES]: NUM x SERIES children of the tiny scene (end time and
# series interval swept; a range has at most 1000 values)
study() {
    strip_scene 2e-4 2 tiny | "$PY" -c "
import json, sys
s = json.load(sys.stdin)
print(json.dumps({'inputs': {'base': s, 'sweep': {'parameters': [
    {'pointer': '/output/series_every', 'values': list(range(1, int(sys.argv[2]) + 1))},
    {'pointer': '/time/end', 'range': {'start': 1e-4, 'stop': 2e-4, 'num': int(sys.argv[1])}}]}}}))" "$1" "${2:-1}"
}
ndirs() { find "$1/jobs" -mindepth 1 -maxdepth 1 -type d | wc -l; }
# ------------------------------------------------ a data directory to break
DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 1 || exit 1
OK_ID=$(submit "$D_URL" "$TMP/tiny.json")
wait_status "$D_URL" "$OK_ID" '^(successful|failed)$'
check "a successful job" [ "$(job_status "$D_URL" "$OK_ID")" = successful ]
study 40 >"$TMP/study40.json"
req POST "$D_URL/processes/study/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/study40.json"
SID=$(jget "$BODY" "d['jobID']")
check "a study of 40 children (201, children = 40)" [ "$STATUS:$(jget "$BODY" "d.get('children')")" = 201:40 ]
req DELETE "$D_URL/jobs/$SID"
wait_status "$D_URL" "$SID" '^(dismissed|failed|successful)$'
kill -TERM "$D_PID"
wait "$D_PID"
NJOBS=$(ndirs "$DATA")
check "41 job directories ($NJOBS), 42 rows" [ "$NJOBS:$(sql "$DATA/tlsphd.sqlite" "SELECT COUNT(*) FROM jobs")" = 41:42 ]
PAGES=$(( $(stat -c %s "$DATA/tlsphd.sqlite") / 4096 ))
check "the database has more than 6 pages ($PAGES)" [ "$PAGES" -gt 6 ]

# ------------------------------------------------ 1. damaged pages
cp -a "$DATA" "$TMP/corrupt"
"$PY" -c "
import os, sys
with open(sys.argv[1], 'r+b') as f:
    f.seek(3 * 4096); f.write(os.urandom(3 * 4096))" "$TMP/corrupt/tlsphd.sqlite"
start_refused C "$TMP/corrupt"
check "random bytes over pages 4-6: start refused, exit 3 (got $C_RC)" [ "$C_RC" = 3 ]
check "  the log names the check and --recover" grep -q 'failed PRAGMA integrity_check.*--recover' "$C_LOG"
check "  it never listened" bash -c "! grep -q listening '$C_LOG'"
start_daemon R "$TMP/corrupt" --recover || exit 1
check "--recover: the damaged file is moved aside" bash -c "ls '$TMP/corrupt' | grep -q '^tlsphd.sqlite.corrupt-'"
check "  logged" grep -q 'moved it aside' "$R_LOG"
req GET "$R_URL/jobs/$OK_ID"
check "  the successful job is back, successful" [ "$STATUS:$(jget "$BODY" "d['status']")" = 200:successful ]
check "  its statusInfo valid" valid job
req GET "$R_URL/jobs?limit=100"
check "  every directory has its row (41)" [ "$(jget "$BODY" "len(d['jobs'])")" = 41 ]
kill -TERM "$R_PID"
wait "$R_PID"

# ------------------------------------------------ 2. a 0-byte database
cp -a "$DATA" "$TMP/empty"
: >"$TMP/empty/tlsphd.sqlite"
rm -f "$TMP/empty/tlsphd.sqlite-wal" "$TMP/empty/tlsphd.sqlite-shm"
start_refused Z "$TMP/empty"
check "0-byte database beside 41 job directories: refused, exit 3 (got $Z_RC)" [ "$Z_RC" = 3 ]
check "  the log counts them and names --recover" grep -q '41 job directories under .* have no row.*--recover' "$Z_LOG"
start_daemon Y "$TMP/empty" --recover || exit 1
check "--recover: rebuilt 41 rows (logged)" grep -q 'rebuilt 41 job row' "$Y_LOG"
req GET "$Y_URL/jobs/$OK_ID"
check "  the successful job is successful again" [ "$(jget "$BODY" "d['status'] + '/' + d.get('outcome', '')")" = successful/successful ]
req GET "$Y_URL/jobs/$OK_ID/results/result.h5"
check "  its result is served again" cmp -s "$BODY" "$TMP/empty/jobs/$OK_ID/result.h5"
req GET "$Y_URL/jobs?limit=100"
# a child may have started before the cancel: it keeps what its result says
check "  the study's children are runs; those that had not run: failed, interrupted" [ "$(jget "$BODY" "(lambda k: all(x in [('failed', 'interrupted'), ('dismissed', 'cancelled'), ('successful', 'successful')] for x in k) and k.count(('failed', 'interrupted')) >= 35)([(j['status'], j.get('outcome')) for j in d['jobs'] if j['jobID'] != '$OK_ID'])")" = True ]
check "  job list valid" valid 'job#/$defs/jobList'
kill -TERM "$Y_PID"
wait "$Y_PID"
start_daemon X "$TMP/empty" || exit 1
check "a plain restart on the recovered directory starts" [ "$(job_status "$X_URL" "$OK_ID")" = successful ]
kill -TERM "$X_PID"
wait "$X_PID"

# ------------------------------------------------ 3. kill -9 mid-submission
# The daemon makes 2000 directories (each scene written and synced) before it
# inserts the rows: it is stopped (SIGSTOP) once directories appear, the
# database is checked to hold no row of the study yet, and then it is killed.
N=2000
study 1000 2 >"$TMP/big.json"
caught=0
for attempt in 1 2 3; do
    K=$TMP/kill$attempt
    start_daemon K "$K" --max-children $N --max-jobs 1 || exit 1
    curl -s -o /dev/null -H 'Content-Type: application/json' --data-binary @"$TMP/big.json" \
        "$K_URL/processes/study/execution" &
    CURL=$!
    # stop the daemon as soon as 20 child directories exist (polled every
    # ms); give up when the request has been answered
    "$PY" - "$K/jobs" "$K_PID" "$CURL" <<'PYEOF'
import os, signal, sys, time
jobs, pid, curl = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
t_end = time.time() + 600  # a hang detector only
while time.time() < t_end:
    try:
        n = sum(1 for e in os.scandir(jobs) if e.is_dir())
    except FileNotFoundError:
        n = 0
    if n >= 20:
        os.kill(pid, signal.SIGSTOP)
        break
    try:
        os.kill(curl, 0)
    except ProcessLookupError:
        break
    time.sleep(0.001)
PYEOF
    rows=$(sql "$K/tlsphd.sqlite" "SELECT COUNT(*) FROM jobs")
    made=$(ndirs "$K")
    kill -KILL "$K_PID"
    wait "$K_PID" 2>/dev/null
    wait "$CURL" 2>/dev/null
    if [ "$rows" = 0 ] && [ "$made" -gt 0 ]; then caught=1; break; fi
    echo "# attempt $attempt: stopped after the submission ($rows rows, $made directories); again"
done
check "killed mid-submission: $made directories, no row" [ "$caught" = 1 ]
check "  an intent file lists them" bash -c "ls -a '$K/jobs' | grep -q '^.intent-'"
start_daemon L "$K" --max-children $N || exit 1
check "restart: the interrupted submission's directories are removed ($(ndirs "$K") left)" [ "$(ndirs "$K")" = 0 ]
check "  logged" grep -q "removed $made job director" "$L_LOG"
check "  the intent file is gone" bash -c "! ls -a '$K/jobs' | grep -q '^.intent-'"
req GET "$L_URL/jobs"
check "  no job listed" [ "$(jget "$BODY" "len(d['jobs'])")" = 0 ]
T=$(submit "$L_URL" "$TMP/tiny.json")
wait_status "$L_URL" "$T" '^(successful|failed)$'
check "  and the daemon runs jobs" [ "$(job_status "$L_URL" "$T")" = successful ]
finish
