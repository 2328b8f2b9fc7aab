# Sourced by the engine's test scripts (tests/engine/*.sh): the paths make check
# exports (defaults for a run by hand from the source tree), the Python with h5py,
# and a temporary directory $tmp removed on exit.
set -u
top_srcdir=${top_srcdir:-$(cd "$(dirname "$0")/../.." && pwd)}
top_builddir=${top_builddir:-$top_srcdir}
PY=${SYSTEM_PYTHON:-/usr/bin/python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
