#!/usr/bin/env python3
"""Validates a JSON document (stdin) against the shipped schemas.

    validate.py NAME [--each KEY] < body.json

NAME is a schema file stem under schemas/ ("job" -> schemas/job.schema.json,
"error", "study", "execute", "scene"), optionally with a fragment
("job#/$defs/jobList"), or "openapi:COMPONENT" for a schema in
schemas/openapi.json#/components/schemas/COMPONENT.  --each KEY validates
every element of the array body[KEY] instead of the body.  References between
the files resolve locally (JSON Schema draft 2020-12).  Exit 0 valid, 1 invalid,
2 usage / missing schema.  SCHEMAS_DIR overrides the schema directory."""
import json
import os
import sys

import jsonschema

BASE = "https://tlsph.invalid/schemas/"


def load_store(d):
    store = {}
    for name in sorted(os.listdir(d)):
        if not name.endswith(".json"):
            continue
        with open(os.path.join(d, name), encoding="utf-8") as f:
            doc = json.load(f)
        store[BASE + name] = doc
        if isinstance(doc, dict) and isinstance(doc.get("$id"), str):
            store[doc["$id"]] = doc
    return store


def main(argv):
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    each = None
    if "--each" in argv:
        i = argv.index("--each")
        each = argv[i + 1]
        argv = argv[:i] + argv[i + 2:]
    name = argv[0]
    here = os.path.dirname(os.path.abspath(__file__))
    d = os.environ.get("SCHEMAS_DIR") or os.path.join(here, "..", "..", "schemas")
    store = load_store(d)
    if name.startswith("openapi:"):
        uri = BASE + "openapi.json"
        ref = uri + "#/components/schemas/" + name.split(":", 1)[1]
    else:
        stem, _, frag = name.partition("#")
        uri = BASE + stem + ".schema.json"
        ref = uri + ("#" + frag if frag else "")
    if uri not in store:
        print(f"validate.py: no schema {uri} in {d}", file=sys.stderr)
        return 2
    schema = {"$schema": "https://json-schema.org/draft/2020-12/schema", "$ref": ref}
    def refuse(url):
        raise ValueError(f"not a local schema: {url}")
    resolver = jsonschema.RefResolver(base_uri=uri, referrer=store[uri], store=store,
                                      handlers={"http": refuse, "https": refuse})
    v = jsonschema.Draft202012Validator(schema, resolver=resolver,
                                        format_checker=jsonschema.Draft202012Validator.FORMAT_CHECKER)
    try:
        body = json.load(sys.stdin)
    except ValueError as e:
        print(f"validate.py: body is not JSON: {e}", file=sys.stderr)
        return 1
    docs = body.get(each, None) if each else [body]
    if not isinstance(docs, list):
        print(f"validate.py: body has no array '{each}'", file=sys.stderr)
        return 1
    bad = 0
    try:
        for doc in docs:
            for err in v.iter_errors(doc):
                path = "/".join(str(p) for p in err.absolute_path)
                print(f"validate.py: {name}: /{path}: {err.message[:300]}", file=sys.stderr)
                bad += 1
    except jsonschema.exceptions.RefResolutionError as e:
        print(f"validate.py: unresolved reference: {e}", file=sys.stderr)
        return 2
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
