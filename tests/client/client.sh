#!/bin/bash
# Integration tests of the tlsph client against a real tlsphd on loopback.
# Environment: top_srcdir, top_builddir, SYSTEM_PYTHON (see tests/daemon/common.sh);
# CLIENT_WRAPPER (e.g. "valgrind --leak-check=full --error-exitcode=99 -q") runs
# every client invocation under a wrapper.
. "$(cd "$(dirname "$0")/.." && pwd)/daemon/common.sh"

CLIENT=$top_builddir/tlsph
[ -x "$CLIENT" ] || { echo "FAIL: $CLIENT not built"; exit 1; }
# run the client: stdout → $TMP/out, stderr → $TMP/err, exit code → RC
cl() { ${CLIENT_WRAPPER:-} "$CLIENT" "$@" >"$TMP/out" 2>"$TMP/err"; RC=$?; }
rc_is() { [ "$RC" = "$1" ] || { echo "# exit code $RC, wanted $1; stderr:"; sed 's/^/#   /' "$TMP/err"; return 1; }; }
out_has() { grep -q -- "$1" "$TMP/out"; }
err_has() { grep -q -- "$1" "$TMP/err"; }

# keep the user's own settings out of the tests
export XDG_CONFIG_HOME=$TMP/xdg HOME=$TMP/home
unset TLSPH_URL TLSPH_TOKEN

start_daemon D "$TMP/data" --max-jobs 1 || exit 1
export TLSPH_URL=$D_URL
DATA=$TMP/data

# ------------------------------------------------------------ submit / watch / wait / status
cl submit "$top_srcdir/examples/elastic-strip.json"
ID=$(cat "$TMP/out")
check "submit prints only a job id" bash -c "[[ '$ID' =~ ^[0-9a-f]{32}$ ]] && [ \$(wc -l <'$TMP/out') = 1 ]"
cl watch "$ID"
check "watch (not a terminal): exit 0" rc_is 0
check "watch: plain lines, no control characters" bash -c "! grep -q \$'[\r\033]' '$TMP/out'"
check "watch: final line says successful" bash -c "tail -1 '$TMP/out' | grep -q '$ID successful'"
cp "$TMP/out" "$TMP/watch.txt"
cl wait "$ID"
check "wait: exit 0, prints successful" bash -c "[ $RC = 0 ] && grep -q successful '$TMP/out'"
cl status "$ID"
check "status: human summary" bash -c "[ $RC = 0 ] && grep -q '^status *successful' '$TMP/out' && grep -q particles '$TMP/out'"
cl status "$ID" --json
check "status --json: the statusInfo" "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["jobID"]==sys.argv[2] and d["status"]=="successful"' "$TMP/out" "$ID"

# ------------------------------------------------------------ fetch (and resume)
F=$TMP/fetched
cl fetch "$ID" -o "$F"
check "fetch: exit 0" rc_is 0
check "fetch: result.h5 identical to the server's" cmp -s "$F/result.h5" "$DATA/jobs/$ID/result.h5"
check "fetch: result.xmf identical to the server's" cmp -s "$F/result.xmf" "$DATA/jobs/$ID/result.xmf"
check "fetch: no .part left" bash -c "! ls '$F' | grep -q part"
rm -f "$F/result.h5"
head -c 1000 "$DATA/jobs/$ID/result.h5" >"$F/result.h5.part"
cl fetch "$ID" -o "$F"
check "resumed fetch: exit 0 and says resumed" bash -c "[ $RC = 0 ] && grep -q 'resumed at 1000' '$TMP/err'"
check "resumed fetch: identical file" cmp -s "$F/result.h5" "$DATA/jobs/$ID/result.h5"
# a partial file from another version (ETag differs): If-Range makes the server send all
rm -f "$F/result.h5"
head -c 1000 /dev/urandom >"$F/result.h5.part"
echo '"stale-etag"' >"$F/result.h5.part.etag"
cl fetch "$ID" -o "$F"
check "stale partial (ETag changed): restarted, identical file" \
    bash -c "[ $RC = 0 ] && cmp -s '$F/result.h5' '$DATA/jobs/$ID/result.h5' && ! grep -q resumed '$TMP/err' && [ ! -e '$F/result.h5.part.etag' ]"
(cd "$TMP" && ${CLIENT_WRAPPER:-} "$CLIENT" fetch "$ID" >/dev/null 2>&1)
check "fetch: default directory ./ID" cmp -s "$TMP/$ID/result.h5" "$DATA/jobs/$ID/result.h5"

# ------------------------------------------------------------ series
cl series "$ID"
check "series: lists names with units" bash -c "[ $RC = 0 ] && grep -q '^kinetic_energy *J' '$TMP/out' && grep -q 'groups/right/displacement' '$TMP/out'"
cl series "$ID" kinetic_energy
curl -s "$D_URL/jobs/$ID/results/series/kinetic_energy" >"$TMP/curl.json"
check "series JSON equals the endpoint" "$PY" -c 'import json,sys; assert json.load(open(sys.argv[1])) == json.load(open(sys.argv[2]))' "$TMP/out" "$TMP/curl.json"
cl series "$ID" kinetic_energy --csv
curl -s "$D_URL/jobs/$ID/results/series/kinetic_energy?format=csv" >"$TMP/curl.csv"
check "series CSV identical bytes" cmp -s "$TMP/out" "$TMP/curl.csv"
cl series "$ID" groups/right/displacement kinetic_energy
check "series with two names: a JSON array" "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert [s["name"] for s in d] == ["groups/right/displacement","kinetic_energy"]' "$TMP/out"
cl series "$ID" no_such_series
check "series: unknown name → exit 2" rc_is 2

# ------------------------------------------------------------ plot
svg_check() { # FILE EXPECTED_POLYLINES SERIES...: each polyline has the series' length
    "$PY" - "$@" <<'PYEOF'
import json, sys, urllib.request, xml.etree.ElementTree as ET
f, n, names = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
root = ET.parse(f).getroot()
ns = "{http://www.w3.org/2000/svg}"
pl = root.findall(".//" + ns + "polyline")
assert len(pl) == n, (len(pl), n)
for p, name in zip(pl, names):
    url, job = name.split("|")
    d = json.load(urllib.request.urlopen(url))
    pts = p.get("points").split()
    assert len(pts) == len(d["time"]), (name, len(pts), len(d["time"]))
    for q in pts:
        x, y = map(float, q.split(","))
texts = " ".join(t.text or "" for t in root.iter(ns + "text"))
assert "[J]" in texts and "time [s]" in texts, texts
PYEOF
}
S=$D_URL/jobs/$ID/results/series
cl plot "$ID" kinetic_energy internal_energy -o "$TMP/energy.svg"
check "plot two series: exit 0" rc_is 0
check "plot: well-formed SVG, 2 polylines with the series' lengths, units" \
    svg_check "$TMP/energy.svg" 2 "$S/kinetic_energy|" "$S/internal_energy|"
cl plot "$ID" groups/right/reaction_force:0 --x groups/right/displacement:x -o "$TMP/fd.svg"
check "plot --x (force-displacement): exit 0" rc_is 0
check "plot --x: 1 polyline, axis labels with units" "$PY" - "$TMP/fd.svg" "$S/groups/right/reaction_force" <<'PYEOF'
import json, sys, urllib.request, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot(); ns = "{http://www.w3.org/2000/svg}"
pl = root.findall(".//" + ns + "polyline")
d = json.load(urllib.request.urlopen(sys.argv[2]))
assert len(pl) == 1 and len(pl[0].get("points").split()) == len(d["time"])
texts = " ".join(t.text or "" for t in root.iter(ns + "text"))
assert "displacement x of groups/right [m]" in texts and "[N]" in texts, texts
PYEOF
cl plot "$ID" kinetic_energy:3 -o "$TMP/bad.svg"
check "plot: component of a scalar series → exit 1" rc_is 1

# ------------------------------------------------------------ cancel, timeout
strip_scene 2e-2 20 >"$TMP/long.json"
cl submit "$TMP/long.json"
LID=$(cat "$TMP/out")
wait_status "$D_URL" "$LID" running
cl wait "$LID" --timeout 1
check "wait --timeout on a running job → exit 8" rc_is 8
cl cancel "$LID"
check "cancel: exit 0, prints dismissed" bash -c "[ $RC = 0 ] && grep -q dismissed '$TMP/out'"
cl wait "$LID"
check "wait on a dismissed job → exit 4" rc_is 4
cl cancel "$ID"
check "cancel on a final job keeps it" bash -c "[ $RC = 0 ] && [ -e '$DATA/jobs/$ID/result.h5' ]"

# ------------------------------------------------------------ study
"$PY" - "$top_srcdir/tests/daemon/examples/study.json" >"$TMP/study.json" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["base"]["bodies"][0]["spacing"] = 0.002
s["sweep"] = {"mode": "product", "parameters": [
    {"pointer": "/parameters/tau", "values": [1e-4, 2e-4]},
    {"pointer": "/parameters/vmax", "values": [0.05, 0.15]}]}
print(json.dumps(s))
PYEOF
cl study submit "$TMP/study.json"
SID=$(cat "$TMP/out")
check "study submit prints an id" bash -c "[[ '$SID' =~ ^[0-9a-f]{32}$ ]]"
cl wait "$SID" --timeout 600  # a hang detector: the study takes seconds alone, longer on a loaded machine
check "study: wait → successful" rc_is 0
cl study status "$SID"
check "study status: 4 children successful" bash -c "[ $RC = 0 ] && grep -q '4 successful' '$TMP/out'"
cl study table "$SID"
check "study table: header + 4 rows per block, at most 100 columns, units, numbers alike" bash -c "[ $RC = 0 ] &&
    head -1 '$TMP/out' | grep -q '^seq  *job_id  *status' && [ \$(grep -c '^ *[0-3]  ' '$TMP/out') -ge 4 ] &&
    '$PY' '$top_srcdir/tests/client/table_check.py' '$TMP/out' 100 peak_reaction final_kinetic 'wall [s]'"
cl study table "$SID" --csv
curl -s "$D_URL/jobs/$SID/results/summary?format=csv" >"$TMP/curl.csv"
check "study table --csv: 4 rows, same bytes as the endpoint" bash -c "[ \$(wc -l <'$TMP/out') = 5 ] && cmp -s '$TMP/out' '$TMP/curl.csv'"
cl list --study "$SID"
check "list --study: 4 jobs" bash -c "[ $RC = 0 ] && [ \$(grep -c successful '$TMP/out') = 4 ]"
cl list --status dismissed --limit 5
check "list --status dismissed shows the cancelled job" bash -c "[ $RC = 0 ] && grep -q '$LID' '$TMP/out'"

# ------------------------------------------------------------ errors and exit codes
echo '{"name": "x"}' >"$TMP/bad.json"
cl submit "$TMP/bad.json"
check "bad scene → exit 2 with pointers" bash -c "[ $RC = 2 ] && grep -q '#/inputs/scene/bodies' '$TMP/err' && [ ! -s '$TMP/out' ]"
echo '{"name": ' >"$TMP/notjson.json"
cl submit "$TMP/notjson.json"
check "scene that is not JSON → exit 1" rc_is 1
cl submit "$TMP/does-not-exist.json"
check "missing scene file → exit 7" rc_is 7
cl status ../../etc/passwd
check "invalid id rejected client-side → exit 1" bash -c "[ $RC = 1 ] && grep -q 'not a job id' '$TMP/err'"
cl status 0123456789abcdef0123456789abcdef
check "unknown job → exit 2, problem title printed" bash -c "[ $RC = 2 ] && grep -q 'No such job' '$TMP/err'"
cl frobnicate
check "unknown command → exit 1" rc_is 1
PORT=$(free_port)
cl --url "http://127.0.0.1:$PORT" list
check "server down → exit 5, 'cannot connect'" bash -c "[ $RC = 5 ] && grep -q 'cannot connect to http://127.0.0.1:$PORT' '$TMP/err'"
cl fetch 0123456789abcdef0123456789abcdef -o "$TMP/nothing"
check "fetch of an unknown job → exit 2, no file left" bash -c "[ $RC = 2 ] && [ -z \"\$(ls '$TMP/nothing')\" ]"

# ------------------------------------------------------------ authentication and settings
TOKEN=$(head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n')
printf '%s\n' "$TOKEN" >"$TMP/tokens"
chmod 600 "$TMP/tokens" # the daemon refuses a token file others can read
start_daemon A "$TMP/data-auth" --token-file "$TMP/tokens" || exit 1
cl --url "$A_URL" --token wrong list
check "wrong token → exit 6, clear message" bash -c "[ $RC = 6 ] && grep -q 'authentication failed' '$TMP/err'"
cl --url "$A_URL" list
check "no token → exit 6" rc_is 6
TLSPH_TOKEN=$TOKEN cl --url "$A_URL" list
check "token from TLSPH_TOKEN → exit 0" rc_is 0
TLSPH_TOKEN=wrong cl --url "$A_URL" --token "$TOKEN" list
check "flag beats env" rc_is 0
mkdir -p "$XDG_CONFIG_HOME/tlsph"
printf '# client settings\nurl = %s\ntoken = %s\n' "$A_URL" "$TOKEN" >"$XDG_CONFIG_HOME/tlsph/client.conf"
TLSPH_URL= cl list
check "url and token from \$XDG_CONFIG_HOME/tlsph/client.conf" rc_is 0
TLSPH_URL= TLSPH_TOKEN=wrong cl list
check "env beats the config file" rc_is 6
printf 'url = %s\n' "$D_URL" >"$TMP/other.conf"
TLSPH_URL= cl --config "$TMP/other.conf" status "$ID"
check "--config FILE replaces the default config file" rc_is 0
cl --config "$TMP/missing.conf" list
check "missing --config file → exit 7" rc_is 7
cl --url ftp://x list
check "non-http URL → exit 1" rc_is 1

finish
