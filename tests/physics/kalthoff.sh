#!/usr/bin/env bash
# Kalthoff-Winkler with virtual links (paper 001 §5.3; docs/virtual-links.md):
# examples/kalthoff-links.json at 1 mm (9900 particles, ~1100 steps at the default cfl 0.6, a few s),
# crack angle by bench/kalthoff_angle.py (its docstring states the definition).
# Reference: the experiment's crack runs at 70° to the notch axis, the paper's at
# 77°.  Checked:
#  - the run ends successful, with the energy balance within 1e-3 of the external
#    work (measured 5.2e-5; 1.7e-5 at cfl 0.3);
#  - the crack starts at the notch tip: in the first frame with any broken link,
#    every particle with a broken link lies within 3 mm (3 spacings) of the tip;
#  - the crack leaving the tip runs at 70° ± 10° (measured 70.8°; 70.4° at cfl 0.3): the band holds
#    the experiment and the paper's 77° and the scatter of the published
#    simulations (the paper's Fig. 15); a crack that follows a lattice direction of
#    the immediate neighbours (45° or 90°) or the particle treatments' path
#    (58°, docs/virtual-links.md) fails it;
#  - and reaches at least 60 mm from the tip (measured 80 mm: the top edge).
. "$(dirname "$0")/../support/script_env.sh"
fail() { echo "FAIL: $*"; exit 1; }
"$PY" -c 'import h5py, numpy' || { echo "SKIP: $PY cannot import h5py"; exit 77; }
"$PY" "$top_srcdir/bench/kalthoff_scene.py" "$top_srcdir/examples/kalthoff-links.json" 0.001 \
  virtual_links "$tmp/k.json" || fail "scene"
"$top_builddir/tlsph-run" "$tmp/k.json" -o "$tmp/k" --threads 1 >"$tmp/k.log" 2>&1 ||
  { cat "$tmp/k.log"; fail "run did not end successful"; }
grep successful "$tmp/k.log"
"$PY" - "$tmp/k" "$top_srcdir/bench" <<'PYEOF' || fail "checks"
import sys
import numpy as np
import h5py
sys.path.insert(0, sys.argv[2])
import kalthoff_angle
tip = np.array([0.05, 0.025])
m = kalthoff_angle.measure(sys.argv[1], tip, 0.2)
print("angle %.1f deg (70 +- 10), length %.1f mm (>= 60), balance %.1e (<= 1e-3)"
      % (m["angle"], m["length"] * 1e3, m["balance"]))
p = h5py.File(sys.argv[1] + "/result.h5", "r")["particles/solid"]
X = p["reference_position"][:, :2]
D = p["link_damage/value"][:]
first = next(k for k in range(len(D)) if (D[k] > 0).any())
r = np.hypot(*(X[D[first] > 0] - tip).T)
print("first frame with broken links: %d, %d particles, farthest %.2f mm from the tip (<= 3)"
      % (first, len(r), r.max() * 1e3))
ok = (60.0 <= m["angle"] <= 80.0 and m["length"] >= 0.060 and m["balance"] <= 1e-3
      and r.max() <= 0.003 + 1e-9)
sys.exit(0 if ok else 1)
PYEOF
echo "ok: kalthoff"
