#!/usr/bin/env python3
"""SVG of the deep beams' crack paths (docs/virtual-links.md, paper 001 §5.4):
one panel per run, the 308 x 76 mm beam in reference coordinates, each particle
with link_damage >= 0.15 a cell shaded by it at the last frame (light to black
at 1), the notch, the supports and the load patch, the notch-to-load line
(blue, dashed) and the crack line bench/deep_beam_path.py fits through the
notch tip (red).

usage: deep_beam_plot.py OUT.svg TITLE=RESULT_DIR=NOTCH_X_MM [...]
Needs h5py (/usr/bin/python3)."""
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import deep_beam_path  # noqa: E402
from kalthoff_plot import damage_cells  # noqa: E402

LENGTH, SCALE, PAD, TOP = 0.308, 3000.0, 20.0, 52.0  # SCALE: px per m
HEIGHT = deep_beam_path.DEPTH * SCALE
SUPPORTS = (0.027, 0.281)


def panel(k, title, path, notch_x):
    f = h5py.File(path + "/result.h5", "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; deep_beam_plot.py reads one count per run"
                 % path)
    X = p["reference_position"][:, :2]
    D = np.clip(p["link_damage/value"][-1], 0.0, 1.0)
    h = math.sqrt(p["volume"][0])
    t_end = p["link_damage/time"][-1]
    m = deep_beam_path.measure(path, notch_x)
    oy = TOP + k * (HEIGHT + TOP + PAD)

    def px(x, y):
        return PAD + x * SCALE, oy + HEIGHT - y * SCALE

    out = ['<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#eef" stroke="#888"/>'
           % (PAD, oy, LENGTH * SCALE, HEIGHT)]
    out += damage_cells(X, D, h, px, max(h * SCALE, 0.6))
    a, b = px(notch_x - 0.001, 0.019)
    out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#fff" stroke="#444"/>'
               % (a, b, 0.002 * SCALE, 0.019 * SCALE))
    for s in SUPPORTS:
        a, b = px(s, 0.0)
        out.append('<path d="M%.1f %.1fl-7 12h14z" fill="#444"/>' % (a, b))
    a, b = px(deep_beam_path.LOAD_X, deep_beam_path.DEPTH)
    out.append('<path d="M%.1f %.1fl-6 -12h12z" fill="#c60"/>' % (a, b))
    tip = (notch_x, 0.019)
    x1, y1 = px(*tip)
    x2, y2 = px(deep_beam_path.LOAD_X, deep_beam_path.DEPTH)
    out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#06c" '
               'stroke-dasharray="6,4" stroke-width="1.5"/>' % (x1, y1, x2, y2))
    if not math.isnan(m["angle"]):
        ang = math.radians(m["angle"])
        r = (deep_beam_path.DEPTH - tip[1]) / max(math.sin(ang), 1e-3)
        x2, y2 = px(tip[0] + r * math.cos(ang), tip[1] + r * math.sin(ang))
        out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#d00" '
                   'stroke-width="1.5"/>' % (x1, y1, x2, y2))
    out.append('<text x="%.1f" y="%.1f" font-size="13" font-family="sans-serif">%s, %.0f µs'
               '</text>' % (PAD, oy - 34, title, t_end * 1e6))
    out.append('<text x="%.1f" y="%.1f" font-size="11" font-family="sans-serif">crack fit '
               '%.1f° (red), notch-to-load line %.1f° (blue dashed); offset from it: mean '
               '%+.1f mm, largest %.1f mm, at the top %+.1f mm; %.0f %% of the ligament</text>'
               % (PAD, oy - 18, m["angle"], m["line_angle"], m["mean_offset"] * 1e3,
                  m["max_offset"] * 1e3, m["top_offset"] * 1e3, 100 * m["height"]))
    return out


def main(argv):
    runs = [a.split("=", 2) for a in argv[2:]]
    width = 2 * PAD + LENGTH * SCALE
    height = len(runs) * (HEIGHT + TOP + PAD) + PAD
    body = []
    for k, (title, path, notch) in enumerate(runs):
        body += panel(k, title, path, float(notch) * 1e-3)
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'viewBox="0 0 %d %d">' % (width, height, width, height),
           '<rect width="100%" height="100%" fill="#fff"/>'] + body + ['</svg>']
    open(argv[1], "w").write("\n".join(svg) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
