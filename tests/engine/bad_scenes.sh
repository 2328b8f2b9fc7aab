#!/bin/sh
# Every scene in tests/scenes/bad must be refused by tlsph-run with exit code 2,
# the expected JSON pointer (tests/scenes/bad/NAME.expect) in the error JSON on
# stderr, and no output written.  Then the JSON Schema is checked against the
# good scenes, the examples and the bad scenes (tests/support/schema_check.py).
# Environment: top_srcdir, top_builddir (set by make check; default ../.. of
# this script), SYSTEM_PYTHON (default /usr/bin/python3).
here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$here/../..}
top_builddir=${top_builddir:-$here/../..}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
run=$top_builddir/tlsph-run

if [ ! -x "$run" ]; then
    echo "bad_scenes: $run not built" >&2
    exit 99
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/bad_scenes.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM

pass=0
fail=0
for scene in "$top_srcdir"/tests/scenes/bad/*.json; do
    name=$(basename "$scene" .json)
    expect_file=${scene%.json}.expect
    if [ ! -f "$expect_file" ]; then
        echo "FAIL $name: missing $expect_file"
        fail=$((fail + 1))
        continue
    fi
    pointer=$(head -n 1 "$expect_file")
    out=$tmp/out-$name
    # A hang detector, not a speed limit: an engine that accepted one of these
    # scenes would run it, and some (a step of 0, 1e9 steps) never end.
    timeout 300 "$run" "$scene" -o "$out" >"$tmp/stdout" 2>"$tmp/stderr"
    rc=$?
    problem=
    if [ "$rc" -eq 124 ]; then
        problem="accepted and still running after 300 s, expected exit code 2"
    elif [ "$rc" -ne 2 ]; then
        problem="exit code $rc, expected 2"
    elif ! grep -F -e "\"pointer\":\"$pointer\"" -e "\"pointer\": \"$pointer\"" "$tmp/stderr" \
            >/dev/null; then
        problem="no error with pointer '$pointer' on stderr"
    elif [ -e "$out/result.h5" ] || { [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; }; then
        problem="output written to $out"
    fi
    if [ -n "$problem" ]; then
        echo "FAIL $name: $problem"
        sed 's/^/    stderr: /' "$tmp/stderr" | head -n 5
        fail=$((fail + 1))
    else
        echo "ok   $name ($pointer)"
        pass=$((pass + 1))
    fi
done
echo "bad scenes: $pass passed, $fail failed"

schema_rc=0
if [ -x "$python" ]; then
    set -- "$top_srcdir"/tests/scenes/good/*.json
    for f in "$top_srcdir"/examples/*.json; do
        [ -f "$f" ] && set -- "$@" "$f"
    done
    "$python" "$top_srcdir/tests/support/schema_check.py" "$top_srcdir/schemas/scene.schema.json" \
        --good "$@" --bad "$top_srcdir"/tests/scenes/bad/*.json
    schema_rc=$?
    [ "$schema_rc" -eq 77 ] && schema_rc=0
else
    echo "schema check skipped: $python not found"
fi

[ "$fail" -eq 0 ] && [ "$schema_rc" -eq 0 ]
