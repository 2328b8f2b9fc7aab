#!/bin/bash
# The convergence process end to end on a real daemon (docs/api.md, "The
# convergence process"): the oscillating plate (examples/oscillating-plate.json,
# end time 0.05 s) at three coarse spacings 5, 3.54 and 2.5 mm (ratio sqrt 2);
# output: the time at which the kinetic energy first falls below half its
# initial value (5e-4 J per metre of thickness; cos^2 decay puts it at T/8,
# T = 0.254 s for the Euler-Bernoulli plate: docs/convergence.md).
# Checks: the process is listed and described; bad input is refused with 422
# naming the field (fewer than three spacings, a non-constant ratio, an unknown
# series at submission is accepted by the schema but gives no value, a target
# <= 0, an unknown reduce); the job runs as a study whose statusInfo says
# convergence; the result is a valid document with three values in the range
# the runs give, the observed order and GCI consistent with the values
# (Richardson's formulas recomputed here), the cost model and a prediction;
# ?format=csv; and the result survives a daemon restart (it is recomputed from
# the children's files).
. "$(dirname "$0")/common.sh"

start_daemon D "$TMP/data" --max-jobs 2 || exit 1

mkreq() { # mkreq LADDER_JSON OUTPUTS_JSON [TARGET_JSON] > request
    "$PY" - "$top_srcdir/examples/oscillating-plate.json" "$@" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["time"]["end"] = 0.05
s["output"]["frames"] = 2
inputs = {"base": s, "ladder": json.loads(sys.argv[2]), "outputs": json.loads(sys.argv[3])}
if len(sys.argv) > 4:
    inputs["target"] = json.loads(sys.argv[4])
print(json.dumps({"inputs": inputs}))
PYEOF
}
post() { req POST "$D_URL/processes/convergence/execution" -H 'Content-Type: application/json' --data-binary @"$1"; }
has_error_at() { [ "$(jget "$BODY" "any(e['pointer'] == '#$1' and '$2' in e['detail'] for e in d.get('errors', []))")" = True ]; }
KE='[{"name": "t_half_ke", "series": "kinetic_energy", "reduce": "time_of_threshold", "threshold": 5e-4, "direction": "falling"}, {"name": "ke_final", "series": "kinetic_energy", "reduce": "final"}]'

# ---------------------------------------------------------- description
req GET "$D_URL/processes"
check "GET /processes lists convergence" [ "$(jget "$BODY" "'convergence' in [p['id'] for p in d['processes']]")" = True ]
check "  valid" valid openapi:processList
req GET "$D_URL/processes/convergence"
check "GET /processes/convergence: 200 with inputs base, ladder, outputs, target" \
    [ "$STATUS" = 200 -a "$(jget "$BODY" "sorted(d['inputs'])")" = "['base', 'ladder', 'outputs', 'target']" ]
check "  valid" valid openapi:process

# ---------------------------------------------------------- bad input
mkreq '{"spacings": [0.005, 0.0025]}' "$KE" >"$TMP/bad.json"
post "$TMP/bad.json"
check "two spacings: 422 at /inputs/ladder/spacings" [ "$STATUS" = 422 ]
check "  names the field" has_error_at /inputs/ladder/spacings 'spacings must be an array of 3'
check "  problem valid" valid error
mkreq '{"spacings": [0.005, 0.0025, 0.002]}' "$KE" >"$TMP/bad.json"
post "$TMP/bad.json"
check "non-constant ratio: 422 at /inputs/ladder/spacings" has_error_at /inputs/ladder/spacings 'constant'
mkreq '{"spacing": 0.005, "ratio": 1.05, "count": 3}' "$KE" >"$TMP/bad.json"
post "$TMP/bad.json"
check "ratio 1.05: 422 at /inputs/ladder/ratio" has_error_at /inputs/ladder/ratio '>= 1.1'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' "$KE" '{"relative_error": 0}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "target 0: 422 at /inputs/target/relative_error" has_error_at /inputs/target/relative_error '(0, 1)'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' "$KE" '{"relative_error": -0.1}' >"$TMP/bad.json"
post "$TMP/bad.json"
check "target < 0: 422 at /inputs/target/relative_error" has_error_at /inputs/target/relative_error '(0, 1)'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' '[{"name": "x", "series": "no such/series!", "reduce": "final"}]' >"$TMP/bad.json"
post "$TMP/bad.json"
check "malformed series name: 422 at /inputs/outputs/0/series" has_error_at /inputs/outputs/0/series 'series name'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' '[{"name": "x", "series": "kinetic_energy", "reduce": "mean"}]' >"$TMP/bad.json"
post "$TMP/bad.json"
check "unknown reduce: 422 at /inputs/outputs/0/reduce" has_error_at /inputs/outputs/0/reduce 'time_of_threshold'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' '[{"name": "x", "series": "kinetic_energy", "reduce": "time_of_threshold"}]' >"$TMP/bad.json"
post "$TMP/bad.json"
check "time_of_threshold without threshold: 422 at /inputs/outputs/0" has_error_at /inputs/outputs/0 'threshold'
mkreq '{"spacing": 0.005, "ratio": 2, "count": 3, "pointers": ["/bodies/0/material"]}' "$KE" >"$TMP/bad.json"
post "$TMP/bad.json"
check "a pointer that is no spacing: 422 at /inputs/ladder/pointers/0" has_error_at /inputs/ladder/pointers/0 'spacing'

"$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); d['inputs']['base']['limits']={'max_particles':300}; print(json.dumps(d))" \
    <(mkreq '{"spacing": 0.005, "ratio": 2, "count": 3}' "$KE") >"$TMP/bad.json"
post "$TMP/bad.json"
check "a spacing whose child exceeds the particle limit: 422 at /inputs/ladder (not the sweep)" \
    [ "$STATUS" = 422 -a "$(jget "$BODY" "[e['pointer'] for e in d['errors']]")" = "['#/inputs/ladder', '#/inputs/ladder']" ]

# ---------------------------------------------------------- a ladder end to end
# an output whose series does not exist is accepted (the schema cannot know
# the scene's series) and reported as missing, with no estimate
mkreq '{"spacings": [0.0025, 0.005, 0.0035355339]}' \
    "$("$PY" -c "import json,sys; o=json.loads(sys.argv[1]); o.append({'name':'nothing','series':'groups/nowhere/reaction_force','reduce':'max'}); print(json.dumps(o))" "$KE")" \
    '{"relative_error": 0.01}' >"$TMP/good.json"
post "$TMP/good.json"
check "convergence job: 201" [ "$STATUS" = 201 ]
check "  processID convergence, 3 children" [ "$(jget "$BODY" "(d['processID'], d.get('children'))")" = "('convergence', 3)" ]
ID=$(jget "$BODY" "d.get('jobID', '')")
req GET "$D_URL/jobs/$ID/results/convergence"
check "results/convergence before the children ran: 200 incomplete, or 404 not ready" \
    [ "$STATUS" = 404 -o "$(jget "$BODY" "d.get('complete')")" = False ]
long_poll_final "$D_URL" "$ID"
check "the study ends successful" [ "$(jget "$BODY" "d['status']")" = successful ]
req GET "$D_URL/jobs/$ID/results"
check "results document links results/convergence" [ "$(jget "$BODY" "d['convergence']['href']")" = "/jobs/$ID/results/convergence" ]
req GET "$D_URL/jobs/$ID/results/convergence"
cp "$BODY" "$TMP/conv.json"
check "results/convergence: 200, complete" [ "$STATUS" = 200 -a "$(jget "$BODY" "d['complete']")" = True ]
check "  valid against study.schema.json#/\$defs/convergence_result" valid 'study#/$defs/convergence_result'
check "  runs finest first: 2.5, 3.54, 5 mm" [ "$(jget "$BODY" "[round(r['spacing'] * 1e4, 1) for r in d['runs']]")" = "[25.0, 35.4, 50.0]" ]
# Richardson recomputed from the three values (Celik et al. 2008): whatever the
# status, the numbers must agree with the values the runs gave
"$PY" - "$TMP/conv.json" >"$TMP/check.txt" <<'PYEOF'
import json, math, sys
d = json.load(open(sys.argv[1]))
o = {x["name"]: x for x in d["outputs"]}
t = o["t_half_ke"]
f1, f2, f3 = t["values"]
r = d["runs"][1]["spacing"] / d["runs"][0]["spacing"]
ok = []
# the crossing lies between 0.02 and 0.05 s at every spacing (T/8 = 0.0318 s analytic)
ok.append(all(0.02 < v < 0.05 for v in t["values"]))
e21, e32 = f2 - f1, f3 - f2
if e32 / e21 > 1:
    p = math.log(e32 / e21) / math.log(r)
    ok.append(abs(t["observed_order"] - p) < 1e-9 * p)
    if t["status"] == "converging":
        fext = f1 + (f1 - f2) / (r**p - 1)
        ok.append(abs(t["extrapolated"] - fext) < 1e-12 * abs(fext))
        ok.append(abs(t["gci"][0] - 1.25 * abs(f1 - fext) / abs(f1)) < 1e-9)
        pr = t["prediction"]
        ok.append(pr is not None and pr["spacing"] > 0 and pr["particles"] > 0 and pr["wall_seconds"] > 0)
        ls = pr["ladder_step"]  # h1 r^k at or below the predicted spacing
        k = math.log(ls["spacing"] / d["runs"][0]["spacing"]) / math.log(r)
        ok.append(ls["spacing"] <= pr["spacing"] * (1 + 1e-12) and abs(k - round(k)) < 1e-9)
else:
    ok.append(t["status"] in ("oscillatory", "divergent") and t["extrapolated"] is None)
n = o["nothing"]
ok.append(n["status"] == "too_few" and n["values"] == [None] * 3 and len(n["missing"]) == 3)
cm = d["cost_model"]
# particles ~ h^-2 in 2-D (the lattice rounds: within 0.3 of 2)
ok.append(abs(cm["particles"]["q"] - 2) < 0.3)
ok.append(cm["wall_seconds"]["q"] is not None and cm["particle_steps"]["q"] > 2.5)
ok.append(all(r["particles"] > 0 and r["steps"] > 0 and r["wall_seconds"] > 0 and r["peak_memory_bytes"] > 0 for r in d["runs"]))
print(" ".join(str(x) for x in ok))
print(t["status"], t["values"], t["observed_order"], t["extrapolated"], file=sys.stderr)
PYEOF
check "  values, order, limit, GCI, cost model consistent ($(cat "$TMP/check.txt"))" [ -n "$(cat "$TMP/check.txt")" -a "$(tr ' ' '\n' <"$TMP/check.txt" | sort -u)" = True ]
req GET "$D_URL/jobs/$ID/results/convergence?format=csv"
check "?format=csv: text/csv, header + 3 outputs x 3 runs" \
    [ "$STATUS" = 200 -a "$(head -1 "$BODY" | cut -d, -f1-4 | tr -d '\r')" = "output,status,spacing,value" -a "$(wc -l <"$BODY")" = 10 ]
req GET "$D_URL/jobs/$ID/results/summary"
check "results/summary of the study still served (final/max/min outputs as columns)" \
    [ "$STATUS" = 200 -a "$(jget "$BODY" "'ke_final' in d['columns'] and 't_half_ke' not in d['columns']")" = True ]
req GET "$D_URL/jobs/$(jget "$TMP/conv.json" "d['runs'][0]['job_id']")/results/convergence"
check "results/convergence of a child run: 404" [ "$STATUS" = 404 ]

# ---------------------------------------------------------- restart
stop_daemons
start_daemon E "$TMP/data" --max-jobs 2 || exit 1
req GET "$E_URL/jobs/$ID/results/convergence"
check "after a restart: the same result (recomputed from the children's files)" \
    [ "$("$PY" -c "import json,sys; a=json.load(open(sys.argv[1])); b=json.load(open(sys.argv[2])); print(a==b)" "$TMP/conv.json" "$BODY")" = True ]
req GET "$E_URL/jobs/$ID"
check "  statusInfo still says convergence" [ "$(jget "$BODY" "d['processID']")" = convergence ]

finish
