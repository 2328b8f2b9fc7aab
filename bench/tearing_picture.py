#!/usr/bin/python3
"""The crack paths of the tearing runs (bench/tearing.sh): for each variant the
plate's middle layer at one crosshead displacement, in its deformed
configuration (not magnified), coloured by the equivalent plastic strain, the
clamp's row and the crack tips' path marked.  Each frame is read with its own
particle count (docs/output.md, "Changing particle counts").

usage: bench/tearing_picture.py OUTDIR OUT.svg [DELTA_MM]   (h5py and
matplotlib, /usr/bin/python3); DELTA_MM: the crosshead displacement shown
(default: the last frame).  The particles are rasterised inside the SVG."""
import json
import math
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
matplotlib.rcParams["svg.fonttype"] = "none"  # text as text: a smaller file
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tearing_report import VARIANTS  # noqa: E402


def main(outdir, out, delta_mm=None):
    runs = [(n, lab) for n, lab, _ in VARIANTS
            if os.path.exists(os.path.join(outdir, n, "result.h5"))]
    fig, axes = plt.subplots(2, 3, figsize=(13, 6.2))
    axes = axes.ravel()
    sc = None
    for ax, (name, label) in zip(axes, runs):
        with h5py.File(os.path.join(outdir, name, "result.h5"), "r") as f:
            scene = json.loads(f["parameters/scene"][()])
            par = scene["parameters"]
            g = f["particles/solid"]
            times = g["position/time"][:]
            delta = par["V"] * (times - par["tau"] * (1 - np.exp(-times / par["tau"])))
            k = len(times) - 1 if delta_mm is None else int(np.argmin(abs(delta - delta_mm / 1e3)))
            n = int(g["count/value"][k])
            X = g["reference_position/value"][k, :n]
            x = g["position/value"][k, :n]
            ep = g["plastic_strain/value"][k, :n]
            h = scene["bodies"][0]["spacing"]
            mid = abs(X[:, 2] - 1.5 * h) < 0.25 * h
            sc = ax.scatter(1e3 * x[mid, 0], 1e3 * x[mid, 1], c=ep[mid], s=4, cmap="viridis",
                            vmin=0, vmax=0.5, rasterized=True)
            tips = f["observables/crack_tips/tip0/position/value"][:] \
                if "observables/crack_tips/tip0/position" in f else None
            length = f["observables/crack_length/value"][:]
            lt = f["observables/crack_length/time"][:]
            cl = float(np.interp(times[k], lt, length))
        ax.set_title(f"{label}: Δ = {1e3 * delta[k]:.0f} mm, crack {1e3 * cl:.0f} mm",
                     fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(-780, -140)
        ax.set_ylim(-380, 60)
        ax.plot([-900], [-50], "k+")
        ax.plot([0], [0], "ko", ms=3)
        ax.tick_params(labelsize=7)
    for ax in axes[len(runs):]:
        ax.axis("off")
    if sc is not None:
        cax = axes[5].inset_axes([0.1, 0.1, 0.06, 0.8])
        cb = fig.colorbar(sc, cax=cax)
        cb.set_label("equivalent plastic strain\n(the matrix strain for the Gurson family)",
                     fontsize=9)
    fig.text(0.01, 0.01, "middle layer, deformed (x, y) in mm; O at the origin, the clamp's "
             "pivot; the crack runs from the pre-crack's tip at x = -650 mm, y = -200 mm",
             fontsize=8)
    fig.savefig(out, dpi=60)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]) if len(sys.argv) > 3 else None)
