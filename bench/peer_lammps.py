#!/usr/bin/python3
"""The copper Taylor bar as one input for tlsph and for LAMMPS MACHDYN
(pair_style smd/tlsph), and the same measures of both results
(bench/peer_lammps.sh drives it; docs/performance.md "Peer: LAMMPS MACHDYN").

usage:
  peer_lammps.py scene SPACING_M [VARIANT ...] > scene.json
      examples/taylor-bar.json at that spacing, to 80 us, 2 frames.  Variants
      (each changes one thing, for the copper-length study):
        no-heating   no thermal block (and so no thermal softening)
        no-rate      no Johnson-Cook rate term
        linear-eos   the linear EOS instead of Mie-Grueneisen
        contact-wall the anvil as a rigid plane with penalty contact
                     (rigid_bodies) instead of the kinematic wall
        tangent      the tangent hourglass spring
        elastic-spring  the elastic (E) hourglass spring
        frames-N     N frames instead of 2 (for rates during the impact)
        strength-F   A and B times F (e.g. strength-0.85: the flow stress
                     scaled, to see how far the constants would have to move)
  peer_lammps.py lammps RESULT_DIR OUT_DIR [no-rate]
      writes OUT_DIR/data.rod (the particles of tlsph's result at t = 0:
      positions, volumes, masses) and OUT_DIR/in.taylor for LAMMPS with the
      same material, spacing and kernel support.
  peer_lammps.py rate-factor RESULT_DIR
      how much the Johnson-Cook rate term raised the flow stress over the
      impact: the plastic-power-weighted mean of 1 + C ln(epsdot_p/epsdot_0)
      over the flowing particles of every frame (run with frames-N), and the
      weighted median plastic strain rate, as JSON.
  peer_lammps.py measure-lammps DUMP SPACING_M
      length, foot diameter (bench/taylor_metrics.py definitions) and the
      peak plastic strain of LAMMPS's final dump, as JSON.

What is the same in both inputs: the particles (taken from tlsph's own
lattice), kernel support 2.01 spacings (LAMMPS: radius = 1.005 spacing, the
pair support is radius_i + radius_j), density, E, nu, Mie-Grueneisen
(c0, S, Gamma0), Johnson-Cook A, B, n, C with eps0 = 1/s, the rigid
frictionless anvil at z = 0, 80 us.  What cannot be the same (MACHDYN has no
choice; shared/notes/lammps-machdyn.md):
  - kernel: spiky (h - r)^3 in LAMMPS, Wendland C2 in tlsph;
  - Johnson-Cook heating: LAMMPS has no thermal term (tlsph heats with chi =
    0.9 and softens with m = 1.09; the `no-heating` variant matches LAMMPS);
    its rate term uses a moving average of the plastic strain rate;
  - stabilisation: LAMMPS's hourglass control hg = 10 (Ganzenmueller) with its
    artificial viscosity Q1 = 0.06 (the MACHDYN examples' values, it is not
    stable without some); tlsph: its hourglass spring, no viscosity;
  - anvil: tlsph's wall stops a particle's centre on the plane (kinematic,
    inelastic); LAMMPS has no such wall for smd atoms, so a harmonic penalty
    wall (fix wall/harmonic) acts on the particles' contact radius (spacing/2)
    with the stiffness of tlsph's penalty contact, pi/4 E* h.
"""
import json
import math
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "tests", "support"))
sys.path.insert(0, here)
from tlsph_result import Result  # noqa: E402
from taylor_metrics import extents  # noqa: E402

EXAMPLE = os.path.join(here, "..", "examples", "taylor-bar.json")


def scene(spacing, variants):
    s = json.load(open(EXAMPLE))
    s["bodies"][0]["spacing"] = spacing
    s["output"]["frames"] = 2
    s.setdefault("limits", {})["max_particles"] = 2000000
    mat = s["materials"]["ofhc_copper"]
    st = mat["strength"]
    for v in variants:
        if v == "no-heating":
            mat.pop("thermal")
            for k in ("thermal_exponent", "reference_temperature", "melting_temperature"):
                st.pop(k)
        elif v == "no-rate":
            st.pop("rate_coefficient")
            st.pop("reference_strain_rate")
        elif v == "linear-eos":
            mat.pop("eos")
        elif v == "contact-wall":
            s.pop("boundary_conditions")
            s["rigid_bodies"] = [{"name": "anvil", "shape": {
                "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}}]
        elif v == "tangent":
            s["discretization"]["hourglass"]["stiffness"] = "tangent"
        elif v == "elastic-spring":
            s["discretization"]["hourglass"]["stiffness"] = "elastic"
        elif v.startswith("frames-"):
            s["output"]["frames"] = int(v.split("-", 1)[1])
        elif v.startswith("strength-"):
            f = float(v.split("-", 1)[1])
            st["yield_stress"] *= f
            st["hardening_coefficient"] *= f
        else:
            raise SystemExit("unknown variant " + v)
    return s


def lammps(result_dir, out_dir, no_rate=False):
    with Result(result_dir) as r:
        r.require_one_count("peer_lammps.py")
        sc = r.scene
        h = r.spacing()
        X = r.field("reference_position")
        vol = r.field("volume")
        mass = r.field("mass")
        v = r.field("velocity", frame=0)
    mat = sc["materials"]["ofhc_copper"]
    st, eos = mat["strength"], mat["eos"]
    E, nu, rho = mat["youngs_modulus"], mat["poisson_ratio"], mat["density"]
    n = len(X)
    radius = 0.5 * sc["discretization"]["support_factor"] * h
    pad = 4 * h
    lo = [-12e-3, -12e-3, -pad]
    hi = [12e-3, 12e-3, X[:, 2].max() + pad]
    with open(os.path.join(out_dir, "data.rod"), "w") as f:
        f.write("tlsph copper Taylor bar, %d particles, spacing %g m\n\n" % (n, h))
        f.write("%d atoms\n1 atom types\n\n" % n)
        for a, b, ax in zip(lo, hi, "xyz"):
            f.write("%.9g %.9g %slo %shi\n" % (a, b, ax, ax))
        f.write("\nAtoms # smd\n\n")
        # id type molecule vfrac rmass radius contact_radius x0 x
        for i in range(n):
            p = "%.12g %.12g %.12g" % tuple(X[i])
            f.write("%d 1 1 %.12g %.12g %.12g %.12g %s %s\n"
                    % (i + 1, vol[i], mass[i], radius, 0.5 * h, p, p))
        f.write("\nVelocities\n\n")
        for i in range(n):
            f.write("%d %.12g %.12g %.12g\n" % (i + 1, *v[i]))
    # penalty anvil: the stiffness of tlsph's line-form contact, pi/4 E* h,
    # E* = E/(1-nu^2); fix wall/harmonic's energy is eps (r - rc)^2, so eps = k/2
    k = math.pi / 4 * E / (1 - nu * nu) * h
    C = 0.0 if no_rate else st.get("rate_coefficient", 0.0)
    t_end = sc["time"]["end"]
    inp = f"""# tlsph's copper Taylor bar for LAMMPS MACHDYN (written by bench/peer_lammps.py)
units           si
dimension       3
boundary        f f f
atom_style      smd
atom_modify     map array
comm_modify     vel yes
newton          off
neighbor        {0.2 * h:.9g} bin
neigh_modify    every 10 delay 0 check yes
read_data       data.rod
group           tlsph type 1
pair_style      smd/tlsph
pair_coeff      1 1 *COMMON {rho} {E} {nu} 0.06 0.0 10.0 {mat.get("thermal", {}).get("specific_heat", 383)} &
                *EOS_SHOCK {eos["c0"]} {eos["s"]} {eos.get("gamma0", 0.0)} &
                *JOHNSON_COOK {st["yield_stress"]} {st["hardening_coefficient"]} {st["hardening_exponent"]} {C} {st.get("reference_strain_rate", 1.0)} 298 1356 1.09 &
                *END
fix             anvil tlsph wall/harmonic zlo 0.0 {k / 2:.9g} 0.0 {0.5 * h:.9g} units box
fix             dtfix tlsph smd/adjust_dt 0.1
fix             integ tlsph smd/integrate_tlsph
compute         ep tlsph smd/plastic/strain
variable        t equal f_dtfix
fix             stop tlsph halt 10 v_t > {t_end} error continue message no
thermo          500
thermo_style    custom step dt f_dtfix ke
thermo_modify   norm no
run             10000000
# the final state (a dump written inside a run: its compute is current there)
unfix           stop
dump            final tlsph custom 1 final.dump id x y z c_ep
dump_modify     final sort id
run             0 post no
print           "PEER_END step $(step) time $(f_dtfix)"
"""
    open(os.path.join(out_dir, "in.taylor"), "w").write(inp)


def rate_factor(result_dir):
    with Result(result_dir) as r:
        st = r.scene["materials"]["ofhc_copper"]["strength"]
        C, e0 = st["rate_coefficient"], st.get("reference_strain_rate", 1.0)
        r.require_one_count("peer_lammps.py")
        vol = r.field("volume")
        rates, weights = [], []
        for k in range(len(r.frame_times("plastic_strain_rate"))):
            rate = r.field("plastic_strain_rate", frame=k)
            w = r.field("von_mises", frame=k) * rate * vol  # plastic power
            on = rate > e0
            rates.append(rate[on])
            weights.append(w[on])
    rate, w = np.concatenate(rates), np.concatenate(weights)
    f = 1.0 + C * np.log(rate / e0)
    o = np.argsort(rate)
    cw = np.cumsum(w[o]) / w.sum()
    return {"weighted_rate_factor": float((f * w).sum() / w.sum()),
            "weighted_median_rate": float(rate[o][np.searchsorted(cw, 0.5)]),
            "rate_p10": float(rate[o][np.searchsorted(cw, 0.1)]),
            "rate_p90": float(rate[o][np.searchsorted(cw, 0.9)]),
            "samples": int(len(rate))}


def measure_lammps(dump, h):
    rows = []
    with open(dump) as f:
        lines = f.read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    for l in lines[i + 1:]:
        if l.strip():
            rows.append([float(t) for t in l.split()])
    a = np.array(rows)
    x = a[:, [cols.index("x"), cols.index("y"), cols.index("z")]]
    out = extents(x, h)
    out["max_plastic_strain"] = float(a[:, cols.index("c_ep")].max())
    out["particles"] = len(a)
    return out


def main(argv):
    if len(argv) >= 3 and argv[1] == "scene":
        print(json.dumps(scene(float(argv[2]), argv[3:])))
    elif len(argv) >= 4 and argv[1] == "lammps":
        lammps(argv[2], argv[3], "no-rate" in argv[4:])
    elif len(argv) == 3 and argv[1] == "rate-factor":
        print(json.dumps(rate_factor(argv[2])))
    elif len(argv) == 4 and argv[1] == "measure-lammps":
        print(json.dumps(measure_lammps(argv[2], float(argv[3]))))
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
