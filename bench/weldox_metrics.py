#!/usr/bin/env python3
"""Tensile-test metrics of a Weldox bar result (paper 000 §6 definitions).

usage: weldox_metrics.py RESULT.h5 [label]
       weldox_metrics.py --header

Reads only the run's own time series: the gauge "bar" (engineering stress and
strain between the loaded end groups) and the section "middle" (means over the
notch section: largest principal stress and equivalent plastic strain), as
bench/weldox_scene.py writes them into every scene.  Prints one Markdown table
row:
  peak engineering stress and the engineering strain there;
  engineering strain at damage initiation (first particle with D_init >= 1),
  at first failure (first particle with D = 1) and at separation (after the
  peak, the load first falls below 2 % of the peak);
  peak of the section-mean principal stress and the section-mean plastic
  strain at first failure (Fig. 5b-c of the paper plots one against the other);
  the largest rise of the load, between first failure and separation, above
  its lowest value so far, in % of the peak (paper: "a steady decay in stress
  is observed");
  particles, steps, wall time (whole run loop, 1 thread; the cost in steps does
  not depend on what else the machine runs) and the run's final status.
"""
import sys

import h5py
import numpy as np

COLUMNS = ["case", "peak eng. stress (MPa)", "strain at peak", "strain at initiation",
           "strain at first failure", "strain at separation", "peak section sigma_1 (MPa)",
           "section eps_p at first failure", "load rise, failure to separation", "particles",
           "steps", "wall (s)", "status"]


def first(mask, values):
    idx = np.flatnonzero(mask)
    return values[idx[0]] if len(idx) else float("nan")


def row(path, label):
    f = h5py.File(path, "r")
    o = f["observables"]
    stress = o["gauges/bar/engineering_stress/value"][:]
    strain = o["gauges/bar/engineering_strain/value"][:]
    s1 = o["sections/middle/max_principal_stress/value"][:]
    eps = o["sections/middle/plastic_strain/value"][:]
    initiated = o["initiated_particles/value"][:]
    failed = o["failed_particles/value"][:]
    k = int(np.argmax(stress))
    peak = stress[k]
    after = np.arange(len(stress)) > k
    sep_idx = np.flatnonzero(after & (stress < 0.02 * peak))
    sep = strain[sep_idx[0]] if len(sep_idx) else float("nan")
    # largest rise of the load above its running minimum between the first
    # failure and separation (after separation the two free halves ring
    # elastically around zero load: that is not the load path)
    rise = float("nan")
    fidx = np.flatnonzero(failed > 0)
    if len(fidx):
        end = sep_idx[0] + 1 if len(sep_idx) else len(stress)
        tail = stress[fidx[0]:max(end, fidx[0] + 1)]
        rise = float(np.max(tail - np.minimum.accumulate(tail))) / peak
    cost = f["cost"].attrs
    status = f["diagnostics"].attrs["status"]
    status = status.decode() if isinstance(status, bytes) else str(status)
    cells = [label, f"{peak / 1e6:.0f}", f"{strain[k]:.3f}",
             f"{first(initiated > 0, strain):.3f}", f"{first(failed > 0, strain):.3f}",
             f"{sep:.3f}", f"{np.max(s1) / 1e6:.0f}", f"{first(failed > 0, eps):.3f}",
             f"{100 * rise:.1f} %", f"{int(cost['particles'])}", f"{int(cost['steps'])}",
             f"{cost['wall_seconds']:.0f}",
             status]
    return "| " + " | ".join(cells) + " |"


def main():
    if sys.argv[1:] == ["--header"]:
        print("| " + " | ".join(COLUMNS) + " |")
        print("|---|" + "---:|" * (len(COLUMNS) - 2) + "---|")
        return
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    print(row(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else sys.argv[1]))


if __name__ == "__main__":
    main()
