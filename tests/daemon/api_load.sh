#!/bin/bash
# tlsphd API under load: 100 submissions from 20 parallel curl processes are all
# accepted (201), get 100 distinct ids, and all reach a final state with
# --max-jobs 2; the database holds exactly 100 rows; concurrent long-polls and
# reads are answered meanwhile.
. "$(dirname "$0")/common.sh"

DATA=$TMP/data
N=${LOAD_JOBS:-100}
start_daemon D "$DATA" --max-jobs 2 || exit 1
B=$D_URL
strip_scene 1e-5 1 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/tiny.json"

t0=$(date +%s.%N)
seq "$N" | xargs -P 20 -I{} curl -s -o "$TMP/sub.{}" -w '%{http_code}\n' \
    -H 'Content-Type: application/json' --data-binary @"$TMP/tiny.json" "$B/processes/run/execution" \
    >"$TMP/codes"
t1=$(date +%s.%N)
echo "# $N submissions in $(awk "BEGIN{printf \"%.2f\", $t1 - $t0}") s"
check "all $N submissions answered 201" [ "$(grep -c '^201$' "$TMP/codes")" = "$N" ]
"$PY" -c "
import glob, json, sys
for f in glob.glob(sys.argv[1] + '/sub.*'):
    print(json.load(open(f)).get('jobID', ''))" "$TMP" >"$TMP/ids"
check "$N distinct job ids" [ "$(sort -u "$TMP/ids" | wc -l)" = "$N" ]
check "ids are 32 lowercase hex" [ "$(grep -cE '^[0-9a-f]{32}$' "$TMP/ids")" = "$N" ]

# parallel long-polls while the batch runs.  A long-poll answers when its job
# is final or when the wait (at most 60 s) expires, whichever comes first; how
# long the batch takes depends on the machine (36 s under ASan on a loaded
# 2-core box), so a poll that expires is repeated: every answer must be 200 and
# the last one final.
poll_until_final() { # id
    local code
    for _ in 1 2 3 4 5 6 7 8; do
        code=$(curl -s -o "$TMP/poll.$1" -w '%{http_code}' "$B/jobs/$1?wait=60")
        echo "$code" >>"$TMP/pollcodes.$1"
        [ "$code" = 200 ] || return
        grep -qE '"status":"(successful|failed|dismissed|unstable)"' "$TMP/poll.$1" && return
    done
}
export -f poll_until_final
export B TMP
head -10 "$TMP/ids" | xargs -P 10 -I{} bash -c 'poll_until_final {}' &
POLLS=$!

final=0
# a hang detector, not a speed test (speed is measured in bench/)
end=$(($(date +%s) + 300))
while [ "$(date +%s)" -le "$end" ]; do
    req GET "$B/healthz"
    final=$(jget "$BODY" "d['jobs']['final']")
    [ "$final" = "$N" ] && break
    sleep 0.5
done
t2=$(date +%s.%N)
echo "# all final after $(awk "BEGIN{printf \"%.1f\", $t2 - $t0}") s"
check "all $N jobs final" [ "$final" = "$N" ]
wait $POLLS
cat "$TMP"/pollcodes.* >"$TMP/pollcodes"
npolled=$(ls "$TMP"/pollcodes.* | wc -l)
nbad=$(grep -vc '^200$' "$TMP/pollcodes")
check "10 concurrent long-polls answered 200" [ "$npolled" = 10 -a "$nbad" = 0 ]
check "long-polls returned final states" [ "$(cat "$TMP"/poll.* | grep -o '"status":"successful"' | wc -l)" = 10 ]
req GET "$B/jobs?status=successful&limit=1000"
check "all $N successful" [ "$(jget "$BODY" "len(d['jobs'])")" = "$N" ]
check "job list valid" valid 'job#/$defs/jobList'
if command -v sqlite3 >/dev/null; then
    rows=$(sqlite3 "$DATA/tlsphd.sqlite" 'SELECT COUNT(*), COUNT(DISTINCT id) FROM jobs')
else
    rows=$("$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); print('|'.join(map(str, c.execute('SELECT COUNT(*), COUNT(DISTINCT id) FROM jobs').fetchone())))" "$DATA/tlsphd.sqlite")
fi
check "database: $N rows, $N distinct ids (got $rows)" [ "$rows" = "$N|$N" ]
check "$N job directories" [ "$(ls "$DATA/jobs" | wc -l)" = "$N" ]
finish
