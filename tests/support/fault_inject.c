/* Disk faults on demand for the daemon tests (LD_PRELOAD), without
 * privileges: an open() or mkdir() of a path containing a chosen text fails
 * with a chosen errno, as a failing disk, a full one or a read-only mount
 * would make it fail.
 *
 * The rules are read from the file named by TLSPH_FAULT_FILE at every call,
 * so a test changes them while the daemon runs: one rule a line,
 *     <open|mkdir> <path text> <errno number>
 * An empty or missing file injects nothing.  Built by the test that uses it
 * (cc -shared -fPIC fault_inject.c -ldl). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

/* The errno of the first rule for (op, path), 0 when none applies.  Reads
 * the rules with raw system calls, so it never recurses into the wrappers. */
static int fault_for(const char *op, const char *path)
{
    const char *file = getenv("TLSPH_FAULT_FILE");
    if (!file || !path)
        return 0;
    int fd = (int)syscall(SYS_openat, AT_FDCWD, file, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return 0;
    char buf[2048];
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0)
        return 0;
    buf[n] = '\0';
    char *save = NULL;
    for (char *line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char rop[16], text[1024];
        int e;
        if (sscanf(line, "%15s %1023s %d", rop, text, &e) == 3 && !strcmp(rop, op) &&
            strstr(path, text))
            return e;
    }
    return 0;
}

typedef int open_fn(const char *, int, ...);
typedef int openat_fn(int, const char *, int, ...);
typedef int mkdir_fn(const char *, mode_t);
typedef int mkdirat_fn(int, const char *, mode_t);

/* -1 with errno set when a rule makes this call fail, else 0. */
static int injected(const char *op, const char *path)
{
    const int e = fault_for(op, path);
    if (e)
        errno = e;
    return e ? -1 : 0;
}

/* The optional mode argument of an open call. */
#define MODE_OF(flags, mode)                                                                   \
    do {                                                                                       \
        va_list ap;                                                                            \
        va_start(ap, flags);                                                                   \
        mode = ((flags)&O_CREAT) || ((flags)&O_TMPFILE) == O_TMPFILE ? va_arg(ap, mode_t) : 0; \
        va_end(ap);                                                                            \
    } while (0)

#define OPEN_WRAPPER(name)                                                                       \
    int name(const char *path, int flags, ...)                                                   \
    {                                                                                            \
        mode_t mode;                                                                             \
        MODE_OF(flags, mode);                                                                    \
        return injected("open", path) ? -1                                                       \
                                      : ((open_fn *)dlsym(RTLD_NEXT, #name))(path, flags, mode); \
    }
#define OPENAT_WRAPPER(name)                                                         \
    int name(int dfd, const char *path, int flags, ...)                              \
    {                                                                                \
        mode_t mode;                                                                 \
        MODE_OF(flags, mode);                                                        \
        return injected("open", path)                                                \
                   ? -1                                                              \
                   : ((openat_fn *)dlsym(RTLD_NEXT, #name))(dfd, path, flags, mode); \
    }

OPEN_WRAPPER(open)
OPEN_WRAPPER(open64)
OPENAT_WRAPPER(openat)
OPENAT_WRAPPER(openat64)

int mkdir(const char *path, mode_t mode)
{
    return injected("mkdir", path) ? -1 : ((mkdir_fn *)dlsym(RTLD_NEXT, "mkdir"))(path, mode);
}

int mkdirat(int dfd, const char *path, mode_t mode)
{
    return injected("mkdir", path) ? -1
                                   : ((mkdirat_fn *)dlsym(RTLD_NEXT, "mkdirat"))(dfd, path, mode);
}
