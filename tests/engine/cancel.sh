#!/usr/bin/env bash
# SIGTERM during a run: tlsph-run finishes the current frame, closes the file
# and exits 5 ("cancelled").  The file must open with a plain (non-SWMR)
# reader, say status "cancelled", hold at least one more frame than at start,
# and end with a "finished" progress line whose status is "cancelled".
. "$(dirname "$0")/../support/script_env.sh"
# a scene long enough (~1 min) that it is certainly still running when signalled
sed -e 's/"end": 2e-5/"end": 2e-3/' "$top_srcdir/tests/scenes/good/output_small.json" >"$tmp/long.json"
grep -q '"end": 2e-3' "$tmp/long.json" || { echo "FAIL: could not derive the long scene"; exit 1; }
"$top_builddir/tlsph-run" "$tmp/long.json" -o "$tmp/out" --progress-fd 3 3>"$tmp/progress.jsonl" 2>"$tmp/err" &
pid=$!
# wait until it runs (a hang detector, not a speed bound: 300 s)
end=$(($(date +%s) + 300))
until grep -q '"event":"progress"' "$tmp/progress.jsonl" 2>/dev/null; do
  [ "$(date +%s)" -le "$end" ] || { echo "FAIL: no progress event within 300 s"; kill -KILL $pid; exit 1; }
  sleep 0.1
done
kill -TERM $pid
wait $pid
code=$?
cat "$tmp/err"
[ $code -eq 5 ] || { echo "FAIL: exit code $code, expected 5 (cancelled)"; exit 1; }
tail -n 1 "$tmp/progress.jsonl"
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$tmp/out/result.h5" "$tmp/progress.jsonl" <<'PYEOF' || exit 1
import sys, json, numpy as np
from tlsph_result import Result
last = json.loads(open(sys.argv[2]).read().strip().splitlines()[-1])
assert last["event"] == "finished" and last["status"] == "cancelled", last
f = Result(sys.argv[1])   # plain open: only works if the writer closed the file
st = f.status
assert st.strip() == "cancelled", st
pos = f.file["particles/solid/position/value"]
t = f.frame_times()
assert pos.shape[0] >= 2 and np.all(np.isfinite(pos[()])), pos.shape
assert t[-1] < 2e-3 * 0.99, t[-1]
print("cancelled file: %d frames, last at t = %.3g s, status %s" % (pos.shape[0], t[-1], st))
PYEOF
echo "PASS: SIGTERM gave exit 5 and a cleanly closed file"
