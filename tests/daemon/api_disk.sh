#!/bin/bash
# tlsphd on a full disk (issue 13, item 9), on a small tmpfs that this test
# mounts (root or CAP_SYS_ADMIN; skipped with a message where that is not
# permitted).  The disk is filled by a filler file while an engine writes,
# the way another job or process fills a shared disk:
#   1. with the reserve file: the engine fails with an I/O error and the job
#      ends failed/io_error (the daemon frees its reserve to record it, where
#      it used to stay `running` with no engine for good); /healthz says
#      degraded and why; a new job is refused with 507 problem+json; DELETE
#      removes the failed job; once space is back, /healthz is ok again (the
#      reserve is allocated anew) and jobs run;
#   2. without a reserve: the final state waits (/healthz names it, DELETE
#      answers 507) and is recorded by the retry as soon as space is freed.
# Reference: the free space the kernel reports (statvfs f_bavail, `df`).
. "$(dirname "$0")/common.sh"

DISK=$TMP/disk
mkdir -p "$DISK"
if ! mount -t tmpfs -o size=24m,mode=0700 tlsphd-test-disk "$DISK" 2>"$TMP/mount.err"; then
    echo "SKIP: cannot mount a 24 MiB tmpfs for the full-disk test ($(cat "$TMP/mount.err")): needs root or CAP_SYS_ADMIN"
    exit 77
fi
disk_cleanup() {
    stop_daemons
    umount "$DISK" 2>/dev/null || umount -l "$DISK"
    cleanup
}
trap disk_cleanup EXIT

free_mib() { df -m --output=avail "$DISK" | tail -1 | tr -d ' '; }
# fill: writes a filler file until the disk refuses (dd stops at ENOSPC)
fill() { dd if=/dev/zero of="$DISK/filler" bs=64k status=none 2>/dev/null; sync; }
health() { req GET "$1/healthz"; jget "$BODY" "d['status']"; }
wrap() { "$PY" -c "import json,sys; print(json.dumps({'inputs':{'scene':json.load(sys.stdin)}}))"; }
strip_scene 2e-2 100 | wrap >"$TMP/long.json"    # 400 particles, estimated ~4.5 MiB
strip_scene 2e-4 2 tiny | wrap >"$TMP/tiny.json"
no_engine() { ! pgrep -f "$1" >/dev/null; }
has_frame() { [ -n "$(ls "$1"/result.h5 2>/dev/null)" ] && [ "$(stat -c %s "$1/result.h5")" -gt 100000 ]; }

# ------------------------------------------------- 1. with the reserve file
start_daemon D "$DISK/data" --min-free-mb 6 --disk-reserve-mb 4 --kill-grace 1 || exit 1
check "healthy at start" [ "$(health "$D_URL")" = ok ]
check "  healthz valid" valid openapi:health
check "  the reserve file is held (4 MiB)" [ "$(stat -c %s "$DISK/data/tlsphd.reserve")" = 4194304 ]
J=$(submit "$D_URL" "$TMP/long.json")
check "long job submitted" [ -n "$J" ]
wait_status "$D_URL" "$J" '^running$'
wait_until has_frame "$DISK/data/jobs/$J"
fill
check "disk full (free $(free_mib) MiB)" [ "$(free_mib)" -le 1 ]
wait_status "$D_URL" "$J" '^(failed|successful|dismissed)$'
req GET "$D_URL/jobs/$J"
check "the engine's I/O failure is recorded: failed" [ "$(jget "$BODY" "d['status']")" = failed ]
check "  outcome io_error ($(jget "$BODY" "d.get('message','')" | head -c 120))" [ "$(jget "$BODY" "d.get('outcome')")" = io_error ]
check "  statusInfo valid" valid job
check "  no engine left" no_engine "$DISK/data/jobs/$J"
check "log: the reserve was freed to record it" grep -q "freed the reserve file to record job $J" "$D_LOG"
check "healthz degraded" [ "$(health "$D_URL")" = degraded ]
check "  healthz valid" valid openapi:health
check "  names the floor" bash -c "grep -q 'below the floor' '$BODY'"
check "  names the reserve" bash -c "grep -q 'reserve file was freed' '$BODY'"
req POST "$D_URL/processes/run/execution" -H 'Content-Type: application/json' --data-binary @"$TMP/tiny.json"
check "new job refused: 507" [ "$STATUS" = 507 ]
check "  problem+json" [ "$(header Content-Type)" = application/problem+json ]
check "  problem valid" valid error
check "  type insufficient-storage, names the floor" [ "$(jget "$BODY" "d['type'].endswith('insufficient-storage') and 'floor' in d['detail']")" = True ]
req DELETE "$D_URL/jobs/$J"
check "DELETE the failed job: removed" [ "$STATUS:$(jget "$BODY" "d.get('removed')")" = "200:$J" ]
check "  its directory is gone" [ ! -e "$DISK/data/jobs/$J" ]
rm -f "$DISK/filler"
back_ok() { [ "$(health "$D_URL")" = ok ]; }
check "space freed: healthz ok again" wait_until back_ok
check "  the reserve is allocated again" [ "$(stat -c %s "$DISK/data/tlsphd.reserve" 2>/dev/null)" = 4194304 ]
T=$(submit "$D_URL" "$TMP/tiny.json")
check "a new job is taken" [ -n "$T" ]
wait_status "$D_URL" "$T" '^(successful|failed)$'
check "  and runs" [ "$(job_status "$D_URL" "$T")" = successful ]
kill -TERM "$D_PID"
wait "$D_PID"

# ------------------------------------------------- 2. no reserve: the retry
rm -rf "$DISK/data"
start_daemon E "$DISK/data" --min-free-mb 6 --disk-reserve-mb 0 --kill-grace 1 || exit 1
J=$(submit "$E_URL" "$TMP/long.json")
wait_status "$E_URL" "$J" '^running$'
wait_until has_frame "$DISK/data/jobs/$J"
fill
waiting() { req GET "$E_URL/healthz"; grep -q 'wait for their final state' "$BODY"; }
check "engine failed, state not recordable: healthz names the waiting job" wait_until waiting
check "  healthz degraded" [ "$(jget "$BODY" "d['status']")" = degraded ]
check "  no engine left" no_engine "$DISK/data/jobs/$J"
req DELETE "$E_URL/jobs/$J"
check "DELETE while the disk is full: 507 problem" [ "$STATUS:$(header Content-Type)" = "507:application/problem+json" ]
rm -f "$DISK/filler"
wait_status "$E_URL" "$J" '^(failed|successful|dismissed)$'
req GET "$E_URL/jobs/$J"
check "space freed: the retry records failed/io_error" [ "$(jget "$BODY" "d['status'] + '/' + d.get('outcome', '')")" = failed/io_error ]
check "log: recorded by the retry" grep -q "job $J: final state recorded" "$E_LOG"
check "healthz ok again" wait_until bash -c "[ \"\$(curl -s '$E_URL/healthz' | '$PY' -c 'import json,sys; print(json.load(sys.stdin)[\"status\"])')\" = ok ]"
finish
