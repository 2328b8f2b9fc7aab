"""The steps and wall time a tlsph-run log reports on its last line
("successful after N steps, t = ..., W s wall"), for the bench tables."""
import re


def steps_and_wall(path):
    """(steps, wall seconds) as strings, "?" when path is None or has no such line."""
    if path is None:
        return "?", "?"
    m = re.search(r"after (\d+) steps, t = [^,]+, ([0-9.]+) s wall", open(path).read())
    return (m.group(1), m.group(2)) if m else ("?", "?")
