#!/usr/bin/env python3
"""The tearing runs of several readings of paper 003's crack criterion side by side
(docs/crack-growth.md "Which quantity the criterion reads").

usage: tearing_readings.py LABEL=OUTDIR [LABEL=OUTDIR ...]

Each OUTDIR holds runs of bench/tearing_scene.py (OUTDIR/<variant>/result.h5 and
OUTDIR/<variant>.log, as bench/tearing.sh or bench/tearing_readings.sh writes
them).  Prints one Markdown row per run: the crack length at Delta = 20, 40, 80
and 120 mm, the crosshead load P at Delta = 20, 40 and 80 mm (averaged over
+-1 mm of Delta), the Delta of the crack's first facet, the wall time and the
status; then, per reading, the paper's orderings: crack at Delta = 20 mm
GTN >= M-Gurson > SM-Gurson, and SM-Gurson the softest (lowest P at 20 mm).
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tests", "support"))
from tearing_report import finished  # noqa: E402
from tlsph_result import Result  # noqa: E402

AT = (0.02, 0.04, 0.08, 0.12)


def at(d, key, x):
    return float(np.interp(x, d["delta"], d[key])) if d["delta"][-1] >= x - 1e-6 \
        else float("nan")


def load(d, x):
    w = np.abs(d["delta"] - x) <= 1e-3
    return float(np.mean(d["P"][w])) if w.any() and d["delta"][-1] >= x - 1e-6 \
        else float("nan")


def zone(run, d, x=0.04, eps=0.05):
    """At the frame nearest Delta = x: the particles with eps_M >= eps = 0.05 (the
    plastic zone, a count) and the shear term's share of the void growth,
    sum f_s / sum (f - f0) over all particles."""
    with Result(run) as r:
        t = r.frame_times()
        tx = float(np.interp(x, d["delta"], d["t"]))
        k = int(np.argmin(np.abs(t - tx)))
        ep = r.field("plastic_strain", k)
        f = r.field("void_fraction", k)
        fs = r.field("void_fraction_shear", k)
        f0 = float(np.min(r.field("void_fraction", 0)))
    grown = float(np.sum(f - f0))
    return int(np.sum(ep >= eps)), (float(np.sum(fs)) / grown if grown > 0 else float("nan"))


def fmt(v, scale, digits=0):
    return "—" if v != v else f"{v * scale:.{digits}f}"


def main():
    print("| reading | variant | crack at 20 / 40 / 80 / 120 mm (mm) | P at 20 / 40 / 80 mm "
          "(kN) | first facet at Δ (mm) | particles ε_M ≥ 0.05 at 40 mm | shear share of "
          "f − f0 at 40 mm | wall (s) | status |")
    print("|---|---|---|---|---:|---:|---:|---:|---|")
    verdicts = []
    for arg in sys.argv[1:]:
        label, outdir = arg.split("=", 1)
        got = {}
        for name, lab, _, run, d in finished(outdir):
            got[name] = d
            started = d["delta"][d["crack"] > 0]
            nz, share = zone(run, d)
            cells = [label, lab,
                     " / ".join(fmt(at(d, "crack", x), 1e3) for x in AT),
                     " / ".join(fmt(load(d, x), 1e-3) for x in AT[:3]),
                     fmt(started[0] if len(started) else float("nan"), 1e3, 1),
                     str(nz), fmt(share, 100, 0) + " %",
                     f"{d['cost']['wall_seconds']:.0f}", d["status"]]
            print("| " + " | ".join(cells) + " |")
        if all(k in got for k in ("gtn", "sm_gurson", "m_gurson")):
            c = {k: at(got[k], "crack", 0.02) for k in got}
            p = {k: load(got[k], 0.02) for k in got}
            order = c["gtn"] >= c["m_gurson"] > c["sm_gurson"]
            soft = p["sm_gurson"] < min(p["gtn"], p["m_gurson"])
            verdicts.append(f"{label}: crack at 20 mm GTN {c['gtn'] * 1e3:.0f}, M-Gurson "
                            f"{c['m_gurson'] * 1e3:.0f}, SM-Gurson {c['sm_gurson'] * 1e3:.0f} mm: "
                            f"the paper's order {'yes' if order else 'no'}; SM-Gurson softest "
                            f"at 20 mm: {'yes' if soft else 'no'}")
    for v in verdicts:
        print(v)


if __name__ == "__main__":
    main()
