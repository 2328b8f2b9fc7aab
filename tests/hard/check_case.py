"""The hard-case contract, checked from the result file alone (read with h5py,
independently of the engine's own checks; docs/hard-cases.md):

    check_case.py RESULT_DIR EXIT_CODE EXPECT TOLERANCE REACH

- the run ended: exit 0 with status `successful`, or exit 3 with status
  `unstable` (any other exit code, a crash or a timeout, is a failure);
- EXPECT is `successful`, `unstable`, `unstable:<quantity>` or `any`: the
  outcome (and the diagnostic's quantity) pinned for the case;
- successful: the energy balance closed, max over the samples of
  |energy_balance| / scale <= TOLERANCE, scale the largest sum seen so far of
  |kinetic| + |internal| + |external work| + |hourglass| + |viscous| + |contact|
  (the engine's own scale, core/run/integrate.c), and output.frames + 1 frames;
- unstable: the diagnostic names a quantity, a step >= 0 and at least one
  particle id;
- no dataset of the file holds a value that is not finite (either outcome);
- REACH (`failed>=F`, `detF<=J`, `eps_p>=E`, `Tmax>=T`, `steps>=N` or `-`): the state that
  makes the case hard was reached, so the case cannot quietly become easy.
Prints one tab-separated row: outcome, diagnostic, particles, steps, energy error, what
was reached, wall seconds; exits 1 with the reasons on stderr when the contract
is broken."""
import sys

import numpy as np

from tlsph_result import Result

ENERGIES = ("kinetic_energy", "internal_energy", "external_work", "hourglass_energy",
            "viscous_energy", "contact_energy")


def energy_error(r):
    """max_t |balance(t)| / scale(t) over the energy_balance samples."""
    _, balance = r.series("energy_balance")
    size = np.zeros_like(balance, dtype=float)
    for name in ENERGIES:
        if r.has_series(name):
            size += np.abs(r.series(name)[1])
    scale = np.maximum.accumulate(size)
    ok = scale > 0
    if not ok.any():
        return 0.0
    return float(np.max(np.abs(balance[ok]) / scale[ok]))


def reached(r):
    """The extremes of the run: smallest det F, largest plastic strain and
    largest temperature over all frames, the fraction of failed particles at the last frame, the steps."""
    out = {"steps": float(r.cost["steps"])}
    if r.has_field("det_F"):
        out["detF"] = float(np.min(r.field_values("det_F")))
    if r.has_field("temperature"):
        out["Tmax"] = float(np.max(r.field_values("temperature")))
    if r.has_field("plastic_strain"):
        out["eps_p"] = float(np.max(r.field_values("plastic_strain")))
    if r.has_field("damage"):
        out["failed"] = float(np.mean(r.field("damage") >= 1.0))
    return out


def check_reach(reach, got):
    """None when REACH holds, else the reason."""
    if reach == "-":
        return None
    for op in (">=", "<="):
        if op in reach:
            key, value = reach.split(op)
            value = float(value)
            if key not in got:
                return "%s: the run has no %s" % (reach, key)
            ok = got[key] >= value if op == ">=" else got[key] <= value
            return None if ok else "%s not reached: %s = %.4g" % (reach, key, got[key])
    return "unknown reach %r" % reach


def main():
    path, code, expect, tol, reach = (sys.argv[1], int(sys.argv[2]), sys.argv[3],
                                      float(sys.argv[4]), sys.argv[5])
    errors = []
    if code not in (0, 3):
        print("crash\texit %d\t-\t-\t-\t-\t-" % code)
        print("exit code %d: neither successful (0) nor unstable (3)" % code, file=sys.stderr)
        return 1
    with Result(path) as r:
        status, d, cost = r.status, r.diagnostics, r.cost
        want = "successful" if code == 0 else "unstable"
        if status != want:
            errors.append("exit %d but status %s" % (code, status))
        want_status, _, want_quantity = expect.partition(":")
        if want_status != "any" and status != want_status:
            errors.append("outcome %s, the case expects %s" % (status, expect))
        elif want_quantity and d["quantity"] != want_quantity:
            errors.append("quantity %s, the case expects %s" % (d["quantity"], want_quantity))
        err = energy_error(r)
        diag = "-"
        if status == "successful":
            if not err <= tol:
                errors.append("energy balance error %.3g above the tolerance %.3g" % (err, tol))
            frames = len(r.frame_times())
            if frames != r.scene["output"]["frames"] + 1:
                errors.append("%d frames, expected output.frames + 1 = %d"
                              % (frames, r.scene["output"]["frames"] + 1))
        else:
            ids = [int(i) for i in d["ids"][:d["nids"]]]
            diag = "%s at step %d, particles %s" % (d["quantity"], d["step"],
                                                     ",".join(map(str, ids[:4])))
            if not d["quantity"]:
                errors.append("unstable without a quantity")
            if not d["step"] >= 0:
                errors.append("unstable without a step")
            if not ids or min(ids) < 0:
                errors.append("unstable without a particle id")
        bad = r.non_finite_datasets()
        if bad:
            errors.append("datasets holding values that are not finite: " + ", ".join(bad))
        got = reached(r)
        why = check_reach(reach, got)
        if why:
            errors.append(why)
        shown = ", ".join("%s %.3g" % (k, got[k]) for k in ("detF", "eps_p", "Tmax", "failed")
                          if k in got) or "-"
        print("%s\t%s\t%d\t%d\t%.3g\t%s\t%.2f" % (status, diag, cost["particles"],
                                                  cost["steps"], err, shown,
                                                  cost["wall_seconds"]))
    for e in errors:
        print("case failed: " + e, file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
