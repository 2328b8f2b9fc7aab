#!/usr/bin/python3
"""Checks the daemon's JSON Schemas and validates example bodies against them.

usage: validate_examples.py [SCHEMA_DIR [EXAMPLES_DIR]]
       (defaults: $top_srcdir/schemas and $top_srcdir/tests/daemon/examples)

1. Every schemas/*.schema.json is a valid draft 2020-12 schema.
2. Every example in EXAMPLES validates against its schema (cross-file $refs
   such as study.schema.json -> scene.schema.json resolve from SCHEMA_DIR,
   never from the network).
3. Mutated copies that break the contract (unknown keys, bad enums, ...) are
   rejected, so the schemas really are strict.
Prints one line per check; exits 1 on any failure, 77 (skip) without jsonschema.
"""
import copy
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    print("SKIP: python3-jsonschema is not installed")
    sys.exit(77)

TOP = os.environ.get("top_srcdir", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCHEMAS = sys.argv[1] if len(sys.argv) > 1 else os.path.join(TOP, "schemas")
EXAMPLES = sys.argv[2] if len(sys.argv) > 2 else os.path.join(TOP, "tests", "daemon", "examples")

# example file -> (schema file, sub-schema pointer or "")
TARGETS = {
    "status_info.json": ("job.schema.json", ""),
    "job_list.json": ("job.schema.json", "#/$defs/jobList"),
    "problem.json": ("error.schema.json", ""),
    "problem_no_such_job.json": ("error.schema.json", ""),
    "study.json": ("study.schema.json", ""),
    "summary.json": ("study.schema.json", "#/$defs/summary"),
    "execute_run.json": ("execute.schema.json", ""),
    "execute_study.json": ("execute.schema.json", ""),
}


def load(path):
    with open(path) as f:
        return json.load(f)


schemas = {}
for name in sorted(os.listdir(SCHEMAS)):
    if name.endswith(".schema.json"):
        schemas[name] = load(os.path.join(SCHEMAS, name))


def make_validator(schema_name, fragment):
    root = schemas[schema_name]
    base = root.get("$id", schema_name)
    schema = {"$ref": base + fragment} if fragment else root
    try:  # jsonschema >= 4.18
        from referencing import Registry, Resource

        registry = Registry().with_resources(
            (s.get("$id", n), Resource.from_contents(s)) for n, s in schemas.items())
        return jsonschema.Draft202012Validator(schema, registry=registry)
    except ImportError:  # Debian 12: jsonschema 4.10 (RefResolver)
        store = {s.get("$id", n): s for n, s in schemas.items()}
        resolver = jsonschema.RefResolver(base_uri=base, referrer=root, store=store)
        return jsonschema.Draft202012Validator(schema, resolver=resolver)


failures = 0


def report(ok, what, why=""):
    global failures
    print("%s: %s%s" % ("ok" if ok else "FAIL", what, (" (" + why + ")") if why else ""))
    if not ok:
        failures += 1


for name, schema in schemas.items():
    try:
        jsonschema.Draft202012Validator.check_schema(schema)
        report(True, "schema " + name)
    except jsonschema.SchemaError as e:
        report(False, "schema " + name, e.message)

validators = {}
examples = {}
for example, (schema_name, fragment) in sorted(TARGETS.items()):
    path = os.path.join(EXAMPLES, example)
    instance = load(path)
    examples[example] = instance
    v = make_validator(schema_name, fragment)
    validators[example] = v
    errs = sorted(v.iter_errors(instance), key=lambda e: list(e.absolute_path))
    report(not errs, "%s valid against %s%s" % (example, schema_name, fragment),
           "; ".join("/%s: %s" % ("/".join(map(str, e.absolute_path)), e.message[:200]) for e in errs[:3]))


def set_at(doc, path, value):
    for key in path[:-1]:
        doc = doc[key]
    if value is DELETE:
        del doc[path[-1]]
    else:
        doc[path[-1]] = value


DELETE = object()

# (example, path, new value, what): each mutation must be rejected
MUTATIONS = [
    ("status_info.json", ["extra"], 1, "unknown key"),
    ("status_info.json", ["status"], "succeeded", "1.1-draft status name"),
    ("status_info.json", ["type"], "job", "type is not process"),
    ("status_info.json", ["jobID"], DELETE, "missing jobID"),
    ("status_info.json", ["progress"], 101, "progress > 100"),
    ("status_info.json", ["progress"], 50.5, "progress not integer"),
    ("status_info.json", ["created"], "2024-05-01 10:00", "not RFC 3339"),
    ("status_info.json", ["cost", "gpu_seconds"], 1, "unknown cost key"),
    ("status_info.json", ["simulation", "frames"], 1, "unknown simulation key"),
    ("status_info.json", ["links", 0, "foo"], 1, "unknown link key"),
    ("status_info.json", ["outcome"], "exploded", "unknown outcome"),
    ("job_list.json", ["jobs", 0, "status"], "done", "bad status inside a list"),
    ("job_list.json", ["total"], 3, "unknown list key"),
    ("problem.json", ["errors", 0, "pointer"], "/inputs/x", "pointer without #"),
    ("problem.json", ["errors", 0, "field"], "x", "unknown error key"),
    ("problem.json", ["status"], 200, "status not an error"),
    ("problem.json", ["type"], DELETE, "missing type"),
    ("study.json", ["sweep", "mode"], "diagonal", "bad mode"),
    ("study.json", ["sweep", "parameters"], [], "empty parameters"),
    ("study.json", ["sweep", "parameters", 0, "range"], {"start": 0, "stop": 1, "num": 2}, "values and range"),
    ("study.json", ["sweep", "parameters", 1, "range", "num"], 0, "num 0"),
    ("study.json", ["sweep", "parameters", 1, "range", "step"], 1, "unknown range key"),
    ("study.json", ["sweep", "parameters", 0, "pointer"], "bodies/0/spacing", "pointer without /"),
    ("study.json", ["sweep", "parameters", 0, "pointer"], "/a~2", "bad pointer escape"),
    ("study.json", ["outputs", 0, "reduce"], "mean", "bad reduce"),
    ("study.json", ["outputs", 0, "component"], 3, "component 3"),
    ("study.json", ["outputs", 0, "series"], "../x", "series with .."),
    ("study.json", ["outputs", 0, "name"], "steps", "reserved output name"),
    ("study.json", ["outputs", 0, "name"], "a b", "bad output name"),
    ("study.json", ["base", "dimension"], 4, "base is checked against the scene schema"),
    ("study.json", ["base", "bogus"], 1, "unknown scene key"),
    ("study.json", ["extra"], 1, "unknown study key"),
    ("summary.json", ["rows", 0, 0], "zero", "seq not an integer"),
    ("summary.json", ["columns", 0], "index", "first column not seq"),
    ("summary.json", ["extra"], 1, "unknown summary key"),
    ("execute_run.json", ["inputs", "scene", "dimension"], 1, "bad scene in run"),
    ("execute_run.json", ["callback"], {}, "unknown execute key"),
    ("execute_run.json", ["inputs", "extra"], 1, "unknown input"),
    ("execute_study.json", ["inputs", "sweep"], DELETE, "study without sweep"),
]

for example, path, value, what in MUTATIONS:
    doc = copy.deepcopy(examples[example])
    set_at(doc, path, value)
    ok = not validators[example].is_valid(doc)
    report(ok, "%s rejects %s" % (example, what), "" if ok else "accepted")

sys.exit(1 if failures else 0)
