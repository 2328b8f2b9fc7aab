#!/usr/bin/python3
"""The engine <-> daemon protocol (docs/protocol.md, core/run/protocol.h):
every line tlsph-run writes on --progress-fd validates against
schemas/progress.schema.json, the stream ends with exactly one final event,
its status names the exit code, and the final event carries what explains a
failure.

Real runs: a successful one, every scene under tests/scenes/bad (invalid: the
errors name the pointer of its .expect file), a broken JSON file (invalid: the
error is about the whole document), tests/scenes/good/unstable.json (unstable:
the diagnostic), an output directory that cannot be created and a result file
that cannot be created (io_error: the errors), and a run stopped by SIGTERM
(cancelled).  Exits 77 (skip) without python3-jsonschema.
"""
import glob
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

try:
    import jsonschema
except ImportError:
    print("SKIP: python3-jsonschema is not installed")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.environ.get("top_srcdir", os.path.join(HERE, "..", ".."))
BUILD = os.environ.get("top_builddir", TOP)
ENGINE = os.path.join(BUILD, "tlsph-run")
SCENES = os.path.join(TOP, "tests", "scenes")

with open(os.path.join(TOP, "schemas", "progress.schema.json")) as f:
    SCHEMA = json.load(f)
jsonschema.Draft202012Validator.check_schema(SCHEMA)
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)

# exit code -> status of the final event (core/run/protocol.h)
STATUS = {0: "successful", 2: "invalid", 3: "unstable", 4: "io_error", 5: "cancelled"}

failures = 0


def report(ok, what, why=""):
    global failures
    print("%s: %s%s" % ("ok" if ok else "FAIL", what, (" (" + why + ")") if why and not ok else ""))
    if not ok:
        failures += 1
    return ok


def start(scene, out, tmp):
    """Starts tlsph-run with its progress on a file; returns (process, stream path)."""
    stream = os.path.join(tmp, "progress-%d.jsonl" % time.monotonic_ns())
    fd = os.open(stream, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    try:
        p = subprocess.Popen([ENGINE, scene, "-o", out, "--progress-fd", str(fd), "--threads", "1"],
                             pass_fds=(fd,), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    finally:
        os.close(fd)
    return p, stream


def check_stream(what, stream, code):
    """Validates every line; returns the final event (or None)."""
    with open(stream) as f:
        lines = f.read().splitlines()
    if not report(lines != [], what + ": the stream is not empty"):
        return None
    events = []
    bad = []
    for i, line in enumerate(lines):
        try:
            ev = json.loads(line)
        except ValueError as e:
            bad.append("line %d is not JSON: %s" % (i + 1, e))
            continue
        errs = list(VALIDATOR.iter_errors(ev))
        if errs:
            bad.append("line %d: %s" % (i + 1, "; ".join(e.message[:160] for e in errs[:2])))
        events.append(ev)
    report(not bad, what + ": %d line(s) valid against progress.schema.json" % len(lines),
           "; ".join(bad[:3]))
    finals = [k for k, ev in enumerate(events) if ev.get("event") == "finished"]
    report(finals == [len(events) - 1], what + ": exactly one final event, the last line",
           "final events at %s of %d" % (finals, len(events)))
    if not finals:
        return None
    final = events[finals[-1]]
    report(final.get("status") == STATUS.get(code),
           what + ": final status %s goes with exit code %d" % (final.get("status"), code))
    return final


def run(what, scene, out, tmp, want_code):
    p, stream = start(scene, out, tmp)
    _, err = p.communicate(timeout=600)
    report(p.returncode == want_code, what + ": exit code %d" % p.returncode,
           "expected %d; stderr: %s" % (want_code, err.decode(errors="replace")[-300:]))
    return check_stream(what, stream, p.returncode), err.decode(errors="replace")


def pointers(final):
    return [e["pointer"] for e in (final or {}).get("errors", [])]


def main():
    if not os.access(ENGINE, os.X_OK):
        print("progress_protocol: %s not built" % ENGINE)
        return 99
    with tempfile.TemporaryDirectory(prefix="progress_protocol.") as tmp:
        # a successful run: started, progress at every frame, finished with the cost
        final, _ = run("successful", os.path.join(SCENES, "good", "output_small.json"),
                       os.path.join(tmp, "ok"), tmp, 0)
        if final:
            report(final["cost"]["steps"] == final["step"] > 0, "successful: cost counts the steps")

        # every invalid scene: the errors carry the pointer the scene is about
        for scene in sorted(glob.glob(os.path.join(SCENES, "bad", "*.json"))):
            name = os.path.basename(scene)[:-5]
            with open(scene[:-5] + ".expect") as f:
                want = f.readline().strip()
            out = os.path.join(tmp, "bad-" + name)
            final, err = run("invalid " + name, scene, out, tmp, 2)
            report(want in pointers(final), "invalid %s: errors name %s" % (name, want or '""'),
                   "pointers %s" % pointers(final))
            report(all(e["detail"] in err for e in (final or {}).get("errors", [])),
                   "invalid %s: the same errors on stderr" % name)
            report(not os.path.exists(os.path.join(out, "result.h5")), "invalid %s: nothing written" % name)

        broken = os.path.join(tmp, "broken.json")
        with open(broken, "w") as f:
            f.write('{"name": "broken\n')
        final, _ = run("broken JSON", broken, os.path.join(tmp, "broken"), tmp, 2)
        report(pointers(final) == [""], "broken JSON: one error about the whole document",
               "pointers %s" % pointers(final))

        # unstable: the diagnostic travels in the final event
        final, err = run("unstable", os.path.join(SCENES, "good", "unstable.json"),
                         os.path.join(tmp, "unstable"), tmp, 3)
        diag = (final or {}).get("diagnostic", {})
        report(diag.get("message", "").startswith("numerically unstable at step"),
               "unstable: the diagnostic message", repr(diag.get("message")))
        report(diag.get("message", "-") in err, "unstable: the same message in the log")

        # I/O: an output directory that cannot be created (a path under a file) ...
        afile = os.path.join(tmp, "a-file")
        open(afile, "w").close()
        final, _ = run("io_error (directory)", os.path.join(SCENES, "good", "unstable.json"),
                       os.path.join(afile, "out"), tmp, 4)
        report(any("cannot create output directory" in e["detail"] for e in (final or {}).get("errors", [])),
               "io_error (directory): the error says why", json.dumps((final or {}).get("errors")))
        # ... and a result file that cannot be created (result.h5 is a directory)
        out = os.path.join(tmp, "io")
        os.makedirs(os.path.join(out, "result.h5"))
        final, _ = run("io_error (file)", os.path.join(SCENES, "good", "unstable.json"), out, tmp, 4)
        report(any("result.h5" in e["detail"] for e in (final or {}).get("errors", [])),
               "io_error (file): the error names the file", json.dumps((final or {}).get("errors")))

        # cancelled: SIGTERM after the first progress line
        with open(os.path.join(SCENES, "good", "output_small.json")) as f:
            text = f.read()
        longer = text.replace('"end": 2e-5', '"end": 2e-3')
        if report(longer != text, "cancelled: derived a long scene"):
            scene = os.path.join(tmp, "long.json")
            with open(scene, "w") as f:
                f.write(longer)
            p, stream = start(scene, os.path.join(tmp, "long"), tmp)
            deadline = time.monotonic() + 300  # a hang detector: waits on the first progress event
            while time.monotonic() < deadline and p.poll() is None:
                with open(stream) as f:
                    if '"event":"progress"' in f.read():
                        break
                time.sleep(0.05)
            p.send_signal(signal.SIGTERM)
            p.communicate(timeout=600)
            report(p.returncode == 5, "cancelled: exit code %d" % p.returncode)
            check_stream("cancelled", stream, p.returncode)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
