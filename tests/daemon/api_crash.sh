#!/bin/bash
# tlsphd crash recovery:
#   - kill -9 the daemon while two jobs run: the engines die with it
#     (PR_SET_PDEATHSIG); a new daemon on the same data directory requeues and
#     completes both, without duplicate rows;
#   - kill -9 one engine: its job fails with a reason naming the signal, and
#     the daemon keeps answering /jobs;
#   - the result.h5 a killed engine left open for writing is repaired by the
#     daemon before the job is final: downloaded through the API it opens with
#     plain h5py (no swmr=True) and holds finite data for its complete frames,
#     and its sidecar references complete frames only (killed_result.py);
#     (and, where pvpython exists, ParaView's XDMF Reader reads it); the
#     same for a thin plate whose crack may grow (the layout for changing particle counts:
#     the repaired sidecar gives each frame its count);
#     without h5clear (TLSPHD_H5CLEAR="") the job's message says so, and the
#     next daemon repairs the file at start-up;
#   - a bare tlsph-run killed with -9: `h5clear -s` (what HDF5's error message
#     suggests) keeps its complete frames, as does the documented
#     `h5clear -s --increment=0` (docs/output.md).
. "$(dirname "$0")/common.sh"

DATA=$TMP/data
start_daemon D "$DATA" --max-jobs 2 --kill-grace 1 || exit 1
strip_scene 1.5e-3 10 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/mid.json"
strip_scene 2e-2 100 | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/long.json"
strip_scene 2e-2 100 >"$TMP/cli.json"
engine_pids() { pgrep -f "$DATA/jobs/$1/" || true; }
# complete frames of a result file being written (SWMR read; 0 until readable)
frames_in() {
    "$PY" -c "import h5py,sys; f=h5py.File(sys.argv[1],'r',libver='latest',swmr=True); print(f['particles/solid/position/step'].shape[0])" "$1" 2>/dev/null || echo 0
}
has_frames() { [ "$(frames_in "$1")" -ge "$2" ]; }
killed_result() { "$PY" "$here/killed_result.py" "$@" --min-frames 2; }
# kill_engine_of URL ID: once the job's file holds 2 complete frames, kill -9
# its engine and wait for the job to fail
kill_engine_of() {
    wait_status "$1" "$2" '^running$'
    wait_until has_frames "$DATA/jobs/$2/result.h5" 2
    local p; p=$(engine_pids "$2" | head -1)
    [ -n "$p" ] && kill -KILL "$p"
    wait_status "$1" "$2" '^failed$'
}
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
wait_until has_frames "$DATA/jobs/$J3/result.h5" 2
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

# the killed engine's result: repaired before the job became final
if command -v h5clear >/dev/null; then
    req GET "$E_URL/jobs/$J3/results/result.h5"
    cp "$BODY" "$TMP/j3.h5"
    req GET "$E_URL/jobs/$J3/results/result.xmf"
    cp "$BODY" "$TMP/j3.xmf"
    check "killed job's result.h5 (API) opens with plain h5py, finite complete frames, sidecar complete" \
        killed_result "$TMP/j3.h5" "$TMP/j3.xmf"
    check "  repair logged" grep -q "job $J3: result.h5 left open by the engine: closed" "$E_LOG"
    check "  sidecar lists every complete frame" [ "$(grep -c '<Grid Name="frame' "$TMP/j3.xmf")" = "$(frames_in "$TMP/j3.h5")" ]
    req GET "$E_URL/jobs/$J3"
    check "  job message says nothing of the file" [ "$(jget "$BODY" "'result.h5' in d.get('message', '')")" = False ]
    if command -v pvpython >/dev/null; then
        mkdir -p "$TMP/j3" && cp "$TMP/j3.h5" "$TMP/j3/result.h5" && cp "$TMP/j3.xmf" "$TMP/j3/result.xmf"
        check "  ParaView's XDMF Reader reads its frames (pvpython)" \
            bash -c "pvpython '$here/paraview_open.py' '$TMP/j3/result.xmf' >'$TMP/pv.log' 2>&1 || { cat '$TMP/pv.log'; false; }"
    else
        echo "# SKIP: pvpython (Debian: python3-paraview) missing: no ParaView check"
    fi
    # a thin plate whose crack may grow (crack_growth): its file has the
    # layout for changing particle counts (docs/output.md); the repaired
    # sidecar gives each frame its count from /particles/solid/count
    "$PY" -c "import json; print(json.dumps({'inputs': {'scene': {'dimension': 3, 'time': {'end': 1e-3}, 'output': {'frames': 400},
        'materials': {'s': {'density': 7850, 'youngs_modulus': 2.1e11, 'poisson_ratio': 0.3,
                            'strength': {'type': 'linear_hardening', 'yield_stress': 3e8, 'hardening_modulus': 5e8},
                            'damage': {'type': 'johnson_cook', 'd1': 0.08, 'd2': 0, 'd3': 0}}},
        'bodies': [{'name': 'plate', 'material': 's', 'spacing': 1e-3, 'thickness_axis': 'z',
                    'geometry': {'box': {'min': [0, 0, 0], 'max': [0.03, 0.03, 0.003]}},
                    'initial_velocity': ['0', '0', '10*sin(3.14159*x/0.03)']}],
        'cracks': [{'polygon': [[-0.001, 0.015, -0.001], [0.01, 0.015, -0.001], [0.01, 0.015, 0.004], [-0.001, 0.015, 0.004]]}],
        'crack_growth': {'tips': [[0.01, 0.015, 0.0015]]}}}}))" >"$TMP/thin.json"
    J6=$(submit "$E_URL" "$TMP/thin.json")
    kill_engine_of "$E_URL" "$J6"
    req GET "$E_URL/jobs/$J6/results/result.h5"
    cp "$BODY" "$TMP/j6.h5"
    req GET "$E_URL/jobs/$J6/results/result.xmf"
    cp "$BODY" "$TMP/j6.xmf"
    check "killed thin-plate job (changing-count layout): plain h5py, finite complete frames" \
        killed_result "$TMP/j6.h5" "$TMP/j6.xmf"
    check "  its sidecar gives every complete frame its count" "$PY" -c "
import sys, h5py, xml.etree.ElementTree as ET
c = h5py.File(sys.argv[1], 'r')['particles/solid/count/value'][:]
g = [int(t.get('NumberOfElements')) for t in ET.parse(sys.argv[2]).getroot().iter('Topology')]
sys.exit(not (len(g) >= 2 and g == list(c[:len(g)]) and len(g) == len(h5py.File(sys.argv[1], 'r')['particles/solid/position/step'])))" "$TMP/j6.h5" "$TMP/j6.xmf"
    if command -v pvpython >/dev/null; then
        mkdir -p "$TMP/j6" && cp "$TMP/j6.h5" "$TMP/j6/result.h5" && cp "$TMP/j6.xmf" "$TMP/j6/result.xmf"
        check "  ParaView's XDMF Reader reads its frames (pvpython)" \
            bash -c "pvpython '$here/paraview_open.py' '$TMP/j6/result.xmf' >'$TMP/pv6.log' 2>&1 || { cat '$TMP/pv6.log'; false; }"
    fi
else
    echo "# SKIP: h5clear (hdf5-tools) missing: no repair checks"
fi
kill -TERM "$E_PID"
wait "$E_PID" 2>/dev/null

# no h5clear: the job says so; the file stays open (SWMR readers still read it)
export TLSPHD_H5CLEAR=
start_daemon F "$DATA" --max-jobs 2 --kill-grace 1 || exit 1
unset TLSPHD_H5CLEAR
check "no h5clear: logged at start" grep -q 'h5clear.*not found' "$F_LOG"
J4=$(submit "$F_URL" "$TMP/long.json")
kill_engine_of "$F_URL" "$J4"
req GET "$F_URL/jobs/$J4"
check "no h5clear: killed job failed, message says the file was not repaired" \
    grep -q 'result.h5 was left open by the engine and could not be repaired' "$BODY"
check "  file still marked open" bash -c "! '$PY' '$here/killed_result.py' '$DATA/jobs/$J4/result.h5' >/dev/null"
check "  SWMR readers read it" has_frames "$DATA/jobs/$J4/result.h5" 2
kill -TERM "$F_PID"
wait "$F_PID" 2>/dev/null
if command -v h5clear >/dev/null; then
    start_daemon G "$DATA" --max-jobs 2 --kill-grace 1 || exit 1
    check "next daemon repairs the left-open result at start-up" \
        grep -q "job $J4: result.h5 left open by the engine: closed" "$G_LOG"
    req GET "$G_URL/jobs/$J4/results/result.h5"
    check "  and it opens with plain h5py" killed_result "$BODY"
fi

# a bare tlsph-run killed with -9 (docs/output.md: what a user does)
if command -v h5clear >/dev/null; then
    "$ENGINE" "$TMP/cli.json" -o "$TMP/cli" --threads 1 --quiet &
    CLI_PID=$!
    wait_until has_frames "$TMP/cli/result.h5" 2
    kill -KILL $CLI_PID
    wait $CLI_PID 2>/dev/null
    check "bare CLI: killed run's file refuses a plain open" bash -c "! '$PY' '$here/killed_result.py' '$TMP/cli/result.h5' >/dev/null"
    cp "$TMP/cli/result.h5" "$TMP/cli_s.h5"
    cp "$TMP/cli/result.h5" "$TMP/cli_inc.h5"
    h5clear -s "$TMP/cli_s.h5"
    h5clear -s --increment=0 "$TMP/cli_inc.h5"
    check "  after h5clear -s: plain open, finite complete frames, sidecar complete" \
        killed_result "$TMP/cli_s.h5" "$TMP/cli/result.xmf"
    check "  after h5clear -s --increment=0: the same" killed_result "$TMP/cli_inc.h5" "$TMP/cli/result.xmf"
fi
finish
