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
  is observed"): raw, and averaged over the bar's acoustic round trip
  2 L0 / c0, the period of the elastic ringing each sudden failure sets off;
  particles, steps, wall time (whole run loop, 1 thread; the cost in steps does
  not depend on what else the machine runs) and the run's final status.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "support"))
from tlsph_result import Result  # noqa: E402

C0 = 5166.0  # m/s, bulk sound speed of the Weldox steels (paper 000 Table 1)

COLUMNS = ["case", "peak eng. stress (MPa)", "strain at peak", "strain at initiation",
           "strain at first failure", "strain at separation", "peak section sigma_1 (MPa)",
           "section eps_p at first failure", "load rise, raw / over 2L/c0", "particles",
           "steps", "wall (s)", "status"]


def largest_rise(stress, peak):
    """Largest rise above the running minimum, as a fraction of peak."""
    if len(stress) == 0:
        return float("nan")
    return float(np.max(stress - np.minimum.accumulate(stress))) / peak


def averaged(t, stress, window):
    """Moving average over window (s) on a uniform resampling of the series."""
    dt = np.min(np.diff(t)) if len(t) > 1 else window
    n = max(1, int(round(window / dt)))
    tu = np.linspace(t[0], t[-1], max(2, int((t[-1] - t[0]) / dt) + 1))
    su = np.interp(tu, t, stress)
    return tu, np.convolve(su, np.ones(n) / n, mode="same")


def first(mask, values):
    idx = np.flatnonzero(mask)
    return values[idx[0]] if len(idx) else float("nan")


def gauge_length(f):
    """The gauge's default length: the distance between the centroids of the
    end groups, here the bottom and top particle layers of the bar."""
    z = f.field("reference_position")[:, 2]
    h = f.spacing()
    return z[z >= z.max() - 0.5 * h].mean() - z[z <= z.min() + 0.5 * h].mean()


def row(path, label):
    f = Result(path)
    t, stress = f.series("gauges/bar/engineering_stress")
    strain = f.series("gauges/bar/engineering_strain")[1]
    s1 = f.series("sections/middle/max_principal_stress")[1]
    eps = f.series("sections/middle/plastic_strain")[1]
    initiated = f.series("initiated_particles")[1]
    failed = f.series("failed_particles")[1]
    k = int(np.argmax(stress))
    peak = stress[k]
    after = np.arange(len(stress)) > k
    sep_idx = np.flatnonzero(after & (stress < 0.02 * peak))
    sep = strain[sep_idx[0]] if len(sep_idx) else float("nan")
    # largest rise of the load above its running minimum between the first
    # failure and separation (after separation the two free halves ring
    # elastically around zero load: that is not the load path); raw, and
    # averaged over the bar's acoustic round trip 2 L0 / c0, which removes the
    # ringing that each sudden failure sets off (the period of that ringing)
    rise = rise_avg = float("nan")
    fidx = np.flatnonzero(failed > 0)
    if len(fidx):
        end = sep_idx[0] + 1 if len(sep_idx) else len(stress)
        end = max(end, fidx[0] + 1)
        rise = largest_rise(stress[fidx[0]:end], peak)
        tu, su = averaged(t, stress, 2.0 * gauge_length(f) / C0)
        sel = (tu >= t[fidx[0]]) & (tu <= t[end - 1])
        rise_avg = largest_rise(su[sel], peak)
    cost, status = f.cost, f.status
    f.close()
    cells = [label, f"{peak / 1e6:.0f}", f"{strain[k]:.3f}",
             f"{first(initiated > 0, strain):.3f}", f"{first(failed > 0, strain):.3f}",
             f"{sep:.3f}", f"{np.max(s1) / 1e6:.0f}", f"{first(failed > 0, eps):.3f}",
             f"{100 * rise:.1f} % / {100 * rise_avg:.1f} %", f"{int(cost['particles'])}", f"{int(cost['steps'])}",
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
