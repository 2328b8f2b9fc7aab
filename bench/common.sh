# Sourced by the bench scripts (not run): where the tree, the engine and
# python are.  Sets here (bench/), top (the tree), run (tlsph-run of the
# out-of-tree build, or of $BUILD_DIR/tlsph-run) and py; stops with a hint
# when the engine has not been built.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
top=$(cd "$here/.." && pwd)
run="${BUILD_DIR:-$top/build}/tlsph-run"  # deploy/build.sh builds out of tree
py=/usr/bin/python3
[ -x "$run" ] || { echo "build first: bash deploy/build.sh"; exit 1; }

# Sets out to a scratch directory removed when the script exits.
scratch_dir() {
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
}
