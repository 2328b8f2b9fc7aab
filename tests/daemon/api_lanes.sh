#!/bin/bash
# tlsphd: a light request never waits behind a heavy one.  Heavy requests (job
# lists, result reads, study summaries) are held by the testing-only hook
# test_hold_heavy (they wait while a file exists); meanwhile /healthz, a job's
# status, a submission and a cancellation must be answered.  The order is
# what is checked, never a duration: every wait is a hang detector.
. "$(dirname "$0")/common.sh"

HOLD=$TMP/hold
printf 'test_hold_heavy = %s\n' "$HOLD" >"$TMP/tlsphd.conf"
start_daemon D "$TMP/data" --config "$TMP/tlsphd.conf" --max-jobs 1 || exit 1
B=$D_URL
strip_scene 4e-4 2 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/tiny.json"
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
ID=$(submit "$B" "$TMP/tiny.json")
wait_status "$B" "$ID" '^successful$'

# hold the heavy lane and send more heavy requests than it has threads
touch "$HOLD"
HEAVY=("$B/jobs?limit=10000" "$B/jobs/$ID/results/series" "$B/jobs/$ID/results/frames"
       "$B/jobs?limit=10000&offset=1" "$B/jobs/$ID/results")
for k in "${!HEAVY[@]}"; do
    (curl -s -o /dev/null -w '%{http_code}\n' --max-time "$HANG_S" "${HEAVY[$k]}" >"$TMP/heavy.$k.tmp"
     mv "$TMP/heavy.$k.tmp" "$TMP/heavy.$k") &
done
held() { grep -q "test_hold: holding" "$D_LOG"; }
check "a heavy request is held" wait_until held

light() { # DESC WANT METHOD URL [curl args]
    local desc=$1 want=$2 m=$3 u=$4; shift 4
    local code; code=$(curl -s -o "$BODY" -w '%{http_code}' --max-time "$HANG_S" -X "$m" "$@" "$u")
    check "$desc while heavy requests are held: $code" [ "$code" = "$want" ]
}
light "/healthz" 200 GET "$B/healthz"
light "a job's status" 200 GET "$B/jobs/$ID"
light "a submission" 201 POST "$B/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/long.json"
NEW=$(jget "$BODY" "d.get('jobID', '')")
light "the new job's status" 200 GET "$B/jobs/$NEW"
light "its cancellation" 200 DELETE "$B/jobs/$NEW"
light "/processes" 200 GET "$B/processes"
n_done() { ls "$TMP"/heavy.[0-9] 2>/dev/null | wc -l; }
check "no heavy request was answered meanwhile ($(n_done) were)" [ "$(n_done)" = 0 ]

rm -f "$HOLD"
all_done() { [ "$(n_done)" = "${#HEAVY[@]}" ]; }
check "the heavy requests are answered once released" wait_until all_done
check "  all 200: $(cat "$TMP"/heavy.[0-9] | tr '\n' ' ')" [ "$(cat "$TMP"/heavy.[0-9] | grep -c '^200$')" = "${#HEAVY[@]}" ]
finish
