#!/usr/bin/env python3
"""SVG of the time step over a Taylor impact (docs/performance.md, "the stable
step"): the step each run took (cfl x its estimate) from the results'
time_step series, and the leapfrog limit dt_crit = 2 / omega_max measured by
bench/stable_step on states of the run (points), with the estimates of those
states before the CFL factor.  Log scale in dt, linear in time.

usage: stable_step_plot.py OUT.svg TITLE ELASTIC_RESULT_DIR TANGENT_RESULT_DIR CRIT.jsonl [LAMMPS_LOG]
(CRIT.jsonl: bench/stable_step's output on the tangent run's scene; LAMMPS_LOG: a
log.lammps of bench/peer_lammps.py's input, its thermo columns step, dt, time.)
Needs h5py (/usr/bin/python3)."""
import json
import math
import sys

import h5py

W, H, L, R, T, B = 640.0, 400.0, 70.0, 20.0, 40.0, 50.0


def series(path):
    f = h5py.File(path + "/result.h5", "r")
    t = f["observables/energy_balance/time"][:]
    dt = f["observables/time_step/value"][:]
    return [(a * 1e6, b) for a, b in zip(t, dt) if b > 0]


def lammps(log):
    """(t in us, dt) from the thermo table of a log.lammps (step dt time ke)."""
    pts, on = [], False
    for line in open(log):
        w = line.split()
        if w[:2] == ["Step", "Dt"]:
            on = True
        elif on and len(w) >= 3 and w[0].isdigit():
            pts.append((float(w[2]) * 1e6, float(w[1])))
        else:
            on = False
    return pts


def main():
    out, title, old, new, crit = sys.argv[1:6]
    runs = [("elastic estimate, cfl 0.3 (run)", series(old), "#888888"),
            ("tangent estimate, cfl 0.3 (run)", series(new), "#1f5fbf")]
    if len(sys.argv) > 6:
        runs.append(("LAMMPS MACHDYN, smd/adjust_dt 0.1", lammps(sys.argv[6]), "#2e8b57"))
    pts = [json.loads(line) for line in open(crit) if line.startswith("{")]
    marks = [("measured limit dt_crit = 2/omega_max", "dt_crit", "#c0392b", "o"),
             ("tangent estimate (before cfl)", "dt_cfl", "#1f5fbf", "s"),
             ("elastic estimate (before cfl)", "dt_cfl_elastic", "#888888", "s")]
    tmax = 80.0
    lo, hi = 1e-9, 1e-6
    x = lambda t: L + (W - L - R) * t / tmax
    y = lambda d: T + (H - T - B) * (math.log10(hi) - math.log10(d)) / (math.log10(hi) - math.log10(lo))
    s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W:.0f}" height="{H:.0f}" '
         f'font-family="sans-serif" font-size="12">',
         f'<rect width="{W:.0f}" height="{H:.0f}" fill="white"/>',
         f'<text x="{W / 2:.0f}" y="20" text-anchor="middle" font-size="14">{title}</text>']
    for e in range(-9, -5):
        for k in range(1, 10):
            d = k * 10.0 ** e
            if lo <= d <= hi:
                s.append(f'<line x1="{L}" x2="{W - R}" y1="{y(d):.1f}" y2="{y(d):.1f}" '
                         f'stroke="#eeeeee" stroke-width="{1 if k > 1 else 1.5}"/>')
        s.append(f'<text x="{L - 6}" y="{y(10.0 ** e) + 4:.1f}" text-anchor="end">1e{e}</text>')
    for t in range(0, 81, 10):
        s.append(f'<line x1="{x(t):.1f}" x2="{x(t):.1f}" y1="{T}" y2="{H - B}" stroke="#eeeeee"/>')
        s.append(f'<text x="{x(t):.1f}" y="{H - B + 16}" text-anchor="middle">{t}</text>')
    s.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="black"/>')
    s.append(f'<text x="{(L + W - R) / 2:.0f}" y="{H - 12}" text-anchor="middle">t (us)</text>')
    s.append(f'<text x="16" y="{(T + H - B) / 2:.0f}" text-anchor="middle" '
             f'transform="rotate(-90 16 {(T + H - B) / 2:.0f})">dt (s)</text>')
    for name, ser, colour in runs:
        d = " ".join(f"{x(a):.1f},{y(b):.1f}" for a, b in ser if a <= tmax and lo <= b <= hi)
        s.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
    for name, key, colour, shape in marks:
        for p in pts:
            px, py = x(p["t"] * 1e6), y(p[key])
            if shape == "o":
                s.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="4" fill="{colour}"/>')
            else:
                s.append(f'<rect x="{px - 3:.1f}" y="{py - 3:.1f}" width="6" height="6" '
                         f'fill="none" stroke="{colour}" stroke-width="1.5"/>')
    ly = T + 16
    for k, (name, _, colour) in enumerate(runs):
        s.append(f'<line x1="{W - 290}" x2="{W - 265}" y1="{ly + 16 * k}" y2="{ly + 16 * k}" '
                 f'stroke="{colour}" stroke-width="1.5"/>')
        s.append(f'<text x="{W - 260}" y="{ly + 16 * k + 4}">{name}</text>')
    for k, (name, _, colour, shape) in enumerate(marks):
        yy = ly + 16 * (k + len(runs))
        if shape == "o":
            s.append(f'<circle cx="{W - 277}" cy="{yy}" r="4" fill="{colour}"/>')
        else:
            s.append(f'<rect x="{W - 280}" y="{yy - 3}" width="6" height="6" fill="none" '
                     f'stroke="{colour}" stroke-width="1.5"/>')
        s.append(f'<text x="{W - 260}" y="{yy + 4}">{name}</text>')
    s.append("</svg>")
    open(out, "w").write("\n".join(s) + "\n")


if __name__ == "__main__":
    main()
