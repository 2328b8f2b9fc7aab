#!/usr/bin/python3
"""The stiffened plate (paper 003 §6.2, docs/crack-growth.md "The stiffened plate"):
the crack path and the cone's force against its displacement, from a run's
result.h5 and its log.

usage: plot.py RESULT_DIR LOG OUT_PREFIX [COMPARE_RESULT_DIR]
writes OUT_PREFIX-path.svg (the plate's top layer seen from +z in the reference
configuration, coloured by the equivalent plastic strain of the last frame, the
tips' path from the log's events, the stiffeners' lines; and the same layer in
the current configuration) and OUT_PREFIX-force.svg (the cone's contact force
along its motion, -F_x, against its displacement).  The cone's direction is
read from its displacement: along x (Simulation I, stiffened-plate.json) or
along y, across the bars (Simulation II, stiffened-plate-across.json, §6.3),
which sets the force's component and the panels' window.  COMPARE_RESULT_DIR,
optional, adds that run's force curve (its cone's own direction) to the force
plot, dashed.  Needs h5py and matplotlib (/usr/bin/python3)."""
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


def cone_motion(f):
    """The cone's displacement along its motion and its force against it, with
    the motion's axis (0 for x, 1 for y): the component it moved most along."""
    obs = f["/observables/rigid/cone"]
    pos = obs["position/value"][:]
    k = int(np.argmax(np.abs(pos[-1] - pos[0])[:2]))
    return k, pos[:, k] - pos[0, k], obs["force/value"][:, k]


def main(res, log, out, compare=None):
    f = h5py.File(res + "/result.h5", "r")
    k, disp, force = cone_motion(f)
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
    if k == 0:
        ax[0].set_xlim(-1, 31)
        ax[0].set_ylim(-20, 20)
        ax[1].set_xlim(-10, 31)
        ax[1].set_ylim(-20, 20)
    else:  # across the bars: the cone enters at y = -30 mm, x = 30 mm
        ax[0].set_xlim(-1, 61)
        ax[0].set_ylim(-31, 14)
        ax[1].set_xlim(-1, 61)
        ax[1].set_ylim(-36, 14)
    fig.savefig(out + "-path.svg")
    fig2, a2 = plt.subplots(figsize=(6, 4))
    a2.plot(1e3 * disp, -1e-3 * force, "k-", lw=1,
            label="along y, across the bars (Simulation II)" if k == 1 else None)
    if compare is not None:
        kc, dc, fc = cone_motion(h5py.File(compare + "/result.h5", "r"))
        a2.plot(1e3 * dc, -1e-3 * fc, "b--", lw=0.8,
                label="along %s, between the bars (Simulation I)" % "xy"[kc])
    if k == 1:  # the cone (apex at y = -30.5 mm, z = 2.5 mm, 30 deg) in the first bar
        # (y in [-18.3, -13.3] mm, z in [-10, 0] mm): its flank reaches the bar's
        # top near edge at 16.5 mm of travel (2.5 mm from the axis, 4.33 mm
        # behind the apex) and its bottom far edge at 38.8 mm (12.5 mm, 21.65 mm)
        a2.axvspan(16.5, 38.8, color="grey", alpha=0.15, lw=0,
                   label="the cone's flank in the first bar")
    if compare is not None or k == 1:
        a2.legend(loc="upper left", fontsize=8)
    a2.set_xlabel("cone displacement (mm)")
    a2.set_ylabel("contact force against the motion, -F_%s (kN)" % ("xy"[k] if compare is None
                                                                   else "x or y"))
    a2.set_title("stiffened plate, cone at 40 m/s" + ("" if k == 0 else " across the bars"))
    a2.grid(True, lw=0.3)
    fig2.tight_layout()
    fig2.savefig(out + "-force.svg")
    print("events %d, tips %d, particles %d, peak force %.3g kN at %.3g mm" % (
        len(events), len(tips), len(X), -1e-3 * force.min(),
        1e3 * disp[int(np.argmin(force))]))


if __name__ == "__main__":
    main(*sys.argv[1:5])
