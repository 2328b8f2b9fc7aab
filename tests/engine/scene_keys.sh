#!/bin/sh
# The scene's key tables (printed by tests/engine/test_scene_keys --json) against
# schemas/scene.schema.json and docs/scene.md, in both directions
# (tests/support/scene_keys_check.py).  Environment: top_srcdir, top_builddir
# (set by make check; default ../.. of this script), SYSTEM_PYTHON (default
# /usr/bin/python3).
here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$here/../..}
top_builddir=${top_builddir:-$here/../..}
python=${SYSTEM_PYTHON:-/usr/bin/python3}
dump=$top_builddir/tests/engine/test_scene_keys

if [ ! -x "$dump" ]; then
    echo "scene_keys: $dump not built" >&2
    exit 99
fi
if [ ! -x "$python" ]; then
    echo "scene_keys: $python not found; skipped"
    exit 77
fi
tmp=$(mktemp "${TMPDIR:-/tmp}/scene_keys.XXXXXX") || exit 99
trap 'rm -f "$tmp"' EXIT INT TERM
"$dump" --json >"$tmp" || exit 99
exec "$python" "$top_srcdir/tests/support/scene_keys_check.py" "$tmp" \
    "$top_srcdir/schemas/scene.schema.json" "$top_srcdir/docs/scene.md"
