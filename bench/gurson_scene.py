#!/usr/bin/env python3
"""Scene of one case of the Gurson-family comparison (paper 003 §6.1).

usage: gurson_scene.py SPECIMEN VARIANT [--spacing H]
  SPECIMEN  r2     the notched round bar R = 2 mm of bench/weldox_scene.py
                   (a mode-I, high-triaxiality specimen), pulled at both ends
            shear  a block 8 x 3 x 2 mm in simple shear: the bottom layer held,
                   the top layer moved along x (zero mean stress to first order)
  VARIANT   gurson | gtn | sm_gurson | m_gurson | gtn_strain | jc
            the paper's five: the four models with the critical void fraction
            f_p = 0.0135 as fracture criterion, and GTN with the critical
            plastic strain 0.35 (its fifth simulation); and its Johnson-Cook
            accumulated damage (eq. 62, Table 2, D_c = 0.1) on the same
            (J2) matrix

Material: paper 003 Table 1 (Normal Strength steel): E = 200 GPa, nu = 0.3,
rho = 7800 kg/m^3, sigma_M = 270 MPa + 833 MPa eps_M (its linear h_M), linear
EOS; every porous parameter is the row's default, i.e. Table 1's.  Prints the
scene JSON.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weldox_scene  # noqa: E402

VARIANTS = {
    "gurson": {"type": "gurson"},
    "gtn": {"type": "gtn_aravas"},
    "sm_gurson": {"type": "sm_gurson"},
    "m_gurson": {"type": "m_gurson"},
    "gtn_strain": {"type": "gtn_aravas", "fracture_criterion": "plastic_strain"},
    # paper 003 §5: Johnson-Cook accumulated damage (eq. 62) with Table 2's
    # constants and D_c = 0.1 (its Simulation III), on the same matrix
    "jc": {"type": "johnson_cook_accumulated", "d1": 0.0705, "d2": 1.732, "d3": -0.54,
           "d4": -0.015, "reference_strain_rate": 1.0, "critical_damage": 0.1},
}

MATERIAL = {"density": 7800, "youngs_modulus": 200e9, "poisson_ratio": 0.3,
            "strength": {"type": "linear_hardening", "yield_stress": 270e6,
                         "hardening_modulus": 833e6}}

DISCRETIZATION = {"kernel": "wendland_c2", "support_factor": 2.01,
                  "hourglass": {"enabled": False}, "viscosity": {"enabled": False},
                  "damage": {"treatment": "damage_aware", "failed_particles": "free"}}


def notched(h):
    """The Weldox bench's R = 2 mm bar, loading and measurements
    (bench/weldox_scene.py, its GTN run length), with this study's material."""
    s = weldox_scene.scene("460e", "r2", "gtn", "damage_aware", h)
    s["bodies"][0]["material"] = "steel"
    del s["materials"], s["name"], s["discretization"]
    return s


def shear(h):
    H = 0.003
    return {
        # to a shear displacement of 1.5 mm (gamma 0.5), where the models have
        # separated; beyond it the corners of the block are crushed (J 0.93,
        # 8-10 GPa: docs/damage.md, "The crushed corners")
        "time": {"end": 8.5e-5, "cfl": 0.3},
        "parameters": {"vmax": 20.0, "tau": 1e-5},
        "output": {"frames": 12, "series_every": 10},
        "bodies": [{"name": "block", "material": "steel", "spacing": h,
                    "geometry": {"box": {"min": [0, 0, 0], "max": [0.008, H, 0.002]}}}],
        "boundary_conditions": [
            {"type": "velocity", "name": "bottom",
             "select": {"box": {"min": [-1, -1, -1], "max": [1, h, 1]}},
             "velocity": [0, 0, 0]},
            {"type": "velocity", "name": "top",
             "select": {"box": {"min": [-1, H - h, -1], "max": [1, 1, 1]}},
             "velocity": ["vmax*(1-exp(-t/tau))", 0, 0]},
        ],
    }


def scene(specimen, variant, spacing):
    h = spacing or {"r2": 0.0005, "shear": 0.0004}[specimen]
    s = {"name": f"gurson-{specimen}-{variant.replace('_', '-')}", "dimension": 3,
         "discretization": DISCRETIZATION,
         "materials": {"steel": dict(MATERIAL, damage=VARIANTS[variant])}}
    s.update(notched(h) if specimen == "r2" else shear(h))
    return s


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("specimen", choices=["r2", "shear"])
    p.add_argument("variant", choices=sorted(VARIANTS))
    p.add_argument("--spacing", type=float, default=0.0)
    o = p.parse_args()
    print(json.dumps(scene(o.specimen, o.variant, o.spacing), indent=1))


if __name__ == "__main__":
    main()
