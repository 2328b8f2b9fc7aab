#!/usr/bin/python3
"""Measures a Taylor-bar result: final length, foot diameter, energy split, cost.

usage: taylor_metrics.py RESULT_DIR [--json]

Assumes the rod axis is z and the anvil is the plane z = 0 (as in
examples/taylor-bar*.json).  Definitions, all from particle centres of the last
frame (h = the body's lattice spacing):
  final length  L = z_max + h/2   (the top layer's half spacing; L(t=0) = L0 exactly)
  foot diameter D = 2 max r over the particles within h/2 of the anvil
                    (centre-based: the outer particles' own half-width, up to
                    h/2, is not added, so D converges from below as h -> 0)
Energies are fractions of the initial kinetic energy.
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "support"))
from tlsph_result import Result  # noqa: E402


def metrics(path):
    with Result(path) as f:
        h = f.spacing()
        x = f.field("position")
        t_end = float(f.frame_times()[-1])
        last = f.last
        cost = f.cost
        ke0 = float(f.series("kinetic_energy")[1][0])
        r = np.hypot(x[:, 0], x[:, 1])
        foot = x[:, 2] < 0.5 * h
        out = {
            "spacing_mm": h * 1e3,
            "particles": int(cost["particles"]),
            "steps": int(cost["steps"]),
            "wall_seconds": float(cost["wall_seconds"]),
            "particle_steps_per_second": float(cost["particle_steps_per_second"]),
            "bytes_per_particle": float(cost["bytes_per_particle"]),
            "t_end_us": t_end * 1e6,
            "length_mm": (x[:, 2].max() + 0.5 * h) * 1e3,
            "foot_diameter_mm": 2e3 * r[foot].max() if foot.any() else float("nan"),
            "max_plastic_strain": float(f.field("plastic_strain").max())
            if f.has_field("plastic_strain") else 0.0,
            "max_temperature_K": last("max_temperature"),
            "kinetic_left": last("kinetic_energy") / ke0,
            "plastic_work": last("plastic_work") / ke0,
            "internal": last("internal_energy") / ke0,
            "hourglass": last("hourglass_energy") / ke0,
            "viscous": last("viscous_energy") / ke0,
            "wall_loss": -last("external_work") / ke0,
            "balance": last("energy_balance") / ke0,
            "min_det_F": float(f.field("det_F").min()),
        }
    return out


def main(argv):
    m = metrics(argv[1])
    if "--json" in argv:
        print(json.dumps(m))
        return 0
    for k, v in m.items():
        print(f"{k:28s} {v:.6g}" if isinstance(v, float) else f"{k:28s} {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
