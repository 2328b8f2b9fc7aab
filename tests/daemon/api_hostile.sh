#!/bin/bash
# tlsphd API: malformed and hostile requests.  Each must get the right 4xx with
# an application/problem+json body valid against schemas/error.schema.json; the
# daemon must stay up.  A second daemon with a token file checks 401s.
# TLSPHD_WRAPPER (e.g. "valgrind --error-exitcode=99") runs the daemon under a tool.
. "$(dirname "$0")/common.sh"

DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 1 --max-children 50 --max-particles 100000 || exit 1
B=$D_URL
CT=(-H 'Content-Type: application/json')

# expect STATUS DESC METHOD URL [curl args]: status, problem content type, schema
expect() {
    local want=$1 desc=$2 m=$3 u=$4; shift 4
    req "$m" "$u" "$@"
    local ct; ct=$(header Content-Type)
    if [ "$STATUS" != "$want" ]; then
        fail "$desc: got $STATUS, want $want ($(head -c 300 "$BODY"))"
    elif [ "$ct" != application/problem+json ]; then
        fail "$desc: content type '$ct'"
    elif ! valid error; then
        fail "$desc: problem body invalid"
    else
        ok "$desc ($want)"
    fi
}
# has_pointer PREFIX: some errors[].pointer starts with PREFIX
has_pointer() { [ "$(jget "$BODY" "any(e['pointer'].startswith('$1') for e in d.get('errors', []))")" = True ]; }

strip_scene 4e-4 2 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/tiny.json"
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
# a finished job (for Range / series / field errors)
FID=$(submit "$B" "$TMP/tiny.json")
wait_status "$B" "$FID" '^successful$'
# a running job and a queued one (max-jobs 1) for result-not-ready (404)
RID=$(submit "$B" "$TMP/long.json")
QID=$(submit "$B" "$TMP/long.json")
wait_status "$B" "$RID" '^running$'
HEX=0123456789abcdef0123456789abcdef
RUN=$B/processes/run/execution
STUDY=$B/processes/study/execution

# ------------------------------------------------------------ bodies
expect 400 "bad JSON" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": '
expect 400 "trailing garbage" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": {}} x'
expect 400 "duplicate keys" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": {}, "inputs": {}}'
expect 400 "invalid UTF-8" POST "$RUN" "${CT[@]}" --data-binary $'{"inputs": {"scene": "\xff\xfe"}}'
expect 400 "empty body" POST "$RUN" "${CT[@]}" --data-binary ''
"$PY" -c "print('['*100000 + ']'*100000)" >"$TMP/deep.json"
expect 400 "deeply nested JSON" POST "$RUN" "${CT[@]}" --data-binary @"$TMP/deep.json"
expect 422 "JSON array instead of object" POST "$RUN" "${CT[@]}" --data-binary '[1, 2]'
check "  pointer #" has_pointer '#'
expect 422 "missing inputs" POST "$RUN" "${CT[@]}" --data-binary '{}'
check "  pointer #/inputs" has_pointer '#/inputs'
expect 422 "unknown top-level member" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": {"scene": {}}, "evil": 1}'
expect 422 "inputs not an object" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": []}'
expect 422 "scene of the wrong type" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": {"scene": "strip"}}'
check "  pointer #/inputs/scene" has_pointer '#/inputs/scene'
expect 422 "unknown input" POST "$RUN" "${CT[@]}" --data-binary '{"inputs": {"scene": {}, "x": 1}}'
"$PY" - "$top_srcdir/examples/elastic-strip.json" >"$TMP/nu.json" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1])); s["materials"]["steel"]["poisson_ratio"] = 0.5
print(json.dumps({"inputs": {"scene": s}}))
PYEOF
expect 422 "invalid scene (nu = 0.5)" POST "$RUN" "${CT[@]}" --data-binary @"$TMP/nu.json"
check "  pointer #/inputs/scene/materials/steel/poisson_ratio" has_pointer '#/inputs/scene/materials/steel/poisson_ratio'
"$PY" - "$top_srcdir/examples/elastic-strip.json" >"$TMP/maxp.json" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1])); s["limits"] = {"max_particles": 1000000}
print(json.dumps({"inputs": {"scene": s}}))
PYEOF
expect 422 "scene particle limit above the server's" POST "$RUN" "${CT[@]}" --data-binary @"$TMP/maxp.json"
check "  pointer #/inputs/scene/limits/max_particles" has_pointer '#/inputs/scene/limits/max_particles'
"$PY" - "$top_srcdir/examples/elastic-strip.json" >"$TMP/big.json" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1])); s["bodies"][0]["spacing"] = 1e-5
print(json.dumps({"inputs": {"scene": s}}))
PYEOF
expect 422 "too many particles for the server limit" POST "$RUN" "${CT[@]}" --data-binary @"$TMP/big.json"
head -c $((9 * 1024 * 1024)) /dev/zero | tr '\0' ' ' >"$TMP/huge.json"
expect 413 "9 MiB body" POST "$RUN" "${CT[@]}" --data-binary @"$TMP/huge.json"
expect 413 "9 MiB chunked body" POST "$RUN" "${CT[@]}" -H 'Transfer-Encoding: chunked' --data-binary @"$TMP/huge.json"
expect 415 "wrong content type" POST "$RUN" -H 'Content-Type: text/plain' --data-binary @"$TMP/tiny.json"
expect 415 "no content type" POST "$RUN" -H 'Content-Type:' --data-binary @"$TMP/tiny.json"
expect 415 "form content type" POST "$RUN" --data-binary @"$TMP/tiny.json"

# ------------------------------------------------------------ studies
"$PY" - "$top_srcdir/examples/elastic-strip.json" "$TMP" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1])); d = sys.argv[2]
def w(name, sweep):
    json.dump({"inputs": {"base": s, "sweep": sweep}}, open(f"{d}/{name}.json", "w"))
w("sweep_ptr", {"mode": "product", "parameters": [{"pointer": "/nope/deeper", "values": [1, 2]}]})
w("sweep_many", {"mode": "product", "parameters": [{"pointer": "/parameters/vmax", "values": list(range(1, 11))},
                                                   {"pointer": "/parameters/tau", "values": list(range(1, 11))}]})
w("sweep_nu", {"mode": "zip", "parameters": [{"pointer": "/materials/steel/poisson_ratio", "values": [0.3, 0.5]}]})
w("sweep_mode", {"mode": "shuffle", "parameters": [{"pointer": "/parameters/vmax", "values": [1]}]})
PYEOF
expect 422 "study: sweep pointer not in the base" POST "$STUDY" "${CT[@]}" --data-binary @"$TMP/sweep_ptr.json"
check "  pointer #/inputs/sweep/parameters/0..." has_pointer '#/inputs/sweep/parameters/0'
expect 422 "study: too many children (100 > 50)" POST "$STUDY" "${CT[@]}" --data-binary @"$TMP/sweep_many.json"
expect 422 "study: swept value invalid (nu = 0.5)" POST "$STUDY" "${CT[@]}" --data-binary @"$TMP/sweep_nu.json"
check "  pointer #/inputs/sweep/parameters/0" has_pointer '#/inputs/sweep/parameters/0'
expect 422 "study: unknown sweep mode" POST "$STUDY" "${CT[@]}" --data-binary @"$TMP/sweep_mode.json"
expect 422 "study: missing base" POST "$STUDY" "${CT[@]}" --data-binary '{"inputs": {"sweep": {"mode": "zip", "parameters": []}}}'

# ------------------------------------------------------------ paths and ids
expect 404 "unknown process (execute)" POST "$B/processes/nope/execution" "${CT[@]}" --data-binary @"$TMP/tiny.json"
expect 404 "unknown process (describe)" GET "$B/processes/nope"
expect 404 "unknown job id (valid hex)" GET "$B/jobs/$HEX"
expect 404 "job id too short" GET "$B/jobs/abc123"
expect 404 "job id uppercase" GET "$B/jobs/$(echo "$FID" | tr a-f A-F)"
expect 404 "job id ../../etc/passwd (encoded)" GET "$B/jobs/..%2F..%2Fetc%2Fpasswd"
expect 404 "job id ../../etc/passwd results" GET "$B/jobs/..%2F..%2Fetc%2Fpasswd/results/result.h5"
expect 404 "job id very long" GET "$B/jobs/$(head -c 8000 /dev/zero | tr '\0' a)"
expect 404 "job id with NUL" GET "$B/jobs/${FID}%00"
expect 404 "/jobs/%2e%2e/x" GET "$B/jobs/%2e%2e/x" --path-as-is
expect 404 "//jobs" GET "$B//jobs" --path-as-is
expect 404 "/jobs/<id>/results/../../x" GET "$B/jobs/$FID/results/../../x" --path-as-is
expect 404 "trailing slash" GET "$B/jobs/$FID/"
expect 404 "unknown resource" GET "$B/nonexistent"
expect 404 "unknown result resource" GET "$B/jobs/$FID/results/secret.txt"
expect 404 "series name with .." GET "$B/jobs/$FID/results/series/..%2F..%2Fscene.json"
expect 404 "unknown series" GET "$B/jobs/$FID/results/series/no_such_series"
expect 404 "unknown field" GET "$B/jobs/$FID/results/fields/no_such_field"
expect 400 "bad frame (abc)" GET "$B/jobs/$FID/results/fields/position?frame=abc"
expect 404 "frame out of range" GET "$B/jobs/$FID/results/fields/position?frame=99999"
expect 400 "bad format" GET "$B/jobs/$FID/results/series/kinetic_energy?format=xml"
expect 404 "summary of a run job" GET "$B/jobs/$FID/results/summary"

# ------------------------------------------------------------ methods
expect 405 "PUT /jobs" PUT "$B/jobs"
check "  Allow header" [ -n "$(header Allow)" ]
expect 405 "DELETE /processes" DELETE "$B/processes"
expect 405 "POST /jobs/<id>" POST "$B/jobs/$FID" "${CT[@]}" --data-binary '{}'
expect 405 "GET execution" GET "$RUN"
check "  Allow: POST" [ "$(header Allow)" = POST ]
expect 405 "PATCH result.h5" PATCH "$B/jobs/$FID/results/result.h5"

# ------------------------------------------------------------ state and ranges
expect 404 "results of a queued job" GET "$B/jobs/$QID/results"
expect 404 "result.h5 of a running job" GET "$B/jobs/$RID/results/result.h5"
expect 416 "bad Range (garbage)" GET "$B/jobs/$FID/results/result.h5" -H 'Range: bytes=abc'
expect 416 "bad Range (b < a)" GET "$B/jobs/$FID/results/result.h5" -H 'Range: bytes=500-100'
# a Range unit other than bytes is ignored (RFC 9110 14.2): api_rfc9110.sh

# ------------------------------------------------------------ query parameters
expect 400 "limit=-1" GET "$B/jobs?limit=-1"
expect 400 "limit=abc" GET "$B/jobs?limit=abc"
expect 400 "offset=-5" GET "$B/jobs?offset=-5"
expect 400 "status=bogus" GET "$B/jobs?status=bogus"
expect 400 "study=zz" GET "$B/jobs?study=zz"
expect 400 "wait=abc" GET "$B/jobs/$FID?wait=abc"
expect 400 "wait=-1" GET "$B/jobs/$FID?wait=-1"
expect 400 "wait=nan" GET "$B/jobs/$FID?wait=nan"

# ------------------------------------------------------------ afterwards
req GET "$B/jobs"
check "daemon still up: GET /jobs 200" [ "$STATUS" = 200 ]
check "job list valid" valid 'job#/$defs/jobList'
req DELETE "$B/jobs/$RID"
req DELETE "$B/jobs/$QID"
check "queued job dismissed" [ "$(job_status "$B" "$QID")" = dismissed ]

# ------------------------------------------------------------ tokens
TOKEN=$(head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '# test tokens\n%s\n' "$TOKEN" >"$TMP/tokens"
chmod 600 "$TMP/tokens" # the daemon refuses a token file others can read
start_daemon A "$TMP/data-auth" --token-file "$TMP/tokens" || exit 1
expect 401 "no token" GET "$A_URL/jobs"
check "  WWW-Authenticate: Bearer" bash -c "grep -qi '^WWW-Authenticate: Bearer' '$HDRS'"
expect 401 "wrong token" GET "$A_URL/jobs" -H "Authorization: Bearer ${TOKEN}x"
expect 401 "wrong scheme" GET "$A_URL/jobs" -H "Authorization: Basic $TOKEN"
expect 401 "token on submit missing" POST "$A_URL/processes/run/execution" "${CT[@]}" --data-binary @"$TMP/tiny.json"
expect 401 "unknown job without token (no id probing)" GET "$A_URL/jobs/$HEX"
req GET "$A_URL/jobs" -H "Authorization: Bearer $TOKEN"
check "right token: 200" [ "$STATUS" = 200 ]
req GET "$A_URL/healthz"
check "/healthz public" [ "$STATUS" = 200 ]
req GET "$A_URL/openapi.json"
check "/openapi.json public" [ "$STATUS" = 200 ]
check "token file plaintext not in the log" bash -c "! grep -q '$TOKEN' '$A_LOG'"
TOKEN2=config-file-token-$(head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '# tlsphd test config\nmax_jobs = 1\ntoken_sha256 = %s\n' "$(printf '%s' "$TOKEN2" | sha256sum | cut -d' ' -f1)" >"$TMP/tlsphd.conf"
start_daemon C "$TMP/data-conf" --config "$TMP/tlsphd.conf" || exit 1
expect 401 "config-file token: missing" GET "$C_URL/jobs"
req GET "$C_URL/jobs" -H "Authorization: Bearer $TOKEN2"
check "config-file token (token_sha256): 200" [ "$STATUS" = 200 ]
PORT2=$(free_port)
"$TLSPHD" --listen "0.0.0.0:$PORT2" --data-dir "$TMP/data-open" --engine "$ENGINE" >"$TMP/open.log" 2>&1
check "non-loopback without tokens: refused" [ $? -ne 0 ]
check "  with a reason" grep -q 'non-loopback' "$TMP/open.log"

req GET "$B/healthz"
check "first daemon still healthy" [ "$STATUS" = 200 ]
finish
