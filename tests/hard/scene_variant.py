"""Writes a variant of a scene: scene_variant.py IN OUT [CHANGE ...], each CHANGE
either spacing*F (every body's spacing times F) or /json/pointer=JSON (the value
at that pointer set; the containers must exist).  Used for the full sizes of the
hard cases (tests/hard/cases.txt, bench/hard_cases.sh) and their variants."""
import json
import sys


def main():
    src, dst, changes = sys.argv[1], sys.argv[2], sys.argv[3:]
    with open(src) as f:
        scene = json.load(f)
    for c in changes:
        if c == "-":
            continue
        if c.startswith("spacing*"):
            for body in scene["bodies"]:
                body["spacing"] *= float(c[len("spacing*"):])
            continue
        pointer, value = c.split("=", 1)
        keys = pointer.strip("/").split("/")
        node = scene
        for k in keys[:-1]:
            node = node[int(k)] if isinstance(node, list) else node[k]
        last = keys[-1]
        if isinstance(node, list):
            node[int(last)] = json.loads(value)
        else:
            node[last] = json.loads(value)
    with open(dst, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
