#!/usr/bin/python3
"""Every relative link in README.md and docs/*.md points at a file that exists,
and every #fragment at a heading of its target page.

Fragments follow the forge's heading slugs (the rule GitHub and GitLab render
Markdown with): the heading's text lower-cased, every character that is not
a letter, digit, '_', '-' or space removed, spaces turned into '-', and a
repeated slug numbered -1, -2, ...  A link such as
crack-growth.md#the-crack-driver to the heading
"The crack driver (`core/crack/crack_driver.{c,h}`)" does not resolve: the
file names in the heading are part of its slug.

Fenced code blocks are skipped (their '#' lines are not headings, their
brackets not links).  Environment: top_srcdir (set by make check; default
../.. of this script).  Prints each broken link; exits 1 if there is one.
"""
import os
import re
import sys

FENCE = re.compile(r"^```.*?^```", re.S | re.M)
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$", re.M)
LINK = re.compile(r"\]\(([^)\s]+)\)")


def slug(text):
    text = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return text.replace(" ", "-")


def anchors(markdown):
    seen = {}
    out = set()
    for m in HEADING.finditer(FENCE.sub("", markdown)):
        s = slug(m.group(1))
        k = seen.get(s, 0)
        seen[s] = k + 1
        out.add(s if k == 0 else "%s-%d" % (s, k))
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    top = os.environ.get("top_srcdir") or os.path.join(here, "..", "..")
    pages = ["README.md"] + sorted(os.path.join("docs", n) for n in os.listdir(os.path.join(top, "docs"))
                                   if n.endswith(".md"))
    text = {}
    for p in pages:
        with open(os.path.join(top, p), encoding="utf-8") as f:
            text[p] = f.read()
    heads = {p: anchors(t) for p, t in text.items()}
    links = bad = 0
    for p in pages:
        for m in LINK.finditer(FENCE.sub("", text[p])):
            target = m.group(1)
            if re.match(r"[a-z][a-z0-9+.-]*:", target):  # http:, mailto:, ...
                continue
            links += 1
            path, _, frag = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(p), path)) if path else p
            if path and not os.path.exists(os.path.join(top, dest)):
                print("FAIL %s: %s: no file %s" % (p, target, dest))
                bad += 1
            elif frag and dest.endswith(".md"):
                if dest not in heads:
                    with open(os.path.join(top, dest), encoding="utf-8") as f:
                        heads[dest] = anchors(f.read())
                if frag not in heads[dest]:
                    print("FAIL %s: %s: no heading of %s has the slug '%s'" % (p, target, dest, frag))
                    bad += 1
    print("%d pages, %d relative links, %d broken" % (len(pages), links, bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
