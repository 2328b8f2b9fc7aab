#!/usr/bin/python3
"""The example examples/precracked-plate.json at its last frame: the plate drawn
in its deformed configuration (displacements magnified), coloured by sigma_yy,
the crack faces open left of the tip and the load carried by the ligament.

usage: bench/precracked_plate.py RESULT.h5 OUT.svg   (h5py and matplotlib,
/usr/bin/python3).  Run the example first:
  tlsph-run examples/precracked-plate.json -o /tmp/precracked"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MAGNIFY = 50.0


def main(path, out):
    with h5py.File(path, "r") as f:
        g = f["particles/solid"]
        if "count" in g:  # particle splitting (docs/output.md, "Changing particle counts")
            sys.exit("%s: the particle count changes during this run; precracked_plate.py reads one count per run"
                     % path)
        X = g["reference_position"][:]
        u = g["displacement/value"][-1]
        s = g["stress/value"][-1]
        t = g["displacement/time"][-1] if "time" in g["displacement"] else None
    x = X + MAGNIFY * u
    fig, ax = plt.subplots(figsize=(5.2, 4.4))
    # the tip's peak would wash out the rest: the scale ends at the 98th percentile
    top = max(sorted(abs(s[:, 3]))[int(0.98 * len(s))] / 1e6, 1e-9)
    sc = ax.scatter(1e3 * x[:, 0], 1e3 * x[:, 1], c=s[:, 3] / 1e6, s=9, cmap="coolwarm",
                    vmin=-top, vmax=top, linewidths=0, rasterized=True)
    ax.plot([-10.5, 0], [0, 0], color="k", lw=0.6, ls=":")
    ax.set_aspect("equal")
    ax.set_xlabel("x + %g u_x (mm)" % MAGNIFY)
    ax.set_ylabel("y + %g u_y (mm)" % MAGNIFY)
    title = "pre-cracked plate, sigma_yy (scale: 98th percentile)"
    if t is not None:
        title += " at %.0f us" % (1e6 * t)
    ax.set_title(title, fontsize=10)
    fig.colorbar(sc, ax=ax, label="sigma_yy (MPa)")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
