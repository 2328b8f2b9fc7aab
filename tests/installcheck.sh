#!/bin/sh
# make installcheck: the installed programs work from their install location.
#   tests/installcheck.sh BINDIR PKGDATADIR
# Starts the installed tlsphd (no --engine/--schemas-dir: it must find the
# installed tlsph-run and share/tlsph/schemas itself) on a free loopback port
# with a temporary data directory, checks /openapi.json against the installed
# schemas/openapi.json, runs the installed examples/elastic-strip.json
# (shortened) as a job to "successful" and fetches its result.h5.
set -u
bindir=$1
pkgdatadir=$2
PY=${SYSTEM_PYTHON:-python3}
fail() { echo "installcheck: FAIL: $*"; [ -f "$tmp/log" ] && cat "$tmp/log"; exit 1; }

for f in "$bindir/tlsph-run" "$bindir/tlsphd" "$bindir/tlsph"; do
  [ -x "$f" ] || fail "$f not installed"
done
for f in schemas/openapi.json schemas/scene.schema.json examples/elastic-strip.json; do
  [ -f "$pkgdatadir/$f" ] || fail "$pkgdatadir/$f not installed"
done
command -v curl >/dev/null 2>&1 || { echo "installcheck: curl missing, skipping the daemon check"; exit 0; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/tlsph-installcheck.XXXXXX") || exit 1
pid=
cleanup() {
  [ -n "$pid" ] && kill -TERM "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT

"$bindir/tlsph-run" "$pkgdatadir/examples/elastic-strip.json" --validate >/dev/null ||
  fail "installed tlsph-run does not validate the installed example"

port=$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
url=http://127.0.0.1:$port
(cd "$tmp" && exec "$bindir/tlsphd" --listen "127.0.0.1:$port" --data-dir "$tmp/data" \
  --threads-per-job 1 >"$tmp/log" 2>&1) &
pid=$!
i=0
until curl -sf "$url/healthz" >/dev/null 2>&1; do
  i=$((i + 1)); [ $i -le 100 ] && kill -0 "$pid" 2>/dev/null || fail "tlsphd did not start"
  sleep 0.1
done
grep -q "engine $bindir/tlsph-run" "$tmp/log" || fail "tlsphd does not use the installed engine"

curl -sf -o "$tmp/openapi.json" "$url/openapi.json" || fail "GET /openapi.json"
cmp -s "$tmp/openapi.json" "$pkgdatadir/schemas/openapi.json" ||
  fail "/openapi.json is not the installed schemas/openapi.json"
curl -sf -o /dev/null "$url/schemas/scene.schema.json" || fail "GET /schemas/scene.schema.json"

"$PY" - "$pkgdatadir/examples/elastic-strip.json" >"$tmp/job.json" <<'EOF' || fail "cannot build the job"
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = 2e-4
s["output"]["frames"] = 2
print(json.dumps({"inputs": {"scene": s}}))
EOF
id=$(curl -sf -H 'Content-Type: application/json' --data-binary @"$tmp/job.json" \
  "$url/processes/run/execution" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["jobID"])') ||
  fail "submit"
status=
i=0
while [ $i -lt 10 ]; do
  status=$(curl -s "$url/jobs/$id?wait=30" | "$PY" -c 'import json,sys; print(json.load(sys.stdin)["status"])')
  case $status in successful|failed|dismissed) break ;; esac
  i=$((i + 1))
done
[ "$status" = successful ] || { curl -s "$url/jobs/$id/log"; fail "job $id ended '$status'"; }
curl -sf -o "$tmp/result.h5" "$url/jobs/$id/results/result.h5" || fail "GET result.h5"
[ "$(head -c 8 "$tmp/result.h5" | od -An -c | tr -d ' ')" = '211HDF\r\n032\n' ] ||
  fail "result.h5 is not an HDF5 file"
echo "installcheck: ok ($bindir/tlsphd served /openapi.json and ran job $id with $bindir/tlsph-run)"
