#!/usr/bin/env python3
"""Tensile-test metrics of a Weldox bar result (paper 000 §6 definitions).

usage: weldox_metrics.py RESULT.h5 SECTION_RADIUS_M GAUGE_LENGTH_M [label]

Engineering stress = mean axial reaction of the two loaded end groups ("top",
"bottom") / (pi R^2), R the radius of the smallest section (bar radius, or the
notch root radius); engineering strain = change of the distance between the
end groups / gauge length (the simulated length).  Prints one Markdown table
row: peak stress, strain at the peak, at damage initiation (first step with
failed_particles > 0 is "first failure"; the damage_energy series turning
positive is initiation), at separation (load below 2 % of the peak), the
particle count and wall time, and the run's final status.
"""
import sys

import h5py
import numpy as np


def main():
    path, radius, gauge = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    label = sys.argv[4] if len(sys.argv) > 4 else path
    f = h5py.File(path, "r")
    o = f["observables"]
    top = o["groups/top/reaction_force/value"][:, 2]
    bottom = o["groups/bottom/reaction_force/value"][:, 2]
    ut = o["groups/top/displacement/value"][:, 2]
    ub = o["groups/bottom/displacement/value"][:, 2]
    stress = 0.5 * (np.abs(top) + np.abs(bottom)) / (np.pi * radius**2)
    strain = (ut - ub) / gauge
    failed = o["failed_particles/value"][:]
    dmg = o["damage_energy/value"][:]
    k = int(np.argmax(stress))
    init = strain[np.argmax(dmg > 0)] if (dmg > 0).any() else float("nan")
    first = strain[np.argmax(failed > 0)] if (failed > 0).any() else float("nan")
    after = np.arange(len(stress)) > k
    sep_idx = np.where(after & (stress < 0.02 * stress[k]))[0]
    sep = strain[sep_idx[0]] if len(sep_idx) else float("nan")
    cost = f["cost"].attrs
    status = f["diagnostics"].attrs["status"]
    status = status.decode() if isinstance(status, bytes) else str(status)
    print(f"| {label} | {stress[k] / 1e6:.0f} | {strain[k]:.3f} | {init:.3f} | {first:.3f} | "
          f"{sep:.3f} | {int(cost['particles'])} | {cost['wall_seconds']:.0f} | {status} |")


if __name__ == "__main__":
    main()
