#!/usr/bin/env bash
# Every scene in examples/ validates; the fast ones run to completion (exit 0)
# and produce result.h5 + result.xmf.
set -u
here=$(cd "$(dirname "$0")" && pwd)
top_srcdir=${top_srcdir:-$here/../..}
top_builddir=${top_builddir:-$top_srcdir}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for f in "$top_srcdir"/examples/*.json; do
  name=$(basename "$f" .json)
  if "$top_builddir/tlsph-run" "$f" --validate >"$tmp/$name.validate" 2>&1; then
    echo "ok: $name validates ($(cat "$tmp/$name.validate"))"
  else
    echo "FAIL: $name does not validate"; cat "$tmp/$name.validate"; fail=1
  fi
done
for name in elastic-strip oscillating-plate crack-growth-plate; do
  if "$top_builddir/tlsph-run" "$top_srcdir/examples/$name.json" -o "$tmp/$name" --quiet &&
     [ -s "$tmp/$name/result.h5" ] && [ -s "$tmp/$name/result.xmf" ]; then
    echo "ok: $name runs"
  else
    echo "FAIL: $name did not run to completion"; fail=1
  fi
done
exit $fail
