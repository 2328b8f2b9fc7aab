#!/usr/bin/env bash
# Configures and builds tlsph out of tree, in build/ (or $BUILD_DIR), optimised
# with OpenMP on.  Objects, programs and test logs stay out of the source tree.
#   BUILD_DIR   build directory (default: build, relative to the source tree)
#   CFLAGS      compiler flags (default: -O3 -march=x86-64-v2 -g)
# Configuring in the source tree itself (./configure && make) also works, but
# then no out-of-tree build of the same tree is possible until `make distclean`.
set -euo pipefail
cd "$(dirname "$0")/.."
top=$(pwd)
build=${BUILD_DIR:-build}
case $build in /*) ;; *) build=$top/$build ;; esac
if [ -f config.status ]; then
  echo "build: the source tree is configured in place; run 'make distclean' in $top first" >&2
  exit 1
fi
if [ ! -x configure ] || [ configure.ac -nt configure ] || [ Makefile.am -nt Makefile.in ]; then
  autoreconf -fi >/dev/null
fi
mkdir -p "$build"
if [ ! -f "$build/Makefile" ] || [ configure -nt "$build/Makefile" ]; then
  (cd "$build" && "$top/configure" --quiet CFLAGS="${CFLAGS:--O3 -march=x86-64-v2 -g}")
fi
make -C "$build" -j"$(nproc)" >/dev/null
echo "build: ok ($build/tlsph-run)"
