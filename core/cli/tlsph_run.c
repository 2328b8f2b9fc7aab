/* tlsph-run: runs one scene through the engine.
 *
 *   tlsph-run SCENE.json -o DIR [--progress-fd N] [--threads N] [--validate] [--quiet]
 *
 * Exit codes (enum tlsph_exit in run/protocol.h): 0 success, 1 usage/internal,
 * 2 invalid scene (errors on stderr as {"errors":[{"pointer","detail"}]}; nothing
 * written), 3 numerically unstable (diagnostic in the log and in DIR/result.h5),
 * 4 I/O failure, 5 cancelled by SIGTERM/SIGINT (current frame finished, file closed).
 * With --progress-fd every outcome but 1 ends with a final event that carries
 * the errors or the diagnostic (docs/protocol.md); stderr is for people.
 * SIGTERM/SIGINT during validation or setup (before the run starts) exit 5 at
 * once, with the final event "cancelled" and nothing written. */
#include <errno.h>
#include <hdf5.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "run/model.h"
#include "run/progress.h"
#include "run/run.h"

static volatile sig_atomic_t cancel_requested;

/* While the run goes on: the run loop polls the flag, finishes the frame and
 * closes the file. */
static void on_signal(int sig)
{
    (void)sig;
    cancel_requested = 1;
}

/* Before the run starts, the scene parser and the model setup (lattice,
 * neighbour search: long for big scenes) do not poll, and nothing has been
 * written: the handler ends the process itself, with the final event
 * formatted beforehand (write and _exit are async-signal-safe). */
static struct {
    int fd;        /* --progress-fd, -1 none */
    char line[96]; /* {"event":"finished","status":"cancelled"} and a newline */
    size_t len;
} setup_cancel = {.fd = -1};

static void on_signal_in_setup(int sig)
{
    (void)sig;
    static const char msg[] = "tlsph: cancelled before the run started\n";
    if (setup_cancel.fd >= 0 && setup_cancel.len > 0) {
        const ssize_t w = write(setup_cancel.fd, setup_cancel.line, setup_cancel.len);
        (void)w;
    }
    const ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)w;
    _exit(TLSPH_EXIT_CANCELLED);
}

static void set_handlers(void (*handler)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
}

/* Formats the final event of a cancel before the run for on_signal_in_setup. */
static void prepare_setup_cancel(int fd)
{
    json_t *o = tlsph_progress_final(TLSPH_EXIT_CANCELLED, NULL);
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    const int len = text ? snprintf(setup_cancel.line, sizeof setup_cancel.line, "%s\n", text) : -1;
    setup_cancel.fd = fd;
    setup_cancel.len = len > 0 && (size_t)len < sizeof setup_cancel.line ? (size_t)len : 0;
    free(text);
    json_decref(o);
}

static void usage(FILE *f)
{
    fprintf(f, "usage: tlsph-run SCENE.json -o DIR [--progress-fd N] [--threads N] [--validate] "
               "[--quiet]\n"
               "exit codes: 0 success, 1 usage, 2 invalid scene, 3 unstable, 4 I/O failure, "
               "5 cancelled\n");
}

static void print_errors(const struct tlsph_errors *err)
{
    json_t *arr = tlsph_errors_to_json(err);
    json_t *o = arr ? json_pack("{s:o}", "errors", arr) : NULL;
    char *text = o ? json_dumps(o, JSON_COMPACT) : NULL;
    if (text)
        fprintf(stderr, "%s\n", text);
    free(text);
    json_decref(o);
    for (size_t k = 0; k < err->count; k++)
        fprintf(stderr, "error: %s: %s\n", err->items[k].pointer[0] ? err->items[k].pointer : "(scene)",
                err->items[k].message);
}

/* The final event of a run that never started (invalid scene, no output
 * directory): the errors are all the caller gets. */
static void emit_final(int fd, enum tlsph_exit code, const struct tlsph_errors *err)
{
    json_t *o = tlsph_progress_final(code, err);
    tlsph_progress_emit(fd, o);
    json_decref(o);
}

static int parse_int(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || *end || end == s || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *out_dir = NULL;
    long progress_fd = -1, threads = 0;
    int validate_only = 0, quiet = 0;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "-o") == 0 && a + 1 < argc) {
            out_dir = argv[++a];
        } else if (strcmp(argv[a], "--progress-fd") == 0 && a + 1 < argc) {
            if (parse_int(argv[++a], 0, 1 << 20, &progress_fd) != 0) {
                usage(stderr);
                return TLSPH_EXIT_USAGE;
            }
        } else if (strcmp(argv[a], "--threads") == 0 && a + 1 < argc) {
            if (parse_int(argv[++a], 1, TLSPH_MAX_THREADS, &threads) != 0) {
                usage(stderr);
                return TLSPH_EXIT_USAGE;
            }
        } else if (strcmp(argv[a], "--validate") == 0) {
            validate_only = 1;
        } else if (strcmp(argv[a], "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(argv[a], "-h") == 0 || strcmp(argv[a], "--help") == 0) {
            usage(stdout);
            return TLSPH_EXIT_SUCCESS;
        } else if (argv[a][0] != '-' && !scene_path) {
            scene_path = argv[a];
        } else {
            usage(stderr);
            return TLSPH_EXIT_USAGE;
        }
    }
    if (!scene_path || (!out_dir && !validate_only)) {
        usage(stderr);
        return TLSPH_EXIT_USAGE;
    }
#ifdef _OPENMP
    if (threads > 0)
        omp_set_num_threads((int)threads);
#endif
    /* No HDF5 clean-up at exit: the writer closes every file it opens, and
     * HDF5 1.10's exit handler crashes (SIGSEGV in H5F__close_cb) on a file
     * whose close failed -- a full disk or a file-size limit -- which would
     * turn exit code 4 into a death by signal after the final event.  Must
     * come before any other HDF5 call. */
    H5dont_atexit();

    signal(SIGPIPE, SIG_IGN);
    prepare_setup_cancel((int)progress_fd);
    set_handlers(on_signal_in_setup);

    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    const int rejected = tlsph_scene_load_file(scene_path, &scene, &err) != 0 ||
                         tlsph_model_create(&scene, &m, &err) != 0;
    set_handlers(on_signal); /* from here on, a signal is one event among others */
    if (rejected) {
        print_errors(&err);
        if (err.count == 0) /* the event promises at least one error */
            tlsph_errors_add(&err, "", "the scene was rejected");
        emit_final((int)progress_fd, TLSPH_EXIT_INVALID, &err);
        tlsph_errors_free(&err);
        return TLSPH_EXIT_INVALID;
    }
    if (validate_only) {
        printf("{\"valid\":true,\"particles\":%zu,\"pairs\":%zu,\"first_step\":%.6g,"
               "\"estimated_steps\":%.0f}\n",
               m->p.n, m->pairs.npairs, m->scene.estimated_dt, m->scene.estimated_steps);
        tlsph_model_free(m);
        tlsph_errors_free(&err);
        return TLSPH_EXIT_SUCCESS;
    }
    if (mkdir(out_dir, 0777) != 0 && errno != EEXIST) {
        const int e = errno;
        fprintf(stderr, "error: cannot create output directory '%s': %s\n", out_dir, strerror(e));
        tlsph_errors_add(&err, "", "cannot create output directory '%s': %s", out_dir, strerror(e));
        emit_final((int)progress_fd, TLSPH_EXIT_IO, &err);
        tlsph_model_free(m);
        tlsph_errors_free(&err);
        return TLSPH_EXIT_IO;
    }
    struct tlsph_run_options opt = {
        .output_dir = out_dir,
        .progress_fd = (int)progress_fd,
        .cancel = &cancel_requested,
        .log = quiet ? NULL : stderr,
    };
    struct tlsph_diagnostic diag;
    memset(&diag, 0, sizeof diag);
    int code = tlsph_run(m, &opt, &diag, &err);
    if (code == TLSPH_EXIT_IO)
        print_errors(&err);
    if (code == TLSPH_EXIT_SUCCESS && !quiet)
        fprintf(stderr, "tlsph: result in %s/result.h5 (open %s/result.xmf in ParaView with the "
                        "\"XDMF Reader\")\n", out_dir, out_dir);
    tlsph_model_free(m);
    tlsph_errors_free(&err);
    return code;
}
