#!/usr/bin/env python3
"""Crack angle of the Kalthoff-Winkler half model (examples/kalthoff-links.json,
paper 001 §5.3) measured from a run's result.h5.

Definition (the experiment's and the paper's): the angle between the crack and
the notch axis, which is also the loading direction (+x, the impact drives the
edge below the notch along the notch); the experiment's crack runs at about 70
degrees to it, the paper's at about 77 ("the angle of the whole cracking path").
Measured here on the reference configuration at the last frame:

 1. damaged particles: link_damage (virtual links: the fraction of a particle's
    links that are broken) or damage (the particle damage of the other
    treatments) >= --threshold (default 0.2: a particle beside a straight crack
    has lost 2-3 of its 8 links);
 2. the crack: the damaged particles connected (through damaged particles at
    most 1.5 spacings apart) to one lying within 3 spacings of the notch tip;
    only particles above the notch line (y >= tip y - one spacing) count: the
    experiment's crack runs into the upper part; damage in the driven strip
    below the notch, at the far edge or at corners is reported, not fitted;
 3. the angle: of the line through the notch tip that best fits the crack's
    particles (the principal axis of sum (X - tip)(X - tip)^T), in degrees
    from +x, 0-180; also the chord from the tip to the crack's farthest
    particle, the first 10 mm of the path (initiation angle) and the length.

usage: kalthoff_angle.py RESULT_DIR [RUN_LOG] [--tip X Y] [--threshold D] [--row]
       (--row prints one markdown row: spacing, angle, error vs 70, chord,
        initial, length, particles, steps, wall time, balance)
Needs h5py and numpy (/usr/bin/python3)."""
import math
import sys
from collections import deque

import h5py
import numpy as np

from run_log import steps_and_wall

EXPERIMENT = 70.0


def crack(X, D, tip, h, threshold):
    """Indices of the damaged particles connected to the notch tip."""
    dam = np.where((D >= threshold) & (X[:, 1] >= tip[1] - h))[0]
    if len(dam) == 0:
        return dam
    P = X[dam]
    cell = {}
    keys = np.floor(P / h).astype(int)
    for k, (a, b) in enumerate(keys):
        cell.setdefault((a, b), []).append(k)
    seen = np.zeros(len(dam), bool)
    start = np.where(np.hypot(P[:, 0] - tip[0], P[:, 1] - tip[1]) <= 3.0 * h)[0]
    q = deque(start)
    seen[start] = True
    while q:
        k = q.popleft()
        a, b = keys[k]
        for da in (-2, -1, 0, 1, 2):
            for db in (-2, -1, 0, 1, 2):
                for m in cell.get((a + da, b + db), ()):
                    if not seen[m] and np.hypot(*(P[m] - P[k])) <= 1.5 * h * (1 + 1e-9):
                        seen[m] = True
                        q.append(m)
    return dam[seen]


def angle_of(d):
    a = math.degrees(math.atan2(d[1], d[0]))
    return a % 180.0


def fit_angle(R):
    """Angle of the principal axis through the origin of the points R."""
    if len(R) < 2:
        return float("nan")
    w, v = np.linalg.eigh(R.T @ R)
    return angle_of(v[:, -1])


def measure(path, tip, threshold):
    f = h5py.File(path + "/result.h5", "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; kalthoff_angle.py reads one count per run"
                 % path)
    X = p["reference_position"][:, :2]
    name = "link_damage" if "link_damage" in p else "damage"
    D = p[name + "/value"][-1]
    h = math.sqrt(p["volume"][0])
    idx = crack(X, D, tip, h, threshold)
    R = X[idx] - tip
    # points beyond 2 spacings: the tip's own neighbourhood says nothing of the direction
    far = R[np.hypot(R[:, 0], R[:, 1]) > 2.0 * h]
    r = np.hypot(far[:, 0], far[:, 1]) if len(far) else np.zeros(0)
    out = {"spacing": h, "n": len(X), "field": name, "crack_particles": len(idx),
           "angle": fit_angle(far),
           "chord": angle_of(far[np.argmax(r)]) if len(far) else float("nan"),
           "initial": fit_angle(far[r <= 0.010]) if len(far) else float("nan"),
           "length": r.max() if len(r) else 0.0,
           "damaged": int((D >= threshold).sum()),
           "damaged_below": int(((D >= threshold) & (X[:, 1] < tip[1] - h)).sum())}
    out["balance"] = balance(f)
    return out


def balance(f):
    """The largest |energy balance| over the run / the largest |external work|, of an
    open result.h5."""
    obs = f["observables"]
    eb = np.abs(obs["energy_balance/value"][:])
    return eb.max() / max(np.abs(obs["external_work/value"][:]).max(), 1e-300)


def main(argv):
    args = argv[1:]
    tip, threshold, row, log = np.array([0.05, 0.025]), 0.2, False, None
    pos = []
    i = 0
    while i < len(args):
        if args[i] == "--tip":
            tip = np.array([float(args[i + 1]), float(args[i + 2])])
            i += 3
        elif args[i] == "--threshold":
            threshold = float(args[i + 1])
            i += 2
        elif args[i] == "--row":
            row = True
            i += 1
        else:
            pos.append(args[i])
            i += 1
    m = measure(pos[0], tip, threshold)
    steps, wall = steps_and_wall(pos[1] if len(pos) > 1 else None)
    if row:
        print("| %.3g mm | %.1f° | %+.1f° | %.1f° | %.1f° | %.1f mm | %d | %d | %s | %s s | %.1e |" %
              (m["spacing"] * 1e3, m["angle"], m["angle"] - EXPERIMENT, m["chord"], m["initial"],
               m["length"] * 1e3, m["crack_particles"], m["n"], steps, wall, m["balance"]))
    else:
        for k, v in m.items():
            print("%s: %s" % (k, v))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
