#!/usr/bin/env python3
"""Checks of a `tlsph plot` picture (stdlib only).

  plot_check.py svg FILE.svg labels|panels|legend [--spread LABEL]...
      labels: every frame has a y label that names a quantity and a unit
              ("energy [J]", not "[J]");
      panels: every curve lies inside a frame, and each curve whose <title>
              is LABEL spans at least a quarter of its frame's height (a small
              series is not flattened onto a large one's axis);
      legend: no legend box overlaps a frame or is crossed by a curve.
  plot_check.py png FILE.png FILE.svg [--colour #RRGGBB]...
      the PNG rendering has the SVG's size, is not blank (ink outside the
      white background, but not everywhere), each frame has curve ink inside,
      and each given curve colour spans at least a quarter of a frame's height
      (counting its pixels inside frames and outside legends).

Frames are <rect class="frame"> (else: fill="none" stroke="black"), legends
<rect class="legend"> (else: stroke="#999"), curves <polyline>."""
import re, struct, sys, zlib
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"


def fail(msg):
    print("plot_check: " + msg)
    sys.exit(1)


def boxes(root, cls, fallback):
    out = []
    for r in root.iter(NS + "rect"):
        if r.get("class") == cls or (r.get("class") is None and fallback(r)):
            out.append(tuple(float(r.get(k)) for k in ("x", "y", "width", "height")))
    return out


def read_svg(path):
    root = ET.parse(path).getroot()
    frames = boxes(root, "frame", lambda r: r.get("fill") == "none" and r.get("stroke") == "black")
    legends = boxes(root, "legend", lambda r: r.get("stroke") == "#999")
    curves = []
    for p in root.iter(NS + "polyline"):
        pts = [tuple(map(float, q.split(","))) for q in p.get("points").split()]
        t = p.find(NS + "title")
        curves.append((t.text if t is not None else "", pts))
    return root, frames, legends, curves


def inside(b, x, y, tol=1.0):
    return b[0] - tol <= x <= b[0] + b[2] + tol and b[1] - tol <= y <= b[1] + b[3] + tol


def overlap(a, b):
    return a[0] < b[0] + b[2] and b[0] < a[0] + a[2] and a[1] < b[1] + b[3] and b[1] < a[1] + a[3]


def frame_of(frames, pts):
    for f in frames:
        if all(inside(f, x, y) for x, y in pts):
            return f
    return None


def check_svg(path, what, spread):
    root, frames, legends, curves = read_svg(path)
    if not frames or not curves:
        fail("%s: %d frames, %d curves" % (path, len(frames), len(curves)))
    {"labels": check_labels, "panels": check_panels, "legend": check_legend}[what](root, frames, legends, curves,
                                                                                spread)
    print("svg %s ok: %d frames, %d legends, %d curves" % (what, len(frames), len(legends), len(curves)))


def check_labels(root, frames, legends, curves, spread):
    ylabels = [t for t in root.iter(NS + "text") if "rotate(-90)" in (t.get("transform") or "")]
    for t in ylabels:
        text = "".join(t.itertext())
        if not re.match(r"^[A-Za-z][^\[]*[A-Za-z] \[[^\]]+\]$", text):
            fail("y label %r does not name a quantity and its unit" % text)
    if len(ylabels) != len(frames):
        fail("%d y labels for %d frames" % (len(ylabels), len(frames)))


def check_panels(root, frames, legends, curves, spread):
    for label, pts in curves:
        f = frame_of(frames, pts)
        if f is None:
            fail("curve %s leaves every frame" % label)
        if label in spread:
            ys = [y for _, y in pts]
            if max(ys) - min(ys) < 0.25 * f[3]:
                fail("curve %s spans %.1f px of its frame's %.1f: flattened" % (label, max(ys) - min(ys), f[3]))
    missing = [s for s in spread if s not in [c[0] for c in curves]]
    if missing:
        fail("no curve titled %s" % missing)


def check_legend(root, frames, legends, curves, spread):
    for lg in legends:
        for f in frames:
            if overlap(lg, f):
                fail("legend %s overlaps frame %s" % (lg, f))
        for label, pts in curves:
            for (x0, y0), (x1, y1) in zip(pts, pts[1:] or pts):
                for k in range(11):
                    if inside(lg, x0 + (x1 - x0) * k / 10, y0 + (y1 - y0) * k / 10, 0):
                        fail("curve %s runs under legend %s" % (label, lg))


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB/RGBA PNG."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(path + ": not a PNG")
    pos, idat, hdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            hdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = hdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        fail("%s: unsupported PNG (depth %d, colour type %d, interlace %d)" % (path, depth, ctype, interlace))
    bpp = 3 if ctype == 2 else 4
    raw, stride, prev, rows, i = zlib.decompress(idat), w * bpp, bytearray(w * bpp), [], 0
    for _ in range(h):
        ft, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if ft == 1:
                line[x] = (line[x] + a) & 255
            elif ft == 2:
                line[x] = (line[x] + b) & 255
            elif ft == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x:x + 3]) if bpp == 3 or line[x + 3] else (255, 255, 255)
                     for x in range(0, stride, bpp)])
        prev = line
    return w, h, rows


def check_png(png, svg, colours):
    root, frames, legends, _ = read_svg(svg)
    w, h, rows = read_png(png)
    sw, sh = float(root.get("width")), float(root.get("height"))
    if (w, h) != (round(sw), round(sh)):
        fail("PNG is %dx%d, the SVG %gx%g" % (w, h, sw, sh))
    ink = sum(1 for r in rows for p in r if min(p) < 200)
    if not 0.005 * w * h < ink < 0.6 * w * h:
        fail("PNG has ink on %d of %d pixels: blank or filled" % (ink, w * h))
    for f in frames:
        x0, y0, x1, y1 = int(f[0]) + 2, int(f[1]) + 2, int(f[0] + f[2]) - 2, int(f[1] + f[3]) - 2
        curve_ink = sum(1 for y in range(y0, y1) for p in rows[y][x0:x1] if max(p) - min(p) > 60)
        if curve_ink < 50:
            fail("frame %s has no curve in the picture (%d coloured pixels)" % (f, curve_ink))
    for c in colours:
        want = tuple(int(c[k:k + 2], 16) for k in (1, 3, 5))
        # curve pixels: inside a frame, outside every legend (its line samples)
        ys = [y for f in frames for y in range(int(f[1]), int(f[1] + f[3]))
              for x in range(int(f[0]), int(f[0] + f[2]))
              if sum(abs(rows[y][x][k] - want[k]) for k in range(3)) < 40
              and not any(inside(lg, x, y, 1) for lg in legends)]
        if not ys or max(ys) - min(ys) < 0.25 * min(f[3] for f in frames):
            fail("curve colour %s spans %s rows: missing or flat" % (c, max(ys) - min(ys) if ys else 0))
    print("png ok: %dx%d, ink on %.1f%% of the picture" % (w, h, 100.0 * ink / (w * h)))


def main():
    args = sys.argv[1:]
    opts = [args[i + 1] for i in range(len(args) - 1) if args[i] in ("--spread", "--colour")]
    pos = [a for i, a in enumerate(args) if a not in ("--spread", "--colour") and
           (i == 0 or args[i - 1] not in ("--spread", "--colour"))]
    if pos[0] == "svg":
        check_svg(pos[1], pos[2], opts)
    elif pos[0] == "png":
        check_png(pos[1], pos[2], opts)
    else:
        fail("usage: plot_check.py svg FILE labels|panels|legend [--spread LABEL]... | png PNG SVG [--colour #RRGGBB]...")


if __name__ == "__main__":
    main()
