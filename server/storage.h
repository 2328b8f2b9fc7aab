/* The data directory's disk (server/storage.c): free space, the floor below
 * which no new work is taken, and the reserve file that lets the daemon
 * record a job's final state on a full disk.
 *
 * Free space is what an unprivileged process may still write on the data
 * directory's filesystem (statvfs f_bavail x f_frsize), read afresh on each
 * call.  Below the floor (min_free_mb) submissions are refused with 507 and
 * the supervisor starts no engine (queued jobs wait), and /healthz reports
 * degraded.
 *
 * The reserve is a file of disk_reserve_mb bytes, <data_dir>/tlsphd.reserve,
 * allocated at start.  When a disk fills up while an engine writes, the
 * engine fails with an I/O error and SQLite cannot record the outcome (its
 * write-ahead log cannot grow); the supervisor then removes the reserve and
 * writes again, so the job ends failed (io_error) instead of staying
 * `running`.  The reserve is allocated again once the free space is back above
 * the floor plus the reserve.  Stateless: the file is the state, so every
 * thread may call these. */
#ifndef TLSPHD_STORAGE_H
#define TLSPHD_STORAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct tcfg;

#define STORAGE_RESERVE_NAME "tlsphd.reserve"

/* Free bytes on the data directory's filesystem, or -1 (errno) when statvfs fails. */
int64_t storage_free_bytes(const struct tcfg *cfg);
/* The floor in bytes (0: none). */
uint64_t storage_floor_bytes(const struct tcfg *cfg);
/* Free space is known and below the floor. */
bool storage_below_floor(const struct tcfg *cfg);
/* The reserve file exists (or none is configured). */
bool storage_reserve_held(const struct tcfg *cfg);
/* Removes the reserve file: true when there was one to free. */
bool storage_release_reserve(const struct tcfg *cfg);
/* Allocates the reserve when it is missing and the free space is at least
 * the floor plus the reserve: 0 (held, allocated, or not yet possible), or
 * -1 with err when the allocation failed for another reason. */
int storage_keep_reserve(const struct tcfg *cfg, char *err, size_t errsize);

#endif
