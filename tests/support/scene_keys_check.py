#!/usr/bin/python3
"""Compares the engine's scene key tables with the scene schema and the scene docs.

usage: scene_keys_check.py TABLES.json SCHEMA DOCS

TABLES.json is what tests/engine/test_scene_keys --json prints: every key table
of core/scene/keys.h (path of the object, the model that selects it, and per
key its kind, presence, range, unit, default and "only with" switch).  The
tables are the reference, checked in both directions:

schemas/scene.schema.json: each table's object (found by its path; a model's
  branch of a oneOf by its "type" const) has exactly the table's keys; per key
  the JSON type, minimum / maximum / exclusive bounds, enum values, "default"
  (and a "default X" in the description), required and dependentRequired, the
  x-unit and the unit in the description's parentheses (vectors read by the
  caller too).  A table whose object holds exactly one of its keys (a
  geometry) is a oneOf of one-key branches.
docs/scene.md: every table marked <!-- keys PATH[,PATH...] [MODEL] --> documents only keys
  the engine accepts, with the same unit, default (or "**required**",
  "required with `X`") and range; every key of every table is documented.  In
  a family's table (PATH of models chosen by "type", no MODEL) a "type" column
  names the model of its row and the rows after it; "every type" documents a
  key of every model.

Prints one line per problem; exits 1 when there is one."""
import json
import re
import sys

PROBLEMS = []


def problem(msg):
    PROBLEMS.append(msg)


def where(path, model, key=None):
    s = (path or "/") + (" [%s]" % model if model else "")
    return s + (" %s" % key if key else "")


# ------------------------------------------------------------------ schema

def deref(schema, node):
    while isinstance(node, dict) and "$ref" in node:
        ref = node["$ref"]
        if not ref.startswith("#/"):
            raise ValueError("external $ref " + ref)
        node = schema
        for part in ref[2:].split("/"):
            node = node[part]
    return node


def branches(schema, node, model):
    """The object schemas a node stands for: itself, or its oneOf branches (only the
    model's, selected by its "type" const, when a model is given and the branches
    have one)."""
    node = deref(schema, node)
    if "oneOf" not in node:
        return [node]
    out = []
    for b in node["oneOf"]:
        b = deref(schema, b)
        const = b.get("properties", {}).get("type", {}).get("const")
        if model is None or const is None or const == model:
            out.append(b)
    return out


def resolve(schema, path, model):
    nodes = [schema]
    for seg in [s for s in path.split("/")[1:]]:
        nxt = []
        for n in nodes:
            for b in branches(schema, n, model):
                if seg == "*":
                    child = b.get("additionalProperties") or b.get("items")
                    child = child if isinstance(child, dict) else None
                else:
                    child = b.get("properties", {}).get(seg)
                if child is not None:
                    nxt.append(child)
        nodes = nxt
    return [b for n in nodes for b in branches(schema, n, model)]


def same_number(a, b):
    return isinstance(b, (int, float)) and not isinstance(b, bool) and float(a) == float(b)


def value_text(v):
    return json.dumps(v)


def check_bounds(w, key, prop):
    for side, plain, excl in (("minimum", "minimum", "exclusiveMinimum"),
                              ("maximum", "maximum", "exclusiveMaximum")):
        bound, is_open = key.get(side), key.get(side + "_open")
        if bound is None:
            for k in (plain, excl):
                if k in prop:
                    problem("%s: schema has %s %s, the engine has no %s" % (w, k, prop[k], side))
            continue
        want, other = (excl, plain) if is_open else (plain, excl)
        if not same_number(bound, prop.get(want)):
            problem("%s: schema %s is %s, the engine's is %s" %
                    (w, want, value_text(prop.get(want)), value_text(bound)))
        if other in prop:
            problem("%s: schema has %s, the engine's %s is %s" %
                    (w, other, side, "open" if is_open else "closed"))


def description_default(desc):
    m = re.search(r"\bdefault (?:is )?(-?[\w.+]+)", desc or "")
    return m.group(1) if m else None


def check_default(w, key, prop):
    engine = key["default"] if not key["required"] else None
    if engine is None:
        if "default" in prop:
            problem("%s: schema default %s, the engine has none" % (w, value_text(prop["default"])))
        return
    schema_default = prop.get("default")
    ok = (same_number(engine, schema_default) if isinstance(engine, (int, float))
          and not isinstance(engine, bool) else schema_default == engine)
    if not ok:
        problem("%s: schema default %s, the engine's is %s" %
                (w, value_text(schema_default), value_text(engine)))
    said = description_default(prop.get("description"))
    if said is not None:
        try:
            said_ok = float(said) == float(engine) if not isinstance(engine, (bool, str)) else \
                said == (json.dumps(engine) if isinstance(engine, bool) else engine)
        except ValueError:
            said_ok = True  # "default the distance ...": not a value
        if not said_ok:
            problem("%s: schema description says default %s, the engine's is %s" %
                    (w, said, value_text(engine)))


def check_unit(w, key, prop):
    unit = key["unit"]
    if prop.get("x-unit") != unit:
        problem("%s: schema x-unit %s, the engine's unit is %s" %
                (w, value_text(prop.get("x-unit")), value_text(unit)))
    desc = prop.get("description", "")
    if "(%s)" % unit not in desc and "(%s;" % unit not in desc and \
            not (unit == "1" and "dimensionless)" in desc):
        problem("%s: schema description does not state the unit (%s): %r" % (w, unit, desc))


SCHEMA_TYPES = {"number": "number", "integer": "integer", "boolean": "boolean",
                "string": "string", "array": "array", "expression": "string"}


NAME_PATTERN = None  # the naming rule (core/util/names.h), from the tables' JSON


def check_name_rule(schema, w, key, prop):
    """A name (or an object whose member names are names) must carry the
    naming rule's pattern in the schema."""
    if key.get("map"):
        prop = deref(schema, prop.get("propertyNames", {}))
    if key.get("name_rule") and prop.get("pattern") != NAME_PATTERN:
        problem("%s: schema pattern %s, the engine's naming rule is %s" %
                (w, prop.get("pattern"), NAME_PATTERN))
    if not key.get("name_rule") and prop.get("pattern") == NAME_PATTERN:
        problem("%s: schema has the naming rule's pattern, the engine does not check it" % w)


def check_key_schema(schema, w, key, prop, required, dependent):
    prop = deref(schema, prop)
    kind = key["kind"]
    name = key["name"]
    check_name_rule(schema, w, key, prop)
    unconditional = key["required"] and not key["with"]
    if unconditional != (name in required):
        problem("%s: required in the %s only" % (w, "engine" if unconditional else "schema"))
    if key["with"]:
        if key["with"] not in dependent.get(name, []):
            problem("%s: schema lacks dependentRequired %s: [%s] (only with it)" %
                    (w, name, key["with"]))
        if key["required"] and name not in dependent.get(key["with"], []):
            problem("%s: schema lacks dependentRequired %s: [%s] (required with it)" %
                    (w, key["with"], name))
    if key.get("caller") and kind in ("object", "array", "string", "expression") and \
            name != "type":
        want = SCHEMA_TYPES.get(kind)
        if want and prop.get("type", want) != want:
            problem("%s: schema type %s, the engine reads a %s" % (w, prop.get("type"), kind))
        if kind == "array" and key["unit"]:  # a vector read by the caller
            check_unit(w, key, prop)
        return
    if name == "type" and "const" in prop:
        return
    if kind == "choice":
        if prop.get("enum") != key["choices"]:
            problem("%s: schema enum %s, the engine accepts %s" %
                    (w, prop.get("enum"), key["choices"]))
    elif kind == "object":
        if prop.get("type") not in (None, "object"):
            problem("%s: schema type %s, the engine reads an object" % (w, prop.get("type")))
        return
    elif prop.get("type") != SCHEMA_TYPES[kind]:
        problem("%s: schema type %s, the engine reads a %s" % (w, prop.get("type"), kind))
    if kind in ("number", "integer"):
        check_bounds(w, key, prop)
        check_unit(w, key, prop)
        if key["below_youngs_modulus"] and "youngs_modulus" not in prop.get("description", ""):
            problem("%s: schema description does not say it must be below the youngs_modulus" % w)
    if kind == "string" and prop.get("maxLength") != key["max_length"]:
        problem("%s: schema maxLength %s, the engine's is %s" %
                (w, prop.get("maxLength"), key["max_length"]))
    check_default(w, key, prop)


def check_one_of(schema, t, nodes):
    """A table whose object holds exactly one of its keys (a geometry): one schema
    branch per key, each with that key alone, required."""
    props = {}
    for node in nodes:
        own = node.get("properties", {})
        if len(own) != 1 or node.get("required") != list(own) or \
                node.get("additionalProperties", True) is not False:
            problem("%s: schema branch %s is not one required key and nothing else" %
                    (where(t["path"], t["model"]), sorted(own)))
        props.update(own)
    names = [k["name"] for k in t["keys"]]
    for extra in sorted(set(props) - set(names)):
        problem("%s: in the schema, not accepted by the engine" %
                where(t["path"], t["model"], extra))
    for k in t["keys"]:
        w = where(t["path"], t["model"], k["name"])
        if k["name"] not in props:
            problem("%s: accepted by the engine, not in the schema" % w)
        else:
            check_key_schema(schema, w, k, props[k["name"]], [], {})


def check_schema(schema, tables):
    for t in tables:
        nodes = resolve(schema, t["path"], t["model"])
        if not nodes:
            problem("%s: no object in the schema" % where(t["path"], t["model"]))
            continue
        if t.get("one_of"):
            check_one_of(schema, t, nodes)
            continue
        names = [k["name"] for k in t["keys"] if not k["refused"]]
        for node in nodes:
            props = node.get("properties", {})
            for extra in sorted(set(props) - set(names)):
                problem("%s: in the schema, not accepted by the engine" %
                        where(t["path"], t["model"], extra))
            if node.get("additionalProperties", False) is not False and not t["path"] == "":
                problem("%s: schema allows additional properties" % where(t["path"], t["model"]))
            for k in t["keys"]:
                w = where(t["path"], t["model"], k["name"])
                if k["refused"]:
                    if k["name"] in props:
                        problem("%s: refused by the engine, in the schema" % w)
                    continue
                if k["name"] not in props:
                    problem("%s: accepted by the engine, not in the schema" % w)
                    continue
                check_key_schema(schema, w, k, props[k["name"]], node.get("required", []),
                                 node.get("dependentRequired", {}))
    # every model of a family (the tables a "type" key chooses) the engine knows,
    # and no other
    families = {}
    for t in tables:
        if t["model"] and t["keys"][0]["name"] == "type":
            families.setdefault(t["path"], set()).add(t["model"])
    for path, models in families.items():
        consts = {b.get("properties", {}).get("type", {}).get("const")
                  for b in resolve(schema, path, None)}
        if consts != models:
            problem("%s: schema models %s, engine models %s" % (path, sorted(consts - {None}),
                                                              sorted(models)))


# ------------------------------------------------------------------ docs

MARK = re.compile(r"^<!--\s*keys\s+(\S+)(?:\s+(\S+))?\s*-->\s*$")
NUM = r"[-−]?\d[\d ]*(?:\.\d+)?(?:e[-+−]?\d+)?"


def number(text):
    return float(text.replace(" ", "").replace("−", "-"))


def doc_tables(doc):
    lines = doc.splitlines()
    out = []
    for i, line in enumerate(lines):
        m = MARK.match(line.strip())
        if not m:
            continue
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        rows = []
        while j < len(lines) and lines[j].strip().startswith("|"):
            rows.append([c.strip() for c in lines[j].strip().strip("|").split("|")])
            j += 1
        if len(rows) < 3:
            problem("docs line %d: marker without a table" % (i + 1))
            continue
        for path in m.group(1).split(","):  # one table documents every path it lists
            path = "" if path == "/" else path
            out.append((i + 1, path, m.group(2), rows[0], rows[2:]))
    return out


def unit_of(cell):
    cell = cell.strip()
    if cell in ("—", "-", ""):
        return None
    cell = re.sub(r"\s+\(.*\)$", "", cell)  # "m² (m in 2-D)", not "J/(kg K)"
    return cell.replace("³", "^3").replace("²", "^2")


def doc_value(cell):
    """The value a default cell starts with, or None."""
    c = cell.replace("`", "").strip()
    m = re.match(r"^(%s)(?![\w.])" % NUM, c)
    if m:
        return number(m.group(1))
    m = re.match(r'^"([^"]*)"', c)
    if m:
        return m.group(1)
    m = re.match(r"^(true|false)\b", c)
    if m:
        return m.group(1) == "true"
    return None


def doc_range(cell):
    """(minimum, open, maximum, open, maximum is E) from the start of a range cell."""
    c = re.sub(r"^integer(\s+in)?\s*", "", cell.replace("`", "").strip())
    m = re.match(r"^([(\[])\s*(%s)\s*,\s*(%s|E)\s*([)\]])" % (NUM, NUM), c)
    if m:
        below_e = m.group(3) == "E"
        return (number(m.group(2)), m.group(1) == "(",
                None if below_e else number(m.group(3)), m.group(4) == ")", below_e)
    m = re.match(r"^(>=|≥|>)\s*(%s)" % NUM, c)
    if m:
        return (number(m.group(2)), m.group(1) == ">", None, False, False)
    m = re.match(r"^(<=|≤|<)\s*(%s)" % NUM, c)
    if m:
        return (None, False, number(m.group(2)), m.group(1) == "<", False)
    if c.startswith("any"):
        return (None, False, None, False, False)
    return None


def check_doc_row(w, key, cols, row, dotted_parent):
    cell = dict(zip(cols, row))
    default = cell.get("default")
    if default is not None:
        plain = default.replace("`", "")
        if plain.startswith("**required**"):
            if not (key["required"] and not key["with"] and not dotted_parent):
                problem("%s: docs say required, the engine does not" % w)
        elif plain.startswith("required with"):
            m = re.match(r"required with (\w+)", plain)
            if not key["required"] or not m or m.group(1) not in (key["with"], dotted_parent):
                problem("%s: docs say %r, the engine: required %s, only with %s" %
                        (w, default, key["required"], key["with"]))
        else:
            if key["required"] and not key["with"] and not dotted_parent:
                problem("%s: required by the engine, docs give a default %r" % (w, default))
            if not key["caller"] and key["kind"] != "object":
                value = doc_value(default)
                engine = key["default"]
                if engine is None and value is not None:
                    problem("%s: docs default %r, the engine has none" % (w, default))
                elif engine is not None and (value is None or (
                        float(value) != float(engine) if isinstance(value, float) else
                        value != engine)):
                    problem("%s: docs default %r, the engine's is %s" %
                            (w, default, value_text(engine)))
    if "unit" in cell and unit_of(cell["unit"]) != key["unit"]:
        problem("%s: docs unit %r, the engine's is %s" % (w, cell["unit"], value_text(key["unit"])))
    if key["kind"] == "choice":  # every choice quoted in the row, and nothing else
        quoted = re.findall(r'"([^"]+)"', " ".join(row))
        if sorted(set(quoted)) != sorted(key["choices"]):
            problem("%s: docs choices %s, the engine accepts %s" %
                    (w, sorted(set(quoted)), key["choices"]))
    rng = cell.get("range")
    if rng is None:
        return
    if key["kind"] in ("number", "integer"):
        parsed = doc_range(rng)
        if parsed is None:
            problem("%s: docs range %r does not start with an interval" % (w, rng))
            return
        lo, lo_open, hi, hi_open, below_e = parsed
        engine = (key["minimum"], key["minimum_open"] if key["minimum"] is not None else False,
                  key["maximum"], key["maximum_open"] if key["maximum"] is not None else False,
                  key["below_youngs_modulus"])
        if (lo, lo_open if lo is not None else False, hi,
                hi_open if hi is not None else False, below_e) != engine:
            problem("%s: docs range %r, the engine's is %s" % (w, rng, engine_range(key)))
    elif key["kind"] == "boolean" and not rng.startswith("boolean"):
        problem("%s: docs range %r for a boolean" % (w, rng))


def engine_range(key):
    lo = "(" if key["minimum_open"] else "["
    hi = ")" if key["maximum_open"] or key["below_youngs_modulus"] else "]"
    a = "-inf" if key["minimum"] is None else "%g" % key["minimum"]
    b = "E" if key["below_youngs_modulus"] else "inf" if key["maximum"] is None else "%g" % key["maximum"]
    return "%s%s, %s%s" % (lo, a, b, hi)


EVERY_TYPE = "every type"


def check_doc_field(line, path, m, field, cols, row, index, documented):
    """One documented field (dotted into linked tables) of model m's table at path."""
    t = index.get((path, m)) or index.get((path, None))
    if t is None:
        problem("docs line %d: %s documented, the engine has no such model" %
                (line, where(path, m, field)))
        return
    parts = field.split(".")
    key, parent = None, None
    for depth, part in enumerate(parts):
        key = next((k for k in t["keys"] if k["name"] == part), None)
        if key is None or key["refused"]:
            key = None
            break
        documented.add((t["path"], t["model"], part))
        if depth < len(parts) - 1:
            if not key.get("table"):
                key = None
                break
            parent = part
            t = index.get((key["table"], m)) or index.get((key["table"], None))
    w = "docs line %d: %s" % (line, where(path, m, field))
    if key is None:
        problem("%s: documented, not accepted by the engine" % w)
        return
    check_doc_row(w, key, cols, row, parent)


def check_docs(doc, tables):
    index = {(t["path"], t["model"]): t for t in tables}
    families = {}
    for t in tables:
        if t["model"]:
            families.setdefault(t["path"], []).append(t["model"])
    documented = set()
    linked_docs = set()
    for line, path, model, header, rows in doc_tables(doc):
        cols = [h.lower() for h in header]
        if "field" not in cols:
            problem("docs line %d: table without a 'field' column" % line)
            continue
        if (path, model) not in index and not (path in families and model is None):
            problem("docs line %d: no engine table at %s" % (line, where(path, model)))
            continue
        linked_docs.add((path, model))
        family = path in families and model is None
        current = None
        for row in rows:
            cell = dict(zip(cols, row))
            if family:  # the type column names the model; "every type": a key they share
                if cell.get("type", "").strip("`"):
                    current = cell["type"].strip("`")
                models = families[path] if current == EVERY_TYPE else [current]
            else:
                models = [model]
            for m in models:
                check_doc_field(line, path, m, cell["field"].strip("`"), cols, row, index,
                                documented)
    for t in tables:
        for k in t["keys"]:
            if k["refused"] or (t["model"] and k["name"] == "type"):
                continue
            if (t["path"], t["model"], k["name"]) in documented:
                continue
            if k.get("table") and any(p == k["table"] for p, _ in linked_docs):
                continue
            problem("%s: accepted by the engine, not in docs/scene.md" %
                    where(t["path"], t["model"], k["name"]))


def main(argv):
    if len(argv) != 4:
        print(__doc__)
        return 2
    global NAME_PATTERN
    keys = json.load(open(argv[1]))
    tables = keys["tables"]
    NAME_PATTERN = keys["name_pattern"]
    schema = json.load(open(argv[2]))
    doc = open(argv[3], encoding="utf-8").read()
    check_schema(schema, tables)
    check_docs(doc, tables)
    nkeys = sum(len(t["keys"]) for t in tables)
    for p in PROBLEMS:
        print("FAIL " + p)
    print("scene keys: %d tables, %d keys; %d problems with %s and %s" %
          (len(tables), nkeys, len(PROBLEMS), argv[2], argv[3]))
    return 1 if PROBLEMS else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
