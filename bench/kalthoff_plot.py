#!/usr/bin/env python3
"""SVG of Kalthoff-Winkler crack paths side by side (docs/virtual-links.md):
one panel per run, the half plate in reference coordinates, each particle a
cell shaded by its damage at the last frame (link_damage or damage >= 0.15, light to
black 1), the notch, the experiment's 70 degree line from the notch tip
(dashed) and the crack line bench/kalthoff_angle.py fits (red).

usage: kalthoff_plot.py OUT.svg TITLE=RESULT_DIR [TITLE=RESULT_DIR ...]
Needs h5py (/usr/bin/python3)."""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kalthoff_angle  # noqa: E402

SIZE, PAD, TOP = 300.0, 20.0, 40.0
TIP = np.array([0.05, 0.025])


def damage_cells(X, D, h, px, c, lowest=0.15):
    """SVG rectangles of the cells of the particles with D >= lowest, in 8 grey
    levels (light to black at 1); a run of equal cells along a row is one
    rectangle.  px maps reference (x, y) to the picture, c is a cell's size there;
    the lattice points lie at (i + 1/2) h (a body box from the origin), cell i
    spans [i h, (i + 1) h]."""
    out = []
    sel = D >= lowest
    col = np.round(X[sel, 0] / h - 0.5).astype(int)
    row = np.round(X[sel, 1] / h - 0.5).astype(int)
    grey = (255 * (1.0 - np.round(D[sel] * 7) / 7)).astype(int)
    order = np.lexsort((col, row))
    k = 0
    while k < len(order):
        i = order[k]
        n = 1
        while (k + n < len(order) and row[order[k + n]] == row[i]
               and col[order[k + n]] == col[i] + n and grey[order[k + n]] == grey[i]):
            n += 1
        a, b = px(col[i] * h, (row[i] + 1) * h)
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="rgb(%d,%d,%d)"/>'
                   % (a, b, c * n, c, grey[i], grey[i], grey[i]))
        k += n
    return out


def panel(k, title, path):
    f = h5py.File(path + "/result.h5", "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; kalthoff_plot.py reads one count per run"
                 % path)
    X = p["reference_position"][:, :2]
    name = "link_damage" if "link_damage" in p else "damage"
    D = np.clip(p[name + "/value"][-1], 0.0, 1.0)
    h = math.sqrt(p["volume"][0])
    m = kalthoff_angle.measure(path, TIP, 0.2)
    ox = PAD + k * (SIZE + PAD)
    s = SIZE / 0.1

    def px(x, y):
        return ox + x * s, TOP + SIZE - y * s

    out = ['<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#eef" stroke="#888"/>'
           % (ox, TOP, SIZE, SIZE)]
    out += damage_cells(X, D, h, px, max(h * s, 0.6))
    a, b = px(0.0, 0.025 + 0.0006)
    out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#fff" stroke="#444"/>'
               % (a, b, 0.05 * s, 0.0012 * s))
    for ang, style in ((70.0, 'stroke="#06c" stroke-dasharray="6,4"'),
                       (m["angle"], 'stroke="#d00"')):
        if math.isnan(ang):
            continue
        r = 0.075 / max(math.sin(math.radians(ang)), 1e-3)
        r = min(r, 0.09)
        x1, y1 = px(*TIP)
        x2, y2 = px(TIP[0] + r * math.cos(math.radians(ang)), TIP[1] + r * math.sin(math.radians(ang)))
        out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" %s stroke-width="1.5"/>'
                   % (x1, y1, x2, y2, style))
    out.append('<text x="%.1f" y="%.1f" font-size="13" font-family="sans-serif">%s</text>'
               % (ox, TOP - 22, title))
    out.append('<text x="%.1f" y="%.1f" font-size="11" font-family="sans-serif">'
               'fit %.1f°, chord %.1f° (red: fit; blue dashed: 70°)</text>'
               % (ox, TOP - 7, m["angle"], m["chord"]))
    return out


def main(argv):
    runs = [a.split("=", 1) for a in argv[2:]]
    width = PAD + len(runs) * (SIZE + PAD)
    body = []
    for k, (title, path) in enumerate(runs):
        body += panel(k, title, path)
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'viewBox="0 0 %d %d">' % (width, TOP + SIZE + PAD, width, TOP + SIZE + PAD),
           '<rect width="100%" height="100%" fill="#fff"/>'] + body + ['</svg>']
    open(argv[1], "w").write("\n".join(svg) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
