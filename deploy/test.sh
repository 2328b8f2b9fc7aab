#!/usr/bin/env bash
# Sets everything up and runs the whole test suite (make check).
# Ends with a line "N passed, N failed".
set -uo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh || exit 1
bash deploy/build.sh || exit 1
make -j"$(nproc)" check >make-check.out 2>&1
status=$?
grep -E '^(PASS|FAIL|XFAIL|XPASS|ERROR|SKIP):' make-check.out || true
if [ $status -ne 0 ]; then
  for log in $(grep -lE '^:test-result: (FAIL|ERROR)' tests/unit/*.trs tests/scripts/*.trs 2>/dev/null); do
    echo "---- ${log%.trs}.log"; tail -n 40 "${log%.trs}.log"
  done
fi
pass=$(grep -cE '^:test-result: (PASS|XFAIL)' tests/unit/*.trs tests/scripts/*.trs 2>/dev/null | awk -F: '{s+=$NF} END {print s+0}')
fail=$(grep -cE '^:test-result: (FAIL|XPASS|ERROR)' tests/unit/*.trs tests/scripts/*.trs 2>/dev/null | awk -F: '{s+=$NF} END {print s+0}')
if [ $status -ne 0 ] && [ "$fail" -eq 0 ]; then fail=1; fi
echo "${pass} passed, ${fail} failed"
[ "$fail" -eq 0 ]
