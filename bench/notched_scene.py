#!/usr/bin/env python3
"""Writes one notched-beam case of paper 001 §5.2 (Tables 2-3) from
examples/notched-beam-links.json (docs/virtual-links.md).

usage: notched_scene.py EXAMPLE NOTCH_TYPE WHERE VELOCITY TREATMENT OUT.json
  NOTCH_TYPE I (W_N 0.8 mm, D_N 2.12 mm), II (1.5, 2.12) or III (0.8, 1.59);
  WHERE mid (one notch at mid-span in the lower face, opposite the impact) or
  supports (one notch at each clamp in the upper face, inside the span next
  to the clamp's edge); VELOCITY the projectile's (m/s);
  TREATMENT virtual_links (the example's link criterion: plastic strain 0.17),
  damage_aware or pseudo_spring (the particle criterion that fits it: the
  accumulated Johnson-Cook damage with D1 = 0.17, D2 = 0, D_c = 1, i.e. the
  particle fails when its equivalent plastic strain reaches 0.17).
The notch is centred on the lattice column nearest its centre and removes the
cells whose centres lie in it: at the example's
spacing H/12 = 0.529 mm, widths 0.8 and 1.5 mm are 1 and 3 columns (0.53 and
1.59 mm), depths 2.12 and 1.59 mm are 4 and 3 rows (2.12 and 1.59 mm)."""
import json
import sys

NOTCH = {"I": (0.0008, 0.00212), "II": (0.0015, 0.00212), "III": (0.0008, 0.00159)}
H, L = 0.00635, 0.07112


def main(argv):
    example, kind, where, v, treatment, out = argv[1:7]
    d = json.load(open(example))
    w, depth = NOTCH[kind]
    beam = d["bodies"][0]
    outer = beam["geometry"]["difference"][0]
    h, x0 = beam["spacing"], beam["origin"][0]

    def column(x):  # the lattice column nearest x: the notch is centred on it
        return x0 + (round((x - x0) / h - 0.5) + 0.5) * h

    if where == "mid":
        c = column(0.0)
        cuts = [{"box": {"min": [c - w / 2, -H - 1e-3, 0], "max": [c + w / 2, -H + depth, 0]}}]
    else:
        cuts = []
        for s in (-1, 1):
            c = column(s * (L - w / 2))
            cuts.append({"box": {"min": [c - w / 2, -depth, 0], "max": [c + w / 2, 1e-3, 0]}})
    beam["geometry"] = {"difference": [outer] + cuts}
    d["name"] = "notched-beam-%s-%s-%s-%s" % (kind, where, v, treatment.replace("_", "-"))
    d["rigid_bodies"][0]["motion"]["velocity"] = [0, -float(v), 0]
    if treatment != "virtual_links":
        d["discretization"]["damage"] = {"treatment": treatment}
        d["materials"]["aluminium"]["damage"] = {
            "type": "johnson_cook_accumulated", "d1": 0.17, "d2": 0, "d3": 0,
            "critical_damage": 1}
    json.dump(d, open(out, "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
