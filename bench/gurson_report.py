#!/usr/bin/env python3
"""Tables and SVG plots of the Gurson-family comparison (bench/gurson.sh).

usage: gurson_report.py OUTDIR SVG_R2 SVG_SHEAR

Reads OUTDIR/{r2,shear}-<variant>/result.h5 for the six variants of
bench/gurson_scene.py.  Notched bar: one Markdown row per run with the metrics
of bench/weldox_metrics.py (peak engineering stress and its strain, strains at
initiation, first failure and separation, ...) and the engineering
stress-strain curves to SVG_R2.  Shear block: peak shear force of the top
group and its displacement, the displacement at the first failed particle,
the force at the end, failed particles, the
largest shear part of f, particles, steps, wall time, and the force-displacement
curves to SVG_SHEAR.  Plain SVG polylines, no plotting library.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "support"))
from tlsph_result import Result  # noqa: E402
import weldox_metrics  # noqa: E402

VARIANTS = [("gurson", "Gurson (eq. 43-44)", "#1f77b4"),
            ("gtn", "GTN (eqs. 45-48)", "#2ca02c"),
            ("sm_gurson", "SM-Gurson (eqs. 49-51)", "#d62728"),
            ("m_gurson", "M-Gurson (eqs. 52-54)", "#ff7f0e"),
            ("gtn_strain", "GTN, critical plastic strain 0.35", "#9467bd"),
            ("jc", "Johnson-Cook, eq. 62, D_c = 0.1", "#8c564b")]


def svg(curves, path, xmax, ymin, ymax, xlabel, ylabel, legend_left=False):
    W, H, L, B, R, T = 640, 420, 70, 50, 20, 20
    pw, ph = W - L - R, H - T - B

    def X(x):
        return L + pw * x / xmax

    def Y(y):
        return T + ph * (1 - (min(max(y, ymin), ymax) - ymin) / (ymax - ymin))
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect x="{L}" y="{T}" width="{pw}" height="{ph}" fill="none" stroke="black"/>']
    for k in range(6):
        x = xmax * k / 5
        y = ymin + (ymax - ymin) * k / 5
        out.append(f'<text x="{X(x):.1f}" y="{H - B + 16}" text-anchor="middle">{x:.2f}</text>')
        out.append(f'<text x="{L - 6}" y="{Y(y) + 4:.1f}" text-anchor="end">{y:.0f}</text>')
        out.append(f'<line x1="{L}" y1="{Y(y):.1f}" x2="{L + pw}" y2="{Y(y):.1f}" stroke="#ddd"/>')
    out.append(f'<text x="{L + pw / 2}" y="{H - 10}" text-anchor="middle">{xlabel}</text>')
    out.append(f'<text x="16" y="{T + ph / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {T + ph / 2})">{ylabel}</text>')
    for i, (label, color, xs, ys) in enumerate(curves):
        pts = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in zip(xs, ys) if x <= xmax)
        out.append(f'<polyline points="{pts}" fill="none" stroke="{color}" stroke-width="1.5"/>')
        # legend top right, or top left where the curves leave room there
        lx = L + 20 if legend_left else L + pw - 230
        ly = T + 18 + 16 * i
        out.append(f'<line x1="{lx}" y1="{ly}" x2="{lx + 25}" y2="{ly}" stroke="{color}" '
                   f'stroke-width="2"/>')
        out.append(f'<text x="{lx + 30}" y="{ly + 4}">{label}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def notched(outdir, path):
    print("| " + " | ".join(weldox_metrics.COLUMNS) + " |")
    print("|---|" + "---:|" * (len(weldox_metrics.COLUMNS) - 2) + "---|")
    curves, xmax, ymax = [], 0.0, 0.0
    for name, label, color in VARIANTS:
        run = os.path.join(outdir, f"r2-{name}")
        if not os.path.exists(os.path.join(run, "result.h5")):
            continue
        print(weldox_metrics.row(run, label))
        with Result(run) as r:
            stress = r.series("gauges/bar/engineering_stress")[1] / 1e6
            strain = r.series("gauges/bar/engineering_strain")[1]
        curves.append((label, color, strain, stress))
        # up to 1.3 x the latest separation (load below 2 % of the peak after it)
        k = int(stress.argmax())
        below = [i for i in range(k, len(stress)) if stress[i] < 0.02 * stress[k]]
        sep = strain[below[0]] if below else strain[-1]
        xmax, ymax = max(xmax, min(1.3 * float(sep), float(strain.max()))), max(ymax, float(stress.max()))
    if curves:
        svg(curves, path, round(xmax, 1), -100.0, 100 * (int(ymax / 100) + 1),
            "engineering strain", "engineering stress (MPa)")


SHEAR_COLUMNS = ["case", "peak force (kN)", "displacement at peak (mm)",
                 "displacement at first failure (mm)", "force at end (kN)", "failed particles", "largest shear part of f", "particles", "steps",
                 "wall (s)", "status"]


def shear(outdir, path):
    print()
    print("| " + " | ".join(SHEAR_COLUMNS) + " |")
    print("|---|" + "---:|" * (len(SHEAR_COLUMNS) - 2) + "---|")
    curves, xmax, ymax = [], 0.0, 0.0
    for name, label, color in VARIANTS:
        run = os.path.join(outdir, f"shear-{name}")
        if not os.path.exists(os.path.join(run, "result.h5")):
            continue
        with Result(run) as r:
            force = r.series("groups/top/reaction_force")[1][:, 0] / 1e3
            disp = r.series("groups/top/displacement")[1][:, 0] * 1e3
            failed = int(r.last("failed_particles"))
            tf, nf = r.series("failed_particles")
            td = r.series("groups/top/displacement")[0]
            try:
                fshear = max(float(r.field("void_fraction_shear", frame=k).max())
                             for k in range(len(r.frame_times())))
            except KeyError:  # no porous model: no void fraction
                fshear = float("nan")
            cost, status = r.cost, r.status
        k = int(force.argmax())
        first = [t for t, v in zip(tf, nf) if v > 0]
        d_fail = float(np.interp(first[0], td, disp)) if first else float("nan")
        cells = [label, f"{force[k]:.2f}", f"{disp[k]:.2f}",
                 f"{d_fail:.2f}" if first else "—", f"{force[-1]:.2f}", f"{failed}",
                 f"{fshear:.2e}" if fshear == fshear else "—", f"{int(cost['particles'])}", f"{int(cost['steps'])}",
                 f"{cost['wall_seconds']:.0f}", status]
        print("| " + " | ".join(cells) + " |")
        curves.append((label, color, disp, force))
        xmax, ymax = max(xmax, float(disp.max())), max(ymax, float(force.max()))
    if curves:
        svg(curves, path, round(xmax + 0.05, 1), 0.0, float(int(ymax) + 1),
            "shear displacement of the top (mm)", "shear force (kN)", legend_left=True)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    notched(sys.argv[1], sys.argv[2])
    shear(sys.argv[1], sys.argv[3])


if __name__ == "__main__":
    main()
