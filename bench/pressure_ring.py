#!/usr/bin/python3
"""Thick ring under internal pressure against Lame (docs/crack-growth.md).

The ring of tests/physics/test_pressure.c (plane strain steel, a = 5 mm,
b = 10 mm, conforming shells, 100 MPa inside ramped over T = 40 us and held to
2T, the pressure's area 2 pi a) at spacings a/5, a/10 and a/20: each particle's
radial displacement and hoop stress averaged over the frames after T (the
ringing the ramp leaves averages out), against Lame's
  u(r) = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r),
  sigma_tt(r) = p a^2 / (b^2 - a^2) (1 + b^2 / r^2).
Writes OUT.svg and prints one line per spacing (particles, steps, CPU
seconds, error of the inner shell's mean displacement).

usage: pressure_ring.py BUILD_DIR OUT.svg
Needs h5py and matplotlib (/usr/bin/python3)."""
import json
import math
import os
import resource
import subprocess
import sys
import tempfile

import h5py
import matplotlib
import numpy as np

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

E, NU, A, B, P0, T = 2.1e11, 0.3, 0.005, 0.01, 1e8, 4e-5


def scene(h):
    ramp = "%.17g*(step(t-%.17g) + (1-step(t-%.17g))*(1-cos(pi*t/%.17g))/2)" % (P0, T, T, T)
    return {
        "name": "pressure-ring", "dimension": 2, "time": {"end": 2 * T},
        "materials": {"steel": {"density": 7850, "youngs_modulus": E, "poisson_ratio": NU}},
        "bodies": [{"name": "ring", "material": "steel", "spacing": h, "placement": "conforming",
                    "geometry": {"difference": [
                        {"sphere": {"center": [0, 0, 0], "radius": B}},
                        {"sphere": {"center": [0, 0, 0], "radius": A}}]}}],
        "boundary_conditions": [{
            "type": "pressure", "name": "inside", "pressure": ramp, "area": 2 * math.pi * A,
            "select": {"expression": "x*x + y*y < %.17g" % ((A + h) ** 2)}}],
        "output": {"frames": 40, "series_every": 100}}


def lame_u(r):
    return (1 + NU) * P0 * A * A / (E * (B * B - A * A)) * ((1 - 2 * NU) * r + B * B / r)


def lame_hoop(r):
    return P0 * A * A / (B * B - A * A) * (1 + B * B / (r * r))


def run(build, h, tmp):
    path = os.path.join(tmp, "ring-%g.json" % h)
    with open(path, "w") as f:
        json.dump(scene(h), f)
    out = os.path.join(tmp, "ring-%g" % h)
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    subprocess.run([os.path.join(build, "tlsph-run"), path, "-o", out, "--quiet"], check=True,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before
    f = h5py.File(os.path.join(out, "result.h5"), "r")
    p = f["particles/solid"]
    if "count" in p:  # particle splitting (docs/output.md, "Changing particle counts")
        sys.exit("%s: the particle count changes during this run; pressure_ring.py reads one count per run"
                 % out)
    X = p["reference_position"][:, :2]
    r = np.hypot(X[:, 0], X[:, 1])
    c, s = X[:, 0] / r, X[:, 1] / r
    times = p["displacement/time"][:]
    late = times > T * (1 + 1e-9)
    u = p["displacement/value"][:][late][:, :, :2]
    ur = (u[:, :, 0] * c + u[:, :, 1] * s).mean(axis=0)
    sig = p["stress/value"][:][late]  # xx xy xz yy yz zz
    hoop = (sig[:, :, 0] * s * s - 2 * sig[:, :, 1] * s * c + sig[:, :, 3] * c * c).mean(axis=0)
    steps = int(f["observables/time_step/step"][-1])
    inner = r < r.min() + 1e-3 * h
    err = ur[inner].mean() / lame_u(r[inner].mean()) - 1
    print("h = a/%d: %d particles, %d steps, %.1f s CPU, inner shell u %+.2f %% off Lame"
          % (round(A / h), len(r), steps, cpu, 100 * err))
    # one point per shell (its particles agree by the shells' symmetry): the mean
    shell = np.round((r - A) / h - 0.5).astype(int)
    ids = np.unique(shell)
    mean = [np.array([q[shell == k].mean() for k in ids]) for q in (r, ur, hoop)]
    return len(r), mean[0], mean[1], mean[2]


def main(build, svg):
    plt.rcParams["svg.hashsalt"] = "tlsph"
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    rr = np.linspace(A, B, 200)
    ax1.plot(rr * 1e3, lame_u(rr) * 1e6, "k-", label="Lamé")
    ax2.plot(rr * 1e3, lame_hoop(rr) * 1e-6, "k-", label="Lamé")
    with tempfile.TemporaryDirectory() as tmp:
        for h, mark in ((A / 5, "o"), (A / 10, "s"), (A / 20, ".")):
            n, r, ur, hoop = run(build, h, tmp)
            lab = "h = a/%d (%d particles)" % (round(A / h), n)
            ax1.plot(r * 1e3, ur * 1e6, mark, ms=5, mfc="none", label=lab)
            ax2.plot(r * 1e3, hoop * 1e-6, mark, ms=5, mfc="none", label=lab)
    ax1.set_xlabel("r (mm)")
    ax1.set_ylabel("radial displacement (µm)")
    ax2.set_xlabel("r (mm)")
    ax2.set_ylabel("hoop stress (MPa)")
    for ax in (ax1, ax2):
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.suptitle("Ring a = 5 mm, b = 10 mm, 100 MPa inside, plane strain: "
                 "mean over 40-80 µs against Lamé")
    fig.tight_layout()
    fig.savefig(svg, metadata={"Date": None})


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
