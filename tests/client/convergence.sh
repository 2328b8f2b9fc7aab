#!/bin/bash
# `tlsph convergence` against a real tlsphd on loopback: submit a convergence
# study (the oscillating plate, end time 0.05 s, spacings 5, 3.54, 2.5 mm;
# output: the time the kinetic energy first falls below 5e-4 J), wait for it,
# print it as text, JSON and CSV (the CSV the same bytes as the endpoint), and
# draw the error vs wall time SVG: every curve inside its frame, the y label
# names a quantity and a unit, no legend over a curve; rendered to PNG by
# rsvg-convert when installed and checked not blank, every frame inked.  Usage
# errors exit 1.
. "$(cd "$(dirname "$0")/.." && pwd)/daemon/common.sh"

CLIENT=$top_builddir/tlsph
[ -x "$CLIENT" ] || { echo "FAIL: $CLIENT not built"; exit 1; }
cl() { ${CLIENT_WRAPPER:-} "$CLIENT" "$@" >"$TMP/out" 2>"$TMP/err"; RC=$?; }
rc_is() { [ "$RC" = "$1" ] || { echo "# exit code $RC, wanted $1; stderr:"; sed 's/^/#   /' "$TMP/err"; return 1; }; }
export XDG_CONFIG_HOME=$TMP/xdg HOME=$TMP/home
unset TLSPH_URL TLSPH_TOKEN
PC=$top_srcdir/tests/client/plot_check.py

start_daemon D "$TMP/data" --max-jobs 2 || exit 1
export TLSPH_URL=$D_URL

"$PY" - "$top_srcdir/examples/oscillating-plate.json" >"$TMP/conv.json" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = 0.05
s["output"]["frames"] = 2
print(json.dumps({"base": s, "ladder": {"spacing": 0.005, "ratio": 2 ** 0.5, "count": 3},
                  "outputs": [{"name": "t_half_ke", "series": "kinetic_energy",
                               "reduce": "time_of_threshold", "threshold": 5e-4,
                               "direction": "falling"},
                              {"name": "ke_final", "series": "kinetic_energy", "reduce": "final"}],
                  "target": {"relative_error": 0.02}}))
PYEOF
cl convergence submit "$TMP/conv.json"
CID=$(cat "$TMP/out")
check "convergence submit prints an id" bash -c "[[ '$CID' =~ ^[0-9a-f]{32}$ ]]"
cl wait "$CID" --timeout 600 # a hang detector: seconds alone, longer on a loaded machine
check "wait → successful" rc_is 0
cl convergence table "$CID"
check "table: the runs, the cost model and each output's verdict" bash -c "[ $RC = 0 ] &&
    grep -q '^cost model: wall = ' '$TMP/out' && grep -q '^t_half_ke (time_of_threshold of kinetic_energy): ' '$TMP/out' &&
    grep -q '^ke_final (final of kinetic_energy): ' '$TMP/out' && [ \$(grep -c successful '$TMP/out') = 3 ]"
cl convergence table "$CID" --json
check "table --json: the result document" "$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["complete"] and len(d["runs"]) == 3 and [o["name"] for o in d["outputs"]] == ["t_half_ke", "ke_final"]' "$TMP/out"
cp "$TMP/out" "$TMP/result.json"
cl convergence table "$CID" --csv
curl -s "$D_URL/jobs/$CID/results/convergence?format=csv" >"$TMP/curl.csv"
check "table --csv: header + 2 outputs x 3 runs, same bytes as the endpoint" \
    bash -c "[ $RC = 0 ] && [ \$(wc -l <'$TMP/out') = 7 ] && cmp -s '$TMP/out' '$TMP/curl.csv'"

# the plot: the estimate (when the ladder supports one) and the true error
# against a reference (here T/8 of the Euler-Bernoulli plate, docs/convergence.md)
cl convergence plot "$CID" -o "$TMP/err.svg" --reference t_half_ke=0.031758 --reference ke_final=1.2e-4
check "plot: exit 0" rc_is 0
check "plot: curves in frames, y label with a unit" "$PY" "$PC" svg "$TMP/err.svg" labels panels
check "plot: no legend over a curve" "$PY" "$PC" svg "$TMP/err.svg" legend
check "plot: a marker at every point of every curve" python3 -c "
import re,sys
s=open(sys.argv[1]).read()
pts=sum(len(m.split()) for m in re.findall(r'<polyline class=\"curve\"[^>]*points=\"([^\"]*)\"', s))
marks=len(re.findall(r'<circle class=\"marker\"', s))
sys.exit(0 if pts > 0 and pts == marks else 1)" "$TMP/err.svg"
check "plot: a true-error curve per output with a reference" bash -c "[ \$(grep -c 'true error' '$TMP/err.svg') -ge 2 ]"
if command -v rsvg-convert >/dev/null 2>&1; then
    rsvg-convert -o "$TMP/err.png" "$TMP/err.svg"
    check "plot PNG: size, not blank, every frame inked" "$PY" "$PC" png "$TMP/err.png" "$TMP/err.svg"
else
    echo "# rsvg-convert missing: PNG check skipped"
fi

# usage errors
cl convergence plot "$CID"
check "plot without -o → exit 1" rc_is 1
cl convergence plot "$CID" -o "$TMP/x.svg" --reference t_half_ke
check "--reference without =VALUE → exit 1" rc_is 1
cl convergence frobnicate
check "unknown subcommand → exit 1" rc_is 1
cl convergence table 0123456789abcdef0123456789abcdef
check "unknown job → exit 2" rc_is 2
finish
