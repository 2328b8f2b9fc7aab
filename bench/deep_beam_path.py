#!/usr/bin/env python3
"""Crack path of the deep beams (examples/deep-beam-*.json, paper 001 §5.4)
measured from a run's result.h5.

The beam lies in x in [0, 308] mm, y in [0, 76] mm (reference coordinates); the
notch rises from the lower face to the tip T = (x_n, a); the load acts on the
upper face at mid-span, L = (154 mm, 76 mm).  The reference line is the
notch-to-load line T-L: vertical for the mid-span notch (the mode-I crack of
the paper's Fig. 17-18 "propagates vertically"), inclined towards the load for
the offset notch (the mixed-mode crack of John & Shah's beams and of the paper's
Fig. 19-20 turns towards the load point).  Measured at the last frame:

 1. the crack: the particles with link_damage >= 0.2 (a particle beside a
    straight crack has lost 2-3 of its 8 links) connected, through such
    particles at most 1.5 spacings apart, to one within 3 spacings of the tip,
    above the notch tip's row (bench/kalthoff_angle.py's rule);
 2. its angle: the line through T that best fits the crack's particles beyond
    2 spacings from T (principal axis), degrees from +x (90 = vertical); the
    notch-to-load line's own angle beside it;
 3. the deviation from the notch-to-load line: each crack particle's
    horizontal offset from the line at its height (mm, + = towards +x), the
    particles in the top 5 mm left out (the load patch breaks links around
    itself, which is not the crack's path): the mean and the largest |offset|;
    and where the crack meets the top: the mean x of its particles 5-8 mm below
    the top face, as an offset from the load point (mm);
 4. the height reached: (highest crack particle - a) / (76 mm - a), the share of
    the ligament the crack has crossed, and when it crossed 90 % of it; where it
    started (the farthest particle from T with a broken link in the first frame
    that has one) and when.

usage: deep_beam_path.py RESULT_DIR [RUN_LOG] --notch X_MM [--depth A_MM] [--row]
Needs h5py and numpy (/usr/bin/python3)."""
import argparse
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kalthoff_angle import balance, crack, fit_angle  # noqa: E402
from run_log import steps_and_wall  # noqa: E402

DEPTH, LOAD_X = 0.076, 0.154


def measure(path, notch_x, notch_depth=0.019, threshold=0.2):
    f = h5py.File(path + "/result.h5", "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; deep_beam_path.py reads one count per run"
                 % path)
    X = p["reference_position"][:, :2]
    Dall = p["link_damage/value"]
    D = Dall[-1]
    h = math.sqrt(p["volume"][0])
    tip = np.array([notch_x, notch_depth])
    load = np.array([LOAD_X, DEPTH])
    idx = crack(X, D, tip, h, threshold)
    R = X[idx] - tip
    far = R[np.hypot(R[:, 0], R[:, 1]) > 2.0 * h]
    line = load - tip
    # horizontal offset of each crack particle from the line T-L at its height
    below = R[X[idx, 1] < DEPTH - 0.005]
    off = below[:, 0] - below[:, 1] * line[0] / line[1]
    band = X[idx][(X[idx, 1] >= DEPTH - 0.008) & (X[idx, 1] < DEPTH - 0.005)]
    end = band[:, 0].mean() - LOAD_X if len(band) else float("nan")
    t = f["particles/solid/link_damage/time"][:]
    through = next((t[k] for k in range(Dall.shape[0])
                    if (lambda c: len(c) and X[c, 1].max() - notch_depth
                        >= 0.9 * (DEPTH - notch_depth))(crack(X, Dall[k], tip, h, threshold))),
                   float("nan"))
    first = next((k for k in range(Dall.shape[0]) if (Dall[k] > 0).any()), None)
    if first is None:
        start, t0 = float("nan"), float("nan")
    else:
        s = X[Dall[first] > 0] - tip
        start = np.hypot(s[:, 0], s[:, 1]).max()
        t0 = t[first]
    out = {"spacing": h, "n": len(X), "crack_particles": len(idx),
           "angle": fit_angle(far), "line_angle": math.degrees(math.atan2(line[1], line[0])),
           "mean_offset": off.mean() if len(off) else float("nan"),
           "max_offset": np.abs(off).max() if len(off) else float("nan"),
           "height": (R[:, 1].max() / (DEPTH - notch_depth)) if len(R) else 0.0,
           "top_offset": end, "through_time": through,
           "first_frame": first, "start_from_tip": start, "start_time": t0,
           "damaged": int((D >= threshold).sum()), "balance": balance(f)}
    return out


def main(argv):
    ap = argparse.ArgumentParser(description="crack path of a deep-beam run")
    ap.add_argument("result_dir")
    ap.add_argument("run_log", nargs="?")
    ap.add_argument("--notch", type=float, required=True, help="notch centre x, mm")
    ap.add_argument("--depth", type=float, default=19.0, help="notch depth, mm")
    ap.add_argument("--row", action="store_true", help="one markdown row")
    a = ap.parse_args(argv[1:])
    m = measure(a.result_dir, a.notch * 1e-3, a.depth * 1e-3)
    row = a.row
    steps, wall = steps_and_wall(a.run_log)
    if row:
        print("| %.3g mm | %.1f° | %.1f° | %+.1f° | %+.1f mm | %.1f mm | %+.1f mm | %.0f %% "
              "| %.1f mm, %.0f µs | %.0f µs | %d | %d | %s | %s s | %.1e |" %
              (m["spacing"] * 1e3, m["angle"], m["line_angle"], m["angle"] - m["line_angle"],
               m["mean_offset"] * 1e3, m["max_offset"] * 1e3, m["top_offset"] * 1e3,
               100 * m["height"], m["start_from_tip"] * 1e3, m["start_time"] * 1e6,
               m["through_time"] * 1e6, m["crack_particles"], m["n"], steps, wall,
               m["balance"]))
    else:
        print("\n".join("%s: %s" % kv for kv in m.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
