/* Files that survive a crash, see durable.h. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* mkostemps */
#endif
#include "durable.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "errmsg.h"

static int write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

static int fsync_dir(const char *path)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    int e = errno;
    close(fd);
    errno = e;
    return rc;
}

int durable_write(const char *dir, char *tmpl, const char *path, const char *data, size_t len,
                  char *err, size_t errsize)
{
    int fd = mkostemps(tmpl, 4, O_CLOEXEC);
    if (fd < 0) {
        errmsg_set(err, errsize, "cannot create %s: %s", tmpl, strerror(errno));
        return -1;
    }
    if (write_all(fd, data, len) < 0 || fsync(fd) < 0) {
        errmsg_set(err, errsize, "cannot write %s: %s", tmpl, strerror(errno));
        close(fd);
        unlink(tmpl);
        return -1;
    }
    if (close(fd) < 0) {
        errmsg_set(err, errsize, "cannot write %s: %s", tmpl, strerror(errno));
        unlink(tmpl);
        return -1;
    }
    if (rename(tmpl, path) < 0) {
        errmsg_set(err, errsize, "cannot rename %s: %s", tmpl, strerror(errno));
        unlink(tmpl);
        return -1;
    }
    if (fsync_dir(dir) < 0) {
        errmsg_set(err, errsize, "cannot sync %s: %s", dir, strerror(errno));
        return -1;
    }
    return 0;
}
