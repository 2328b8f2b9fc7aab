#!/usr/bin/env bash
# A result file that cannot be set up (here: a file-size limit of 8 blocks, far
# below the size of the layout; a full disk fails the same way) must give exit
# code 4 ("io_error"), a final progress event with status "io_error" whose
# errors say why, and leave neither result.h5 nor result.xmf behind: a file
# with no frames and no /diagnostics status would look like a result.
# Reference (issue 13, item 4): before, tlsph-run left the partial result.h5
# and died of SIGSEGV in HDF5's exit handler after the final event.
. "$(dirname "$0")/../support/script_env.sh"

# SIGXFSZ ignored: a write past the limit then fails with EFBIG, as on a full disk
(trap '' XFSZ; ulimit -f 8 2>/dev/null || exit 77
 exec "$top_builddir/tlsph-run" "$top_srcdir/tests/scenes/good/output_small.json" -o "$tmp/out" \
     --progress-fd 3 --quiet 3>"$tmp/progress.jsonl") 2>"$tmp/err"
code=$?
cat "$tmp/err"
[ $code -eq 77 ] && { echo "SKIP: cannot lower the file-size limit here"; exit 77; }
[ $code -eq 4 ] || { echo "FAIL: exit code $code, expected 4 (io_error)"; exit 1; }
for f in result.h5 result.xmf; do
  [ ! -e "$tmp/out/$f" ] || { echo "FAIL: $f left behind"; ls -l "$tmp/out"; exit 1; }
done
"$PY" - "$tmp/progress.jsonl" <<'PYEOF' || exit 1
import sys, json
lines = open(sys.argv[1]).read().strip().splitlines()
last = json.loads(lines[-1])
assert last["event"] == "finished" and last["status"] == "io_error", last
detail = last["errors"][0]["detail"]
assert "File too large" in detail and "unknown HDF5 error" not in detail, detail
print("final event:", detail)
PYEOF
echo "PASS: a result file that could not be set up gave exit 4, a final event and no file"
