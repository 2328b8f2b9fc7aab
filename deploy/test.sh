#!/usr/bin/env bash
# Sets everything up and runs the whole test suite twice:
#   1. the optimised build (as users run it, build/): make check;
#   2. a second out-of-tree build (build-sanitize/) with AddressSanitizer +
#      UndefinedBehaviorSanitizer (leak detection on): make check again (all but
#      the three production-size physics validations), so the tests also prove
#      the code free of memory errors, leaks and undefined behaviour;
#   3. make distcheck from build/, counted as one test: the release
#      tarball holds everything the build and the tests need, the whole suite
#      passes in a VPATH build from the read-only unpacked sources, and
#      install (systemd unit included) / installcheck / uninstall are clean.
# Ends with one line "N passed, N failed" over all of it.
set -uo pipefail
cd "$(dirname "$0")/.."
top=$(pwd)
bash deploy/install-deps.sh --test-tools || exit 1
bash deploy/build.sh || exit 1

pass=0
fail=0
run_check() { # dir label [timeout multiplier [tests]]
  local dir=$1 label=$2 mult=${3:-1} tests=${4:-} status p f trs_files
  # A Check test's timeout only detects a hang (see docs/reliability.md); it is
  # sized for the optimised build, and CK_TIMEOUT_MULTIPLIER (Check's own
  # variable) scales it for slower builds.  A user's own value multiplies it.
  (cd "$dir" && CK_TIMEOUT_MULTIPLIER=$((${CK_TIMEOUT_MULTIPLIER:-1} * mult)) \
    make -j"$(nproc)" check ${tests:+TESTS="$tests"} >make-check.out 2>&1)
  status=$?
  echo "== $label"
  grep -E '^(PASS|FAIL|XFAIL|XPASS|ERROR|SKIP):' "$dir/make-check.out" || true
  trs_files=$(find "$dir/tests" -name '*.trs' 2>/dev/null)
  p=$(cat $trs_files /dev/null | grep -cE '^:test-result: (PASS|XFAIL)')
  f=$(cat $trs_files /dev/null | grep -cE '^:test-result: (FAIL|XPASS|ERROR)')
  if [ $status -ne 0 ]; then
    for trs in $(grep -lE '^:test-result: (FAIL|ERROR)' $trs_files /dev/null); do
      echo "---- ${trs%.trs}.log"; tail -n 40 "${trs%.trs}.log"
    done
    [ "$f" -eq 0 ] && f=1
  fi
  pass=$((pass + p)); fail=$((fail + f))
}

run_check "$top/build" "optimised build"

# Sanitizer build: a second out-of-tree build of the same sources.
san="$top/build-sanitize"
rm -rf "$san" && mkdir -p "$san"
(cd "$san" && "$top/configure" --quiet \
    CFLAGS="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined" \
    LDFLAGS="-fsanitize=address,undefined" >/dev/null 2>&1 &&
  make -j"$(nproc)" >/dev/null 2>&1) || { echo "sanitizer build failed"; fail=$((fail + 1)); }
# ASan + UBSan run the engine 3-5x slower: the hang detectors scale by 4.  The
# production-size physics validations (SANITIZER_SKIPPED_TESTS in Makefile.am)
# check accuracy, which the optimised build has just done; the sanitizers see
# their code paths in the smaller tests.
if [ -x "$san/tlsph-run" ]; then
  san_tests=$(make -s --no-print-directory -C "$san" print-sanitizer-tests | tr '\n' ' ')
  if [ -n "$san_tests" ]; then
    run_check "$san" "sanitizer build (ASan + UBSan + LeakSanitizer)" 4 "$san_tests"
  else
    echo "sanitizer build: no test list"; fail=$((fail + 1))
  fi
fi

# make distcheck (~1-2 min on 2 cores, plus its own make check).
dc="$top/build"
t0=$(date +%s)
if make -C "$dc" -j"$(nproc)" distcheck >"$dc/make-distcheck.out" 2>&1; then
  echo "== make distcheck"
  echo "PASS: distcheck ($(grep -m1 -E '^# TOTAL:' "$dc/make-distcheck.out" | sed 's/# TOTAL: *//') tests in the VPATH build, $(($(date +%s) - t0)) s)"
  pass=$((pass + 1))
else
  echo "== make distcheck"
  echo "FAIL: distcheck"
  grep -E '^(FAIL|ERROR):' "$dc/make-distcheck.out"
  tail -n 40 "$dc/make-distcheck.out"
  fail=$((fail + 1))
fi

echo "${pass} passed, ${fail} failed"
[ "$fail" -eq 0 ]
