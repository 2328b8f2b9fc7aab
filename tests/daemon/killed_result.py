#!/usr/bin/python3
"""Checks the result of a run whose engine was killed (kill -9) before it closed
its file: usage  killed_result.py RESULT_H5 [RESULT_XMF] [--min-frames K]

The file must open as a plain HDF5 file (h5py without swmr=True, as ParaView
and h5dump open it): the superblock's "open for writing" flags cleared.  Its
complete frames and series rows are those counted by each `step` dataset (the
writer's commit marker, docs/output.md); every value, time and step of those
rows must be finite, and there must be at least K complete frames (default 1).
The XDMF sidecar, when given, must reference complete frames only: each
frame's hyperslab starts below the frame count, and the frame axis it declares
is no longer than the datasets'.  Prints one line per finding; exit 0 when all
hold, 1 otherwise.
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from tlsph_result import PARTICLES, OBSERVABLES, Result  # noqa: E402

FLAGS_OFFSET = 11  # superblock v2/v3: signature (8), version, offset size, length size, flags


def superblock_flags(path):
    with open(path, "rb") as fp:
        head = fp.read(12)
    if head[:8] != b"\x89HDF\r\n\x1a\n" or head[8] < 2:
        return None
    return head[FLAGS_OFFSET]


def complete_rows(group):
    """(rows, problems) of a step/time/value group: rows = len(step)."""
    problems = []
    rows = group["step"].shape[0]
    for name in ("step", "time", "value"):
        if name not in group:
            continue
        ds = group[name]
        if ds.shape[0] < rows:
            problems.append("%s/%s has %d rows, step %d" % (group.name, name, ds.shape[0], rows))
            continue
        try:
            data = ds[:rows]
        except OSError as e:
            problems.append("%s/%s: cannot read its %d complete rows: %s" % (group.name, name, rows, e))
            continue
        if data.dtype.kind == "f" and not np.all(np.isfinite(data)):
            problems.append("%s/%s: non-finite values in its %d complete rows"
                            % (group.name, name, rows))
    return rows, problems


def check_xmf(path, frames, frame_rows):
    problems = []
    root = ET.parse(path).getroot()
    grids = [g for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
    for k, grid in enumerate(grids):
        for slab in grid.iter("DataItem"):
            if slab.get("ItemType") != "HyperSlab":
                continue
            items = slab.findall("DataItem")
            start = int(items[0].text.split()[0])
            declared = int(items[1].get("Dimensions").split()[0])
            if start >= frames:
                problems.append("sidecar frame %d reads frame %d of %d complete" % (k, start, frames))
            if declared > frame_rows:
                problems.append("sidecar declares %d frames, the datasets hold %d"
                                % (declared, frame_rows))
    return len(grids), problems


def main(argv):
    min_frames = 1
    if "--min-frames" in argv:
        i = argv.index("--min-frames")
        min_frames = int(argv[i + 1])
        del argv[i:i + 2]
    h5 = argv[1]
    xmf = argv[2] if len(argv) > 2 else None
    problems = []
    flags = superblock_flags(h5)
    print("superblock status flags: %s" % flags)
    if flags:
        problems.append("superblock still marked open (flags %#x)" % flags)
    try:
        r = Result(h5)  # a plain open, no SWMR
    except OSError as e:
        print("FAIL: a plain h5py open fails: %s" % e)
        return 1
    with r:
        frames = None
        frame_rows = None
        for name in r.frame_fields():
            g = r.file[PARTICLES][name]
            rows, p = complete_rows(g)
            problems += p
            frames = rows if frames is None else min(frames, rows)
            n = g["value"].shape[0]
            frame_rows = n if frame_rows is None else min(frame_rows, n)
        nseries = 0

        def visit(name, obj):
            nonlocal nseries
            if hasattr(obj, "keys") and "step" in obj and "value" in obj:
                nseries += 1
                problems.extend(complete_rows(obj)[1])

        try:
            r.file[OBSERVABLES].visititems(visit)
        except (OSError, RuntimeError) as e:
            problems.append("cannot walk the series: %s" % e)
        print("plain open: %s complete frames (status attribute '%s'), %d series"
              % (frames, r.status, nseries))
        if frames is None or frames < min_frames:
            problems.append("%s complete frames, expected at least %d" % (frames, min_frames))
    if xmf and frames is not None:
        nx, p = check_xmf(xmf, frames, frame_rows)
        print("sidecar: %d frames" % nx)
        problems += p
    for p in problems:
        print("FAIL: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
