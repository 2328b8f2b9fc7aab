#!/usr/bin/env python3
"""Makes schemas/openapi.json, the API definition tlsphd serves at
/openapi.json, from its source schemas/openapi.src.json.

    bundle_openapi.py [--check] [SRC [DST]]

The source refers to the shipped schema files ("error.schema.json",
"job.schema.json#/$defs/jobList") so that each is written once.  A document
that refers to other files cannot be loaded alone: tools fetch
/openapi.json and resolve "error.schema.json" against it, where the daemon
serves no such file.  The served document is therefore one file:

  - every schema file the source refers to (and each one they refer to) is
    copied into #/components/schemas, without its $schema and $id: the file
    as <stem>Schema ("error.schema.json" -> errorSchema) and each of its
    $defs as <stem>_<name> ("job.schema.json#/$defs/jobList" ->
    job_jobList), and every reference to it or into it, in the source or
    between the files (a file's own "#/$defs/x"), becomes a reference inside
    the document.  The $defs become components of their own because some
    tools resolve a reference by replacing the object that holds it, which
    loses the $defs of a schema whose root is itself a "$ref";
  - every GET operation gets its HEAD twin (the daemon answers HEAD on every
    GET resource): the same parameters, security and status codes, the
    headers, no content, operationId + "Head".

--check: exit 1 unless DST is what SRC makes (tests/daemon/api_openapi.sh).
Standard library only."""
import argparse
import copy
import json
import os
import sys

REF = "$ref"


def component_name(filename):
    return stem_of(filename) + "Schema"


def rewrite(node, own, files, here):
    """Rewrites the references of node (a part of file own, or of the source
    when own is None), loading every file it meets into files."""
    if isinstance(node, dict):
        out = {}
        for k, v in node.items():
            if k == REF and isinstance(v, str):
                out[k] = rewrite_ref(v, own, files, here)
            else:
                out[k] = rewrite(v, own, files, here)
        return out
    if isinstance(node, list):
        return [rewrite(v, own, files, here) for v in node]
    return node


def stem_of(filename):
    return filename[: -len(".schema.json")] if filename.endswith(".schema.json") else filename


def pointer_in(filename, frag):
    """Where fragment frag of file filename lands in the document."""
    if frag.startswith("/$defs/"):
        name, _, rest = frag[len("/$defs/"):].partition("/")
        return "#/components/schemas/" + stem_of(filename) + "_" + name + ("/" + rest if rest else "")
    return "#/components/schemas/" + component_name(filename) + frag


def rewrite_ref(ref, own, files, here):
    target, _, frag = ref.partition("#")
    if not target:  # inside the same document
        return ref if own is None else pointer_in(own, frag)
    if "/" in target or ":" in target:
        raise SystemExit(f"bundle_openapi.py: cannot bundle the reference {ref!r}")
    if target not in files:
        files[target] = None  # mark before recursing (files may refer to each other)
        with open(os.path.join(here, target), encoding="utf-8") as f:
            doc = json.load(f)
        doc.pop("$schema", None)
        doc.pop("$id", None)
        files[target] = rewrite(doc, target, files, here)
    return pointer_in(target, frag)


def head_twin(get):
    head = {}
    for k, v in get.items():
        if k == "operationId":
            head[k] = v + "Head"
        elif k == "summary":
            head[k] = v + " (headers only)"
        elif k == "responses":
            head[k] = {}
            for status, resp in v.items():
                r = {key: copy.deepcopy(val) for key, val in resp.items() if key != "content"}
                head[k][status] = r
        else:
            head[k] = copy.deepcopy(v)
    return head


def bundle(src_path):
    here = os.path.dirname(os.path.abspath(src_path))
    with open(src_path, encoding="utf-8") as f:
        src = json.load(f)
    files = {}
    doc = rewrite(src, None, files, here)
    schemas = doc.setdefault("components", {}).setdefault("schemas", {})
    for name in sorted(files):
        parts = {component_name(name): files[name]}
        for def_name, schema in files[name].pop("$defs", {}).items():
            parts[stem_of(name) + "_" + def_name] = schema
        for key, schema in parts.items():
            if key in schemas:
                raise SystemExit(f"bundle_openapi.py: component {key} exists in the source")
            schemas[key] = schema
    for item in doc.get("paths", {}).values():
        if "get" in item and "head" not in item:
            twin = head_twin(item["get"])
            # keep the method order of the source, HEAD right after GET
            rebuilt = {}
            for method, op in item.items():
                rebuilt[method] = op
                if method == "get":
                    rebuilt["head"] = twin
            item.clear()
            item.update(rebuilt)
    return doc


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description="Makes schemas/openapi.json from its source.")
    parser.add_argument("--check", action="store_true", help="exit 1 unless DST is up to date")
    parser.add_argument("src", nargs="?", default=os.path.join(here, "openapi.src.json"))
    parser.add_argument("dst", nargs="?")
    opts = parser.parse_args(argv)
    dst = opts.dst or os.path.join(os.path.dirname(opts.src), "openapi.json")
    text = json.dumps(bundle(opts.src), indent=2, ensure_ascii=False) + "\n"
    if not opts.check:
        with open(dst, "w", encoding="utf-8") as f:
            f.write(text)
        return 0
    with open(dst, encoding="utf-8") as f:
        if f.read() == text:
            return 0
    print(f"{dst} is not what {opts.src} makes: run python3 schemas/bundle_openapi.py",
          file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
