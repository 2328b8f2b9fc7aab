#!/usr/bin/env python3
"""Checks real tlsphd responses against the API definition it serves.

    openapi_responses.py URL SCENES [TOKEN_URL TOKEN]

SCENES: a JSON file {"tiny": scene, "long": scene, "unstable": scene}.

Fetches URL/openapi.json, then makes a request of every documented
operation (every path and method, the HEAD twins included) in the states
that give its documented answers: a successful run, a failed one, a
dismissed one, a study, bad input.  For each answer it finds the operation
by path template, method and status in the document and checks, as an
independent reader of the document would (python3-jsonschema, Draft 2020-12,
references resolved inside the document):

  - the status is documented for that operation;
  - a body's Content-Type is documented for that status, and a JSON body
    validates against the documented schema;
  - every documented response header the daemon must send is there.

With TOKEN_URL (a daemon with bearer tokens) the security requirements are
checked too: an operation whose security allows {} answers without a token
on URL, and 401 is documented where TOKEN_URL refuses one.  Finally every
operation of the document must have been exercised.  Prints one line per
check ("ok" / "FAIL") and exits 1 when one failed.  Standard library and
python3-jsonschema only."""
import http.client
import json
import re
import sys
import time
import urllib.parse

import jsonschema

FAILS = []
SEEN = set()  # (template, method, status)


def say(ok, what):
    print(("ok - " if ok else "FAIL - ") + what)
    if not ok:
        FAILS.append(what)


class Api:
    def __init__(self, url, token=None):
        u = urllib.parse.urlsplit(url)
        self.host, self.port = u.hostname, u.port
        self.token = token

    def call(self, method, path, body=None, headers=None):
        h = dict(headers or {})
        if self.token:
            h["Authorization"] = "Bearer " + self.token
        if body is not None and not isinstance(body, bytes):
            body = json.dumps(body).encode()
            h.setdefault("Content-Type", "application/json")
        c = http.client.HTTPConnection(self.host, self.port, timeout=300)
        c.request(method, path, body=body, headers=h)
        r = c.getresponse()
        data = r.read()
        c.close()
        return r.status, {k.lower(): v for k, v in r.getheaders()}, data


class Doc:
    def __init__(self, doc):
        self.doc = doc
        self.templates = []
        for tpl, item in doc["paths"].items():
            rx = "^" + re.sub(r"\\\{[^}]+\\\}", "[^/]+", re.escape(tpl)) + "$"
            self.templates.append((tpl, re.compile(rx), item))
        # literal templates first, so /results/result.h5 beats a parameter
        self.templates.sort(key=lambda t: t[0].count("{"))
        self.resolver = jsonschema.RefResolver("", doc)

    def operation(self, path, method):
        """The operation for path and method; a method the path does not
        have is answered 405, which the path's GET documents."""
        raw = urllib.parse.urlsplit(path).path
        for tpl, rx, item in self.templates:
            if rx.match(raw) and method.lower() in item:
                return tpl, item[method.lower()]
        for tpl, rx, item in self.templates:
            if rx.match(raw) and "get" in item:
                return tpl, item["get"]
        return None, None

    def validate(self, schema, value):
        v = jsonschema.Draft202012Validator(schema, resolver=self.resolver)
        errs = sorted(v.iter_errors(value), key=lambda e: list(e.path))
        return [f"{'/'.join(map(str, e.path))}: {e.message[:200]}" for e in errs[:3]]


def check(api, doc, method, path, want=None, body=None, headers=None, label=None):
    """Makes the request and checks the answer against the document."""
    status, hdrs, data = api.call(method, path, body, headers)
    what = f"{method} {path} {status}" + (f" ({label})" if label else "")
    if want is not None and status != want:
        say(False, f"{what}: wanted {want} {data[:200]!r}")
        return status, hdrs, data
    tpl, op = doc.operation(path, method)
    if op is None:
        say(False, f"{what}: no such operation in the document")
        return status, hdrs, data
    resp = op.get("responses", {}).get(str(status))
    if resp is None:
        say(False, f"{what}: status not documented for {method} {tpl} "
                   f"(documented: {', '.join(op.get('responses', {}))})")
        return status, hdrs, data
    SEEN.add((tpl, method.lower(), str(status)))
    problems = []
    for name, h in resp.get("headers", {}).items():
        if h.get("required") and name.lower() not in hdrs:
            problems.append(f"required header {name} missing")
    ctype = hdrs.get("content-type", "").split(";")[0].strip()
    content = resp.get("content")
    if method != "HEAD" and data and content is not None:
        media = content.get(ctype) or next(
            (m for k, m in content.items() if k.split(";")[0].strip() == ctype), None)
        if media is None:
            problems.append(f"Content-Type {ctype} not documented ({', '.join(content)})")
        elif "schema" in media and ctype.endswith("json"):
            try:
                value = json.loads(data)
            except ValueError as e:
                problems.append(f"body is not JSON: {e}")
            else:
                try:
                    problems += doc.validate(media["schema"], value)
                except jsonschema.exceptions.RefResolutionError as e:
                    problems.append(f"the document's schema cannot be resolved: {e}")
    elif method != "HEAD" and data and content is None and status not in (304,):
        problems.append(f"a body ({ctype}) where the document declares none")
    if method == "HEAD" and data:
        problems.append("HEAD answered with a body")
    say(not problems, what + (": " + "; ".join(problems) if problems else ""))
    return status, hdrs, data


def get_and_head(api, doc, path, want=200, headers=None, label=None, head_want=None):
    """GET and its HEAD twin (head_want: where they differ, as for Range,
    which RFC 9110 defines for GET only)."""
    r = check(api, doc, "GET", path, want, headers=headers, label=label)
    check(api, doc, "HEAD", path, head_want or want, headers=headers, label=label)
    return r


def wait_final(api, job, hang=300):
    last, t_last = None, time.time()
    while True:
        status, _, data = api.call("GET", f"/jobs/{job}?wait=20")
        info = json.loads(data)
        if info["status"] not in ("accepted", "running"):
            return info["status"]
        if data != last:
            last, t_last = data, time.time()
        if time.time() - t_last > hang:
            raise SystemExit(f"job {job} stuck: {info}")


def main(argv):
    api = Api(argv[0])
    status, _, data = api.call("GET", "/openapi.json")
    if status != 200:
        print("FAIL - GET /openapi.json", status)
        return 1
    doc = Doc(json.loads(data))
    with open(argv[1], encoding="utf-8") as f:
        scenes = json.load(f)
    tiny, long_, unstable = scenes["tiny"], scenes["long"], scenes["unstable"]

    # the service's own resources
    for p in ["/", "/conformance", "/openapi.json", "/healthz", "/processes", "/processes/run",
              "/processes/study", "/processes/convergence", "/schemas/job.schema.json"]:
        get_and_head(api, doc, p)
    get_and_head(api, doc, "/processes/nope", 404)
    get_and_head(api, doc, "/schemas/nope.json", 404)
    check(api, doc, "PUT", "/processes", 405, body=b"")

    # submissions
    ex = "/processes/run/execution"
    _, _, d = check(api, doc, "POST", ex, 201, body={"inputs": {"scene": tiny}})
    ok_id = json.loads(d)["jobID"]
    _, _, d = check(api, doc, "POST", ex, 201, body={"inputs": {"scene": unstable}})
    bad_id = json.loads(d)["jobID"]
    study = {"inputs": {"base": tiny, "sweep": {"parameters": [
        {"pointer": "/output/series_every", "values": [1, 2]}]}}}
    _, _, d = check(api, doc, "POST", "/processes/study/execution", 201, body=study)
    study_id = json.loads(d)["jobID"]
    conv = {"inputs": {"base": tiny, "ladder": {"spacings": [tiny["bodies"][0]["spacing"] * f
                                                             for f in (1, 0.5, 0.25)]},
                       "outputs": [{"name": "ke", "series": "kinetic_energy", "reduce": "final"}]}}
    _, _, d = check(api, doc, "POST", "/processes/convergence/execution", 201, body=conv)
    conv_id = json.loads(d)["jobID"]
    conv["inputs"]["ladder"] = {"spacings": [1, 2]}
    check(api, doc, "POST", "/processes/convergence/execution", 422, body=conv,
          label="two spacings")
    check(api, doc, "POST", ex, 400, body=b"{nope", headers={"Content-Type": "application/json"})
    check(api, doc, "POST", ex, 415, body=b"{}", headers={"Content-Type": "text/plain"})
    check(api, doc, "POST", ex, 422, body={"inputs": {"scene": {}}})
    check(api, doc, "POST", ex, 422, body={"inputs": {"scene": tiny}, "subscriber": {}},
          label="subscriber")
    check(api, doc, "POST", "/processes/nope/execution", 404, body={"inputs": {}})
    _, _, d = check(api, doc, "POST", ex, 201, body={"inputs": {"scene": long_}})
    long_id = json.loads(d)["jobID"]

    # the job list and statusInfo
    get_and_head(api, doc, "/jobs")
    get_and_head(api, doc, "/jobs?status=successful,failed&type=process&datetime=2000-01-01T00:00:00Z/..")
    get_and_head(api, doc, "/jobs?status=bogus", 400)
    get_and_head(api, doc, f"/jobs/{long_id}")
    get_and_head(api, doc, f"/jobs/{long_id}?wait=x", 400)
    get_and_head(api, doc, "/jobs/" + "0" * 32, 404)
    get_and_head(api, doc, f"/jobs/{long_id}/results", 404, label="not ready")

    for j in (ok_id, bad_id, study_id, conv_id):
        wait_final(api, j)
    # results of a successful run
    r = f"/jobs/{ok_id}/results"
    get_and_head(api, doc, r)
    _, hdrs, _ = get_and_head(api, doc, r + "/result.h5")
    etag = hdrs.get("etag", "")
    get_and_head(api, doc, r + "/result.h5", 206, headers={"Range": "bytes=0-99"}, head_want=200)
    get_and_head(api, doc, r + "/result.h5", 304, headers={"If-None-Match": etag})
    get_and_head(api, doc, r + "/result.h5", 416, headers={"Range": "bytes=999999999-"},
                 head_want=200)
    get_and_head(api, doc, r + "/result.xmf")
    get_and_head(api, doc, r + "/result.xmf", 206, headers={"Range": "bytes=0-9"}, head_want=200)
    get_and_head(api, doc, r + "/result.xmf", 304, headers={"If-None-Match": "*"})
    get_and_head(api, doc, r + "/series")
    get_and_head(api, doc, r + "/series/kinetic_energy")
    get_and_head(api, doc, r + "/series/kinetic_energy?format=csv")
    # a series name with '/' as an OpenAPI client sends it: percent-encoded
    enc = urllib.parse.quote("groups/right/reaction_force", safe="")
    get_and_head(api, doc, r + "/series/" + enc, label="name with %2F")
    get_and_head(api, doc, r + "/series/nope", 404)
    get_and_head(api, doc, r + "/series/kinetic_energy?format=xml", 400)
    get_and_head(api, doc, r + "/frames")
    get_and_head(api, doc, r + "/fields/position?frame=-1")
    get_and_head(api, doc, r + "/fields/position?frame=-1", headers={"Accept": "application/json"})
    get_and_head(api, doc, r + "/fields/position?frame=x", 400)
    get_and_head(api, doc, r + "/fields/nope", 404)
    get_and_head(api, doc, r + "/summary", 404, label="a run has no summary")
    get_and_head(api, doc, f"/jobs/{ok_id}/log")
    # a failed run, a study
    get_and_head(api, doc, f"/jobs/{bad_id}/results", 422, label="failed: unstable")
    s = f"/jobs/{study_id}/results"
    get_and_head(api, doc, s)
    get_and_head(api, doc, s + "/summary")
    get_and_head(api, doc, s + "/summary?format=csv")
    get_and_head(api, doc, s + "/summary?format=xml", 400)
    get_and_head(api, doc, f"/jobs/{study_id}/log", 404)
    get_and_head(api, doc, s + "/convergence", 404, label="a study that is no convergence")
    c = f"/jobs/{conv_id}/results"
    get_and_head(api, doc, c)
    get_and_head(api, doc, c + "/convergence")
    get_and_head(api, doc, c + "/convergence?format=csv")
    get_and_head(api, doc, c + "/convergence?format=xml", 400)
    get_and_head(api, doc, c + "/summary")
    # cancel, then the dismissed job, then remove
    check(api, doc, "DELETE", f"/jobs/{long_id}", 200)
    wait_final(api, long_id)
    get_and_head(api, doc, f"/jobs/{long_id}/results", 404, label="dismissed")
    check(api, doc, "DELETE", f"/jobs/{long_id}", 200, label="remove")
    check(api, doc, "DELETE", f"/jobs/{long_id}", 404)

    if len(argv) > 3:  # tokens
        tapi = Api(argv[2])
        for p in ["/jobs", "/processes"]:
            check(tapi, doc, "GET", p, 401, label="no token")
        tapi.token = argv[3]
        check(tapi, doc, "GET", "/jobs", 200, label="token")
        for tpl, item in doc.doc["paths"].items():
            for m, op in item.items():
                if not isinstance(op, dict) or m == "parameters":
                    continue
                sec = op.get("security", doc.doc.get("security", []))
                anon = sec == [] or {} in sec
                if not anon and "401" not in op.get("responses", {}):
                    say(False, f"{m.upper()} {tpl}: needs a token but 401 is not documented")
        say(all(op.get("security") == [] or {} in op.get("security", [{}])
                for item in doc.doc["paths"].values()
                for m, op in item.items() if isinstance(op, dict) and m != "parameters"),
            "every operation allows anonymous use (tokens are optional)")

    # every documented operation was exercised
    missing = [f"{m.upper()} {tpl}" for tpl, item in doc.doc["paths"].items()
               for m, op in item.items() if m != "parameters" and
               not any(s[0] == tpl and s[1] == m for s in SEEN)]
    say(not missing, "every documented operation exercised" +
        (": missing " + ", ".join(missing) if missing else ""))
    print(f"# {len(FAILS)} failed")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
