/* Post-mortem repair of a job's result file (server/result_repair.c).
 *
 * The engine writes result.h5 under SWMR (core/io/output/h5md.c): while it
 * writes, the superblock's status flags mark the file open for (SWMR)
 * writing, and the engine clears them when it closes the file.  An engine
 * that dies without closing it (SIGKILL, a crash, the wall-clock limit's
 * SIGKILL after the grace period) leaves them set, and HDF5 then refuses every
 * open but a SWMR read: h5py without swmr=True, h5dump and ParaView fail with
 * "file is already open for write".  Its frames are intact up to the last
 * complete one (each frame ends with flushes; `step` is the commit marker).
 *
 * The repair, after the engine has been reaped:
 *  1. `h5clear -s --increment=0 result.h5` (Debian: hdf5-tools): clears the
 *     flags and sets the recorded end of allocated space (EOA) to the end of
 *     the file.  Plain `h5clear -s` would instead cut the file at the recorded
 *     EOA, which may be older than the last frame's data (HDF5 1.10 keeps the
 *     superblock's EOA from the last file flush).  libhdf5 1.10 has no public
 *     call that clears the flags (h5clear sets an undocumented file-access
 *     property); running the documented tool keeps the daemon off HDF5
 *     internals and keeps a damaged file's writes out of the daemon's process.
 *     A tool that does not know --increment (HDF5 < 1.10.2) refuses the
 *     command line and leaves the file untouched.
 *  2. Checks that the flags are clear and that the file did not shrink.
 *  3. Rewrites the XDMF sidecar (core/io/output/xdmf.h) so that it lists every
 *     complete frame: the engine rewrites it at most every 2 s, so a killed
 *     run's sidecar may miss its last frames (it never lists an incomplete
 *     one).
 * A file that cannot be repaired is left as it is (h5py opens it with
 * swmr=True); the caller tells the job's user. */
#ifndef TLSPHD_RESULT_REPAIR_H
#define TLSPHD_RESULT_REPAIR_H

#include <stddef.h>

enum result_mark {
    RESULT_ABSENT,    /* no file, or not an HDF5 file with a version >= 2 superblock */
    RESULT_CLOSED,    /* status flags clear: opens everywhere */
    RESULT_LEFT_OPEN, /* status flags set: the writer did not close it */
    RESULT_UNREADABLE /* the file exists but cannot be read */
};

/* The superblock's status of the HDF5 file at path (searched at offset 0 and
 * at 512, 1024, 2048, ... as HDF5 does for files with a user block). */
enum result_mark result_mark(const char *path);

/* Finds the h5clear program and writes its absolute path to buf: the
 * environment variable TLSPHD_H5CLEAR if set (empty: repair disabled), else
 * the first executable "h5clear" in PATH, else /usr/bin/h5clear or
 * /usr/local/bin/h5clear.  -1 (buf empty) when there is none. */
int result_repair_find_tool(char *buf, size_t size);

enum result_repair_rc {
    RESULT_NOTHING_TO_DO, /* no result.h5, or one that was closed */
    RESULT_REPAIRED,      /* it was left open and opens everywhere now */
    RESULT_NOT_REPAIRED   /* it was left open and still is */
};

/* Repairs result.h5 of job id under jobs_dir if it was left open (steps 1-3
 * above), appending h5clear's output to the job's log.  tool is
 * result_repair_find_tool's answer ("" when none).  msg (one line for people):
 * when repaired, how many complete frames the rewritten sidecar lists, or why
 * the sidecar kept the frames the engine listed; when not repaired, why. */
enum result_repair_rc result_repair_job(const char *tool, const char *jobs_dir, const char *id,
                                        char *msg, size_t msgsize);

/* Calls fn(id, ctx) for each job directory under jobs_dir whose result.h5 is
 * left open. */
void result_repair_each_left_open(const char *jobs_dir, void (*fn)(const char *id, void *ctx),
                                  void *ctx);

#endif
