/* The data directory's disk, see storage.h. */
#include "storage.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "config.h"
#include "errmsg.h"

#define MIB (1024.0 * 1024.0)

static int reserve_path(const struct tcfg *cfg, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s/" STORAGE_RESERVE_NAME, cfg->data_dir);
    return n < 0 || (size_t)n >= size ? -1 : 0;
}

static uint64_t reserve_bytes(const struct tcfg *cfg)
{
    return cfg->disk_reserve_mb > 0 ? (uint64_t)cfg->disk_reserve_mb * (uint64_t)MIB : 0;
}

int64_t storage_free_bytes(const struct tcfg *cfg)
{
    struct statvfs v;
    if (statvfs(cfg->data_dir, &v) != 0)
        return -1;
    const double bytes = (double)v.f_bavail * (double)v.f_frsize;
    return bytes > (double)INT64_MAX ? INT64_MAX : (int64_t)bytes;
}

uint64_t storage_floor_bytes(const struct tcfg *cfg)
{
    return cfg->min_free_mb > 0 ? (uint64_t)cfg->min_free_mb * (uint64_t)MIB : 0;
}

bool storage_below_floor(const struct tcfg *cfg)
{
    const int64_t free_bytes = storage_free_bytes(cfg);
    return free_bytes >= 0 && (uint64_t)free_bytes < storage_floor_bytes(cfg);
}

bool storage_reserve_held(const struct tcfg *cfg)
{
    char path[PATH_MAX];
    if (!reserve_bytes(cfg) || reserve_path(cfg, path, sizeof path) != 0)
        return true;
    return access(path, F_OK) == 0;
}

bool storage_release_reserve(const struct tcfg *cfg)
{
    char path[PATH_MAX];
    if (!reserve_bytes(cfg) || reserve_path(cfg, path, sizeof path) != 0)
        return false;
    return unlink(path) == 0;
}

int storage_keep_reserve(const struct tcfg *cfg, char *err, size_t errsize)
{
    const uint64_t want = reserve_bytes(cfg);
    char path[PATH_MAX], tmp[PATH_MAX + 8];
    if (!want || storage_reserve_held(cfg))
        return 0;
    const int64_t free_bytes = storage_free_bytes(cfg);
    if (free_bytes < 0 || (uint64_t)free_bytes < storage_floor_bytes(cfg) + want)
        return 0; /* not yet: the space is better left to the jobs */
    if (reserve_path(cfg, path, sizeof path) != 0 ||
        snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp) {
        errmsg_set(err, errsize, "reserve file: path too long");
        return -1;
    }
    /* allocated under a temporary name and renamed: a reserve that exists is whole */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0600);
    int e = fd < 0 ? errno : posix_fallocate(fd, 0, (off_t)want);
    if (fd >= 0 && close(fd) != 0 && e == 0)
        e = errno;
    if (e == 0 && rename(tmp, path) != 0)
        e = errno;
    if (e != 0) {
        unlink(tmp);
        errmsg_set(err, errsize, "cannot allocate the reserve file %s (%.0f MiB): %s", path,
                   (double)want / MIB, strerror(e));
        return -1;
    }
    return 0;
}
