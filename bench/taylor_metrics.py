#!/usr/bin/python3
"""Measures a Taylor-bar result: final length, foot diameter, energy split, cost.

usage: taylor_metrics.py RESULT_DIR [--json]

Assumes the rod axis is z and the anvil is the plane z = 0 (as in
examples/taylor-bar*.json).  Definitions, from the particles of the last frame
(h = the body's lattice spacing): a particle stands for the cube (square) of
side h around its centre, so the bar's extents are the centres' extents plus
h/2 on each side, and they are measured from the bar's own lowest point, not
from the anvil (a bar that rebounds lifts off: measured from the anvil its
length would include the gap and its foot would be empty):
  bottom        z_b = max(z_min - h/2, 0)   (the bar's lowest point, reported as
                    lift_off_mm.  The wall stops particle centres on its plane,
                    so a bar resting on the anvil has z_min = 0 and its lowest
                    cells reach h/2 into the anvil; nothing is below the
                    anvil, so z_b is 0 then, and z_min - h/2 once it lifts off)
  final length  L = z_max + h/2 - z_b   (L(t=0) = L0 exactly)
  foot diameter D = 2 (max r + h/2) over the lowest layer: the particles within
                    h/2 of the lowest centre (the outer edge, not the centres)
  foot diameter, material (foot_diameter_surface_mm): where the bar's surface
                    material of the lowest layer went.  Over the particles of the
                    lowest reference layer (reference z within h/2 of the lowest)
                    whose reference radius r0 lies within 2h of the bar's radius R
                    (the scene's cylinder), the final radius is fitted as
                    a + b r0 (least squares) and D = 2 (a + b R).  The extent
                    measure above starts wrong by the placement's own outline:
                    at t = 0 a lattice's outermost centres sit near R (their cells
                    reach past it: 2 (max r + h/2) = 6.96 mm for the 6.4 mm bar at
                    h = 0.6 mm) while a conforming cylinder's sit half a shell
                    inside (6.36 mm); the material measure is 2R at t = 0 for both,
                    so it compares placements (NaN without a cylinder or without
                    reference positions).
The former centre-based values are kept as length_anvil_mm (z_max + h/2, from
the anvil) and foot_diameter_centres_mm (2 max r of the centres within h/2 of
the anvil, 4-5 % under the outer edge at the examples' spacings; NaN once the
bar has lifted off): the tables measured before 2026-11-26 use those.
Energies are fractions of the initial kinetic energy.
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "support"))
from tlsph_result import Result  # noqa: E402


def extents(x, h):
    """Length, foot diameter and lift-off (mm) of a bar with particle centres x
    [N, 3] (m, axis z, anvil z = 0) and spacing h (m), as defined above; also
    used for other codes' bars (bench/peer_lammps.py)."""
    r = np.hypot(x[:, 0], x[:, 1])
    z = x[:, 2]
    bottom = max(z.min() - 0.5 * h, 0.0)
    lowest = z < z.min() + 0.5 * h
    return {
        "length_mm": (z.max() + 0.5 * h - bottom) * 1e3,
        "foot_diameter_mm": 2e3 * (r[lowest].max() + 0.5 * h),
        "lift_off_mm": bottom * 1e3,
    }


def foot_surface(x, x_ref, h, radius):
    """Foot diameter (mm) from where the lowest layer's surface material went,
    as defined above: final radius fitted linearly in the reference radius over
    the outer 2h of the lowest reference layer, evaluated at the radius R (m)."""
    r = np.hypot(x[:, 0], x[:, 1])
    r0 = np.hypot(x_ref[:, 0], x_ref[:, 1])
    z0 = x_ref[:, 2]
    outer = (z0 < z0.min() + 0.5 * h) & (r0 > radius - 2.0 * h)
    if outer.sum() < 2 or np.ptp(r0[outer]) <= 0.0:
        return float("nan")
    a = np.vstack([np.ones(outer.sum()), r0[outer]]).T
    (c0, c1), *_ = np.linalg.lstsq(a, r[outer], rcond=None)
    return 2e3 * (c0 + c1 * radius)


def cylinder_radius(scene):
    """The first body's cylinder radius (m), or None."""
    try:
        return float(scene["bodies"][0]["geometry"]["cylinder"]["radius"])
    except (KeyError, IndexError, TypeError, ValueError):
        return None


def metrics(path):
    with Result(path) as f:
        h = f.spacing()
        x = f.field("position")
        t_end = float(f.frame_times()[-1])
        last = f.last
        cost = f.cost
        ke0 = float(f.series("kinetic_energy")[1][0])
        r = np.hypot(x[:, 0], x[:, 1])
        z = x[:, 2]
        foot_anvil = z < 0.5 * h
        radius = cylinder_radius(f.scene)
        foot_surf = (foot_surface(x, f.field("reference_position"), h, radius)
                     if radius is not None and f.has_field("reference_position")
                     else float("nan"))
        out = {
            "spacing_mm": h * 1e3,
            "particles": int(cost["particles"]),
            "steps": int(cost["steps"]),
            "wall_seconds": float(cost["wall_seconds"]),
            "particle_steps_per_second": float(cost["particle_steps_per_second"]),
            "bytes_per_particle": float(cost["bytes_per_particle"]),
            "t_end_us": t_end * 1e6,
            **extents(x, h),
            "foot_diameter_surface_mm": foot_surf,
            "length_anvil_mm": (z.max() + 0.5 * h) * 1e3,
            "foot_diameter_centres_mm": 2e3 * r[foot_anvil].max() if foot_anvil.any() else float("nan"),
            "max_plastic_strain": float(f.field("plastic_strain").max())
            if f.has_field("plastic_strain") else 0.0,
            "max_temperature_K": last("max_temperature"),
            "kinetic_left": last("kinetic_energy") / ke0,
            "plastic_work": last("plastic_work") / ke0,
            "internal": last("internal_energy") / ke0,
            "hourglass": last("hourglass_energy") / ke0,
            "viscous": last("viscous_energy") / ke0,
            "wall_loss": -last("external_work") / ke0,
            "balance": last("energy_balance") / ke0,
            "min_det_F": float(f.field("det_F").min()),
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
