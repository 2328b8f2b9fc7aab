#!/usr/bin/env python3
"""Load-displacement and crack length of the tearing runs (bench/tearing.sh).

usage: tearing_report.py OUTDIR SVG

Reads OUTDIR/<variant>/result.h5 for the variants of bench/tearing_scene.py.
The crosshead displacement Delta(t) = V (t - tau (1 - exp(-t/tau))) (the
scene's parameters); the crosshead load P by the paper's moment balance about
O: the clamp is rigid and massless, so P x_A' = sum over the clamp columns of
(x R_y - y R_x), with R the columns' reaction forces and (x, y) their current
positions (reference + mean displacement), x_A' = l cos(alpha - beta) (eqs.
63-66).  Prints one Markdown row per run (peak P and its Delta, P at the
end, crack length at the end and at Delta = 60 mm, advances, particles before
and after, steps, wall time, the driver's share, balance, status) and writes
both curves of every run to SVG (two panels; plain polylines).
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "support"))
from tlsph_result import Result  # noqa: E402

VARIANTS = [("gurson", "Gurson", "#1f77b4"),
            ("gtn", "GTN", "#2ca02c"),
            ("sm_gurson", "SM-Gurson", "#d62728"),
            ("m_gurson", "M-Gurson", "#ff7f0e"),
            ("gtn_strain", "GTN, eps_p 0.35", "#9467bd")]


def nice(top):
    """(axis end, tick step): steps of 1, 2 or 5 x 10^k, at most 6 ticks."""
    k = 10 ** math.floor(math.log10(top)) if top > 0 else 1
    for m in (0.1, 0.2, 0.5, 1, 2, 5, 10):
        step = m * k
        if math.ceil(top / step) <= 6:
            return step * math.ceil(top / step), step
    return top, top
COLUMNS = ["variant", "peak P (kN)", "Delta at peak (mm)", "P at end (kN)",
           "crack at Delta 60 mm (mm)", "crack at end (mm)", "advances", "particles",
           "steps", "wall (s)", "driver", "balance / ext. work", "status"]


def curves(run):
    with Result(run) as r:
        sc = r.scene
        if isinstance(sc, str):
            sc = json.loads(sc)
        par = sc["parameters"]
        V, tau, l, am = par["V"], par["tau"], par["l"], par["am"]
        sa = par["sa"]
        alpha = am + math.pi
        t, R0 = None, None
        M = None
        for bc in sc["boundary_conditions"]:
            if not bc["name"].startswith("clamp"):
                continue
            tb, R = r.series(f"groups/{bc['name']}/reaction_force")
            _, u = r.series(f"groups/{bc['name']}/displacement")
            lo, hi = bc["select"]["box"]["min"], bc["select"]["box"]["max"]
            x0 = 0.5 * (lo[0] + hi[0])
            h = sc["bodies"][0]["spacing"]
            y0 = sc["bodies"][0]["geometry"]["box"]["max"][1] - 0.5 * h
            m = (x0 + u[:, 0]) * R[:, 1] - (y0 + u[:, 1]) * R[:, 0]
            M = m if M is None else M + m
            t = tb
        delta = V * (t - tau * (1 - np.exp(-t / tau)))
        beta = am + np.arcsin(delta / l + sa)
        xA = l * np.cos(alpha - beta)
        P = M / xA
        tc, c = r.series("crack_length")
        crack = np.interp(t, tc, c)
        tn, adv = r.series("crack_tip_advances")
        cost, status = r.cost, r.status
        ext = r.last("external_work")
        bal = r.last("energy_balance")
        counts = r.series("particle_count")[1]
    return dict(t=t, delta=delta, P=P, crack=crack, advances=int(adv[-1]), cost=cost,
                status=status, balance=bal / ext if ext else float("nan"),
                n0=int(counts[0]), n1=int(counts[-1]))


def svg(runs, path):
    W, H = 900, 480
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>']
    xmax, xstep = nice(max(float(d["delta"].max()) for _, _, d in runs) * 1e3)
    pmax, pstep = nice(max(float(d["P"].max()) for _, _, d in runs) / 1e3)
    cmax, cstep = nice(max(50.0, max(float(d["crack"].max()) for _, _, d in runs) * 1e3))
    panels = [(70, "P (kN), by the moment balance about O", pmax, pstep, "P", 1e-3),
              (520, "crack length (mm)", cmax, cstep, "crack", 1e3)]
    T, B, pw, ph = 30, 60, 340, 300
    for L, label, ymax, ystep, key, scale in panels:
        def X(x):
            return L + pw * x / xmax

        def Y(y):
            return T + ph * (1 - min(max(y, 0), ymax) / ymax)
        out.append(f'<rect x="{L}" y="{T}" width="{pw}" height="{ph}" fill="none" '
                   f'stroke="black"/>')
        for k in range(int(round(xmax / xstep)) + 1):
            x = xstep * k
            out.append(f'<text x="{X(x):.1f}" y="{T + ph + 16}" text-anchor="middle">{x:.0f}'
                       f'</text>')
        for k in range(int(round(ymax / ystep)) + 1):
            y = ystep * k
            out.append(f'<text x="{L - 6}" y="{Y(y) + 4:.1f}" text-anchor="end">{y:.0f}</text>')
            out.append(f'<line x1="{L}" y1="{Y(y):.1f}" x2="{L + pw}" y2="{Y(y):.1f}" '
                       f'stroke="#ddd"/>')
        out.append(f'<text x="{L + pw / 2}" y="{T + ph + 34}" text-anchor="middle">crosshead '
                   f'displacement Delta (mm)</text>')
        out.append(f'<text x="{L + pw / 2}" y="{T - 10}" text-anchor="middle">{label}</text>')
        for name, (lab, color), d in runs:
            xs, ys = d["delta"] * 1e3, d[key] * scale
            pts = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in zip(xs, ys))
            out.append(f'<polyline points="{pts}" fill="none" stroke="{color}" '
                       f'stroke-width="1.5"/>')
    for i, (name, (lab, color), d) in enumerate(runs):
        lx, ly = 70 + 150 * (i % 5), 412
        out.append(f'<line x1="{lx}" y1="{ly - 4}" x2="{lx + 20}" y2="{ly - 4}" '
                   f'stroke="{color}" stroke-width="2"/>')
        out.append(f'<text x="{lx + 24}" y="{ly}">{lab}</text>')
    for i, line in enumerate(TRENDS):
        out.append(f'<text x="70" y="{440 + 15 * i}" font-size="11" fill="#333">{line}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


# The paper's findings to set the curves against (no data of its Fig. 8 are
# available here, only its text, §6.1)
TRENDS = ["Paper 003 (§6.1, Figs. 8 and 12): all models overlap in the elastic phase; the "
          "original Gurson model is the stiffest; SM-Gurson much softer (mode I);",
          "GTN fits the experiment best, M-Gurson close to it; at 14 ms GTN has the longest "
          "crack, M-Gurson almost the same, SM-Gurson a much shorter one."]


def finished(outdir):
    """(name, label, colour, run directory, curves) of every variant whose run
    in outdir has a readable result, in VARIANTS' order."""
    for name, lab, color in VARIANTS:
        run = os.path.join(outdir, name)
        if not os.path.exists(os.path.join(run, "result.h5")):
            continue
        try:
            d = curves(run)
        except (OSError, KeyError):  # still being written
            continue
        yield name, lab, color, run, d


def main():
    outdir, path = sys.argv[1], sys.argv[2]
    print("| " + " | ".join(COLUMNS) + " |")
    print("|---|" + "---:|" * (len(COLUMNS) - 2) + "---|")
    runs = []
    for name, lab, color, run, d in finished(outdir):
        k = int(np.argmax(d["P"]))
        c60 = float(np.interp(0.06, d["delta"], d["crack"])) if d["delta"][-1] >= 0.06 \
            else float("nan")
        cost = d["cost"]
        share = float("nan")  # the driver's share: the run's log (tearing.sh keeps it)
        try:
            with open(os.path.join(outdir, name + ".log")) as f:
                for line in f:
                    if line.startswith("tlsph: crack growth:") and "% of the run" in line:
                        share = float(line.split("(")[-1].split("%")[0]) / 100
        except OSError:
            pass
        cells = [lab, f"{d['P'][k] / 1e3:.0f}", f"{d['delta'][k] * 1e3:.1f}",
                 f"{d['P'][-1] / 1e3:.0f}", f"{c60 * 1e3:.0f}", f"{d['crack'][-1] * 1e3:.0f}",
                 f"{d['advances']}", f"{d['n0']} → {d['n1']}", f"{int(cost['steps'])}",
                 f"{cost['wall_seconds']:.0f}",
                 f"{100 * share:.2f} %" if share == share else "—",
                 f"{d['balance']:.1e}", d["status"]]
        print("| " + " | ".join(cells) + " |")
        runs.append((name, (lab, color), d))
    if runs:
        svg(runs, path)


if __name__ == "__main__":
    main()
