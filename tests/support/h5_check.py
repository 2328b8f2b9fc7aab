"""Checks a tlsph result directory against the layout documented in docs/output.md.

    h5_check.py live  DOCS H5FILE PID    read the file with SWMR while process PID writes it
    h5_check.py final DOCS DIR SCENE     check the finished DIR/result.h5 and DIR/result.xmf

The documented tables (between the <!-- fields:begin --> ... markers of docs/output.md) are the
reference: every documented dataset must exist with its shape, dtype, units and components, and
every field or column in the file must be documented.

Exit status: 0 all checks passed; 1 a check failed; 3 (live only) the writer finished before
two different partial states could be observed (the caller retries with a larger scene).
Run with the system Python (h5py 3.7, numpy)."""
import json
import math
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np

CHECKS = []


class CheckFailed(Exception):
    pass


def check(cond, what):
    if not cond:
        raise CheckFailed(what)
    CHECKS.append(what)


def text(v):
    return v.decode() if isinstance(v, (bytes, np.bytes_)) else str(v)


# ------------------------------------------------------------------ documented tables

def table(doc, name):
    m = re.search(r"<!-- %s:begin -->(.*?)<!-- %s:end -->" % (name, name), doc, re.S)
    if not m:
        raise CheckFailed("docs/output.md has no %s table" % name)
    rows = []
    lines = [l.strip() for l in m.group(1).strip().splitlines() if l.strip().startswith("|")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    for l in lines[2:]:
        cells = [c.strip() for c in l.strip("|").split("|")]
        row = dict(zip(header, cells))
        row["name"] = row["name"].strip("`")
        rows.append(row)
    return rows


def load_docs(path):
    with open(path) as fp:
        doc = fp.read()
    optional = table(doc, "optional-series")  # present only with their module
    for row in optional:
        row["optional"] = True
    # per-item families: boundary groups, gauges and sections (columns of
    # sections are optional like the global ones: they follow the modules)
    families = {"groups": table(doc, "group-series"), "gauges": table(doc, "gauge-series"),
                "sections": table(doc, "section-series"), "walls": table(doc, "wall-series"),
                "contacts": table(doc, "contact-series"), "rigid": table(doc, "rigid-series"),
                "probes": table(doc, "probe-series"), "extents": table(doc, "extent-series"),
                "crack_tips": table(doc, "crack-tip-series")}
    for row in families["sections"]:
        row["optional"] = row.get("present when", "always") != "always"
    return table(doc, "fields"), table(doc, "series") + optional, families


def shape_of(spec, F, N, T):
    """'[F, N, 3]' -> (F, N, 3)"""
    out = []
    for tok in spec.strip("[]").split(","):
        tok = tok.strip()
        out.append({"F": F, "N": N, "T": T}.get(tok, None) if tok.isalpha() else int(tok))
    return tuple(out)


DTYPES = {"float64": np.float64, "float32": np.float32, "int64": np.int64, "int32": np.int32}


# ------------------------------------------------------------------ the HDF5 checks

def check_fields(f, fields, live):
    """Checks /particles/solid against the documented fields; returns (F, N,
    step).  With a changing particle count (docs/output.md, "Changing particle
    counts") every field is per frame and N is the particle extent Nmax."""
    solid = f["particles/solid"]
    changing = "count" in solid
    N = solid["id/value"].shape[1] if changing else solid["id"].shape[0]
    check(N > 0, "N = %d particles" % N)
    frame_step = None
    F = None
    for row in fields:
        name = row["name"]
        if name not in solid:
            check(row["always"] != "yes", "documented field %s present" % name)
            continue
        if row["kind"] == "reference" and not changing:
            ds = solid[name]
            check(isinstance(ds, h5py.Dataset), "%s is a dataset" % name)
            want = shape_of(row["shape"], None, N, None)
        else:
            g = solid[name]
            check(isinstance(g, h5py.Group) and {"step", "time", "value"} <= set(g.keys()),
                  "%s has step, time, value" % name)
            ds = g["value"]
            st, tm = g["step"], g["time"]
            if live:
                for d in (st, tm, ds):  # step first: value is never shorter
                    d.refresh()
            if F is None:
                F = st.shape[0]
                frame_step = st
            nrows = ds.shape[0]
            if live:
                # the writer keeps appending while we read: counts only grow, and a
                # value is written before step and time, so it is never shorter
                check(st.shape[0] >= F and tm.shape[0] >= F and nrows >= F,
                      "%s step/time/value have at least the %d frames seen" % (name, F))
            else:
                check(st.shape == (F,) and tm.shape == (F,) and nrows == F,
                      "%s step/time/value have the common frame count %d" % (name, F))
            check(text(tm.attrs["units"]) == "s", "%s/time units s" % name)
            want = shape_of(row["shape"], nrows, N, None)
            if row["kind"] == "reference":  # changing count: [N(, C)] per frame
                want = (nrows,) + want
        check(ds.shape == want, "%s shape %s == documented %s" % (name, ds.shape, row["shape"]))
        check(ds.dtype == DTYPES[row["type"]], "%s dtype %s" % (name, row["type"]))
        check(text(ds.attrs.get("units", b"?")) == row["units"],
              "%s units %r" % (name, row["units"]))
        check("description" in ds.attrs, "%s has a description" % name)
        if row["components"]:
            check(text(ds.attrs.get("components", b"")) == row["components"],
                  "%s components %r" % (name, row["components"]))
    documented = {r["name"] for r in fields}
    if changing:
        c = solid["count"]["value"]
        if live:
            c.refresh()
        check(c.dtype == np.int64 and c.shape[0] >= F, "count int64 with every frame")
        check(np.all(c[:F] > 0) and np.all(c[:F] <= N), "every frame's count within 1..Nmax")
        check(solid["count"]["step"].id == frame_step.id or
              np.array_equal(solid["count"]["step"][:F], frame_step[:F]), "count on the frame steps")
    for name in solid:
        if name != "box" and not (changing and name == "count"):
            check(name in documented, "file field %s is documented" % name)
    return F, N, frame_step


def check_series_group(g, rows, where, live):
    lengths = []
    for row in rows:
        name = row["name"]
        if row.get("optional") and name not in g:
            continue
        check(name in g, "%s/%s exists" % (where, name))
        c = g[name]
        ds, st, tm = c["value"], c["step"], c["time"]
        if live:
            for d in (st, tm, ds):  # step first: value is never shorter
                d.refresh()
        T = st.shape[0]
        check(tm.shape == (T,) or (live and tm.shape[0] >= T),
              "%s/%s time has %d rows" % (where, name, T))
        check(ds.shape[0] == T or (live and ds.shape[0] >= T),
              "%s/%s value rows match step" % (where, name))
        check(ds.shape[1:] == shape_of(row["shape"], None, None, T)[1:],
              "%s/%s shape %s matches %s" % (where, name, ds.shape, row["shape"]))
        check(text(ds.attrs.get("units", b"?")) == row["units"],
              "%s/%s units %r" % (where, name, row["units"]))
        lengths.append(T)
    documented = {r["name"] for r in rows}
    for name in g:
        if name not in ("groups", "gauges", "sections", "walls", "contacts", "rigid", "probes",
                        "crack_tips", "extents"):
            check(name in documented, "%s/%s is documented" % (where, name))
    return lengths


NAME_RULE = re.compile(r"[A-Za-z_][A-Za-z0-9_.-]{0,62}\Z")


# the damage models with a porous yield surface (core/material/damage/registry.c)
POROUS_MODELS = ("gtn", "gurson", "gtn_aravas", "sm_gurson", "m_gurson")


def contact_items(scene):
    """The contact family's items (docs/output.md): none without contact (on by
    default with more than one body, a damage model or virtual links, off with "enabled":
    false); else every body, then the pairs <a>--<b> (at most 66 pairs; a pair
    name that breaks the naming rule or is taken names nothing)."""
    bodies = [b["name"] for b in scene.get("bodies", [])]
    damage = any("damage" in m for m in scene.get("materials", {}).values())
    treatment = scene.get("discretization", {}).get("damage", {}).get("treatment")
    damage = damage or treatment == "virtual_links"
    if scene.get("contact", {}).get("enabled", True) is False or (len(bodies) < 2 and not damage):
        return []
    pairs = ["%s--%s" % (a, b) for i, a in enumerate(bodies) for b in bodies[i + 1:]]
    if len(pairs) > 66:
        pairs = []
    names = [p for p in pairs if NAME_RULE.match(p) and p not in bodies and pairs.count(p) == 1]
    return bodies + names


def check_series(f, series, families, scene, live):
    obs = f["observables"]
    lengths = check_series_group(obs, series, "/observables", live)
    loaded = [b["name"] for b in scene.get("boundary_conditions", [])
              if b.get("type") in ("fixed", "velocity")]
    out = scene.get("output", {})
    walls = [b.get("name", "bc%d" % i) for i, b in enumerate(scene.get("boundary_conditions", []))
             if b.get("type") == "wall"]
    items = {"groups": loaded,
             "gauges": [g["name"] for g in out.get("gauges", [])],
             "sections": [c["name"] for c in out.get("sections", [])],
             "walls": walls,
             "contacts": contact_items(scene),
             "rigid": [r["name"] for r in scene.get("rigid_bodies", [])],
             "probes": [q["name"] for q in out.get("probes", [])],
             "extents": [e["name"] for e in out.get("extents", [])],
             "crack_tips": ["tip%d" % k for k in
                            range(len(scene.get("crack_growth", {}).get("tips", [])))]}
    check("groups" in obs, "/observables/groups exists")
    for family, names in items.items():
        if not names:
            check(family == "groups" or family not in obs, "no /observables/%s" % family)
            continue
        check(family in obs, "/observables/%s exists" % family)
        for name in names:
            name = name.replace("/", "_")
            check(name in obs[family], "%s series for %s" % (family, name))
            lengths += check_series_group(obs[family][name], families[family],
                                          "/observables/%s/%s" % (family, name), live)
        check(len(obs[family]) == len(names), "one %s series group per scene item" % family)
    return lengths


def check_metadata(f, scene_path):
    check(list(f["h5md"].attrs["version"]) == [1, 1], "/h5md version [1, 1]")
    check(text(f["h5md/creator"].attrs["name"]) == "tlsph", "/h5md/creator name tlsph")
    check(len(text(f["h5md/creator"].attrs["version"])) > 0, "/h5md/creator version")
    p = f["parameters"]
    scene = json.loads(text(p["scene"][()]))
    with open(scene_path) as fp:
        submitted = json.load(fp)
    check(scene == submitted, "/parameters/scene parses as JSON and equals the submitted scene")
    check(isinstance(json.loads(text(p["modules"][()])), list), "/parameters/modules is a JSON array")
    check(int(p.attrs["dimension"]) == submitted["dimension"], "/parameters dimension")
    check(text(p.attrs["units_system"]) == "SI", "/parameters units_system SI")
    check(len(text(p.attrs["engine_version"])) > 0, "/parameters engine_version")
    return submitted


# ------------------------------------------------------------------ XDMF

def check_xmf(path, f, F, N, times):
    root = ET.parse(path).getroot()
    check(root.tag == "Xdmf", "result.xmf parses as XML with an Xdmf root")
    coll = root.find("Domain/Grid")
    check(coll is not None and coll.get("CollectionType") == "Temporal", "temporal collection")
    grids = coll.findall("Grid")
    check(len(grids) == F, "result.xmf has %d frames (file has %d)" % (len(grids), F))
    xtimes = [float(g.find("Time").get("Value")) for g in grids]
    check(np.allclose(xtimes, times, rtol=1e-12, atol=0), "result.xmf times equal position/time")
    paths = set()
    solid = f["particles/solid"]
    counts = solid["count/value"][:F] if "count" in solid else [N] * F
    for k, g in enumerate(grids):
        topo = g.find("Topology")
        n = counts[k]
        check(int(topo.get("NumberOfElements")) == n, "frame %d topology has its %d points" % (k, n))
        check(g.find("Geometry") is not None, "frame %d has geometry" % k)
        for item in g.iter("DataItem"):
            if item.get("Format") == "HDF":
                h5name, hpath = item.text.strip().split(":", 1)
                check(h5name == "result.h5", "relative h5 path")
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                check(hpath in f, "xmf path %s exists" % hpath)
                check(f[hpath].shape == dims,
                      "xmf dims %s of %s match the file %s" % (dims, hpath, f[hpath].shape))
                paths.add(hpath)
            if item.get("ItemType") == "HyperSlab":
                sel, data = item.findall("DataItem")
                nums = [int(v) for v in sel.text.split()]
                r = len(nums) // 3
                start, stride, count = nums[:r], nums[r:2 * r], nums[2 * r:]
                check(start[0] == k and count[0] == 1 and count[1] == n and stride == [1] * r,
                      "frame %d hyperslab selects frame %d of %d particles" % (k, k, n))
                check(tuple(int(d) for d in item.get("Dimensions").split()) == tuple(count[1:]),
                      "frame %d hyperslab dimensions" % k)
        for a in g.findall("Attribute"):
            check(a.get("AttributeType") in ("Scalar", "Vector", "Tensor6"), "attribute type")
    check(any(p.endswith("position/value") for p in paths), "geometry from position/value")
    check(any(p.endswith("stress/value") for p in paths), "stress in the xmf")
    return len(paths)


# ------------------------------------------------------------------ h5dump

def check_h5dump(h5, F, N):
    out = subprocess.run(["h5dump", "-H", h5], capture_output=True, text=True)
    check(out.returncode == 0, "h5dump -H reads the file")
    stack, shapes = [], {}
    for line in out.stdout.splitlines():
        s = line.strip()
        m = re.match(r'(GROUP|DATASET|ATTRIBUTE) "([^"]*)" \{$', s)
        if m:
            stack.append(m.group(2) if m.group(1) != "ATTRIBUTE" else "@" + m.group(2))
            continue
        if s.endswith("{"):
            stack.append(None)
            continue
        if s == "}":
            stack.pop()
            continue
        m = re.match(r"DATASPACE\s+SIMPLE \{ \( ([^)]*) \)", s)
        if m and stack and stack[-1] and not stack[-1].startswith("@"):
            path = "/".join(x for x in stack if x and x != "/")
            shapes["/" + path] = tuple(int(v) for v in m.group(1).split(","))
    check(shapes.get("/particles/solid/position/value") == (F, N, 3),
          "h5dump: position/value is [F, N, 3] = %s" % ((F, N, 3),))
    check(shapes.get("/particles/solid/stress/value") == (F, N, 6),
          "h5dump: stress/value is [F, N, 6]")
    a = subprocess.run(["h5dump", "-a", "/particles/solid/stress/value/components", h5],
                       capture_output=True, text=True)
    check(a.returncode == 0 and '"xx xy xz yy yz zz"' in a.stdout,
          "h5dump: stress components attribute is \"xx xy xz yy yz zz\"")
    a = subprocess.run(["h5dump", "-a", "/particles/solid/position/value/units", h5],
                       capture_output=True, text=True)
    check(a.returncode == 0 and '"m"' in a.stdout, "h5dump: position units \"m\"")
    return len(shapes)


# ------------------------------------------------------------------ modes

def alive(pid):
    try:
        with open("/proc/%d/stat" % pid) as fp:
            return fp.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def live(docs, h5, pid):
    fields, series, families = load_docs(docs)
    deadline = time.time() + 600
    seen = []  # frame counts observed while the writer was running
    opened = False
    while alive(pid) and time.time() < deadline:
        if not os.path.exists(h5):
            time.sleep(0.02)
            continue
        try:
            f = h5py.File(h5, "r", libver="latest", swmr=True)
        except OSError:
            time.sleep(0.05)  # not yet in SWMR mode
            continue
        opened = True
        with f:
            scene = json.loads(text(f["parameters/scene"][()]))
            while alive(pid) and time.time() < deadline:
                F, N, _ = check_fields(f, fields, live=True)
                check_series(f, series, families, scene, live=True)
                if alive(pid):  # the reads above happened while the writer ran
                    if not seen or seen[-1] != F:
                        print("live: %d frames of %d particles, status %s" %
                              (F, N, text(f["diagnostics"].attrs["status"])))
                    check(not seen or F >= seen[-1], "frame count never decreases")
                    seen.append(F)
                time.sleep(0.05)
    distinct = sorted(set(seen))
    print("live: opened=%s, distinct frame counts seen while running: %s" % (opened, distinct))
    if len(distinct) < 2:
        return 3
    print("live: SWMR reads of the partially written file passed (%d checks)" % len(CHECKS))
    return 0


def final(docs, outdir, scene_path):
    fields, series, families = load_docs(docs)
    h5 = os.path.join(outdir, "result.h5")
    with h5py.File(h5, "r") as f:  # a plain (non-SWMR) open must work after the run
        scene = check_metadata(f, scene_path)
        F, N, step = check_fields(f, fields, live=False)
        frames = scene["output"]["frames"]
        check(F == frames + 1, "frame count %d is output.frames + 1 = %d" % (F, frames + 1))
        times = f["particles/solid/position/time"][:]
        steps = step[:]
        check(np.all(np.diff(times) > 0), "frame times strictly increasing")
        check(np.all(np.diff(steps) > 0), "frame steps strictly increasing")
        check(times[-1] >= 0.9 * scene["time"]["end"], "last frame near time.end")
        lengths = check_series(f, series, families, scene, live=False)
        T = lengths[0]
        check(T > 1 and all(x == T for x in lengths), "all series have %d samples" % T)
        st = f["observables/kinetic_energy/time"][:]
        check(np.all(np.diff(st) > 0), "series times strictly increasing")
        se = scene["output"].get("series_every", 1)
        dsteps = np.diff(f["observables/kinetic_energy/step"][:])
        check(np.all(dsteps > 0) and np.median(dsteps) == se, "series sampled every %d steps" % se)
        non_finite = []
        f.visititems(lambda path, o: non_finite.append(path) if isinstance(o, h5py.Dataset)
                     and o.dtype.kind == "f" and not np.all(np.isfinite(o[()])) else None)
        check(not non_finite, "every dataset finite (not: %s)" % ", ".join(non_finite))
        cost = f["cost"].attrs
        for k in ("particles", "pairs", "steps", "wall_seconds", "particle_steps_per_second",
                  "peak_memory_bytes", "bytes_per_particle"):
            v = float(cost[k])
            check(math.isfinite(v) and v > 0, "/cost %s = %g positive" % (k, v))
        contact_attrs = ("contact_searches", "contact_search_share", "contact_phase_share")
        if contact_items(scene):
            for k in contact_attrs:
                v = float(cost[k])
                check(math.isfinite(v) and 0 <= v and (k == "contact_searches" or v < 1),
                      "/cost %s = %g" % (k, v))
            check(int(cost["contact_searches"]) >= 1, "/cost contact_searches >= 1")
        else:
            check(not any(k in cost for k in contact_attrs), "no /cost contact attributes")
        porous = any(m.get("damage", {}).get("type") in POROUS_MODELS
                     for m in scene.get("materials", {}).values())
        if porous:
            v = float(cost["material_phase_share"])
            check(math.isfinite(v) and 0 < v < 1, "/cost material_phase_share = %g" % v)
        else:
            check("material_phase_share" not in cost, "no /cost material_phase_share")
        last_n = f["particles/solid/count/value"][-1] if "count" in f["particles/solid"] else N
        check(int(cost["particles"]) == last_n, "/cost particles == the last frame's count")
        check(int(cost["steps"]) >= steps[-1], "/cost steps >= last frame step")
        check(text(f["diagnostics"].attrs["status"]) == "successful", "/diagnostics status successful")
        nx = check_xmf(os.path.join(outdir, "result.xmf"), f, F, N, times)
    nd = check_h5dump(h5, F, N)
    print("final: F=%d frames, N=%d particles, T=%d samples, %d xmf paths, %d datasets in h5dump"
          % (F, N, T, nx, nd))
    print("final: %d checks passed" % len(CHECKS))
    return 0


def main():
    try:
        if len(sys.argv) == 5 and sys.argv[1] == "live":
            return live(sys.argv[2], sys.argv[3], int(sys.argv[4]))
        if len(sys.argv) == 5 and sys.argv[1] == "final":
            return final(sys.argv[2], sys.argv[3], sys.argv[4])
    except CheckFailed as e:
        print("FAILED: %s" % e)
        return 1
    print(__doc__)
    return 1


if __name__ == "__main__":
    sys.exit(main())
