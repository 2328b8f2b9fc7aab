#!/usr/bin/env bash
# Runs that go unstable stop with exit code 3 ("unstable") and a diagnostic (step,
# time, quantity, particle ids) on stderr and in result.h5, and no dataset of the
# file -- frame fields, time series, reference fields -- holds a value that is not
# finite (docs/output.md):
#  - tests/scenes/good/unstable.json: a fixed step ~20x the CFL limit; its state
#    turns NaN at step 2, and the series sampled every step must stop before it
#    (they held NaN at steps 2-4 when only the frames were guarded);
#  - tests/scenes/good/unstable_energy.json: a Mie-Grueneisen (s = 3) block at 1.3x
#    the CFL limit blows up on the energy balance, a global sum: the diagnostic
#    must still name particles (those whose energy changed most).
. "$(dirname "$0")/../support/script_env.sh"

# run NAME QUANTITY: runs tests/scenes/good/NAME.json and checks the outcome.
run() {
    "$top_builddir/tlsph-run" "$top_srcdir/tests/scenes/good/$1.json" -o "$tmp/$1" 2>"$tmp/$1.err"
    code=$?
    cat "$tmp/$1.err"
    if [ $code -ne 3 ]; then echo "FAIL $1: exit code $code, expected 3 (unstable)"; exit 1; fi
    grep -q "numerically unstable at step" "$tmp/$1.err" || { echo "FAIL $1: no diagnostic on stderr"; exit 1; }
    grep -q "particles \[[0-9]" "$tmp/$1.err" || { echo "FAIL $1: diagnostic names no particle id"; exit 1; }
    PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$tmp/$1/result.h5" "$2" <<'PYEOF' || exit 1
import sys
from tlsph_result import Result
f = Result(sys.argv[1])
d = f.diagnostics
assert f.status == "unstable", f.status
for q in ("step", "time", "quantity", "nids", "message"):
    print("diagnostic", q, "=", d[q])
assert d["quantity"] == sys.argv[2], "quantity %s, expected %s" % (d["quantity"], sys.argv[2])
assert d["nids"] > 0, "no particle named"
bad = f.non_finite_datasets()
assert not bad, "datasets holding values that are not finite: " + ", ".join(bad)
print("frames written: %d; all %d numeric datasets finite"
      % (len(f.frame_times()), f.numeric_datasets()))
PYEOF
    echo "ok $1: stopped with exit 3 and a $2 diagnostic naming particles"
}

run unstable non_finite
run unstable_energy energy_balance
echo "PASS: unstable scenes stop with a diagnostic, every dataset finite"
