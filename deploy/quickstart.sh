#!/usr/bin/env bash
# The main job: install dependencies, build, run an example scene through the
# engine and report where the result is, with a short summary read back from
# the HDF5 file.  (The daemon issue will route this through tlsphd.)
#
# usage: bash deploy/quickstart.sh [SCENE.json] [OUTPUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-examples/elastic-strip.json}
out=${2:-results/$(basename "$scene" .json)}
bash deploy/install-deps.sh
bash deploy/build.sh
mkdir -p "$(dirname "$out")"
rm -rf "$out"
./tlsph-run "$scene" -o "$out"
/usr/bin/python3 - "$out/result.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
cost = f["/cost"]
get = lambda g, k: (g.attrs[k] if k in g.attrs else g[k][()])
print("summary of", sys.argv[1])
print("  modules:", get(f["/parameters"], "modules").decode() if isinstance(get(f["/parameters"], "modules"), bytes) else get(f["/parameters"], "modules"))
print("  frames: %d, particles: %d" % f["/particles/solid/position/value"].shape[:2])
for k in ("kinetic_energy", "internal_energy", "external_work", "energy_balance"):
    print("  final %-16s %.6g J" % (k, f["/observables/%s/value" % k][-1]))
if "groups" in f["/observables"]:
    for g, grp in f["/observables/groups"].items():
        r = grp["reaction_force/value"][-1]
        print("  group %-8s reaction force [%.4g, %.4g, %.4g] N" % (g, *r))
for k in ("particles", "steps", "wall_seconds", "particle_steps_per_second", "bytes_per_particle"):
    v = get(cost, k)
    print("  cost %-26s %s" % (k, v))
PY
echo "result: $(pwd)/$out/result.h5 and $(pwd)/$out/result.xmf (ParaView: File > Open, choose \"XDMF Reader\")"
