#!/usr/bin/env python3
"""Deflection and outcome of a notched clamped beam (paper 001 §5.2, Tables
2-3; scenes by bench/notched_scene.py) from a run's result.h5.

Deflection: the permanent mid-span deflection, the mean over the frames in
[1.5 ms, end] of the lower face's deflection at mid-span (the two particles of
its lowest row nearest x = 0; with a mid-span notch these are the ones beside
it), as bench/links_beam.py measures the unnotched beam.

Outcome, per notch, from the damage at the last frame (rules stated here, the
paper gives none):
  cracked particle: link_damage >= 0.25 (virtual links: 2 or more of its 8
    links broken) or damage = 1 (failed, the particle treatments);
  CI  (crack initiated): a cracked particle within one spacing of the notch root;
  crack depth a: the largest distance from the notch root, through the
    ligament, of a cracked particle in the notch's columns +- 2 spacings,
    plus half a spacing (a particle's cell), as a fraction of the ligament
    H - D_N;
  B   (broken at the notch): the crack runs through the whole ligament
    (a >= 1) and the ligament has come apart: the opposite face's particles
    within 2 spacings of the notch's sides have moved apart by one spacing or
    more (an unbroken ligament keeps them together; the opposite face is in
    compression while the beam bends). Cracked particles through the whole
    ligament without that opening are reported as CI (a = 100 %): links are
    broken in every row, but others still hold the two sides together;
  LN  (local necking): the ligament's thickness (mean of the three columns
    through the notch, current distance between the notch root row and the
    opposite face's row) has shrunk by 5 % or more.
usage: notched_beams.py RESULT_DIR SCENE.json [RUN_LOG]  (prints a markdown row)
Needs h5py (/usr/bin/python3)."""
import json
import sys

import h5py
import numpy as np

from run_log import steps_and_wall

H = 0.00635


def notches(scene):
    return [c["box"] for c in scene["bodies"][0]["geometry"]["difference"][1:]]


def main(argv):
    res, scene = argv[1], json.load(open(argv[2]))
    f = h5py.File(res + "/result.h5", "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; notched_beams.py reads one count per run"
                 % res)
    X = p["reference_position"][:, :2]
    h = scene["bodies"][0]["spacing"]
    t = p["displacement/time"][:] if "time" in p["displacement"] else p["det_F/time"][:]
    U = p["displacement/value"]
    if "link_damage" in p:
        cracked = p["link_damage/value"][-1] >= 0.25
    else:
        cracked = p["damage/value"][-1] >= 1.0
    ylow, ytop = X[:, 1].min(), X[:, 1].max()
    low = np.where(np.abs(X[:, 1] - ylow) < 1e-9)[0]
    mid = np.sort(low[np.argsort(np.abs(X[low, 0]))[:2]])
    w = -U[:, mid, 1].mean(axis=1)
    late = t >= 1.5e-3 - 1e-12
    perm, peak = w[late].mean(), w.max()
    outcome = []
    for b in notches(scene):
        xc = 0.5 * (b["min"][0] + b["max"][0])
        lower = b["min"][1] < -H  # notch in the lower face: ligament above it
        root = b["max"][1] if lower else b["min"][1]
        face = ytop if lower else ylow
        lig = abs(face - root)
        near = np.abs(X[:, 0] - xc) <= 0.5 * (b["max"][0] - b["min"][0]) + 2.0 * h
        depth = np.abs(X[:, 1] - root)
        side = (X[:, 1] > root) if lower else (X[:, 1] < root)
        c = cracked & near & side
        a = min(1.0, (depth[c].max() + 0.5 * h) / lig) if c.any() else 0.0
        ci = bool((c & (depth <= 1.0 * h)).any())
        # ligament thinning at the notch: rows next to the root and at the face
        col = np.abs(X[:, 0] - xc) <= 1.5 * h
        lig_col = col & side
        r_row = lig_col & (depth <= depth[lig_col].min() + 1e-3 * h) if lig_col.any() else lig_col
        f_row = col & (np.abs(X[:, 1] - face) < 1e-9)
        thin = float("nan")
        if r_row.any() and f_row.any():
            y_now = X[:, 1] + U[-1, :, 1]
            t0 = abs(X[f_row, 1].mean() - X[r_row, 1].mean())
            thin = 1.0 - abs(y_now[f_row].mean() - y_now[r_row].mean()) / t0
        half = 0.5 * (b["max"][0] - b["min"][0])
        fr = np.where((np.abs(X[:, 1] - face) < 1e-9) & (np.abs(X[:, 0] - xc) <= half + 2.0 * h))[0]
        left, right = fr[np.argmin(X[fr, 0])], fr[np.argmax(X[fr, 0])]
        x_now = X[:, 0] + U[-1, :, 0]
        opening = (x_now[right] - x_now[left]) - (X[right, 0] - X[left, 0])
        tags = []
        if thin >= 0.05:
            tags.append("LN")
        if a >= 1.0 - 1e-9 and opening >= h:
            tags.append("B")
        elif ci:
            tags.append("CI (a = %.0f %%)" % (100 * a))
        outcome.append("%s [thinning %.0f %%, opening %.2f mm]" %
                       (" and ".join(tags) or "none", 100 * thin, opening * 1e3))
    obs = f["observables"]
    broken = int(obs["broken_links/value"][-1]) if "broken_links" in obs else \
        int(obs["failed_particles/value"][-1]) if "failed_particles" in obs else 0
    V = -scene["rigid_bodies"][0]["motion"]["velocity"][1]
    hs = scene["rigid_bodies"][0]["shape"]["half_sizes"]
    G = scene["rigid_bodies"][0]["motion"]["density"] * 4 * hs[0] * hs[1]
    balance = np.abs(obs["energy_balance/value"][:]).max() / (0.5 * G * V * V)
    steps, wall = steps_and_wall(argv[3] if len(argv) > 3 else None)
    print("| %.1f | %.2f mm | %.2f mm | %s | %d | %d | %s | %s s | %.1e |" %
          (V, perm * 1e3, peak * 1e3, "; ".join(outcome), broken, len(X), steps, wall, balance))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
