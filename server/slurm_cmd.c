/* Running one Slurm command, see slurm_cmd.h. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "slurm_cmd.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "spawn_attr.h"
#include "util/clock.h"

extern char **environ;

static void close_fd(int *fd)
{
    if (*fd >= 0)
        close(*fd);
    *fd = -1;
}

/* Spawns argv with its stdin, stdout and stderr on the child ends of the
 * three pipes.  The pid, or -1 with errno. */
static pid_t spawn(char *const argv[], const int in[2], const int out[2], const int err[2])
{
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    if (posix_spawn_file_actions_init(&fa) != 0)
        return -1;
    int e = spawn_attr_defaults(&at);
    if (e) {
        posix_spawn_file_actions_destroy(&fa);
        errno = e;
        return -1;
    }
    e = posix_spawn_file_actions_adddup2(&fa, in[0], 0);
    e = e ? e : posix_spawn_file_actions_adddup2(&fa, out[1], 1);
    e = e ? e : posix_spawn_file_actions_adddup2(&fa, err[1], 2);
    pid_t pid = -1;
    if (!e)
        e = posix_spawnp(&pid, argv[0], &fa, &at, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    if (e) {
        errno = e;
        return -1;
    }
    return pid;
}

/* Reads what is there from *fd into b; closes it at EOF or error. */
static void drain(int *fd, struct strbuf *b)
{
    char buf[4096];
    for (;;) {
        const ssize_t n = read(*fd, buf, sizeof buf);
        if (n > 0) {
            strbuf_add(b, buf, (size_t)n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return;
        close_fd(fd);
        return;
    }
}

static int wait_status(pid_t pid)
{
    int st = 0;
    pid_t r;
    do {
        r = waitpid(pid, &st, 0);
    } while (r < 0 && errno == EINTR);
    if (r < 0)
        return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
}

int slurm_cmd_run(char *const argv[], const char *input, double timeout,
                  struct slurm_cmd_result *res)
{
    memset(res, 0, sizeof *res);
    res->status = -1;
    int in[2] = {-1, -1}, out[2] = {-1, -1}, err[2] = {-1, -1};
    if (pipe2(in, O_CLOEXEC) < 0 || pipe2(out, O_CLOEXEC) < 0 || pipe2(err, O_CLOEXEC) < 0) {
        strbuf_printf(&res->err, "cannot run %s: pipe: %s", argv[0], strerror(errno));
        goto done;
    }
    const pid_t pid = spawn(argv, in, out, err);
    if (pid < 0) {
        strbuf_printf(&res->err, "cannot run %s: %s", argv[0], strerror(errno));
        goto done;
    }
    close_fd(&in[0]);
    close_fd(&out[1]);
    close_fd(&err[1]);
    /* the input is small (a batch script): written whole before reading, it
     * fits the pipe buffer; a command that does not read it gets EPIPE */
    size_t left = input ? strlen(input) : 0;
    const char *p = input;
    while (left > 0) {
        const ssize_t w = write(in[1], p, left);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            break;
        p += w;
        left -= (size_t)w;
    }
    close_fd(&in[1]);
    fcntl(out[0], F_SETFL, O_NONBLOCK);
    fcntl(err[0], F_SETFL, O_NONBLOCK);
    const double end = tlsph_monotonic_seconds() + timeout;
    bool killed = false;
    while (out[0] >= 0 || err[0] >= 0) {
        struct pollfd pf[2] = {{.fd = out[0], .events = POLLIN}, {.fd = err[0], .events = POLLIN}};
        const double rest = end - tlsph_monotonic_seconds();
        if (rest <= 0) {
            kill(pid, SIGKILL);
            killed = true;
            break;
        }
        const int pr = poll(pf, 2, (int)(rest * 1000) + 1);
        if (pr < 0 && errno != EINTR)
            break;
        if (out[0] >= 0 && pf[0].revents)
            drain(&out[0], &res->out);
        if (err[0] >= 0 && pf[1].revents)
            drain(&err[0], &res->err);
    }
    res->status = wait_status(pid);
    if (killed) {
        strbuf_printf(&res->err, "%s%s did not answer within %g s", res->err.len ? "; " : "",
                      argv[0], timeout);
        res->status = -1;
    }
done:
    close_fd(&in[0]);
    close_fd(&in[1]);
    close_fd(&out[0]);
    close_fd(&out[1]);
    close_fd(&err[0]);
    close_fd(&err[1]);
    return res->status;
}

void slurm_cmd_free(struct slurm_cmd_result *res)
{
    strbuf_free(&res->out);
    strbuf_free(&res->err);
}

const char *slurm_cmd_why(const struct slurm_cmd_result *res, char *buf, size_t size)
{
    const struct strbuf *b = res->err.len ? &res->err : &res->out;
    const char *s = b->p ? b->p : "";
    const char *nl = strchr(s, '\n');
    const int n = nl ? (int)(nl - s) : (int)strlen(s);
    snprintf(buf, size, "%.*s", n, s);
    if (!buf[0])
        snprintf(buf, size, "exit status %d", res->status);
    return buf;
}
