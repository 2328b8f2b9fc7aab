"""Reading a tlsph result file (result.h5, layout in docs/output.md) for tests
and benchmarks: one place that knows the paths, the string encodings h5py
returns and how series, fields, diagnostics and cost are stored.

    from tlsph_result import Result
    with Result("out/strip") as r:            # a result directory or its result.h5
        t, ke = r.series("kinetic_energy")    # global series: times (s), values
        t, R = r.series("groups/left/reaction_force")
        D = r.field("damage", frame=-1)       # per-particle field at one frame
        r.status, r.cost["steps"], r.scene["bodies"][0]["spacing"]

A run whose particle count changes (particle splitting; docs/output.md,
"Changing particle counts") stores every field per frame with the frame's
count in particles/solid/count: field() returns that frame's particles (and
"id" names them), so a caller that compares frames by index must use ids
(r.changing_count says which layout the file has).

Scripts outside tests/support put that folder on sys.path first
(bench/*_metrics.py do).  Needs h5py and numpy (Debian: python3-h5py,
python3-numpy; run with /usr/bin/python3).  Units are those of the file: SI.
"""
import json
import os

import h5py
import numpy as np

PARTICLES = "particles/solid"
OBSERVABLES = "observables"


def text(v):
    """An HDF5 string attribute or scalar dataset as str (h5py gives bytes
    for fixed-length strings; the writer pads some with NULs)."""
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
    if isinstance(v, bytes):
        v = v.decode()
    return str(v).rstrip("\x00")


class Result:
    """A finished (or, with swmr=True, a running) result file."""

    def __init__(self, path, swmr=False):
        if os.path.isdir(path):
            path = os.path.join(path, "result.h5")
        self.path = path
        if swmr:
            self.file = h5py.File(path, "r", libver="latest", swmr=True)
        else:
            self.file = h5py.File(path, "r")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.file.close()

    # -------------------------------------------------------------- metadata
    @property
    def scene(self):
        """The scene as submitted (dict)."""
        return json.loads(text(self.file["parameters/scene"][()]))

    @property
    def modules(self):
        """The active modules of the run, in pipeline order (list of str)."""
        return json.loads(text(self.file["parameters/modules"][()]))

    @property
    def status(self):
        """successful, unstable, cancelled or io_error."""
        return text(self.file["diagnostics"].attrs["status"])

    @property
    def diagnostics(self):
        """The stability diagnostic as a dict (empty values when successful)."""
        a = self.file["diagnostics"].attrs
        return {k: (text(a[k]) if a[k].dtype.kind in "SOU" else a[k]) for k in a}

    @property
    def cost(self):
        """particles, pairs, steps, wall_seconds, particle_steps_per_second,
        peak_memory_bytes, bytes_per_particle."""
        return {k: v.item() if hasattr(v, "item") else v
                for k, v in self.file["cost"].attrs.items()}

    # -------------------------------------------------------------- series
    def has_series(self, name):
        return name in self.file[OBSERVABLES]

    def series(self, name):
        """(time s, values) of a time series: a global one ("kinetic_energy")
        or a per-item one ("groups/left/reaction_force", "gauges/bar/
        engineering_stress", "sections/middle/damage").  Per-item series
        without their own clock share the energy_balance samples' times."""
        g = self.file[OBSERVABLES][name]
        if "time" in g:
            t = g["time"][:]
        else:
            t = self.file[OBSERVABLES]["energy_balance/time"][:]
        return t, g["value"][:]

    def last(self, name, default=float("nan")):
        """The last sample of a global series, or default when the run has no
        such series (its module was not active)."""
        if not self.has_series(name):
            return default
        return float(self.file[OBSERVABLES][name]["value"][-1])

    # -------------------------------------------------------------- fields
    def has_field(self, name):
        return name in self.file[PARTICLES]

    @property
    def changing_count(self):
        """True when the particle count changes between frames (the layout
        with particles/solid/count)."""
        return "count" in self.file[PARTICLES]

    def count(self, frame=-1):
        """The number of particles of a frame."""
        if self.changing_count:
            return int(self.file[PARTICLES]["count"]["value"][frame])
        return int(self.file[PARTICLES]["id"].shape[0])

    def field(self, name, frame=-1):
        """A per-frame field at one frame ([N] or [N, components]), or a
        per-particle constant ("reference_position", "volume", "mass", "body",
        "id") when the name has no frames.  With a changing count every field
        has frames and N is the frame's count."""
        g = self.file[PARTICLES][name]
        if isinstance(g, h5py.Dataset):
            return g[()]
        if self.changing_count:
            return g["value"][frame, :self.count(frame)]
        return g["value"][frame]

    def field_values(self, name):
        """Every frame's values of a per-frame field, the frames' particles
        one after the other ([sum of counts] or [..., components]): for
        extremes over the run, with either layout."""
        v = self.file[PARTICLES][name]["value"]
        if not self.changing_count:
            return v[()].reshape((-1,) + v.shape[2:])
        counts = self.file[PARTICLES]["count"]["value"][:v.shape[0]]
        return np.concatenate([v[k, :n] for k, n in enumerate(counts)])

    def require_one_count(self, who):
        """Exits with a message when the particle count changes during the
        run: for scripts that compare frames particle by particle by index."""
        if self.changing_count:
            raise SystemExit("%s: %s: the particle count changes during this run (particle "
                             "splitting); this script needs one count per run" % (who, self.path))

    def frame_times(self, name="position"):
        return self.file[PARTICLES][name]["time"][:]

    def frame_fields(self):
        """Names of the per-frame fields the file holds."""
        return [k for k, g in self.file[PARTICLES].items()
                if isinstance(g, h5py.Group) and "value" in g and k != "count"]

    def spacing(self, body=0):
        """Lattice spacing of a body (m), from the stored scene."""
        return self.scene["bodies"][body]["spacing"]

    # -------------------------------------------------------------- checks
    def non_finite_datasets(self):
        """Paths of the numeric datasets holding a value that is not finite
        (NaN or +-Inf): none, in any result file (docs/output.md)."""
        bad = []

        def visit(path, obj):
            if (isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f"
                    and not np.all(np.isfinite(obj[()]))):
                bad.append(path)
        self.file.visititems(visit)
        return bad

    def numeric_datasets(self):
        """How many numeric datasets the file holds (what non_finite_datasets
        looked at)."""
        n = [0]

        def visit(path, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
                n[0] += 1
        self.file.visititems(visit)
        return n[0]
