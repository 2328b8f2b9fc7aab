#!/usr/bin/env python3
"""Writes a Kalthoff-Winkler scene from examples/kalthoff-links.json at another
spacing and/or with another crack treatment (docs/virtual-links.md).

usage: kalthoff_scene.py EXAMPLE SPACING TREATMENT OUT.json
  TREATMENT: virtual_links (the example's Rankine links), damage_aware or
  pseudo_spring (the particle Rankine criterion, "damage": {"type": "rankine"},
  at the same threshold 0.0044; a damage block needs a plastic material, so the
  steel gets a yield stress of 100 GPa that it never reaches: it stays elastic).
The driven edge is the first column of particles (x < 0.51 spacing)."""
import json
import sys


def main(argv):
    example, spacing, treatment, out = argv[1], float(argv[2]), argv[3], argv[4]
    d = json.load(open(example))
    stretch = d["discretization"]["damage"]["links"]["stretch"]
    d["bodies"][0]["spacing"] = spacing
    for bc in d["boundary_conditions"]:
        if bc["type"] == "velocity":
            bc["select"]["box"]["max"][0] = 0.51 * spacing
    if treatment != "virtual_links":
        d["name"] = "kalthoff-" + treatment.replace("_", "-")
        d["discretization"]["damage"] = {"treatment": treatment}
        steel = d["materials"]["steel"]
        steel["strength"] = {"type": "linear_hardening", "yield_stress": 1e11,
                             "hardening_modulus": 0}
        steel["damage"] = {"type": "rankine", "stretch": stretch}
    json.dump(d, open(out, "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
