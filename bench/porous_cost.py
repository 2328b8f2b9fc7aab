#!/usr/bin/env python3
"""Cost of the porous update and of plasticity without it (bench/porous_cost.sh).

usage: porous_cost.py scene CASE SPACING   prints the scene JSON of one case
       porous_cost.py report OUTDIR         the Markdown table of OUTDIR/times.txt

Cases, all on the Weldox 460E notched bar R = 2 mm of bench/weldox_scene.py
(Mie-Grueneisen EOS, Johnson-Cook strength, no hourglass control):
  plastic       J2 plasticity, no damage
  jc000         + paper 000's Johnson-Cook initiation and evolution
  jc003         + paper 003's accumulated Johnson-Cook damage (D_c = 1)
  gtn           paper 000's GTN (q1 1.5, q2 1, f0 1e-4, f_c 0.01, f_F 0.2, k_w 5.5)
  gtn_aravas    the same surface (q3 = q1^2, no nucleation) on paper 003's update
  sm_gurson     the same with the shear term k_w = 5.5 (the same equations as gtn)
times.txt: one line per run, "ENGINE CASE REPEAT WALL_S CPU_S STEPS PARTICLES
MATERIAL_SHARE" (whole-process wall and user + system CPU time, measured by
the shell script).
"""
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weldox_scene  # noqa: E402

JC = {"type": "johnson_cook", "d1": 0.636, "d2": 1.936, "d3": -2.969}
SURFACE = {"q1": 1.5, "q2": 1.0, "initial_void_fraction": 1e-4,
           "critical_void_fraction": 0.01, "failure_void_fraction": 0.2}
POROUS = dict(SURFACE, q3=2.25, nucleation={"amplitude": 0.0},
              fracture_void_fraction=0.2)
DAMAGE = {
    "plastic": None,
    "jc000": JC,
    "jc003": dict(JC, type="johnson_cook_accumulated", critical_damage=1.0),
    "gtn": dict(SURFACE, type="gtn", shear_coefficient=5.5),
    "gtn_aravas": dict(POROUS, type="gtn_aravas"),
    "sm_gurson": dict(POROUS, type="sm_gurson", shear_coefficient=5.5),
}


def scene(case, h):
    s = weldox_scene.scene("460e", "r2", "gtn", "damage_aware", h)
    s["output"]["frames"] = 4
    s["time"]["end"] = 1.2e-4  # to about first failure: every case flows, few fail
    for m in s["materials"].values():
        m.pop("damage", None)
        if DAMAGE[case]:
            m["damage"] = DAMAGE[case]
    if not DAMAGE[case]:
        s["discretization"].pop("damage", None)
    s["name"] = "porous-cost-" + case.replace("_", "-")
    return s


def report(outdir):
    runs = {}
    for line in open(os.path.join(outdir, "times.txt")):
        engine, case, _, wall, cpu, steps, n, share = line.split()
        runs.setdefault((engine, case), []).append(
            (float(wall), float(cpu), int(steps), int(n), float(share)))
    base = {}
    print("| engine | case | particles | steps | runs | CPU, median (s) | CPU spread (s) | "
          "particle-steps per CPU s | CPU vs base engine | wall, median (s) | "
          "material phase share |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for (engine, case), rs in runs.items():
        cpus = [r[1] for r in rs]
        cpu = statistics.median(cpus)
        wall = statistics.median(r[0] for r in rs)
        steps, n = rs[0][2], rs[0][3]
        if engine == "base":
            base[case] = cpu
        rel = ("%+.1f %%" % (100 * (cpu / base[case] - 1))
               if engine != "base" and case in base else "—")
        share = statistics.median(r[4] for r in rs)
        print("| %s | %s | %d | %d | %d | %.2f | %.2f-%.2f | %.3g | %s | %.2f | %s |" % (
            engine, case, n, steps, len(rs), cpu, min(cpus), max(cpus), n * steps / cpu, rel,
            wall, "%.2f" % share if share == share else "—"))


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "scene":
        print(json.dumps(scene(sys.argv[2], float(sys.argv[3])), indent=1))
    elif len(sys.argv) == 3 and sys.argv[1] == "report":
        report(sys.argv[2])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
