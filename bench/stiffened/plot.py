#!/usr/bin/python3
"""The stiffened plate (paper 003 §6.2, docs/crack-growth.md "The stiffened plate"):
the crack path and the cone's force against its displacement, from a run's
result.h5 and its log.

usage: plot.py RESULT_DIR LOG OUT_PREFIX
writes OUT_PREFIX-path.svg (the plate's top layer seen from +z in the reference
configuration, coloured by the equivalent plastic strain of the last frame, the
tips' path from the log's events, the stiffeners' lines; and the same layer in
the current configuration) and OUT_PREFIX-force.svg (the cone's contact force
along its motion, -F_x, against its displacement).  Needs h5py and matplotlib
(/usr/bin/python3)."""
import re
import sys

import h5py
import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def last_frame(f, name):
    g = f["/particles/solid/" + name + "/value"]
    n = int(f["/particles/solid/count/value"][-1])
    return g[-1, :n]


def main(res, log, out):
    f = h5py.File(res + "/result.h5", "r")
    X = last_frame(f, "reference_position")
    x = last_frame(f, "position")
    names = list(f["/particles/solid"].keys())
    ep_name = next(k for k in ("plastic_strain", "equivalent_plastic_strain", "eps_p")
                   if k in names)
    ep = last_frame(f, ep_name)
    top = X[:, 2] > X[:, 2].max() - 1e-6  # the plate's top layer
    events = []  # (tip, position); a start: (None, position, its first tip)
    for line in open(log):
        m = re.search(r"(crack starts at|crack tip (\d+) ->) fibre \d+.*? at \(([^)]*)\) m", line)
        if m:
            p = [float(v) for v in m.group(3).split(",")]
            first = re.search(r"tips (\d+)( and the next)?", line)
            events.append((m.group(2), p, first and (int(first.group(1)), bool(first.group(2)))))
    fig, ax = plt.subplots(1, 2, figsize=(11, 5))
    for a, P, title in ((ax[0], X, "reference"), (ax[1], x, "current (last frame)")):
        sc = a.scatter(1e3 * P[top, 0], 1e3 * P[top, 1], c=ep[top], s=6, cmap="viridis",
                       vmin=0, vmax=max(0.35, float(np.percentile(ep[top], 99))),
                       rasterized=True)  # an SVG of 5000 vector dots is 0.5 MB
        a.set_aspect("equal")
        a.set_xlabel("x (mm)")
        a.set_ylabel("y (mm)")
        a.set_title(title)
        for ys in (-15.8333, 15.8333):
            a.axhline(ys, color="grey", lw=0.8, ls="--")
    fig.colorbar(sc, ax=ax, label=ep_name + " (top layer)")
    tips = {}
    starts = []
    for tip, p, first in events:
        if tip is None:  # a start: the tips it makes begin there
            starts.append(p)
            for q in range(first[0], first[0] + (2 if first[1] else 1)):
                tips[str(q)] = [p]
            continue
        tips.setdefault(tip, []).append(p)
    for tip, path in tips.items():
        path = np.array(path)
        ax[0].plot(1e3 * path[:, 0], 1e3 * path[:, 1], ".-", lw=1.2, ms=3)
    if starts:
        S = np.array(starts)
        ax[0].plot(1e3 * S[:, 0], 1e3 * S[:, 1], "r*", ms=10, ls="none", label="starts")
    ax[0].legend(loc="upper right", fontsize=8)
    ax[0].set_xlim(-1, 31)
    ax[0].set_ylim(-20, 20)
    ax[1].set_xlim(-10, 31)
    ax[1].set_ylim(-20, 20)
    fig.savefig(out + "-path.svg")
    obs = f["/observables/rigid/cone"]
    pos = obs["position/value"][:, 0]
    force = obs["force/value"][:, 0]
    fig2, a2 = plt.subplots(figsize=(6, 4))
    a2.plot(1e3 * (pos - pos[0]), -1e-3 * force, "k-", lw=1)
    a2.set_xlabel("cone displacement (mm)")
    a2.set_ylabel("contact force against the motion, -F_x (kN)")
    a2.set_title("stiffened plate, cone at 40 m/s")
    a2.grid(True, lw=0.3)
    fig2.tight_layout()
    fig2.savefig(out + "-force.svg")
    print("events %d, tips %d, particles %d, peak force %.3g kN at %.3g mm" % (
        len(events), len(tips), len(X), -1e-3 * force.min(),
        1e3 * (pos - pos[0])[int(np.argmin(force))]))


if __name__ == "__main__":
    main(*sys.argv[1:4])
