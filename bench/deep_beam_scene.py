#!/usr/bin/env python3
"""Writes a deep-beam scene (examples/deep-beam-*.json, paper 001 §5.4) at
another spacing (docs/virtual-links.md, case 4).

The lattice points lie at (i + 1/2) h, so a box edge on a multiple of the
spacing h (a cell boundary) selects whole cells without ties.  The examples'
edges (notch, supports, load patch) are multiples of 1 mm, hence of 1 and
0.5 mm; at a spacing they are not multiples of, each edge is moved outwards to
the next cell boundary (at 2 mm: the notch 4 mm wide and 20 mm deep, the
patches 6 and 4 mm wide, one row of cells thick).

usage: deep_beam_scene.py EXAMPLE SPACING OUT.json [END_TIME]"""
import json
import math
import sys


def snap(box, h):
    """box edges moved outwards to multiples of h (unbounded edges kept)."""
    lo, hi = box["min"], box["max"]
    for a in range(2):
        if abs(lo[a]) < 0.5:
            lo[a] = math.floor(lo[a] / h + 1e-9) * h
        if abs(hi[a]) < 0.5:
            hi[a] = math.ceil(hi[a] / h - 1e-9) * h


def main(argv):
    d = json.load(open(argv[1]))
    h = float(argv[2])
    d["bodies"][0]["spacing"] = h
    snap(d["bodies"][0]["geometry"]["difference"][1]["box"], h)
    for bc in d["boundary_conditions"]:
        snap(bc["select"]["box"], h)
    if len(argv) > 4:
        d["time"]["end"] = float(argv[4])
        d["output"]["frames"] = max(1, round(float(argv[4]) / 10e-6))
    json.dump(d, open(argv[3], "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
