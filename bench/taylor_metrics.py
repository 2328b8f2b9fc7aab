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
import sys

import h5py
import numpy as np


def metrics(path):
    with h5py.File(path + "/result.h5", "r") as f:
        scene = json.loads(f["parameters/scene"][()].decode() if isinstance(
            f["parameters/scene"][()], bytes) else f["parameters/scene"][()])
        h = scene["bodies"][0]["spacing"]
        x = f["particles/solid/position/value"][-1]
        t_end = float(f["particles/solid/position/time"][-1])
        ps = f["particles/solid"]
        obs = f["observables"]

        def last(name):
            return float(obs[name]["value"][-1]) if name in obs else float("nan")

        ke0 = float(obs["kinetic_energy"]["value"][0])
        r = np.hypot(x[:, 0], x[:, 1])
        foot = x[:, 2] < 0.5 * h
        out = {
            "spacing_mm": h * 1e3,
            "particles": int(f["cost"].attrs["particles"]),
            "steps": int(f["cost"].attrs["steps"]),
            "wall_seconds": float(f["cost"].attrs["wall_seconds"]),
            "particle_steps_per_second": float(f["cost"].attrs["particle_steps_per_second"]),
            "bytes_per_particle": float(f["cost"].attrs["bytes_per_particle"]),
            "t_end_us": t_end * 1e6,
            "length_mm": (x[:, 2].max() + 0.5 * h) * 1e3,
            "foot_diameter_mm": 2e3 * r[foot].max() if foot.any() else float("nan"),
            "max_plastic_strain": float(ps["plastic_strain/value"][-1].max())
            if "plastic_strain" in ps else 0.0,
            "max_temperature_K": last("max_temperature"),
            "kinetic_left": last("kinetic_energy") / ke0,
            "plastic_work": last("plastic_work") / ke0,
            "internal": last("internal_energy") / ke0,
            "hourglass": last("hourglass_energy") / ke0,
            "viscous": last("viscous_energy") / ke0,
            "wall_loss": -last("external_work") / ke0,
            "balance": last("energy_balance") / ke0,
            "min_det_F": float(ps["det_F/value"][-1].min()),
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
