#!/usr/bin/env python3
"""A stand-in for tlsphd's result endpoints (stdlib only), serving data of known
shape so the client's plots, tables and downloads can be checked exactly:

  GET /jobs/<id>/results/series/<name>   series documents (docs/api.md)
  GET /jobs/<id>/results/summary         a study summary table (job ffff...f:
                                         one too wide for any terminal)
  GET /jobs/<id>/results/result.h5|.xmf  a file of BLOB_SIZE bytes, sent in
                                         slices with short pauses (a download
                                         that lasts long enough to show progress)
  GET /schemas/<name>                    the shipped schemas

usage: fake_results.py SCHEMAS_DIR PORT_FILE -- writes the chosen port to
PORT_FILE once listening; runs until killed."""
import hashlib, json, math, os, sys, time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

N = 101
TIMES = [i * 1e-5 for i in range(N)]
STEPS = [10 * i for i in range(N)]
BLOB_SIZE = 3 << 20


def ramp(i):
    return i / (N - 1)


def scalar(name, units, f):
    return {"name": name, "units": units, "components": None, "step": STEPS, "time": TIMES,
            "value": [f(i) for i in range(N)]}


def vector(name, units, f):
    return {"name": name, "units": units, "components": ["x", "y", "z"], "step": STEPS,
            "time": TIMES, "value": [list(f(i)) for i in range(N)]}


# energies 1e-3 J (kinetic) beside 10 J (internal, external work): one axis
# would flatten kinetic energy onto zero; all of them rise towards the top
# right, where a legend inside the frame would cover them
SERIES = {s["name"]: s for s in [
    scalar("kinetic_energy", "J", lambda i: 1e-3 * math.sin(math.pi * ramp(i)) + 1e-4),
    scalar("internal_energy", "J", lambda i: 10.0 * ramp(i) ** 2),
    scalar("external_work", "J", lambda i: 10.5 * ramp(i) ** 2),
    vector("groups/right/reaction_force", "N", lambda i: (2e5 * ramp(i), 15.0 * ramp(i), 0.0)),
    vector("groups/right/displacement", "m", lambda i: (1e-3 * ramp(i), 0.0, 0.0)),
]}

# a study of 4 children: swept end time (s) and a user parameter, one output,
# the cost columns; numbers of very different magnitudes and digits
SUMMARY = {
    "columns": ["seq", "job_id", "status", "/time/end", "/parameters/vmax", "peak_force",
                "particles", "steps", "wall_seconds", "particle_steps_per_second"],
    "rows": [
        [i, hashlib.md5(b"child %d" % i).hexdigest(), st, end, vmax, pf, parts, steps, wall, rate]
        for i, (st, end, vmax, pf, parts, steps, wall, rate) in enumerate([
            ("successful", 1e-4, 0.05, 711348.7526996768, 100, 2001, 0.27872819999993226, 717903.6782071159),
            ("successful", 2e-4, 0.15, 1422003.4009285646, 400, 4001, 1.330214900000101, 1203113.8728034685),
            ("failed", 3e-4, 0.05, None, 100, 55, 0.0124845470000655, 441.67),
            ("successful", 4e-4, 0.15, 1363772.2195094577, 1600, 40021, 12.9040545779998865, 1770689.5567539518),
        ])
    ],
}

# a study with many outputs: wider than any terminal even when shortened
WIDE = {
    "columns": SUMMARY["columns"][:5] + ["output_%02d_of_the_study" % k for k in range(12)] + SUMMARY["columns"][6:],
    "rows": [r[:5] + [1.5 * 10 ** (k - 6) * (i + 1) for k in range(12)] + r[6:]
             for i, r in enumerate(SUMMARY["rows"])],
}
WIDE_ID = "f" * 32


class Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, *a):
        pass

    def send(self, code, body, ctype="application/json"):
        self.send_response(code)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def do_GET(self):
        path = self.path.split("?")[0]
        parts = path.split("/")
        if path.startswith("/schemas/"):
            f = os.path.join(self.server.schemas, os.path.basename(path))
            if os.path.isfile(f):
                return self.send(200, open(f, "rb").read(), "application/schema+json")
        elif len(parts) >= 5 and parts[1] == "jobs" and parts[3] == "results":
            what = "/".join(parts[4:])
            if what.startswith("series/") and what[7:] in SERIES:
                return self.send(200, json.dumps(SERIES[what[7:]]).encode())
            if what == "summary":
                return self.send(200, json.dumps(WIDE if parts[2] == WIDE_ID else SUMMARY).encode())
            if what in ("result.h5", "result.xmf"):
                return self.blob()
        self.send(404, b'{"type":"urn:tlsph:problem:no-such-result","title":"No such result","status":404}',
                  "application/problem+json")

    def blob(self):
        self.send_response(200)
        self.send_header("Content-Type", "application/octet-stream")
        self.send_header("Content-Length", str(BLOB_SIZE))
        self.send_header("ETag", '"fake-1"')
        self.end_headers()
        chunk = bytes(range(256)) * 256  # 64 KiB
        for _ in range(BLOB_SIZE // len(chunk)):
            self.wfile.write(chunk)
            self.wfile.flush()
            time.sleep(0.01)


def main():
    srv = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    srv.schemas = sys.argv[1]
    with open(sys.argv[2] + ".tmp", "w") as f:
        f.write(str(srv.server_address[1]))
    os.rename(sys.argv[2] + ".tmp", sys.argv[2])
    srv.serve_forever()


if __name__ == "__main__":
    main()
