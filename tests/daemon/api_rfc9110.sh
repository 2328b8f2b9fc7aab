#!/bin/bash
# RFC 9110 details of the result files and disk faults (issue 13, item 18):
#   - Range (section 14.2): a unit other than bytes is ignored (200, the whole
#     file); a last position past the end, even past 2^64, is clamped to the
#     end (206, Content-Range naming the real end); a suffix longer than the
#     file is the whole file (206); range handling applies to GET only (HEAD
#     answers 200); the unit is case-insensitive;
#   - If-None-Match (section 13.1.2): "*" matches any current file, entity
#     tags compare weakly (W/"..." matches), a list matches when one member
#     does: 304 with the ETag; it is evaluated before Range (section 13.2.2);
#   - disk faults are answered 507 (the disk cannot take it: ENOSPC, EROFS)
#     or 503 with Retry-After (it fails for now: EIO, EMFILE), as
#     problem+json naming what failed, never 500 "internal" or a misleading
#     404 / empty 200.  The faults come from tests/support/fault_inject.c
#     (LD_PRELOAD: open()/mkdir() of a chosen path fail with a chosen errno),
#     so no privileges are needed; that part skips only without a C compiler.
. "$(dirname "$0")/common.sh"

strip_scene 2e-4 2 tiny | "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))" >"$TMP/tiny.json"

# the fault shim (built here: it is a test tool, not part of the daemon)
FAULTS=$TMP/faults
: >"$FAULTS"
SHIM=""
if command -v "${CC:-cc}" >/dev/null 2>&1 &&
    "${CC:-cc}" -shared -fPIC -o "$TMP/fault_inject.so" "$top_srcdir/tests/support/fault_inject.c" -ldl; then
    SHIM=$TMP/fault_inject.so
fi
if [ -n "$SHIM" ]; then
    # an ASan build wants its runtime first; the shim only wraps open/mkdir
    LD_PRELOAD=$SHIM TLSPH_FAULT_FILE=$FAULTS \
        ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" \
        start_daemon D "$TMP/data" || exit 1
else
    echo "# no C compiler: the disk-fault checks are skipped"
    start_daemon D "$TMP/data" || exit 1
fi

ID=$(submit "$D_URL" "$TMP/tiny.json")
check "job submitted" [ -n "$ID" ]
wait_status "$D_URL" "$ID" '^successful$' || { fail "job did not succeed"; finish; }
XMF=$D_URL/jobs/$ID/results/result.xmf
SIZE=$(stat -c %s "$TMP/data/jobs/$ID/result.xmf")

# ---------------------------------------------------------- Range
req GET "$XMF" -H 'Range: lines=1-2'
check "Range: lines=1-2 (unknown unit) ignored: 200" [ "$STATUS" = 200 ]
check "  the whole file, no Content-Range" [ "$(stat -c %s "$BODY"):$(header Content-Range)" = "$SIZE:" ]
req GET "$XMF" -H 'Range: bytes=10-99999999'
check "Range past the end: 206" [ "$STATUS" = 206 ]
check "  Content-Range names the real end" [ "$(header Content-Range)" = "bytes 10-$((SIZE - 1))/$SIZE" ]
check "  the rest of the file" [ "$(stat -c %s "$BODY")" = $((SIZE - 10)) ]
req GET "$XMF" -H 'Range: bytes=0-99999999999999999999999999'
check "Range end past 2^64: clamped, 206" [ "$STATUS" = 206 ]
check "  Content-Range bytes 0-(size-1)/size" [ "$(header Content-Range)" = "bytes 0-$((SIZE - 1))/$SIZE" ]
req GET "$XMF" -H 'Range: bytes=-99999999999999999999999999'
check "suffix longer than the file: 206, the whole file" \
    [ "$STATUS:$(header Content-Range)" = "206:bytes 0-$((SIZE - 1))/$SIZE" ]
req GET "$XMF" -H 'Range: BYTES=0-9'
check "the unit is case-insensitive: 206, 10 bytes" [ "$STATUS:$(stat -c %s "$BODY")" = 206:10 ]
STATUS=$(curl -s -I -o /dev/null -w '%{http_code}' -H 'Range: bytes=0-9' "$XMF")
check "HEAD with Range: 200 (range handling is for GET)" [ "$STATUS" = 200 ]
req GET "$XMF" -H "Range: bytes=$SIZE-"
check "a first position at the end: still 416" [ "$STATUS" = 416 ]

# ---------------------------------------------------------- If-None-Match
req GET "$XMF"
ETAG=$(header ETag)
check "ETag is a strong entity tag" bash -c '[[ $1 =~ ^\"[^\"]+\"$ ]]' _ "$ETAG"
req GET "$XMF" -H 'If-None-Match: *'
check "If-None-Match: * → 304" [ "$STATUS" = 304 ]
check "  with the ETag" [ "$(header ETag)" = "$ETAG" ]
req GET "$XMF" -H "If-None-Match: W/$ETAG"
check "If-None-Match: W/<etag> (weak comparison) → 304" [ "$STATUS" = 304 ]
req GET "$XMF" -H "If-None-Match: \"other\", W/\"x\", $ETAG"
check "If-None-Match: a list holding the tag → 304" [ "$STATUS" = 304 ]
req GET "$XMF" -H 'If-None-Match: "other"'
check "If-None-Match: another tag → 200" [ "$STATUS" = 200 ]
req GET "$XMF" -H "If-None-Match: $ETAG" -H 'Range: bytes=0-9'
check "If-None-Match is evaluated before Range: 304" [ "$STATUS" = 304 ]
STATUS=$(curl -s -I -o /dev/null -w '%{http_code}' -H 'If-None-Match: *' "$D_URL/jobs/$ID/results/result.h5")
check "HEAD result.h5 with If-None-Match: * → 304" [ "$STATUS" = 304 ]

# ---------------------------------------------------------- disk faults
if [ -z "$SHIM" ]; then
    echo "# SKIP disk faults: no C compiler for the fault shim"
    finish
fi
EIO=5 EMFILE=24 ENOSPC=28 EROFS=30
fault() { printf '%s\n' "$@" >"$FAULTS"; }
problem() { # STATUS: the status, problem+json, valid
    [ "$STATUS" = "$1" ] && [ "$(header Content-Type)" = application/problem+json ] && valid error
}

fault "open result.xmf $EIO"
req GET "$XMF"
check "EIO reading result.xmf: 503 problem+json (was 404)" problem 503
check "  Retry-After, the detail names the read" \
    [ -n "$(header Retry-After)" -a "$(jget "$BODY" "'cannot read the result file' in d['detail']")" = True ]
fault "open result.h5 $EMFILE"
req GET "$D_URL/jobs/$ID/results/result.h5"
check "EMFILE opening result.h5: 503" problem 503
req GET "$D_URL/jobs/$ID/results/series/kinetic_energy"
check "EMFILE under a series read (HDF5): 503 (was 500)" problem 503
req GET "$D_URL/jobs/$ID/results/fields/position?frame=-1"
check "EMFILE under a field read: 503 (was 500)" problem 503
fault "open log.txt $EIO"
req GET "$D_URL/jobs/$ID/log"
check "EIO reading the log: 503 (was an empty 200)" problem 503
fault "mkdir /jobs/ $ENOSPC"
req POST "$D_URL/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/tiny.json"
check "ENOSPC creating the job directory: 507 (was 500)" problem 507
fault "mkdir /jobs/ $EROFS"
req POST "$D_URL/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/tiny.json"
check "EROFS creating the job directory: 507 (was 500)" problem 507
check "  the detail names the write" [ "$(jget "$BODY" "'cannot write' in d['detail']")" = True ]
fault
req GET "$XMF"
check "fault gone: result.xmf 200 again" [ "$STATUS" = 200 ]
req GET "$D_URL/jobs?limit=100"
check "  the refused submissions left no job" [ "$(jget "$BODY" "len(d['jobs'])")" = 1 ]
finish
