#!/usr/bin/env python3
"""Renders schemas/openapi.json (the source, served by tlsphd at /openapi.json)
as schemas/openapi.yaml.

    json2yaml.py [--check] [JSON [YAML]]

--check: exit 1 unless YAML parses to exactly the same document as JSON
(tests/daemon/openapi_check.sh runs this)."""
import json
import os
import sys

import yaml

HEADER = ("# Generated from openapi.json by json2yaml.py - do not edit; edit openapi.src.json\n"
          "# and run: python3 schemas/bundle_openapi.py && python3 schemas/json2yaml.py\n")


def main(argv):
    check = "--check" in argv
    args = [a for a in argv if a != "--check"]
    here = os.path.dirname(os.path.abspath(__file__))
    src = args[0] if args else os.path.join(here, "openapi.json")
    dst = args[1] if len(args) > 1 else os.path.join(os.path.dirname(src), "openapi.yaml")
    with open(src, encoding="utf-8") as f:
        doc = json.load(f)
    if check:
        with open(dst, encoding="utf-8") as f:
            other = yaml.safe_load(f)
        if other != doc:
            print(f"{dst} differs from {src}: run python3 schemas/json2yaml.py", file=sys.stderr)
            return 1
        return 0
    text = yaml.safe_dump(doc, sort_keys=False, allow_unicode=True, width=100)
    with open(dst, "w", encoding="utf-8") as f:
        f.write(HEADER + text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
