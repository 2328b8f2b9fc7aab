/* Post-mortem repair of a job's result file, see result_repair.h.
 *
 * Besides the supervisor's engines, h5clear is the one program the daemon
 * starts: from the supervisor thread, after the engine has been reaped, and
 * waited for (it touches one superblock; REPAIR_TIMEOUT_S only detects a
 * hang). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "result_repair.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <limits.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "errmsg.h"
#include "spawn_attr.h"
#include "io/fields.h"
#include "io/output/xdmf.h"
#include "jobdir.h"
#include "results_h5.h"
#include "util/clock.h"

extern char **environ;

#define REPAIR_TIMEOUT_S      120.0      /* s before a silent h5clear is killed */
#define SUPERBLOCK_SEARCH_MAX (1u << 30) /* last user-block size HDF5 would try, B */

static const unsigned char hdf5_signature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

/* ------------------------------------------------------------ the mark */

enum result_mark result_mark(const char *path)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0)
        return errno == ENOENT ? RESULT_ABSENT : RESULT_UNREADABLE;
    struct stat st;
    enum result_mark mark = RESULT_ABSENT;
    if (fstat(fd, &st) < 0) {
        mark = RESULT_UNREADABLE;
        goto done;
    }
    /* Superblock v2/v3 (HDF5 file format spec, section II.A): signature (8
     * bytes), version, size of offsets, size of lengths, file consistency
     * flags (bit 0: open for writing, bit 2: open for SWMR writing). */
    for (off_t at = 0; at < st.st_size && at <= (off_t)SUPERBLOCK_SEARCH_MAX;
         at = at ? 2 * at : 512) {
        unsigned char head[12];
        ssize_t n = pread(fd, head, sizeof head, at);
        if (n < 0) {
            mark = RESULT_UNREADABLE;
            break;
        }
        if ((size_t)n < sizeof head || memcmp(head, hdf5_signature, sizeof hdf5_signature))
            continue;
        /* versions 0 and 1 have no SWMR, and the engine never writes them */
        if (head[8] >= 2)
            mark = head[11] ? RESULT_LEFT_OPEN : RESULT_CLOSED;
        break;
    }
done:
    close(fd);
    return mark;
}

/* ------------------------------------------------------------ the tool */

static int executable_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0;
}

int result_repair_find_tool(char *buf, size_t size)
{
    buf[0] = '\0';
    const char *env = getenv("TLSPHD_H5CLEAR");
    if (env) {
        if (!*env || !executable_file(env) || strlen(env) >= size)
            return -1;
        snprintf(buf, size, "%s", env);
        return 0;
    }
    const char *path = getenv("PATH");
    while (path && *path) {
        const char *end = strchr(path, ':');
        size_t len = end ? (size_t)(end - path) : strlen(path);
        /* only absolute directories: the daemon's working directory is no place to look */
        if (len > 0 && path[0] == '/' && len + sizeof "/h5clear" <= size) {
            snprintf(buf, size, "%.*s/h5clear", (int)len, path);
            if (executable_file(buf))
                return 0;
        }
        path = end ? end + 1 : NULL;
    }
    static const char *const fallback[] = {"/usr/bin/h5clear", "/usr/local/bin/h5clear"};
    for (size_t i = 0; i < sizeof fallback / sizeof *fallback; i++)
        if (executable_file(fallback[i]) && strlen(fallback[i]) < size) {
            snprintf(buf, size, "%s", fallback[i]);
            return 0;
        }
    buf[0] = '\0';
    return -1;
}

/* ------------------------------------------------------------ h5clear */

/* Runs tool -s --increment=0 h5 with its output appended to log; 0 when it
 * exits with 0. */
static int run_h5clear(const char *tool, const char *h5, const char *log, char *err, size_t errsize)
{
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t attr;
    if (posix_spawn_file_actions_init(&fa) != 0) {
        errmsg_set(err, errsize, "cannot prepare h5clear: out of memory");
        return -1;
    }
    /* the supervisor thread blocks every signal: give the tool the defaults */
    if (spawn_attr_defaults(&attr) != 0) {
        posix_spawn_file_actions_destroy(&fa);
        errmsg_set(err, errsize, "cannot prepare h5clear: out of memory");
        return -1;
    }
    int rc = -1, e = 0;
    if ((e = posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0)) != 0 ||
        (e = posix_spawn_file_actions_addopen(
             &fa, 1, log, O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW, 0640)) != 0 ||
        (e = posix_spawn_file_actions_adddup2(&fa, 1, 2)) != 0) {
        errmsg_set(err, errsize, "cannot prepare h5clear: %s", strerror(e));
        goto done;
    }
    char *const argv[] = {(char *)tool, (char *)"-s", (char *)"--increment=0", (char *)h5, NULL};
    pid_t pid;
    if ((e = posix_spawn(&pid, tool, &fa, &attr, argv, environ)) != 0) {
        errmsg_set(err, errsize, "cannot start %s: %s", tool, strerror(e));
        goto done;
    }
    const double deadline = tlsph_monotonic_seconds() + REPAIR_TIMEOUT_S;
    int st = 0;
    for (;;) {
        pid_t r = waitpid(pid, &st, WNOHANG);
        if (r == pid)
            break;
        if (r < 0 && errno != EINTR) {
            errmsg_set(err, errsize, "waitpid(h5clear): %s", strerror(errno));
            goto done;
        }
        if (tlsph_monotonic_seconds() > deadline) {
            kill(pid, SIGKILL);
            while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
                ;
            errmsg_set(err, errsize, "h5clear did not finish within %.0f s", REPAIR_TIMEOUT_S);
            goto done;
        }
        struct timespec pause = {0, 10 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0)
        rc = 0;
    else if (WIFEXITED(st))
        errmsg_set(err, errsize, "h5clear exited with %d (its output is in the job's log)",
                   WEXITSTATUS(st));
    else
        errmsg_set(err, errsize, "h5clear was killed by signal %d", WTERMSIG(st));
done:
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    return rc;
}

/* ------------------------------------------------------------ the sidecar */

#define FRAME_STEP  "/particles/solid/position/step"
#define FRAME_TIME  "/particles/solid/position/time"
#define FRAME_VALUE "/particles/solid/position/value"
#define FRAME_COUNT "/particles/solid/count/value" /* only with a changing count */

/* The first nframes rows of the rank-1 dataset at path as mtype (esize
 * bytes each), malloc'ed; NULL with err. */
static void *read_frame_rows(hid_t f, const char *path, hsize_t nframes, hid_t mtype,
                             size_t esize, const char *h5, char *err, size_t errsize)
{
    int rank;
    hsize_t dims[3];
    void *buf = NULL;
    hid_t d = h5r_open_refreshed(f, path, &rank, dims, err, errsize);
    if (d < 0)
        return NULL;
    if (rank != 1 || dims[0] < nframes)
        errmsg_set(err, errsize, "%s: the frame datasets disagree", h5);
    else if (!(buf = malloc((nframes ? nframes : 1) * esize)))
        errmsg_set(err, errsize, "out of memory");
    else if (nframes > 0 && h5r_read_rows(d, rank, dims, nframes, mtype, buf) < 0) {
        h5r_error(err, errsize, "cannot read", path);
        free(buf);
        buf = NULL;
    }
    h5r_close(&d, H5Dclose);
    return buf;
}

/* A file whose particle count changes (io/output/output.h): each frame's
 * count into *counts (malloc'ed), checked against the particle extent n.
 * 1, 0 when the file has one count per run (*counts NULL), -1 with err. */
static int read_counts(hid_t f, hsize_t nframes, hsize_t n, size_t **counts, const char *h5,
                       char *err, size_t errsize)
{
    *counts = NULL;
    const int changing = h5r_path_exists(f, FRAME_COUNT);
    if (changing <= 0) {
        if (changing < 0)
            h5r_error(err, errsize, "cannot look up", FRAME_COUNT);
        return changing;
    }
    int64_t *c = read_frame_rows(f, FRAME_COUNT, nframes, H5T_NATIVE_INT64, sizeof *c, h5, err,
                                 errsize);
    if (!c)
        return -1;
    size_t *out = malloc((nframes ? nframes : 1) * sizeof *out);
    int rc = out ? 1 : -1;
    if (!out)
        errmsg_set(err, errsize, "out of memory");
    for (hsize_t k = 0; k < nframes && rc == 1; k++) {
        if (c[k] < 0 || (hsize_t)c[k] > n) {
            errmsg_set(err, errsize, "%s: frame %llu's count %lld is outside the datasets", h5,
                       (unsigned long long)k, (long long)c[k]);
            rc = -1;
        } else
            out[k] = (size_t)c[k];
    }
    free(c);
    if (rc < 0)
        free(out);
    else
        *counts = out;
    return rc;
}

/* Rewrites xmf to list every complete frame of h5 (frames: len(step), the
 * writer's commit marker) with the fields the file holds, as the engine's
 * writer would at close.  Returns the frame count or -1 with err. */
static long rewrite_sidecar(const char *h5, const char *xmf, char *err, size_t errsize)
{
    /* HDF5 calls from this thread beside the result readers need a
     * thread-safe library (Debian's is); otherwise leave the sidecar */
    hbool_t safe = 0;
    if (H5is_library_threadsafe(&safe) < 0 || !safe) {
        errmsg_set(err, errsize, "libhdf5 is not thread-safe: the sidecar was not rewritten");
        return -1;
    }
    h5r_quiet(); /* error printing is per thread in a thread-safe HDF5 */
    long frames = -1;
    double *times = NULL;
    size_t *counts = NULL; /* a changing count: each frame's */
    const struct tlsph_field **present = NULL;
    hid_t f = h5r_open_file(h5, err, errsize), step = -1, value = -1;
    if (f < 0)
        return -1;
    int srank, vrank;
    hsize_t sdims[3], vdims[3];
    if ((step = h5r_open_refreshed(f, FRAME_STEP, &srank, sdims, err, errsize)) < 0 ||
        (value = h5r_open_refreshed(f, FRAME_VALUE, &vrank, vdims, err, errsize)) < 0)
        goto done;
    const hsize_t nframes = sdims[0];
    if (srank != 1 || vrank != 3 || vdims[0] < nframes) {
        errmsg_set(err, errsize, "%s: the frame datasets disagree", h5);
        goto done;
    }
    if (!(times = read_frame_rows(f, FRAME_TIME, nframes, H5T_NATIVE_DOUBLE, sizeof *times, h5,
                                  err, errsize)) ||
        read_counts(f, nframes, vdims[1], &counts, h5, err, errsize) < 0)
        goto done;
    if (!(present = malloc((tlsph_nfields ? tlsph_nfields : 1) * sizeof *present))) {
        errmsg_set(err, errsize, "out of memory");
        goto done;
    }
    size_t npresent = 0;
    for (size_t i = 0; i < tlsph_nfields; i++) {
        char path[256];
        snprintf(path, sizeof path, "/particles/solid/%s", tlsph_fields[i].name);
        const int e = h5r_path_exists(f, path);
        if (e < 0) {
            h5r_error(err, errsize, "cannot look up", path);
            goto done;
        }
        if (e)
            present[npresent++] = &tlsph_fields[i];
    }
    const char *slash = strrchr(h5, '/');
    if (tlsph_xdmf_write(xmf, slash ? slash + 1 : h5, (size_t)vdims[1], (size_t)nframes, times,
                         counts, present, npresent) < 0) {
        errmsg_set(err, errsize, "cannot write %s: %s", xmf, strerror(errno));
        goto done;
    }
    frames = (long)nframes;
done:
    h5r_close(&value, H5Dclose);
    h5r_close(&step, H5Dclose);
    h5r_close(&f, H5Fclose);
    free(times);
    free(counts);
    free(present);
    return frames;
}

/* ------------------------------------------------------------ repair */

enum result_repair_rc result_repair_job(const char *tool, const char *jobs_dir, const char *id,
                                        char *msg, size_t msgsize)
{
    char h5[PATH_MAX], xmf[PATH_MAX], log[PATH_MAX];
    if (jobdir_path(h5, sizeof h5, jobs_dir, id, JOBDIR_RESULT) < 0 ||
        jobdir_path(xmf, sizeof xmf, jobs_dir, id, JOBDIR_SIDECAR) < 0 ||
        jobdir_path(log, sizeof log, jobs_dir, id, JOBDIR_LOG) < 0 ||
        result_mark(h5) != RESULT_LEFT_OPEN)
        return RESULT_NOTHING_TO_DO;
    if (!tool || !*tool) {
        errmsg_set(msg, msgsize, "h5clear not found (Debian package hdf5-tools)");
        return RESULT_NOT_REPAIRED;
    }
    struct stat before, after;
    if (stat(h5, &before) < 0) {
        errmsg_set(msg, msgsize, "%s: %s", h5, strerror(errno));
        return RESULT_NOT_REPAIRED;
    }
    if (run_h5clear(tool, h5, log, msg, msgsize) < 0)
        return RESULT_NOT_REPAIRED;
    const enum result_mark mark = result_mark(h5);
    if (stat(h5, &after) < 0 || mark != RESULT_CLOSED) {
        errmsg_set(msg, msgsize, "h5clear left it %s",
                   mark == RESULT_LEFT_OPEN ? "marked open" : "unreadable");
        return RESULT_NOT_REPAIRED;
    }
    if (after.st_size < before.st_size) {
        errmsg_set(msg, msgsize, "h5clear shrank it from %lld to %lld bytes",
                   (long long)before.st_size, (long long)after.st_size);
        return RESULT_NOT_REPAIRED;
    }
    char why[384];
    const long frames = rewrite_sidecar(h5, xmf, why, sizeof why);
    if (frames < 0)
        errmsg_set(msg, msgsize, "closed; %s", why);
    else
        errmsg_set(msg, msgsize, "closed, the sidecar lists its %ld complete frame%s", frames,
                   frames == 1 ? "" : "s");
    return RESULT_REPAIRED;
}

void result_repair_each_left_open(const char *jobs_dir, void (*fn)(const char *id, void *ctx),
                                  void *ctx)
{
    DIR *d = opendir(jobs_dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        char h5[PATH_MAX];
        /* jobdir_path accepts only valid job ids */
        if (jobdir_path(h5, sizeof h5, jobs_dir, e->d_name, JOBDIR_RESULT) == 0 &&
            result_mark(h5) == RESULT_LEFT_OPEN)
            fn(e->d_name, ctx);
    }
    closedir(d);
}
