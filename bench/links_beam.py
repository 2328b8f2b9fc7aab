#!/usr/bin/env python3
"""Permanent mid-span deflection of the clamped beam struck by the rigid
projectile (examples/projectile-beam-links.json, paper 001 §5.1) from a run's
result.h5, against the rigid-plastic solution of Liu & Jones (1987), paper 001
eq. 36 with its denominator read as 1 + L/(2L - L) = 2:
    w_f / H = 1/2 (-1 + sqrt(1 + (G V^2 L / (M_p H)) / 2)),
G the projectile's mass per metre, M_p = sigma_y H^2 / 4 per metre, V the
projectile's speed in the scene the run stored.
The deflection is that of the beam's lower face at mid-span (the mean of the
two particles of its lowest row nearest x = 0); the permanent deflection is
its mean over the frames in [1.5, 3] ms, as docs/contact.md measures it.

usage: links_beam.py RESULT_DIR [RUN_LOG]   (prints one markdown table row)
Needs h5py (/usr/bin/python3)."""
import json
import math
import sys

import h5py
import numpy as np

from run_log import steps_and_wall

H, L, SIGMA_Y = 0.00635, 0.07112, 277.8e6
G = 14311.4 * 0.01474 * 0.05  # kg/m: the rigid box of the example


def reference(V):
    mp = SIGMA_Y * H * H / 4.0
    return H * 0.5 * (-1.0 + math.sqrt(1.0 + (G * V * V * L / (mp * H)) / 2.0))


def main(argv):
    f = h5py.File(argv[1] + "/result.h5", "r")
    # the projectile's speed, from the scene the run stored
    V = -json.loads(f["parameters/scene"][()])["rigid_bodies"][0]["motion"]["velocity"][1]
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; links_beam.py reads one count per run"
                 % argv[1])
    X = p["reference_position"][:]
    body = p["body"][:]
    beam = body == 0
    ylow = X[beam, 1].min()
    low = np.where(beam & (np.abs(X[:, 1] - ylow) < 1e-9))[0]
    mid = np.sort(low[np.argsort(np.abs(X[low, 0]))[:2]])
    t = p["displacement/time"][:] if "time" in p["displacement"] else p["det_F/time"][:]
    w = -p["displacement/value"][:, mid, 1].mean(axis=1)
    late = (t >= 1.5e-3 - 1e-12) & (t <= 3e-3 + 1e-12)
    perm, peak = w[late].mean(), w.max()
    obs = f["observables"]
    broken = int(obs["broken_links/value"][-1]) if "broken_links" in obs else 0
    ke0 = 0.5 * G * V * V
    balance = np.abs(obs["energy_balance/value"][:]).max() / ke0
    spacing = math.sqrt(p["volume"][0])  # 2-D: the particle's area, spacing^2
    steps, wall = steps_and_wall(argv[2] if len(argv) > 2 else None)
    ref = reference(V)
    print("| %.4g mm (%d) | %g m/s | %d | %s | %.2f mm | %.3f mm | %.3f mm | %+.1f %% | %d | %.1e | %s s |" %
          (spacing * 1e3, round(H / spacing), V, int(beam.sum()), steps, peak * 1e3, perm * 1e3,
           ref * 1e3,
           100.0 * (perm / ref - 1.0), broken, balance, wall))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
