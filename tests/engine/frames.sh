#!/usr/bin/env bash
# A run that reaches time.end writes output.frames + 1 frames (docs/output.md):
# t = 0, the first step end at or after each k end / frames, and t = end.
#  - tests/scenes/good/strip_2d.json as it is: 2001 CFL steps, 10 frames;
#  - the same with end = 2e-6 s (about 20 CFL steps of 1e-7 s) and 50 frames: the
#    steps that would pass two frame times end at the next one, so every frame
#    time gets its frame (this run wrote 21 frames before).
# Reference: the frame times k end / frames; tolerance 1e-12 relative (the
# engine's own frame-time test).
. "$(dirname "$0")/../support/script_env.sh"

sed -e 's/"end": 2e-4/"end": 2e-6/' -e 's/"frames": 10/"frames": 50/' \
    "$top_srcdir/tests/scenes/good/strip_2d.json" >"$tmp/short.json"
grep -q '"frames": 50' "$tmp/short.json" || { echo "FAIL: could not edit the scene"; exit 1; }

for scene in "$top_srcdir/tests/scenes/good/strip_2d.json" "$tmp/short.json"; do
    name=$(basename "$scene" .json)
    "$top_builddir/tlsph-run" "$scene" -o "$tmp/$name" --quiet ||
        { echo "FAIL $name: tlsph-run exited with $?"; exit 1; }
    PYTHONPATH="$top_srcdir/tests/support" "$PY" - "$tmp/$name/result.h5" <<'PYEOF' || exit 1
import sys
import numpy as np
from tlsph_result import Result
with Result(sys.argv[1]) as r:
    frames, end = r.scene["output"]["frames"], r.scene["time"]["end"]
    t = r.frame_times()
    steps = r.cost["steps"]
    print("%s: %d steps, %d frames written for output.frames = %d" % (r.scene["name"], steps, len(t), frames))
    assert r.status == "successful", r.status
    assert len(t) == frames + 1, "%d frames, expected output.frames + 1 = %d" % (len(t), frames + 1)
    assert np.all(np.diff(t) > 0), "frame times do not increase"
    k = np.arange(frames + 1)
    assert np.all(t >= k * end / frames * (1 - 1e-12)), "a frame before its frame time"
    assert abs(t[-1] - end) <= 1e-12 * end, "last frame at %g, not at end %g" % (t[-1], end)
    if steps < 2 * frames:  # steps longer than the interval end exactly at the frame times
        assert np.allclose(t, k * end / frames, rtol=1e-12, atol=0), "frame times %s" % t
    assert not r.non_finite_datasets(), "a dataset holds a value that is not finite"
PYEOF
done
echo "PASS: output.frames + 1 frames, at the frame times"
