#!/usr/bin/env python3
"""Writes a deep-beam scene (examples/deep-beam-*.json, paper 001 §5.4) at
another spacing (docs/virtual-links.md, case 4).

The lattice points lie at (i + 1/2) h, so a box edge on a multiple of the
spacing h (a cell boundary) selects whole cells without ties.  The examples'
edges (notch, supports, load patch) are multiples of 1 mm, hence of 1 and
0.5 mm; at a spacing they are not multiples of, each edge is moved outwards to
the next cell boundary (at 2 mm: the notch 4 mm wide and 20 mm deep, the
patches 6 and 4 mm wide, one row of cells thick).

With --striker K the held velocity on the load patch is replaced by a free
rigid striker (docs/virtual-links.md, "The load"): a 4 x 50 mm box of K times
the beam's mass, centred over the patch half a millimetre above the upper face,
at the patch's velocity, in contact with the beam.

usage: deep_beam_scene.py [--striker K] EXAMPLE SPACING OUT.json [END_TIME]"""
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


def striker(d, ratio):
    """The "impact" condition replaced by a free rigid box of ratio x the beam's mass."""
    impact = next(bc for bc in d["boundary_conditions"] if bc["name"] == "impact")
    d["boundary_conditions"].remove(impact)
    lo, hi = impact["select"]["box"]["min"], impact["select"]["box"]["max"]
    beam = d["bodies"][0]["geometry"]["difference"][0]["box"]
    length, depth = (beam["max"][a] - beam["min"][a] for a in range(2))
    beam_mass = d["materials"]["steel"]["density"] * length * depth  # kg per metre, notch aside
    half = [0.002, 0.025, 0.0]
    d["rigid_bodies"] = [{
        "name": "striker",
        "shape": {"type": "box", "center": [0.5 * (lo[0] + hi[0]), beam["max"][1] + 0.0005 + half[1], 0],
                  "half_sizes": half},
        "motion": {"type": "free", "density": ratio * beam_mass / (4 * half[0] * half[1]),
                   "velocity": [0.0 if v is None else v for v in impact["velocity"]]}}]


def main(argv):
    ratio = None
    if len(argv) > 2 and argv[1] == "--striker":
        ratio = float(argv[2])
        argv = argv[:1] + argv[3:]
    d = json.load(open(argv[1]))
    if ratio is not None:
        striker(d, ratio)
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
