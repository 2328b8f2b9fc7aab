#!/usr/bin/python3
"""The example examples/crack-growth-plate.json (a growing crack, paper 003):
left, the plate's middle layer at three frames in its deformed configuration
(displacements magnified), coloured by damage, with the crack tip's path;
right, the crack length and the particle count against the opening of the
loaded rows (the result file's series crack_length, particle_count and the
velocity groups' displacement).  Each frame is read with its own particle
count (docs/output.md, "Changing particle counts").

usage: bench/crack_growth_plate.py RESULT.h5 OUT.svg   (h5py and matplotlib,
/usr/bin/python3).  Run the example first:
  tlsph-run examples/crack-growth-plate.json -o /tmp/crack-growth"""
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MAGNIFY = 3.0


def frame(g, k):
    """Frame k's particles: the first count[k] entries of every per-frame field."""
    n = int(g["count/value"][k]) if "count" in g else g["position/value"].shape[1]
    ref = g["reference_position"]
    ref = ref["value"][k, :n] if isinstance(ref, h5py.Group) else ref[:n]
    return ref, g["displacement/value"][k, :n], g["damage/value"][k, :n], float(g["position/time"][k])


def main(path, out):
    with h5py.File(path, "r") as f:
        g = f["particles/solid"]
        nf = g["position/value"].shape[0]
        picks = [nf // 3, (2 * nf) // 3, nf - 1]
        frames = [frame(g, k) for k in picks]
        o = f["observables"]
        t = o["crack_length/time"][:] if "time" in o["crack_length"] else o["energy_balance/time"][:]
        length = o["crack_length/value"][:]
        count = o["particle_count/value"][:]
        tip = o["crack_tips/tip0/position/value"][:]
        top = o["groups/top/displacement/value"][:, 1] if "groups/top/displacement" in o else None
        bottom = o["groups/bottom/displacement/value"][:, 1] if "groups/bottom/displacement" in o else None
    fig, axes = plt.subplots(1, 4, figsize=(14.5, 3.8), layout="constrained",
                             gridspec_kw={"width_ratios": [1, 1, 1, 1.15], "wspace": 0.08})
    for ax, (X, u, D, tf) in zip(axes[:3], frames):
        mid = np.abs(X[:, 2] - 0.0015) < 1e-4  # the middle of the three layers
        x = X[mid] + MAGNIFY * u[mid]
        sc = ax.scatter(1e3 * x[:, 0], 1e3 * x[:, 1], c=D[mid], s=5, cmap="inferno_r", vmin=0, vmax=1,
                        linewidths=0, rasterized=True)
        ax.set_aspect("equal")
        ax.set_title("t = %.0f us, %d particles" % (1e6 * tf, len(X)), fontsize=9)
        ax.set_xlabel("x + %g u_x (mm)" % MAGNIFY, fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0].set_ylabel("y + %g u_y (mm)" % MAGNIFY, fontsize=8)
    cb = fig.colorbar(sc, ax=axes[2], fraction=0.05, pad=0.02)
    cb.set_label("damage", fontsize=8)
    ax = axes[3]
    opening = (top - bottom) if top is not None and bottom is not None else None
    xs = 1e3 * opening if opening is not None else 1e6 * t
    ax.plot(xs, 1e3 * length, color="C0", label="crack length grown (mm)")
    ax.set_xlabel("opening of the loaded rows (mm)" if opening is not None else "t (us)", fontsize=8)
    ax.set_ylabel("crack length grown (mm)", fontsize=8, color="C0")
    ax.tick_params(labelsize=7)
    ax2 = ax.twinx()
    ax2.plot(xs, count, color="C3", ls="--")
    ax2.set_ylabel("particles", fontsize=8, color="C3")
    ax2.tick_params(labelsize=7)
    ax.set_title("tip at x = %.1f mm at the end" % (1e3 * tip[-1, 0]), fontsize=9)
    fig.savefig(out, bbox_inches="tight")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
