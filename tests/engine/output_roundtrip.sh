#!/bin/bash
# Output round trip: run tests/scenes/good/output_small.json with tlsph-run and check the
# result files against docs/output.md (tests/support/h5_check.py does the checking):
#  - while the run writes: an h5py SWMR reader sees the documented datasets with the
#    documented shapes and units, and frame counts that grow;
#  - after exit 0: plain h5py and h5dump read every documented dataset ([F,N,3] position,
#    [F,N,6] stress with components "xx xy xz yy yz zz", units), times strictly increase,
#    /cost values are positive, /parameters/scene is the submitted JSON, and result.xmf is
#    XML whose HyperSlabs and HDF paths match the file.
# If the scene runs too fast to observe two partial states, the live check is repeated
# with the same scene and a longer end time (x8, then x64).
# Environment (set by make check): top_srcdir, top_builddir, SYSTEM_PYTHON.
set -u

here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$(cd "$here/../.." && pwd)}
top_builddir=${top_builddir:-$top_srcdir}
PY=${SYSTEM_PYTHON:-/usr/bin/python3}
if [ "$PY" = no ] || [ -z "$PY" ]; then PY=/usr/bin/python3; fi

RUN=$top_builddir/tlsph-run
CHECK=$top_srcdir/tests/support/h5_check.py
DOCS=$top_srcdir/docs/output.md
SCENE=$top_srcdir/tests/scenes/good/output_small.json

fail() {
    echo "FAIL: $*"
    exit 1
}

[ -x "$RUN" ] || fail "$RUN not built"
"$PY" -c 'import h5py, numpy' || fail "$PY cannot import h5py and numpy"
command -v h5dump >/dev/null || fail "h5dump not found (hdf5-tools)"

TMP=$(mktemp -d "${TMPDIR:-/tmp}/tlsph-output.XXXXXX") || fail "mktemp"
pid=
cleanup() {
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then kill "$pid"; wait "$pid" 2>/dev/null; fi
    rm -rf "$TMP"
}
trap cleanup EXIT

# run SCENE OUTDIR: runs tlsph-run in the background with the live SWMR check alongside.
# Sets run_rc (exit status of tlsph-run) and live_rc (0 ok, 1 failed, 3 too fast to see).
run() {
    "$RUN" "$1" -o "$2" --progress-fd 3 3>"$TMP/progress.jsonl" &
    pid=$!
    "$PY" "$CHECK" live "$DOCS" "$2/result.h5" "$pid"
    live_rc=$?
    if [ "$live_rc" = 1 ]; then
        kill "$pid" 2>/dev/null
    fi
    wait "$pid"
    run_rc=$?
    pid=
}

echo "== run $SCENE"
run "$SCENE" "$TMP/out"
[ "$run_rc" = 0 ] || fail "tlsph-run exited with $run_rc"
[ "$live_rc" = 1 ] && fail "live SWMR check"
echo "== progress stream"
"$PY" - "$TMP/progress.jsonl" <<'EOF' || fail "progress stream is not JSON lines"
import json, sys
lines = [l for l in open(sys.argv[1]) if l.strip()]
assert lines, "no progress lines"
for l in lines:
    json.loads(l)
print("progress: %d JSON lines" % len(lines))
EOF

echo "== final checks"
"$PY" "$CHECK" final "$DOCS" "$TMP/out" "$SCENE" || fail "final checks"

# the extent (docs/output.md), recomputed from the last frame's positions (a
# series sample too): axis x through (0, 5, 5) mm, the radius over the lowest
# layer (centres within h/2 = 0.5 mm of the lowest), edges at centre +- h/2
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$TMP/out/result.h5" <<'EOF' || fail "extent series"
import sys
import numpy as np
from tlsph_result import Result
with Result(sys.argv[1]) as r:
    x = r.field("position").astype(float)
    ext = r.file["observables/extents/block"]
    k = list(ext["radius/step"][:]).index(r.file["particles/solid/position/step"][-1])
    s = x[:, 0]
    rad = np.hypot(x[:, 1] - 0.005, x[:, 2] - 0.005)
    h2 = 0.0005
    want = {"radius": rad[s < s.min() + h2].max() + h2, "lower": s.min() - h2,
            "upper": s.max() + h2}
    want["diameter"] = 2 * want["radius"]
    want["length"] = want["upper"] - want["lower"]
    for name, v in want.items():
        got = ext[name + "/value"][k]
        # the field is float32: a few 1e-9 m at 20 mm
        assert abs(got - v) <= 1e-8, "extent %s %.9g, from the field %.9g" % (name, got, v)
    print("extent: radius %.6g mm, length %.6g mm" % (want["radius"] * 1e3, want["length"] * 1e3))
EOF

# Module-dependent output: a plastic scene with thermal coupling writes the
# plastic and thermal fields and series (documented in docs/output.md); the
# elastic scene above writes none of them.
PSCENE=$top_srcdir/tests/scenes/good/plastic_thermal.json
echo "== plastic + thermal scene $PSCENE"
"$RUN" "$PSCENE" -o "$TMP/plastic" --quiet || fail "tlsph-run on the plastic scene"
"$PY" "$CHECK" final "$DOCS" "$TMP/plastic" "$PSCENE" || fail "final checks (plastic scene)"
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$TMP/out/result.h5" "$TMP/plastic/result.h5" <<'EOF' || fail "module-dependent output"
import sys
import numpy as np
from tlsph_result import Result
optional_fields = ("plastic_strain", "plastic_strain_rate", "temperature")
optional_series = ("plastic_work", "max_temperature")
with Result(sys.argv[1]) as r:
    for name in optional_fields:
        assert not r.has_field(name), "elastic run wrote %s" % name
    for name in optional_series:
        assert not r.has_series(name), "elastic run wrote %s" % name
with Result(sys.argv[2]) as r:
    for name in optional_fields:
        assert r.has_field(name), "plastic run lacks %s" % name
    for name in optional_series:
        assert r.has_series(name), "plastic run lacks %s" % name
    eps = r.field("plastic_strain")
    T = r.field("temperature")
    work = r.series("plastic_work")[1]
    tmax = r.series("max_temperature")[1]
    assert eps.max() > 0.01, "no plastic flow (max eps_p %g)" % eps.max()
    assert np.all(np.diff(work) >= 0) and work[-1] > 0, "plastic work not growing"
    assert np.isclose(tmax[-1], np.nanmax(T), rtol=1e-6), "max_temperature %g vs field %g" % (tmax[-1], np.nanmax(T))
    assert tmax[-1] > tmax[0], "no heating"
    print("plastic output: max eps_p %.3f, plastic work %.4g J, max T %.2f K" % (eps.max(), work[-1], tmax[-1]))
EOF

# damage fields and series (docs/output.md): present only with a damage model,
# and consistent with each other.
DSCENE=$top_srcdir/tests/scenes/good/damage_jc_thermal.json
echo "== damage scene $DSCENE"
"$RUN" "$DSCENE" -o "$TMP/damage" --quiet || fail "tlsph-run on the damage scene"
"$PY" "$CHECK" final "$DOCS" "$TMP/damage" "$DSCENE" || fail "final checks (damage scene)"
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$TMP/plastic/result.h5" "$TMP/damage/result.h5" <<'EOF' || fail "damage output"
import sys
import numpy as np
from tlsph_result import Result
fields = ("damage", "damage_initiation", "triaxiality")
series = ("failed_particles", "damage_energy")
with Result(sys.argv[1]) as r:
    for name in fields:
        assert not r.has_field(name), "undamaged run wrote %s" % name
    for name in series:
        assert not r.has_series(name), "undamaged run wrote %s" % name
with Result(sys.argv[2]) as r:
    assert not r.has_field("void_fraction"), "Johnson-Cook damage run wrote the GTN void_fraction"
    D = r.field("damage")
    Di = r.field("damage_initiation")
    nf = r.series("failed_particles")[1]
    ed = r.series("damage_energy")[1]
    assert D.min() >= 0 and D.max() <= 1, "damage outside [0, 1]"
    assert not np.any((Di < 1) & (D > 0)), "damage without initiation"
    assert np.all(np.diff(ed) >= 0) and ed[-1] > 0, "damage energy not growing"
    assert nf[-1] == np.count_nonzero(D >= 1), "failed_particles %g vs field %d" % (nf[-1], np.count_nonzero(D >= 1))
    assert nf[-1] > 0, "nothing failed"
    print("damage output: %d failed, damage energy %.4g J" % (nf[-1], ed[-1]))
    # gauge and section (docs/output.md), recomputed here from the group series
    # and the fields of the last frame, which is also a series sample
    gstress = r.series("gauges/strip/engineering_stress")[1]
    gstrain = r.series("gauges/strip/engineering_strain")[1]
    rc = r.series("groups/clamp/reaction_force")[1][:, 0]
    rp = r.series("groups/pull/reaction_force")[1][:, 0]
    uc = r.series("groups/clamp/displacement")[1][:, 0]
    up = r.series("groups/pull/displacement")[1][:, 0]
    X = r.field("reference_position")
    V = r.field("volume")
    clamp, pull = X[:, 0] < 0.0006, X[:, 0] > 0.0094
    L0 = X[pull, 0].mean() - X[clamp, 0].mean()
    assert np.allclose(gstress, 0.5 * (rp - rc) / 0.002, rtol=1e-12, atol=1e-3), "gauge stress"
    assert np.allclose(gstrain, (up - uc) / L0, rtol=1e-9, atol=1e-15), "gauge strain"
    inside = np.abs(X[:, 0] - 0.005) <= 0.5 * 0.000375
    w = V[inside] / V[inside].sum()
    sec = r.file["observables/sections/notch"]
    k = list(sec["damage/step"][:]).index(r.file["particles/solid/damage/step"][-1])
    assert np.isclose(sec["damage/value"][k], (w * D[inside]).sum(), rtol=1e-6, atol=1e-7), "section damage"
    s = r.field("stress")[inside]  # float32: xx xy xz yy yz zz
    assert np.isclose(sec["normal_stress/value"][k], (w * s[:, 0]).sum(), rtol=1e-5, atol=1e3), "section normal stress"
    A = np.stack([s[:, [0, 1, 2]], s[:, [1, 3, 4]], s[:, [2, 4, 5]]], axis=1).astype(float)
    s1 = np.linalg.eigvalsh(A)[:, -1]
    assert np.isclose(sec["max_principal_stress/value"][k], (w * s1).sum(), rtol=1e-5, atol=1e3), "section sigma_1"
    print("gauge: peak %.4g MPa; notch section: %d particles, mean D %.3f at the end" % (
        gstress.max() / 1e6, inside.sum(), sec["damage/value"][k]))
EOF

# contact output (docs/output.md, docs/contact.md): the contact series only with
# contact, and the module named; the bars of examples/two-bars.json touch and
# part; the pair series striker--target is the force between them.
CSCENE=$top_srcdir/examples/two-bars.json
echo "== contact scene $CSCENE"
"$RUN" "$CSCENE" -o "$TMP/contact" --quiet || fail "tlsph-run on the contact scene"
"$PY" "$CHECK" final "$DOCS" "$TMP/contact" "$CSCENE" || fail "final checks (contact scene)"
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$TMP/out/result.h5" "$TMP/contact/result.h5" <<'EOF' || fail "contact output"
import sys
from tlsph_result import Result
with Result(sys.argv[1]) as r:
    for name in ("contact_energy", "contact_pairs"):
        assert not r.has_series(name), "run without contact wrote %s" % name
with Result(sys.argv[2]) as r:
    pairs = r.series("contact_pairs")[1]
    work = r.series("contact_energy")[1]
    assert pairs.max() > 0 and pairs[-1] == 0, "the bars did not touch and part"
    assert work.max() > 0, "no contact work booked"
    # the body pair's series (docs/output.md): with two bodies the force on the
    # striker from the target is the striker's contact force, and the opposite
    # of the target's (f_ij = -f_ji: to round-off of the forces' size)
    fp = r.series("contacts/striker--target/force")[1]
    fs = r.series("contacts/striker/force")[1]
    ft = r.series("contacts/target/force")[1]
    scale = abs(fs).max()
    assert scale > 0, "no contact force in the series"
    assert abs(fp - fs).max() <= 1e-12 * scale, "pair series differs from the striker's"
    assert abs(fp + ft).max() <= 1e-12 * scale, "pair series is not the opposite of the target's"
    print("contact output: up to %d pairs, peak contact work %.3g J, peak pair force %.4g N/m"
          % (pairs.max(), work.max(), scale))
EOF

# rigid-body output (docs/output.md, docs/contact.md): the rigid series and
# rigid_contacts only with rigid bodies; a free disc hits the block, which rests
# on a plane with friction, while a prescribed wedge pushes into its side.
RSCENE=$top_srcdir/tests/scenes/good/rigid_bodies.json
echo "== rigid-body scene $RSCENE"
"$RUN" "$RSCENE" -o "$TMP/rigid" --quiet || fail "tlsph-run on the rigid-body scene"
"$PY" "$CHECK" final "$DOCS" "$TMP/rigid" "$RSCENE" || fail "final checks (rigid-body scene)"
PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$TMP/out/result.h5" "$TMP/rigid/result.h5" <<'EOF' || fail "rigid-body output"
import json
import sys
from tlsph_result import Result, text
with Result(sys.argv[1]) as r:
    assert not r.has_series("rigid_contacts"), "run without rigid bodies wrote rigid_contacts"
    assert "rigid" not in r.file["observables"], "run without rigid bodies wrote /observables/rigid"
with Result(sys.argv[2]) as r:
    contacts = r.series("rigid_contacts")[1]
    v = r.series("rigid/ball/velocity")[1]
    f = r.series("rigid/wedge/force")[1]
    modules = json.loads(text(r.file["parameters/modules"][()]))
    assert contacts.max() > 0, "no particle touched a rigid body"
    assert v[0, 1] < 0 < v[-1, 1], "the ball did not bounce"
    assert f[:, 0].max() > 0, "the block did not push back on the wedge"
    assert "rigid:penalty_hertz" in modules, "module not named"
    print("rigid output: up to %d contacts, ball %.3g -> %.3g m/s, wedge force up to %.3g N/m"
          % (contacts.max(), v[0, 1], v[-1, 1], f[:, 0].max()))
EOF

factor=8
while [ "$live_rc" = 3 ]; do
    [ "$factor" -le 64 ] || fail "never observed a partially written file (the run is too fast)"
    echo "== too fast to observe growth; rerun with time.end x$factor"
    "$PY" - "$SCENE" "$TMP/slow.json" "$factor" <<'EOF' || fail "cannot write the slower scene"
import json, sys
scene = json.load(open(sys.argv[1]))
scene["time"]["end"] *= int(sys.argv[3])
json.dump(scene, open(sys.argv[2], "w"))
EOF
    rm -rf "$TMP/slow"
    run "$TMP/slow.json" "$TMP/slow"
    [ "$run_rc" = 0 ] || fail "tlsph-run (time.end x$factor) exited with $run_rc"
    [ "$live_rc" = 1 ] && fail "live SWMR check (time.end x$factor)"
    factor=$((factor * 8))
done

echo "PASS: output round trip"
exit 0
