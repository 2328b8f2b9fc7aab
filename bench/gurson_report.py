#!/usr/bin/env python3
"""Table and SVG plot of the Gurson-family comparison (bench/gurson.sh).

usage: gurson_report.py OUTDIR SVG

Reads OUTDIR/r2-<variant>/result.h5 for the five variants of
bench/gurson_scene.py, prints one Markdown row per run with the metrics of
bench/weldox_metrics.py (peak engineering stress and its strain, strains at
initiation, first failure and separation, ...) and writes the engineering
stress-strain curves of the notched bar, one line per variant, to SVG (no
plotting library: plain SVG polylines).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "support"))
from tlsph_result import Result  # noqa: E402
import weldox_metrics  # noqa: E402

VARIANTS = [("gurson", "Gurson (eq. 43-44)", "#1f77b4"),
            ("gtn", "GTN (eqs. 45-48)", "#2ca02c"),
            ("sm_gurson", "SM-Gurson (eqs. 49-51)", "#d62728"),
            ("m_gurson", "M-Gurson (eqs. 52-54)", "#ff7f0e"),
            ("gtn_strain", "GTN, critical plastic strain 0.35", "#9467bd")]


def svg(curves, path, xmax, ymax):
    W, H, L, B, R, T = 640, 420, 70, 50, 20, 20
    pw, ph = W - L - R, H - T - B

    def X(x):
        return L + pw * x / xmax

    def Y(y):
        return T + ph * (1 - y / ymax)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect x="{L}" y="{T}" width="{pw}" height="{ph}" fill="none" stroke="black"/>']
    for k in range(6):
        x = xmax * k / 5
        y = ymax * k / 5
        out.append(f'<text x="{X(x):.1f}" y="{H - B + 16}" text-anchor="middle">{x:.2f}</text>')
        out.append(f'<text x="{L - 6}" y="{Y(y) + 4:.1f}" text-anchor="end">{y:.0f}</text>')
        out.append(f'<line x1="{L}" y1="{Y(y):.1f}" x2="{L + pw}" y2="{Y(y):.1f}" stroke="#ddd"/>')
    out.append(f'<text x="{L + pw / 2}" y="{H - 10}" text-anchor="middle">engineering strain</text>')
    out.append(f'<text x="16" y="{T + ph / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {T + ph / 2})">engineering stress (MPa)</text>')
    for i, (label, color, xs, ys) in enumerate(curves):
        pts = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in zip(xs, ys) if x <= xmax)
        out.append(f'<polyline points="{pts}" fill="none" stroke="{color}" stroke-width="1.5"/>')
        out.append(f'<line x1="{L + pw - 230}" y1="{T + 18 + 16 * i}" x2="{L + pw - 205}" '
                   f'y2="{T + 18 + 16 * i}" stroke="{color}" stroke-width="2"/>')
        out.append(f'<text x="{L + pw - 200}" y="{T + 22 + 16 * i}">{label}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    outdir, path = sys.argv[1], sys.argv[2]
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
        xmax, ymax = max(xmax, float(strain.max())), max(ymax, float(stress.max()))
    svg(curves, path, round(xmax + 0.05, 1), 100 * (int(ymax / 100) + 1))


if __name__ == "__main__":
    main()
