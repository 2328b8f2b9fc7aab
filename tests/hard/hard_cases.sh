#!/usr/bin/env bash
# The hard-case suite (docs/hard-cases.md): every case of tests/hard/cases.txt must
# end successful with a closed energy balance, or unstable with a diagnostic naming
# the quantity, the step and particles; never a value that is not finite in any
# dataset (read back with h5py), never a crash, never a hang (each run under a
# timeout: HARD_TIMEOUT seconds, 600 by default, times CK_TIMEOUT_MULTIPLIER).
# The contract is checked from the result file by check_case.py.
#   hard_cases.sh [--full] [--threads N] [--markdown] [CASE ...]
# Without --full the small versions run (make check, 1 thread); --full applies each
# case's full-size changes (bench/hard_cases.sh).  --markdown prints the table for
# the docs.  CASE names choose cases (default: all).
. "$(dirname "$0")/../support/script_env.sh"

full=0 threads=1 markdown=0
while [ $# -gt 0 ]; do
  case $1 in
    --full) full=1 ;;
    --threads) threads=$2; shift ;;
    --markdown) markdown=1 ;;
    --*) echo "hard_cases.sh: unknown option $1" >&2; exit 1 ;;
    *) break ;;
  esac
  shift
done
limit=$(( ${HARD_TIMEOUT:-600} * ${CK_TIMEOUT_MULTIPLIER:-1} ))
hard=$top_srcdir/tests/hard
export PYTHONPATH=$top_srcdir/tests/support

if [ $markdown -eq 1 ]; then
  echo "| case | outcome | diagnostic | particles | steps | energy error | reached | wall s |"
  echo "|---|---|---|---:|---:|---:|---|---:|"
fi
failed=0 ran=0
while IFS='|' read -r name scene expect tol reach changes; do
  name=$(echo $name) scene=$(echo $scene) expect=$(echo $expect) tol=$(echo $tol)
  reach=$(echo $reach) changes=$(echo $changes)
  case $name in ''|'#'*) continue ;; esac
  if [ $# -gt 0 ]; then
    case " $* " in *" $name "*) ;; *) continue ;; esac
  fi
  ran=$((ran + 1))
  input=$top_srcdir/$scene
  if [ $full -eq 1 ] && [ "$changes" != "-" ]; then
    input=$tmp/$name.json
    # shellcheck disable=SC2086  # changes are words by design
    "$PY" "$hard/scene_variant.py" "$top_srcdir/$scene" "$input" $changes || exit 1
  fi
  timeout -k 10 "$limit" "$top_builddir/tlsph-run" "$input" -o "$tmp/$name" \
    --threads "$threads" --quiet 2>"$tmp/$name.err"
  code=$?
  if [ $code -eq 124 ] || [ $code -eq 137 ]; then
    row="hang	no end within ${limit} s	-	-	-	-	-"
    ok=1
    echo "FAIL $name: no end within $limit s (a hang)" >&2
  else
    row=$("$PY" "$hard/check_case.py" "$tmp/$name" "$code" "$expect" "$tol" "$reach" \
          2>"$tmp/$name.check")
    ok=$?
    if [ $ok -ne 0 ]; then
      sed "s/^/FAIL $name: /" "$tmp/$name.check" >&2
      cat "$tmp/$name.err" >&2
    fi
  fi
  [ $ok -eq 0 ] || failed=$((failed + 1))
  if [ $markdown -eq 1 ]; then
    echo "| $name | $(echo "$row" | sed 's/	/ | /g') |"
  else
    printf '%s %-18s %s\n' "$([ $ok -eq 0 ] && echo ok || echo FAIL)" "$name" "$row"
  fi
  rm -rf "${tmp:?}/$name"
done < "$hard/cases.txt"

[ $ran -gt 0 ] || { echo "FAIL: no case ran" >&2; exit 1; }
if [ $failed -ne 0 ]; then
  echo "FAIL: $failed of $ran hard cases broke the contract" >&2
  exit 1
fi
[ $markdown -eq 1 ] || echo "PASS: $ran hard cases kept the contract"
