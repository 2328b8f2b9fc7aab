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

# Runs the scene DIR/NAME.json into DIR/NAME/ (replaced) on 1 OpenMP thread,
# its output in DIR/NAME.log; reports "NAME exit RC" on stderr.  Exported, for
# scripts that run several at a time through xargs.
run_scene() {
  local dir=$1 name=$2 rc=0
  rm -rf "${dir:?}/$name"
  OMP_NUM_THREADS=1 "$run" "$dir/$name.json" -o "$dir/$name" --threads 1 --quiet \
    >"$dir/$name.log" 2>&1 || rc=$?
  echo "$name exit $rc" >&2
}
export -f run_scene

# Calls the exported shell function FN on each CASE, JOBS at a time.
run_parallel() { # FN JOBS CASE...
  local fn=$1 jobs=$2
  shift 2
  printf '%s\n' "$@" | xargs -P "$jobs" -I{} bash -c "$fn {}"
}
