#!/usr/bin/env python3
"""The effects table: what each effect costs in memory and time, one at a time.

One scene, a copper bar stretched from both ends (3-D, cylinder r = 3 mm,
L = 15 mm, spacing 0.5 mm, ends at +-40 m/s, a fixed number of steps),
is run in its plainest form (elastic, no hourglass control, no viscosity) and
then with one effect switched on at a time, each against the variant it adds
to (its parent: thermal coupling is measured against Johnson-Cook strength
without it, and so on).  Each run reports the engine's own record: active
modules (/parameters/modules) and engine bytes per particle (/cost); the
time is the process's CPU time per particle-step (setup included: it is a few
steps' worth at this length).  The table shows the modules the effect
adds, its bytes per particle and time per particle-step, and both relative to
the parent: an effect a scene does not call for must add no module, no byte
and no time.

Runs are single-threaded and interleaved (every variant once per round); the
time is the smallest of the rounds, the least disturbed by other work on the
machine (CPU time, not wall time, for the same reason).

With --scenes DIR it also runs every scene of DIR (the examples, the hard
cases) for the same number of steps (time.max_steps lowered to it, one frame)
and lists each one's modules, bytes per particle and time per particle-step.

Usage: effects.py TLSPH_RUN [--rounds N] [--steps N] [--scenes DIR ...]
"""
import argparse
import copy
import json
import os
import subprocess
import sys
import tempfile

import h5py

COPPER = {"density": 8960, "youngs_modulus": 124e9, "poisson_ratio": 0.34}
JC = {"type": "johnson_cook", "yield_stress": 90e6, "hardening_coefficient": 292e6,
      "hardening_exponent": 0.31, "rate_coefficient": 0.025, "reference_strain_rate": 1.0}
JC_THERMAL = {"thermal_exponent": 1.09, "reference_temperature": 298, "melting_temperature": 1356}
THERMAL = {"specific_heat": 383, "initial_temperature": 298, "taylor_quinney": 0.9}
JC_DAMAGE = {"type": "johnson_cook", "d1": 0.54, "d2": 4.89, "d3": -3.03, "d4": 0.014,
             "reference_strain_rate": 1.0}
GTN = {"type": "gtn", "q1": 1.5, "q2": 1.0, "initial_void_fraction": 1e-4,
       "critical_void_fraction": 0.01, "failure_void_fraction": 0.2}


def base_scene(steps):
    # the bar is stretched from the start (a linear velocity field, the ends
    # held at +-40 m/s): every particle flows plastically within the run, in
    # tension, where the damage and void models act
    return {
        "name": "effects-base", "dimension": 3,
        "time": {"end": 1e-3, "cfl": 0.3, "max_steps": steps},
        "discretization": {"kernel": "wendland_c2", "support_factor": 2.01,
                           "hourglass": {"enabled": False}, "viscosity": {"enabled": False}},
        "output": {"frames": 1, "series_every": 50},
        "materials": {"copper": copy.deepcopy(COPPER)},
        "bodies": [{"name": "rod", "material": "copper", "spacing": 0.0005,
                    "geometry": {"cylinder": {"base": [0, 0, 0], "axis": [0, 0, 1],
                                              "radius": 0.003, "length": 0.015}},
                    "initial_velocity": [0, 0, "80 * (z / 0.015 - 0.5)"]}],
        "boundary_conditions": [
            {"type": "velocity", "name": "bottom",
             "select": {"box": {"min": [-1, -1, -1], "max": [1, 1, 0.0005]}}, "velocity": [0, 0, -40]},
            {"type": "velocity", "name": "top",
             "select": {"box": {"min": [-1, -1, 0.0145], "max": [1, 1, 1]}}, "velocity": [0, 0, 40]}],
    }


def mat(s):
    return s["materials"]["copper"]


def disc(s):
    return s["discretization"]


# name: (parent, what it switches on, edit of the parent's scene)
def _hourglass(s):
    disc(s)["hourglass"] = {"enabled": True, "coefficient": 1.0, "stiffness": "elastic"}


def _hourglass_tangent(s):
    disc(s)["hourglass"] = {"enabled": True, "coefficient": 1.0, "stiffness": "tangent"}


def _viscosity(s):
    disc(s)["viscosity"] = {"enabled": True, "linear": 1.0, "quadratic": 0.0}


def _mie(s):
    mat(s)["eos"] = {"type": "mie_gruneisen", "c0": 3940, "s": 1.49, "gamma0": 2.02}


def _linear_hardening(s):
    mat(s)["strength"] = {"type": "linear_hardening", "yield_stress": 90e6,
                          "hardening_modulus": 300e6}


def _jc(s):
    mat(s)["strength"] = copy.deepcopy(JC)


def _thermal(s):
    mat(s)["thermal"] = copy.deepcopy(THERMAL)
    mat(s)["strength"].update(JC_THERMAL)


def _jc_damage(s):
    mat(s)["damage"] = copy.deepcopy(JC_DAMAGE)


def _contact_off(s):
    s["contact"] = {"enabled": False}


def _pseudo_spring(s):
    disc(s)["damage"] = {"treatment": "pseudo_spring"}


def _links(s):
    mat(s).pop("damage")  # the links carry the damage
    disc(s)["damage"] = {"treatment": "virtual_links",
                         "links": {"type": "plastic_strain", "threshold": 0.5}}


def _gtn(s):
    mat(s)["damage"] = copy.deepcopy(GTN)


def _gtn_aravas(s):
    mat(s)["damage"] = {"type": "gtn_aravas"}


def _output(s):
    s["output"] = {"frames": 10, "series_every": 5,
                   "sections": [{"name": "middle", "point": [0, 0, 0.0075], "normal": [0, 0, 1],
                                 "thickness": 0.001}]}


VARIANTS = [
    ("elastic", None, "the plainest scene: elastic, linear EOS, two velocity conditions", None),
    ("+hourglass", "elastic", "hourglass control (elastic spring)", _hourglass),
    ("+viscosity", "elastic", "artificial viscosity", _viscosity),
    ("+mie_gruneisen", "elastic", "Mie-Grueneisen EOS", _mie),
    ("+output", "elastic", "10 frames, series every 5 steps, a section", _output),
    ("+linear_hardening", "elastic", "J2 plasticity, linear hardening", _linear_hardening),
    ("+johnson_cook", "elastic", "J2 plasticity, Johnson-Cook strength", _jc),
    ("jc +hourglass", "+johnson_cook", "hourglass control (elastic spring)", _hourglass),
    ("jc +hourglass tangent", "jc +hourglass", "the tangent spring instead", _hourglass_tangent),
    ("jc +thermal", "+johnson_cook", "adiabatic heating, thermal softening", _thermal),
    ("jc +damage", "+johnson_cook", "JC damage, damage-aware (contact on: fragments)", _jc_damage),
    ("jc +damage, no contact", "jc +damage", "contact switched off", _contact_off),
    ("jc +damage, pseudo-spring", "jc +damage", "pseudo-spring treatment instead", _pseudo_spring),
    ("jc +damage, virtual links", "jc +damage", "virtual links (plastic-strain criterion) instead of JC damage", _links),
    ("jc +gtn", "+johnson_cook", "GTN (paper 000)", _gtn),
    ("jc +gtn_aravas", "+johnson_cook", "GTN on the implicit porous return (paper 003)", _gtn_aravas),
]


def build_scenes(steps):
    scenes = {}
    for name, parent, _, edit in VARIANTS:
        s = copy.deepcopy(scenes[parent]) if parent else base_scene(steps)
        if edit:
            edit(s)
        s["name"] = "effects-" + name.replace(" ", "_").replace("+", "").replace(",", "")
        scenes[name] = s
    return scenes


def run_one(engine, scene, work):
    """Runs one scene on one thread; the cost is the process's CPU time (user +
    system, from wait4) per particle-step: on a shared machine the wall clock
    also counts the time other work held the core, the CPU time does not."""
    path = os.path.join(work, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    out = os.path.join(work, "r")
    subprocess.run(["rm", "-rf", out], check=True)
    with open(os.path.join(work, "stderr"), "w+") as err:
        proc = subprocess.Popen([engine, path, "-o", out, "--threads", "1", "--quiet"],
                                stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode not in (0, 3):  # 3: unstable, a hard case may end so by design
            err.seek(0)
            raise SystemExit("%s: exit %d\n%s" % (scene["name"], proc.returncode, err.read()))
    with h5py.File(os.path.join(out, "result.h5"), "r") as h:
        c = h["cost"].attrs
        modules = json.loads(h["parameters/modules"][()].decode())
        psteps = int(c["particles"]) * int(c["steps"])
        return {"modules": modules, "bytes": float(c["bytes_per_particle"]),
                "us": 1e6 * (usage.ru_utime + usage.ru_stime) / psteps,
                "particles": int(c["particles"]), "steps": int(c["steps"]),
                "outcome": "successful" if proc.returncode == 0 else "unstable"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("engine")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--scenes", action="append", default=[])
    a = ap.parse_args()
    scenes = build_scenes(a.steps)
    best = {}
    with tempfile.TemporaryDirectory() as work:
        for r in range(a.rounds):
            for name, *_ in VARIANTS:
                res = run_one(a.engine, scenes[name], work)
                if name not in best or res["us"] < best[name]["us"]:
                    best[name] = res
            print("round %d of %d done" % (r + 1, a.rounds), file=sys.stderr)
    print("load average at the end: %.1f %.1f %.1f" % os.getloadavg())
    print()
    print("| variant | adds to | what | modules added | B/particle | vs parent | CPU us/particle-step | vs parent |")
    print("|---|---|---|---|---:|---:|---:|---:|")
    for name, parent, what, _ in VARIANTS:
        b = best[name]
        if b["outcome"] != "successful":
            raise SystemExit("variant %s ended %s: its cost is not comparable" % (name, b["outcome"]))
        us = b["us"]
        if parent:
            pb = best[parent]
            added = sorted(set(b["modules"]) - set(pb["modules"]))
            removed = sorted(set(pb["modules"]) - set(b["modules"]))
            mods = ", ".join(["+" + m for m in added] + ["-" + m for m in removed]) or "none"
            db = "%+.0f" % (b["bytes"] - pb["bytes"])
            dt = "%+.0f %%" % (100 * (us / pb["us"] - 1))
        else:
            mods = ", ".join(b["modules"])
            db = dt = ""
        print("| %s | %s | %s | %s | %.0f | %s | %.3f | %s |" % (
            name, parent or "", what, mods, b["bytes"], db, us, dt))
    print()
    print("particles %d, steps %d per run" % (best["elastic"]["particles"], best["elastic"]["steps"]))
    if a.scenes:
        scenes_table(a)


def shortened(path, steps):
    with open(path) as f:
        s = json.load(f)
    t = s.setdefault("time", {})
    t["max_steps"] = min(t.get("max_steps") or steps, steps)
    s.setdefault("output", {})["frames"] = 1
    return s


def scenes_table(a):
    files = sorted(os.path.join(d, n) for d in a.scenes for n in os.listdir(d) if n.endswith(".json"))
    best = {}
    with tempfile.TemporaryDirectory() as work:
        for _ in range(a.rounds):
            for path in files:
                res = run_one(a.engine, shortened(path, a.steps), work)
                if path not in best or res["us"] < best[path]["us"]:
                    best[path] = res
    print()
    print("load average at the end: %.1f %.1f %.1f" % os.getloadavg())
    print()
    print("| scene | particles | steps | outcome | modules | B/particle | CPU us/particle-step |")
    print("|---|---:|---:|---|---|---:|---:|")
    top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    for path in files:
        b = best[path]
        print("| %s | %d | %d | %s | %s | %.0f | %.3f |" % (
            os.path.relpath(path, top), b["particles"], b["steps"], b["outcome"], ", ".join(b["modules"]),
            b["bytes"], b["us"]))


if __name__ == "__main__":
    main()
