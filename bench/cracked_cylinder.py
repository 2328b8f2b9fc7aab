#!/usr/bin/python3
"""The capped cylinder of paper 003 §6.4 with its growing crack, as an SVG.

Usage: bench/cracked_cylinder.py RESULT.h5 OUT.svg
after `tlsph-run examples/cracked-cylinder.json -o DIR` (RESULT.h5 = DIR/result.h5).

Three frames of the wall around the crack, unrolled: hoop arc r_m theta
(theta the current azimuth, r_m = 0.226 m the reference mean radius, so an
opening crack is a gap) against the current z, every particle of the window
coloured by its damage (0 blue to 1 red), the halves of the split particles
(new ids: the grown crack's faces) ringed in black; and a plot of the crack length grown (the driver's facets, both
tips) and the crack's opening at mid-length (the current distance of the two
middle-shell particles facing each other across the pre-crack at z = 0.34 m,
less their reference distance) against time.  Every frame is read with its
own particle count (the changing-count layout, docs/output.md).  Prints the
numbers it plots.  Needs h5py and numpy (/usr/bin/python3)."""
import math
import sys

import h5py
import numpy as np

RM = 0.226                       # reference mean radius, m
THETA = 0.40                     # half-width of the window, rad (the opening reaches 113 mm at 600 us)
Z0, Z1 = 0.20, 0.48              # the window's z range, m
W, H = 250, 300                  # a frame's plot, px


def frame(f, k):
    g = f["particles/solid"]
    n = int(g["count/value"][k])
    x = g["position/value"][k, :n]
    X = g["reference_position/value"][k, :n]
    D = g["damage/value"][k, :n]
    split = g["id/value"][k, :n] >= int(g["count/value"][0])  # both halves get new ids
    return g["position/time"][k], x, X, D, split


def colour(d):
    d = min(max(float(d), 0.0), 1.0)
    r = int(60 + 195 * d)
    gr = int(110 + 80 * (1 - d) - 90 * d) if d < 1 else 20
    b = int(200 * (1 - d) + 20)
    return "rgb(%d,%d,%d)" % (r, max(gr, 20), b)


def panel(out, f, k, ox, oy, title):
    t, x, X, D, split = frame(f, k)
    th = np.arctan2(x[:, 1], x[:, 0])
    z = x[:, 2]
    keep = (np.abs(th) < THETA) & (z > Z0) & (z < Z1)
    sx = lambda s: ox + (s / (RM * THETA) + 1) * W / 2
    sz = lambda v: oy + H - (v - Z0) / (Z1 - Z0) * H
    out.append('<rect x="%g" y="%g" width="%d" height="%d" fill="#f4f4f4" stroke="#888"/>'
               % (ox, oy, W, H))
    order = np.argsort(D[keep])
    for i in np.flatnonzero(keep)[order]:
        out.append('<circle cx="%.1f" cy="%.1f" r="1.6" fill="%s"/>'
                   % (sx(RM * th[i]), sz(z[i]), colour(D[i])))
    for i in np.flatnonzero(keep & split):  # the split fibres' halves: the grown crack
        out.append('<circle cx="%.1f" cy="%.1f" r="3.2" fill="none" stroke="black"/>'
                   % (sx(RM * th[i]), sz(z[i])))
    out.append('<text x="%g" y="%g" font-size="12">%s, t = %.0f µs</text>'
               % (ox, oy - 6, title, t * 1e6))
    out.append('<text x="%g" y="%g" font-size="10">hoop arc r_m θ (±%.0f mm)</text>'
               % (ox + 40, oy + H + 14, RM * THETA * 1e3))
    out.append('<text x="%g" y="%g" font-size="10" transform="rotate(-90 %g %g)">z, %.2f-%.2f m</text>'
               % (ox - 5, oy + H / 2 + 30, ox - 5, oy + H / 2 + 30, Z0, Z1))
    return t, int(keep.sum()), float(D.max())


def opening(f):
    """Opening of the pre-crack's faces at mid-length, per frame."""
    g = f["particles/solid"]
    X = g["reference_position/value"][0, : int(g["count/value"][0])]
    r = np.hypot(X[:, 0], X[:, 1])
    th = np.arctan2(X[:, 1], X[:, 0])
    mid = (np.abs(X[:, 2] - 0.34) < 1e-3) & (np.abs(r - RM) < 4e-3)
    a = np.flatnonzero(mid & (th > 0) & (th < 0.05))
    b = np.flatnonzero(mid & (th < 0) & (th > -0.05))
    if len(a) != 1 or len(b) != 1:
        return None
    ida, idb = g["id/value"][0, a[0]], g["id/value"][0, b[0]]
    t, w = [], []
    for k in range(g["count/value"].shape[0]):
        n = int(g["count/value"][k])
        ids = g["id/value"][k, :n]
        ia, ib = np.flatnonzero(ids == ida), np.flatnonzero(ids == idb)
        if len(ia) != 1 or len(ib) != 1:
            continue
        x = g["position/value"][k, :n]
        Xk = g["reference_position/value"][k, :n]
        t.append(g["position/time"][k])
        w.append(np.linalg.norm(x[ia[0]] - x[ib[0]]) - np.linalg.norm(Xk[ia[0]] - Xk[ib[0]]))
    return np.array(t), np.array(w)


def plot(out, f, ox, oy):
    obs = f["observables"]
    t = obs["crack_length/time"][:] * 1e6
    L = obs["crack_length/value"][:] * 1e3
    op = opening(f)
    tmax = max(t.max(), 1.0)
    lmax = max(L.max(), 1.0)
    wmax = max(op[1].max() * 1e3, 1.0) if op else 1.0
    sx = lambda v: ox + v / tmax * W
    out.append('<rect x="%g" y="%g" width="%d" height="%d" fill="none" stroke="#888"/>'
               % (ox, oy, W, H))
    pts = " ".join("%.1f,%.1f" % (sx(a), oy + H - b / lmax * H) for a, b in zip(t, L))
    out.append('<polyline points="%s" fill="none" stroke="#c00" stroke-width="1.5"/>' % pts)
    if op:
        pts = " ".join("%.1f,%.1f" % (sx(a * 1e6), oy + H - b * 1e3 / wmax * H)
                       for a, b in zip(*op))
        out.append('<polyline points="%s" fill="none" stroke="#06c" stroke-width="1.5"/>' % pts)
    out.append('<text x="%g" y="%g" font-size="11">crack grown (red, 0-%.0f mm)</text>'
               % (ox, oy - 20, lmax))
    out.append('<text x="%g" y="%g" font-size="11">opening at mid-length (blue, 0-%.0f mm)</text>'
               % (ox, oy - 6, wmax))
    out.append('<text x="%g" y="%g" font-size="10">t, 0-%.0f µs</text>'
               % (ox + W / 2 - 30, oy + H + 14, tmax))
    return t, L, op


def main():
    f = h5py.File(sys.argv[1], "r")
    nf = f["particles/solid/count/value"].shape[0]
    ks = [nf // 2, (3 * nf) // 4, nf - 1]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif">'
           % (4 * (W + 40) + 60, H + 80)]
    out.append('<rect width="100%" height="100%" fill="white"/>')
    for j, k in enumerate(ks):
        t, n, dmax = panel(out, f, k, 30 + j * (W + 40), 40, "frame %d" % k)
        print("frame %d: t = %.1f us, %d particles in the window, max damage %.3f" % (k, t * 1e6, n, dmax))
    t, L, op = plot(out, f, 30 + 3 * (W + 40) + 20, 40)
    out.append('<text x="30" y="%d" font-size="11">particles coloured by damage, 0 (blue) to 1 (red); '
               'ringed: the halves of split particles (the grown crack\'s faces); the pre-crack is '
               'the gap at mid-height</text>' % (H + 68))
    out.append("</svg>")
    with open(sys.argv[2], "w") as o:
        o.write("\n".join(out) + "\n")
    print("crack grown at the end: %.1f mm" % L[-1])
    if op:
        for a, b in zip(*op):
            print("t = %6.1f us  opening %.3f mm" % (a * 1e6, b * 1e3))
    e = f["observables"]
    bal = e["energy_balance/value"][:]
    W_ext = e["external_work/value"][:]
    print("energy balance at the end %.4g J of %.4g J external work (%.2e); largest |balance| %.4g J"
          % (bal[-1], W_ext[-1], abs(bal[-1]) / max(abs(W_ext[-1]), 1e-300), np.abs(bal).max()))


if __name__ == "__main__":
    main()
