#!/bin/bash
# Small inconsistencies and limits of tlsphd (issue 13, items 9, 14 and 20),
# each checked against what the API itself says elsewhere:
#   - a study range whose step overflows (-1e308..1e308, num 2) is refused
#     (it used to yield one value: half the children); a study's 201 answer
#     says how many children were created;
#   - /healthz counts studies too;
#   - JSON and CSV print the same shortest numbers (0.05, not
#     0.050000000000000003 in JSON; an integral real is "1.0" in JSON, "1" in
#     CSV);
#   - a full last page of /jobs has no `next` link;
#   - a cancelled study reports the progress it reached, not 100;
#   - a cancelled run's simulation.step equals its cost.steps;
#   - a child of a finished study is removed only with its study (its summary
#     row and the study's message count it);
#   - a taken port is named in the start-up error (was "port 0");
#   - a token file others can read is refused;
#   - a job's estimated result file above max_output_mb: 413 naming the
#     estimate; free space below min_free_mb: 507 (both problem+json).
. "$(dirname "$0")/common.sh"

wrap() { "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))"; }
strip_scene 2e-4 2 tiny | wrap >"$TMP/tiny.json"
strip_scene 2e-2 100 | wrap >"$TMP/long.json"
post() { req POST "$1/processes/$2/execution" -H 'Content-Type: application/json' --data-binary @"$3"; }
# study_of SCENE_REQUEST PARAMS_JSON: a study request over the scene of a run request
study_of() {
    "$PY" -c "
import json, sys
s = json.load(open(sys.argv[1]))['inputs']['scene']
print(json.dumps({'inputs': {'base': s, 'sweep': {'parameters': json.loads(sys.argv[2])}}}))" "$1" "$2"
}

DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 1 --kill-grace 1 || exit 1

# ---------------------------------------------------------- study ranges
study_of "$TMP/tiny.json" '[{"pointer": "/time/end", "range": {"start": -1e308, "stop": 1e308, "num": 2}},
                           {"pointer": "/output/series_every", "values": [1, 2]}]' >"$TMP/huge_range.json"
post "$D_URL" study "$TMP/huge_range.json"
check "range -1e308..1e308 (step not finite): 422" [ "$STATUS" = 422 ]
check "  points at the range, says why" [ "$(jget "$BODY" "any(e['pointer'] == '#/inputs/sweep/parameters/0/range' and 'not a finite number' in e['detail'] for e in d['errors'])")" = True ]
check "  problem valid" valid error
study_of "$TMP/tiny.json" '[{"pointer": "/parameters/vmax", "values": [0.05, 0.1, 0.3]},
                           {"pointer": "/output/series_every", "values": [1, 2]}]' >"$TMP/study6.json"
post "$D_URL" study "$TMP/study6.json"
SID=$(jget "$BODY" "d['jobID']")
check "study 3 x 2: 201 with children = 6" [ "$STATUS:$(jget "$BODY" "d.get('children')")" = 201:6 ]
check "  statusInfo valid" valid job

# ---------------------------------------------------------- /healthz
req GET "$D_URL/healthz"
check "healthz counts the study" [ "$(jget "$BODY" "sum(d['studies'].values())")" = 1 ]
check "  and its 6 children as jobs" [ "$(jget "$BODY" "sum(d['jobs'].values())")" = 6 ]
check "  healthz valid" valid openapi:health

# ---------------------------------------------------------- numbers
wait_status "$D_URL" "$SID" '^(successful|failed)$'
req GET "$D_URL/jobs/$SID/results/summary"
check "summary JSON prints 0.05 (shortest), not 0.050000000000000003" bash -c "grep -q '0\.05,' '$BODY' && ! grep -q '0\.0500000' '$BODY'"
cp "$BODY" "$TMP/summary.json"
req GET "$D_URL/jobs/$SID/results/summary?format=csv"
check "  the same numbers in JSON and CSV (every row)" "$PY" - "$TMP/summary.json" "$BODY" <<'PYEOF'
import csv, re, sys
raw = open(sys.argv[1]).read()
rows_json = [re.findall(r'(?:"[^"]*"|[^,\[\]]+)', r) for r in re.findall(r'\[([^\[\]]*)\]', raw.split('"rows":', 1)[1])]
# JSON keeps ".0" on an integral real (a real to a JSON reader); CSV has no types
rows_json = [[c.strip('"') if c != 'null' else '' for c in r] for r in rows_json]
rows_json = [[c[:-2] if c.endswith('.0') else c for c in r] for r in rows_json]
rows_csv = list(csv.reader(open(sys.argv[2])))[1:]
sys.exit(rows_json != rows_csv)
PYEOF
KID=$(curl -s "$D_URL/jobs?study=$SID" | "$PY" -c "import json,sys; print(json.load(sys.stdin)['jobs'][0]['jobID'])")
req GET "$D_URL/jobs/$KID/results/series/kinetic_energy"
cp "$BODY" "$TMP/series.json"
req GET "$D_URL/jobs/$KID/results/series/kinetic_energy?format=csv"
check "series: JSON and CSV times are the same text" "$PY" - "$TMP/series.json" "$BODY" <<'PYEOF'
import re, sys
raw = open(sys.argv[1]).read()
times_json = [t[:-2] if t.endswith('.0') else t
              for t in re.search(r'"time":\[([^\]]*)\]', raw).group(1).split(',')]
times_csv = [line.split(',')[1] for line in open(sys.argv[2]).read().splitlines()[1:]]
sys.exit(times_json != times_csv or len(times_csv) < 2)
PYEOF

# ---------------------------------------------------------- study children
req DELETE "$D_URL/jobs/$KID"
check "DELETE a child of a finished study: 409" [ "$STATUS" = 409 ]
check "  names the study to delete instead" [ "$(jget "$BODY" "'/jobs/$SID' in d['detail']")" = True ]
req GET "$D_URL/jobs/$SID/results/summary"
check "  the summary keeps its 6 rows" [ "$(jget "$BODY" "len(d['rows'])")" = 6 ]
req GET "$D_URL/jobs/$SID"
check "  the message still counts 6" [ "$(jget "$BODY" "d.get('message')")" = "all 6 children successful" ]

# ---------------------------------------------------------- paging
req GET "$D_URL/jobs?processID=study"
check "one study listed, no next link" [ "$(jget "$BODY" "len(d['jobs']) == 1 and not any(l['rel'] == 'next' for l in d['links'])")" = True ]
req GET "$D_URL/jobs?limit=6&study=$SID"
check "a full last page (6 of 6): no next link" [ "$(jget "$BODY" "len(d['jobs']) == 6 and not any(l['rel'] == 'next' for l in d['links'])")" = True ]
req GET "$D_URL/jobs?limit=4&study=$SID"
NEXT=$(jget "$BODY" "[l['href'] for l in d['links'] if l['rel'] == 'next'][0]")
check "a page of 4 of 6: next link" [ -n "$NEXT" ]
req GET "$D_URL$NEXT"
check "  the next page holds the other 2, no further next" [ "$(jget "$BODY" "len(d['jobs']) == 2 and not any(l['rel'] == 'next' for l in d['links'])")" = True ]

# ---------------------------------------------------------- cancelled run: steps
L=$(submit "$D_URL" "$TMP/long.json")
stepped() { req GET "$D_URL/jobs/$L"; [ "$(jget "$BODY" "d.get('simulation', {}).get('step', 0)")" -gt 0 ]; }
wait_until stepped
req DELETE "$D_URL/jobs/$L"
wait_status "$D_URL" "$L" '^dismissed$'
req GET "$D_URL/jobs/$L"
check "cancelled run: simulation.step = cost.steps ($(jget "$BODY" "d['simulation']['step']") / $(jget "$BODY" "d.get('cost', {}).get('steps')"))" [ "$(jget "$BODY" "d['simulation']['step'] == d['cost']['steps'] > 0")" = True ]

# ---------------------------------------------------------- cancelled study: progress
study_of "$TMP/long.json" '[{"pointer": "/output/series_every", "values": [1, 2, 3]}]' >"$TMP/long3.json"
post "$D_URL" study "$TMP/long3.json"
LS=$(jget "$BODY" "d['jobID']")
moving() { req GET "$D_URL/jobs/$LS"; [ "$(jget "$BODY" "d['progress']")" -gt 0 ]; }
wait_until moving
req DELETE "$D_URL/jobs/$LS"
wait_status "$D_URL" "$LS" '^dismissed$'
req GET "$D_URL/jobs/$LS"
P=$(jget "$BODY" "d['progress']")
EXPECT=$(curl -s "$D_URL/jobs?study=$LS" | "$PY" -c "import json,sys; k=json.load(sys.stdin)['jobs']; print(int(sum(j['progress'] for j in k) / len(k)))")
reached() { [ "$1" -lt 100 ] && [ "$1" -ge $(($2 - 1)) ] && [ "$1" -le $(($2 + 1)) ]; }
check "cancelled study: progress $P is what its children reached ($EXPECT), not 100" reached "$P" "$EXPECT"
check "  statusInfo valid" valid job

# ---------------------------------------------------------- start-up messages
PORT=${D_URL##*:}
start_refused P "$TMP/other" --listen "127.0.0.1:$PORT"
check "a taken port: exit 1 (got $P_RC)" [ "$P_RC" = 1 ]
check "  the log names the address and why" grep -q "cannot listen on 127.0.0.1:$PORT: Address already in use" "$P_LOG"
check "  no 'port 0'" bash -c "! grep -q 'port 0' '$P_LOG'"
TOKEN=$(head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '%s\n' "$TOKEN" >"$TMP/tokens"
chmod 644 "$TMP/tokens"
start_refused T "$TMP/other" --token-file "$TMP/tokens"
check "a token file others can read (0644): refused, exit 2 (got $T_RC)" [ "$T_RC" = 2 ]
check "  the log says why and what to do" grep -q "readable by other users (mode 0644).*chmod 600" "$T_LOG"
chmod 600 "$TMP/tokens"
start_daemon A "$TMP/data-auth" --token-file "$TMP/tokens" || exit 1
check "  mode 0600: accepted" [ "$(curl -s -o /dev/null -w '%{http_code}' -H "Authorization: Bearer $TOKEN" "$A_URL/jobs")" = 200 ]

# ---------------------------------------------------------- quota and floor
start_daemon Q "$TMP/data-quota" --max-output-mb 2 || exit 1
post "$Q_URL" run "$TMP/long.json"
check "estimated result above max_output_mb 2: 413" [ "$STATUS" = 413 ]
check "  problem+json, type output-quota" [ "$(header Content-Type):$(jget "$BODY" "d['type']")" = "application/problem+json:urn:tlsph:problem:output-quota" ]
check "  names the estimate (400 particles x (52 B + 101 frames x 136 B))" [ "$(jget "$BODY" "any(e['pointer'] == '#/inputs/scene/output/frames' and '400 particles x (52 B + 101 frames x 136 B)' in e['detail'] for e in d['errors'])")" = True ]
check "  problem valid" valid error
study_of "$TMP/long.json" '[{"pointer": "/output/frames", "values": [10, 100]}]' >"$TMP/quota_study.json"
post "$Q_URL" study "$TMP/quota_study.json"
check "a study with one child above the quota: 413 naming that child" [ "$STATUS:$(jget "$BODY" "[e['detail'][:8] for e in d['errors']]")" = "413:['child 1 ']" ]
post "$Q_URL" run "$TMP/tiny.json"
check "a job within the quota: 201" [ "$STATUS" = 201 ]
start_daemon F "$TMP/data-floor" --min-free-mb 1099511627776 || exit 1
post "$F_URL" run "$TMP/tiny.json"
check "free space below min_free_mb: 507" [ "$STATUS" = 507 ]
check "  problem+json, type insufficient-storage, names the floor" [ "$(header Content-Type):$(jget "$BODY" "d['type'].endswith('insufficient-storage') and 'floor' in d['detail']")" = "application/problem+json:True" ]
req GET "$F_URL/healthz"
check "  healthz degraded, naming the floor" [ "$(jget "$BODY" "d['status'] == 'degraded' and any('floor' in p for p in d['problems'])")" = True ]
finish
