# Shared helpers for the tlsphd API tests (sourced by api*.sh).
# Environment: top_srcdir, top_builddir (default: this directory's ../..),
# SYSTEM_PYTHON (default /usr/bin/python3), KEEP=1 keeps the temp directory.
set -u
here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$(cd "$here/../.." && pwd)}
top_builddir=${top_builddir:-$top_srcdir}
PY=${SYSTEM_PYTHON:-/usr/bin/python3}
TLSPHD=${TLSPHD:-$top_builddir/tlsphd}
ENGINE=$top_builddir/tlsph-run
export SCHEMAS_DIR=$top_srcdir/schemas
FAILS=0
NCHECKS=0
T0=$(date +%s.%N)

for tool in curl "$PY"; do
    command -v "$tool" >/dev/null 2>&1 || { echo "SKIP: $tool missing"; exit 77; }
done
[ -x "$TLSPHD" ] && [ -x "$ENGINE" ] || { echo "FAIL: $TLSPHD or $ENGINE not built"; exit 1; }

TMP=$(mktemp -d "${TMPDIR:-/tmp}/tlsphd-test.XXXXXX")
DAEMON_PIDS=""

# stop_daemons: SIGTERM to every daemon started here, SIGKILL after 5 s
stop_daemons() {
    for p in $DAEMON_PIDS; do kill -TERM "$p" 2>/dev/null; done
    for p in $DAEMON_PIDS; do
        for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$p" 2>/dev/null
    done
    DAEMON_PIDS=""
}
cleanup() {
    stop_daemons
    if [ "${KEEP:-0}" = 1 ]; then echo "# kept $TMP"; else rm -rf "$TMP"; fi
}
trap cleanup EXIT

ok() { NCHECKS=$((NCHECKS + 1)); echo "ok $NCHECKS - $*"; }
fail() { NCHECKS=$((NCHECKS + 1)); FAILS=$((FAILS + 1)); echo "FAIL $NCHECKS - $*"; }
check() { local d=$1; shift; if "$@"; then ok "$d"; else fail "$d"; fi; }

finish() {
    local t1; t1=$(date +%s.%N)
    echo "# $NCHECKS checks, $FAILS failed, $(awk "BEGIN{printf \"%.1f\", $t1 - $T0}") s"
    [ "$FAILS" -eq 0 ]
    exit $?
}

free_port() { "$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }

# The daemon's thread budget follows the machine's cores (--cores defaults to
# the CPUs it may use); the tests say 2, so that jobs the tests expect to run
# side by side do so on a one-CPU runner too (a test's own --cores wins).
# start_daemon VAR_PREFIX DATA_DIR [extra args...]: starts tlsphd on a free port,
# sets ${VAR}_PID, ${VAR}_URL, ${VAR}_LOG; waits for /healthz.
start_daemon() {
    local var=$1 data=$2; shift 2
    local port; port=$(free_port)
    local log="$TMP/$var.$port.log"
    "$TLSPHD" --listen "127.0.0.1:$port" --data-dir "$data" --engine "$ENGINE" \
        --schemas-dir "$top_srcdir/schemas" --threads-per-job 1 --cores 2 "$@" >"$log" 2>&1 &
    local pid=$!
    DAEMON_PIDS="$DAEMON_PIDS $pid"
    eval "${var}_PID=$pid; ${var}_URL=http://127.0.0.1:$port; ${var}_LOG=$log"
    for _ in $(seq 100); do
        curl -sf "http://127.0.0.1:$port/healthz" >/dev/null 2>&1 && return 0
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    echo "FAIL: daemon did not start"; cat "$log"; return 1
}

# start_refused VAR DATA [args]: starts tlsphd where it should refuse to
# start; waits until it exits or answers (a hang detector, not a deadline);
# sets VAR_RC (the exit status, "running" when it serves after all) and VAR_LOG.
start_refused() {
    local var=$1 data=$2; shift 2
    local log="$TMP/$var.log" port; port=$(free_port)
    "$TLSPHD" --listen "127.0.0.1:$port" --data-dir "$data" --engine "$ENGINE" \
        --schemas-dir "$top_srcdir/schemas" --threads-per-job 1 --cores 2 "$@" >"$log" 2>&1 &
    local pid=$! rc=running
    DAEMON_PIDS="$DAEMON_PIDS $pid"
    exited_or_up() { ! kill -0 "$pid" 2>/dev/null || curl -sf "http://127.0.0.1:$port/healthz" >/dev/null; }
    wait_until exited_or_up
    if ! kill -0 "$pid" 2>/dev/null; then wait "$pid"; rc=$?; fi
    eval "${var}_RC=$rc; ${var}_LOG=$log"
}

# req METHOD URL [curl args...]: sets STATUS, BODY (file), HDRS (file).
BODY=$TMP/body
HDRS=$TMP/hdrs
req() {
    local m=$1 u=$2; shift 2
    STATUS=$(curl -s -X "$m" -o "$BODY" -D "$HDRS" -w '%{http_code}' "$@" "$u")
}
header() { grep -i "^$1:" "$HDRS" | head -1 | cut -d' ' -f2- | tr -d '\r'; }
# jq-like: jget FILE PYEXPR (d is the document)
jget() { "$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }
valid() { "$PY" "$here/validate.py" "$@" <"$BODY"; }

# wrap a scene file as an execute request for "run"
wrap_scene() { "$PY" -c "import json,sys; print(json.dumps({'inputs': {'scene': json.load(open(sys.argv[1]))}}))" "$1"; }
# scene variants from examples/elastic-strip.json: strip_scene END FRAMES [tiny]
strip_scene() {
    "$PY" - "$top_srcdir/examples/elastic-strip.json" "$@" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = float(sys.argv[2])
s["output"]["frames"] = int(sys.argv[3])
if len(sys.argv) > 4 and sys.argv[4] == "tiny":
    s["name"] = "tiny"
    s["bodies"][0]["geometry"]["box"]["max"] = [0.004, 0.004, 0]
    s["boundary_conditions"][1]["select"]["box"]["min"] = [0.003, -1, -1]
print(json.dumps(s))
PYEOF
}
# study_request END FRAMES TAUS [MAX_PARALLEL]: the execute request of a study
# of examples/elastic-strip.json (time.end END, FRAMES frames) over
# /parameters/vmax (0.05, 0.1, 0.2) x /parameters/tau (TAUS, comma-separated),
# with the output peak_force (and max_parallel when given)
study_request() {
    "$PY" - "$top_srcdir/examples/elastic-strip.json" "$@" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = float(sys.argv[2])
s["output"]["frames"] = int(sys.argv[3])
inputs = {"base": s,
    "sweep": {"mode": "product", "parameters": [
        {"pointer": "/parameters/vmax", "values": [0.05, 0.1, 0.2]},
        {"pointer": "/parameters/tau", "values": [float(t) for t in sys.argv[4].split(",")]}]},
    "outputs": [{"name": "peak_force", "series": "groups/right/reaction_force",
                 "component": 0, "reduce": "max"}]}
if len(sys.argv) > 5:
    inputs["max_parallel"] = int(sys.argv[5])
print(json.dumps({"inputs": inputs}))
PYEOF
}
# submit URL SCENE_JSON_FILE → prints the job id (empty on failure)
submit() {
    curl -s -H 'Content-Type: application/json' --data-binary @"$2" "$1/processes/run/execution" |
        "$PY" -c "import json,sys; print(json.load(sys.stdin).get('jobID',''))" 2>/dev/null
}
job_status() { curl -s "$1/jobs/$2" | "$PY" -c "import json,sys; print(json.load(sys.stdin)['status'])" 2>/dev/null; }
# Waits are hang detectors, never speed tests: on a loaded machine (CI runs the
# optimised and the ASan builds' tests side by side) a job that takes 2 s alone
# can take a minute.  A wait fails only when nothing has happened for HANG_S
# seconds.
HANG_S=${HANG_S:-300}
# wait_until CMD [ARGS...]: polls CMD every 0.1 s until it succeeds; 1 after HANG_S.
wait_until() {
    local end=$(($(date +%s) + HANG_S))
    until "$@"; do
        [ "$(date +%s)" -le "$end" ] || return 1
        sleep 0.1
    done
}
# long_poll_final URL ID: long-polls GET /jobs/ID?wait=30 until the job is final
# and leaves the last answer in BODY (req's file); gives up, like wait_status,
# only when the answers stop changing for HANG_S seconds.
long_poll_final() {
    local end=$(($(date +%s) + HANG_S)) cap=$(($(date +%s) + 4 * HANG_S)) last="" s
    while [ "$(date +%s)" -le "$cap" ]; do
        req GET "$1/jobs/$2?wait=30"
        s=$(jget "$BODY" "d['status']")
        case "$s" in accepted | running) ;; *) return 0 ;; esac
        if [ "$(cat "$BODY")" != "$last" ]; then
            last=$(cat "$BODY")
            end=$(($(date +%s) + HANG_S))
        fi
        [ "$(date +%s)" -le "$end" ] || break
    done
    echo "# long_poll_final: job $2 still '$s'" >&2
    return 1
}
# wait_status URL ID REGEX: polls until the job's status matches REGEX.  Fails
# only when the job's statusInfo (status, progress, message) has stayed the same
# for HANG_S seconds: a slow job that advances is waited for, a stuck one is not
# (and nothing is waited for longer than 4 HANG_S).
wait_status() {
    local end=$(($(date +%s) + HANG_S)) cap=$(($(date +%s) + 4 * HANG_S)) s info last=""
    while [ "$(date +%s)" -le "$cap" ]; do
        info=$(curl -s "$1/jobs/$2")
        s=$(printf '%s' "$info" | "$PY" -c "import json,sys; print(json.load(sys.stdin)['status'])" 2>/dev/null)
        [[ "$s" =~ $3 ]] && return 0
        if [ "$info" != "$last" ]; then
            last=$info
            end=$(($(date +%s) + HANG_S))
        fi
        [ "$(date +%s)" -le "$end" ] || break
        sleep 0.2
    done
    echo "# wait_status: job $2 is '$s', wanted $3 (no change for $HANG_S s, or waited 4x that)" >&2
    return 1
}
