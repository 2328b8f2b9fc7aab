#!/usr/bin/env python3
"""Checks `tlsph study table` output (stdlib only).

  table_check.py FILE WIDTH COLUMN...
      every line has at most WIDTH characters; the output is blocks (separated
      by a blank line) of a header line and rows, each block starting with
      seq; every COLUMN (a header text such as "wall [s]") is present, and its
      numbers (every cell but "-") have 4 significant digits (zero aside) and are aligned:
      all on one decimal point position or all ending at one position."""
import re, sys


def fail(msg):
    print("table_check: " + msg)
    sys.exit(1)


def cells(line):
    """(text, start, end) of the cells: separated by two or more spaces."""
    return [(m.group(0), m.start(), m.end()) for m in re.finditer(r"\S+(?: \S+)*", line)]


def significant(t):
    mant = t.lstrip("+-").split("e")[0]
    return len(mant.replace(".", "").lstrip("0")) or 1


def main():
    path, width, wanted = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    lines = open(path).read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    for i, l in enumerate(lines):
        if len(l) > width:
            fail("line %d has %d characters (> %d): %r" % (i + 1, len(l), width, l))
    blocks, cur = [], []
    for l in lines + [""]:
        if l.strip():
            cur.append(l)
        elif cur:
            blocks.append(cur)
            cur = []
    found = set()
    for b in blocks:
        head = cells(b[0])
        if head[0][0] != "seq":
            fail("a block starts with %r, not seq" % head[0][0])
        rows = [cells(l) for l in b[1:]]
        for r in rows:
            if len(r) != len(head):
                fail("row %r has %d cells for %d columns" % (r, len(r), len(head)))
        for k, (name, _, _) in enumerate(head):
            if name not in wanted:
                continue
            found.add(name)
            nums = [r[k] for r in rows if r[k][0] != "-"]
            for t, _, _ in nums:
                if re.match(r"^-?0(\.0*)?(e[+-]00)?$", t):
                    continue  # zero has no significant digits to count
                if not re.match(r"^-?\d+(\.\d+)?(e[+-]\d+)?$", t) or significant(t) != 4:
                    fail("column %s: %r is not a number with 4 significant digits" % (name, t))
            dots = {s + t.find(".") if "." in t and "e" not in t else s + len(t) for t, s, _ in nums}
            ends = {e for _, _, e in nums}
            if len(dots) > 1 and len(ends) > 1:
                fail("column %s: numbers not aligned: %s" % (name, [t for t, _, _ in nums]))
    missing = [w for w in wanted if w not in found]
    if missing:
        fail("no column headed %s in %s" % (missing, [c[0] for b in blocks for c in cells(b[0])]))
    print("table ok: %d blocks, %d lines" % (len(blocks), len(lines)))


if __name__ == "__main__":
    main()
