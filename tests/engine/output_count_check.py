"""Reads a result file whose particle count changes (written by
tests/engine/test_output_count.c) with h5py alone, as a user would, and
checks it against DIR/facts.json: usage  python3 output_count_check.py DIR

While the writer still holds the file (SWMR): output_count_check.py live DIR
COUNT0 COUNT1 ... checks that a SWMR reader sees those frames' counts, each
frame's ids unique and >= 0 and its masses > 0, the entries past the count
the fill value.

 - /particles/solid/count/value holds each frame's count;
 - every field is per frame, [F, Nmax(, C)], Nmax the largest count; the
   entries past a frame's count hold the fill value (0; -1 for id and body);
 - each frame's ids are unique; after a split the parent's id is absent and
   both halves' ids are present, and the halves' masses (the per-frame
   `mass` looked up by id) sum to the parent's to 1e-15 relative (split.h:
   m2 = m - m1, one rounding);
 - ids present in two frames have the same reference position X in both
   unless the particle was split (ids are stable);
 - the layout against docs/output.md's field table (tests/support/h5_check.py's
   check_fields and check_xmf, which know both layouts), and the file opens
   with swmr=True as a reader during a run would;
 - result.xmf: one grid per frame, its NumberOfElements and every HyperSlab's
   count equal to the frame's count, the HDF dimensions equal to the
   datasets';
 - where ParaView's pvbatch is installed: ParaView's "XDMF Reader" opens every
   frame with the frame's count of points and a finite mass range
   (output_count_paraview.py); else it says SKIP.
Exit 0 when every check passes."""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
import h5_check  # noqa: E402


def main(d):
    facts = json.load(open(os.path.join(d, "facts.json")))
    fields = h5_check.load_docs(os.path.join(HERE, "..", "..", "docs", "output.md"))[0]
    try:
        with h5py.File(os.path.join(d, "result.h5"), "r", libver="latest", swmr=True) as f:
            F, N, _ = h5_check.check_fields(f, fields, live=True)
        with h5py.File(os.path.join(d, "result.h5"), "r") as f:
            F, N, _ = h5_check.check_fields(f, fields, live=False)
            h5_check.check_xmf(os.path.join(d, "result.xmf"), f, F, N,
                               f["particles/solid/position/time"][:])
    except h5_check.CheckFailed as e:
        fail("against docs/output.md: %s" % e)
    print("docs/output.md: %d checks of the layout passed" % len(h5_check.CHECKS))
    counts = facts["counts"]
    with h5py.File(os.path.join(d, "result.h5"), "r") as f:
        solid = f["particles/solid"]
        got = list(solid["count/value"][:])
        if got != counts:
            fail("counts %s, expected %s" % (got, counts))
        nmax = max(counts)
        nframes = len(counts)
        for name, obj in solid.items():
            if name == "box" or name == "count":
                continue
            v = obj["value"]
            if v.shape[0] != nframes or v.shape[1] != nmax:
                fail("%s/value has shape %s, expected [%d, %d, ...]" % (name, v.shape, nframes, nmax))
            fill = -1 if v.dtype.kind == "i" else 0
            for k, n in enumerate(counts):
                if not np.all(v[k, n:] == fill):
                    fail("%s frame %d: entries past the count %d are not the fill %d" % (name, k, n, fill))
        if not np.array_equal(solid["count/step"][:], solid["position/step"][:]):
            fail("count and position do not share their steps")
        ids = [solid["id/value"][k, :n] for k, n in enumerate(counts)]
        mass = [solid["mass/value"][k, :n] for k, n in enumerate(counts)]
        X = [solid["reference_position/value"][k, :n] for k, n in enumerate(counts)]
        for k, i in enumerate(ids):
            if len(set(i.tolist())) != len(i) or i.min() < 0:
                fail("frame %d: ids not unique or negative" % k)
        split_ids = set()
        for s in facts["splits"]:
            k = s["frame"]
            before, after = set(ids[k - 1].tolist()), dict((v, j) for j, v in enumerate(ids[k].tolist()))
            p, (a, b) = s["parent"], s["halves"]
            if p not in before or p in after:
                fail("split of %d at frame %d: parent id %s before, %s after" % (
                    p, k, p in before, p in after))
            if a not in after or b not in after or a in before or b in before:
                fail("split of %d at frame %d: halves %d, %d not new in the frame" % (p, k, a, b))
            m1, m2 = mass[k][after[a]], mass[k][after[b]]
            if abs(m1 + m2 - s["mass"]) > 1e-15 * s["mass"]:
                fail("split of %d: halves' mass %.17g + %.17g != %.17g" % (p, m1, m2, s["mass"]))
            split_ids |= {p, a, b}
        for k in range(1, nframes):
            prev = dict(zip(ids[k - 1].tolist(), range(len(ids[k - 1]))))
            for j, i in enumerate(ids[k].tolist()):
                if i in prev and i not in split_ids and not np.array_equal(X[k][j], X[k - 1][prev[i]]):
                    fail("frame %d: id %d moved in the reference configuration" % (k, i))
        shapes = {name: obj["value"].shape for name, obj in solid.items() if name not in ("box",)}
    print("h5py: %d frames, counts %s, %d splits checked" % (nframes, counts, len(facts["splits"])))

    root = ET.parse(os.path.join(d, "result.xmf")).getroot()
    grids = [g for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
    if len(grids) != nframes:
        fail("result.xmf lists %d frames, expected %d" % (len(grids), nframes))
    for k, g in enumerate(grids):
        n = counts[k]
        topo = g.find("Topology")
        if int(topo.get("NumberOfElements")) != n:
            fail("xmf frame %d: %s elements, expected %d" % (k, topo.get("NumberOfElements"), n))
        for slab in g.iter("DataItem"):
            if slab.get("ItemType") != "HyperSlab":
                continue
            sel, src = list(slab)
            dims = [int(x) for x in slab.get("Dimensions").split()]
            start_stride_count = [int(x) for x in sel.text.split()]
            r = len(start_stride_count) // 3
            start, count = start_stride_count[:r], start_stride_count[2 * r:]
            name = src.text.split(":/particles/solid/")[1].split("/")[0]
            sdims = [int(x) for x in src.get("Dimensions").split()]
            if dims[0] != n or start[0] != k or count[:2] != [1, n] or tuple(sdims) != shapes[name]:
                fail("xmf frame %d, %s: slab %s %s of %s" % (k, name, dims, start_stride_count, sdims))
    print("xmf: %d grids, each with its frame's count" % len(grids))

    pv = shutil.which("pvbatch")
    if not pv:
        print("SKIP: pvbatch (Debian: paraview) not installed: no ParaView check")
        return 0
    cmd = [pv, os.path.join(HERE, "output_count_paraview.py"), os.path.join(d, "result.xmf")]
    cmd += [str(c) for c in counts]
    xvfb = shutil.which("xvfb-run")
    if xvfb:
        cmd = [xvfb, "-a"] + cmd
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        fail("ParaView could not read every frame")
    return 0


def live(d, counts):
    with h5py.File(os.path.join(d, "result.h5"), "r", libver="latest", swmr=True) as f:
        solid = f["particles/solid"]
        step, count = solid["position/step"], solid["count/value"]
        ids, mass = solid["id/value"], solid["mass/value"]
        for ds in (step, count, ids, mass):
            ds.refresh()
        F = step.shape[0]
        got = [int(c) for c in count[:F]]
        if got != counts:
            fail("live: counts %s, expected %s" % (got, counts))
        for k, n in enumerate(counts):
            i, m = ids[k], mass[k]
            if len(set(i[:n].tolist())) != n or i[:n].min() < 0 or not np.all(i[n:] == -1):
                fail("live: frame %d ids" % k)
            if not np.all(m[:n] > 0) or not np.all(m[n:] == 0):
                fail("live: frame %d masses" % k)
    print("live (SWMR, the writer still writing): %d frames, counts %s" % (F, counts))
    return 0


if __name__ == "__main__":
    if sys.argv[1] == "live":
        sys.exit(live(sys.argv[2], [int(c) for c in sys.argv[3:]]))
    sys.exit(main(sys.argv[1]))
