#!/bin/bash
# OGC API - Processes - Part 1: Core 1.0 (OGC 18-062r2) where tlsphd used to
# deviate (issue 13, item 19); what remains is listed in docs/api.md,
# "Conformance and deviations":
#   - the execute request may carry outputs and response (7.11.2: both
#     accepted; outputs names the process's one output, by reference), and a
#     subscriber is refused with 422 naming it (no callback conformance class);
#   - statusInfo has updated (7.12, statusInfo.yaml);
#   - GET /jobs filters by type, processID, status (repeated or comma
#     separated: every value counts), datetime (instant or interval, open
#     ends) and minDuration / maxDuration (11.2, the job-list parameters);
#   - the results of a successful job are the map of its declared outputs
#     (7.13, /req/core/job-results-async-document);
#   - results not ready: 404 with the OGC type result-not-ready
#     (/req/core/job-results-exception/results-not-ready);
#   - results of a failed or dismissed job: an exception (4xx/5xx) whose type
#     names why (/req/core/job-results-failed).
. "$(dirname "$0")/common.sh"

OGC_NOT_READY=http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/result-not-ready
wrap() { "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))"; }
strip_scene 2e-4 2 tiny | wrap >"$TMP/tiny.json"
strip_scene 2e-2 100 | wrap >"$TMP/long.json"
wrap <"$top_srcdir/tests/scenes/good/unstable.json" >"$TMP/unstable.json"
# with_members FILE JSON_MEMBERS: the request of FILE with extra top-level members
with_members() { "$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); d.update(json.loads(sys.argv[2])); print(json.dumps(d))" "$1" "$2"; }
post() { req POST "$D_URL/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$1"; }
has_error_at() { [ "$(jget "$BODY" "any(e['pointer'] == '#$1' and '$2' in e['detail'] for e in d.get('errors', []))")" = True ]; }

start_daemon D "$TMP/data" --max-jobs 1 --kill-grace 1 || exit 1

# ---------------------------------------------------------- execute request
with_members "$TMP/tiny.json" '{"outputs": {"result": {"transmissionMode": "reference", "format": {"mediaType": "application/x-hdf5"}}}, "response": "document"}' >"$TMP/doc.json"
post "$TMP/doc.json"
check "execute with outputs and response document: 201 (was 422)" [ "$STATUS" = 201 ]
OK_ID=$(jget "$BODY" "d.get('jobID', '')")
with_members "$TMP/tiny.json" '{"response": "raw"}' >"$TMP/raw.json"
post "$TMP/raw.json"
check "execute with response raw: 201" [ "$STATUS" = 201 ]
with_members "$TMP/tiny.json" '{"response": "inline"}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "response other than document/raw: 422" [ "$STATUS" = 422 ]
check "  at /response" has_error_at /response document
with_members "$TMP/tiny.json" '{"subscriber": {"successUri": "http://127.0.0.1:9/done"}}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "subscriber: 422 naming callbacks as unsupported" [ "$STATUS" = 422 ]
check "  at /subscriber" has_error_at /subscriber 'not supported'
check "  problem valid" valid error
with_members "$TMP/tiny.json" '{"outputs": {"movie": {}}}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "an output the process does not declare: 422 at /outputs/movie" has_error_at /outputs/movie 'unknown output'
with_members "$TMP/tiny.json" '{"outputs": {"result": {"transmissionMode": "value"}}}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "transmissionMode value: 422 (outputs go by reference)" has_error_at /outputs/result/transmissionMode 'reference'

# ---------------------------------------------------------- results not ready
LONG=$(submit "$D_URL" "$TMP/long.json")
req GET "$D_URL/jobs/$LONG/results"
check "results of an unfinished job: 404 (was 409 or 200)" [ "$STATUS" = 404 ]
check "  type result-not-ready (OGC URI)" [ "$(jget "$BODY" "d['type']")" = "$OGC_NOT_READY" ]
req GET "$D_URL/jobs/$LONG"
check "statusInfo has updated" [ "$(jget "$BODY" "'updated' in d")" = True ]
check "  statusInfo valid" valid job

# ---------------------------------------------------------- results of finished jobs
wait_status "$D_URL" "$OK_ID" '^successful$' || fail "tiny job did not succeed"
req GET "$D_URL/jobs/$OK_ID/results"
check "results of a successful run: the map of its outputs" [ "$(jget "$BODY" "sorted(d)")" = "['result']" ]
check "  result by reference: the HDF5 file" [ "$(jget "$BODY" "d['result']['href'] + ' ' + d['result']['type']")" = "/jobs/$OK_ID/results/result.h5 application/x-hdf5" ]
check "  valid (openapi results)" valid openapi:results
HREF=$(jget "$BODY" "d['result']['href']")
STATUS=$(curl -s -o /dev/null -w '%{http_code}' "$D_URL$HREF")
check "  the output's href serves it" [ "$STATUS" = 200 ]
req GET "$D_URL/jobs/$OK_ID"
check "statusInfo: updated is the latest of created, started, finished" \
    [ "$(jget "$BODY" "d['updated'] == max(d['created'], d['started'], d['finished'])")" = True ]
# dismissed while running, so it counts among the jobs that ran (maxDuration
# below): on a busy machine it may still be queued behind the tiny job here
wait_status "$D_URL" "$LONG" '^running$' || fail "long job did not start"
req DELETE "$D_URL/jobs/$LONG"
wait_status "$D_URL" "$LONG" '^dismissed$'
req GET "$D_URL/jobs/$LONG/results"
check "results of a dismissed job: an exception, 404" [ "$STATUS" = 404 ]
check "  type job-dismissed" [ "$(jget "$BODY" "d['type']")" = urn:tlsph:problem:job-dismissed ]
check "  problem valid" valid error
BAD=$(submit "$D_URL" "$TMP/unstable.json")
wait_status "$D_URL" "$BAD" '^failed$' || fail "unstable job did not fail"
req GET "$D_URL/jobs/$BAD/results"
check "results of a failed (unstable) run: 422 exception (was 200)" [ "$STATUS" = 422 ]
check "  type names why: job-unstable" [ "$(jget "$BODY" "d['type']")" = urn:tlsph:problem:job-unstable ]
check "  links to the partial result and the log" \
    [ "$(jget "$BODY" "sorted(l['rel'] for l in d['links'])")" = "['enclosure', 'log', 'up']" ]
check "  problem valid" valid error

"$PY" -c "
import json, sys
s = json.load(open(sys.argv[1]))
print(json.dumps({'inputs': {'base': s, 'sweep': {'parameters': [{'pointer': '/output/series_every', 'values': [1, 2]}]}}}))" \
    "$top_srcdir/tests/scenes/good/unstable.json" >"$TMP/bad_study.json"
req POST "$D_URL/processes/study/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/bad_study.json"
BAD_STUDY=$(jget "$BODY" "d.get('jobID', '')")
wait_status "$D_URL" "$BAD_STUDY" '^failed$' || fail "study of unstable children did not fail"
req GET "$D_URL/jobs/$BAD_STUDY/results"
check "results of a failed study: 422 job-children_failed, linking its summary" \
    [ "$STATUS:$(jget "$BODY" "d['type'] + ' ' + ','.join(l['rel'] for l in d['links'])")" = "422:urn:tlsph:problem:job-children_failed up,summary" ]
req DELETE "$D_URL/jobs/$BAD_STUDY"

# ---------------------------------------------------------- /jobs filters

wait_until bash -c "[ \"\$(curl -s '$D_URL/jobs?status=accepted,running' | '$PY' -c 'import json,sys; print(len(json.load(sys.stdin)[\"jobs\"]))')\" = 0 ]"
count() { req GET "$D_URL/jobs?$1"; jget "$BODY" "len(d['jobs'])"; }
check "all jobs: 4" [ "$(count limit=100)" = 4 ]
check "status=successful&status=dismissed: both values count (was the first only)" \
    [ "$(count 'status=successful&status=dismissed')" = 3 ]
check "status=failed,dismissed (comma list)" [ "$(count 'status=failed,dismissed')" = 2 ]
check "status=bogus: 400" bash -c "[ \"\$(curl -s -o /dev/null -w '%{http_code}' '$D_URL/jobs?status=bogus')\" = 400 ]"
check "type=process: all" [ "$(count type=process)" = 4 ]
check "type=other: none (was all)" [ "$(count type=other)" = 0 ]
check "datetime in 2000: none (was all)" [ "$(count 'datetime=2000-01-01T00:00:00Z/2000-12-31T23:59:59Z')" = 0 ]
check "datetime ../2000-01-01T00:00:00Z: none" [ "$(count 'datetime=../2000-01-01T00:00:00Z')" = 0 ]
check "datetime 2000-01-01T00:00:00Z/..: all" [ "$(count 'datetime=2000-01-01T00:00:00%2B01:00/..')" = 4 ]
check "datetime=yesterday: 400" bash -c "[ \"\$(curl -s -o /dev/null -w '%{http_code}' '$D_URL/jobs?datetime=yesterday')\" = 400 ]"
check "minDuration=1e9: none (was all)" [ "$(count minDuration=1e9)" = 0 ]
check "maxDuration=1e9: every job that ran" [ "$(count maxDuration=1e9)" = 4 ]
check "minDuration=-1: 400" bash -c "[ \"\$(curl -s -o /dev/null -w '%{http_code}' '$D_URL/jobs?minDuration=-1')\" = 400 ]"
req GET "$D_URL/jobs?limit=1&status=successful&status=dismissed&type=process"
check "the next link keeps the filters" \
    [ "$(jget "$BODY" "[l['href'] for l in d['links'] if l['rel'] == 'next'][0]")" = "/jobs?limit=1&offset=1&status=successful,dismissed&type=process" ]
check "job list valid" valid 'job#/$defs/jobList'
finish
