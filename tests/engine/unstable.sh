#!/usr/bin/env bash
# A scene whose fixed time step is ~20x the CFL limit must stop with exit code
# 3 ("unstable") and a diagnostic (step, time, particle ids, quantity) on stderr
# and in result.h5, and no frame in the file may contain a non-finite value.
set -u
here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$here/../..}
top_builddir=${top_builddir:-$top_srcdir}
PY=${SYSTEM_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$top_builddir/tlsph-run" "$top_srcdir/tests/scenes/good/unstable.json" -o "$tmp/out" 2>"$tmp/err"
code=$?
cat "$tmp/err"
if [ $code -ne 3 ]; then echo "FAIL: exit code $code, expected 3 (unstable)"; exit 1; fi
grep -q "numerically unstable at step" "$tmp/err" || { echo "FAIL: no diagnostic on stderr"; exit 1; }
grep -q "particles \[[0-9]" "$tmp/err" || { echo "FAIL: diagnostic names no particle id"; exit 1; }
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$tmp/out/result.h5" <<'PYEOF' || exit 1
import sys, numpy as np
from tlsph_result import Result
f = Result(sys.argv[1])
d = f.diagnostics
assert f.status == "unstable", f.status
for q in ("step", "time", "quantity", "message"):
    print("diagnostic", q, "=", d[q])
frames = 0
for name in f.frame_fields():
    v = f.file["particles/solid"][name]["value"][()]
    frames = v.shape[0]
    assert np.all(np.isfinite(v)), "non-finite values in frame field " + name
print("frames written:", frames, "- all finite")
PYEOF
echo "PASS: unstable scene stopped with exit 3 and a diagnostic"
