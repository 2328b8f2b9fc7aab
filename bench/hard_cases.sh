#!/usr/bin/env bash
# The hard-case suite at full size (docs/hard-cases.md): every case of
# tests/hard/cases.txt with its full-size changes, under the same contract as
# the small versions in make check (tests/hard/hard_cases.sh, check_case.py).
# Prints the docs table (case, outcome, diagnostic, particles, steps, energy
# error, what the run reached, wall time) and the machine's load.
#   bash bench/hard_cases.sh [CASE ...]
#   THREADS   engine threads per run (default 2)
#   HARD_TIMEOUT  hang detector per run, s (default 3600)
. "$(dirname "$0")/common.sh"
echo "# $(date -u +%FT%TZ), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
top_srcdir=$top top_builddir=$(dirname "$run") SYSTEM_PYTHON=$py \
  HARD_TIMEOUT=${HARD_TIMEOUT:-3600} \
  bash "$top/tests/hard/hard_cases.sh" --full --markdown --threads "${THREADS:-2}" "$@"
status=$?
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
exit $status
