#!/usr/bin/env bash
# Configures and builds tlsph in the source tree (optimised, OpenMP on).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x configure ] || [ configure.ac -nt configure ] || [ Makefile.am -nt Makefile.in ]; then
  autoreconf -fi >/dev/null
fi
if [ ! -f Makefile ] || [ configure -nt Makefile ]; then
  ./configure --quiet CFLAGS="${CFLAGS:--O3 -march=x86-64-v2 -g}"
fi
make -j"$(nproc)" >/dev/null
echo "build: ok ($(pwd)/tlsph-run)"
