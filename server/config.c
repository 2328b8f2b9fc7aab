/* tlsphd configuration, see config.h. */
#include "config.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <netinet/in.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run/protocol.h"
#include "scene/scene.h"
#include "thread_budget.h"

#ifndef TLSPH_ENGINE_DEFAULT
#define TLSPH_ENGINE_DEFAULT "tlsph-run"
#endif

void tcfg_usage(FILE *f)
{
    fprintf(f,
            "usage: tlsphd [--listen ADDR:PORT] [--data-dir DIR] [--config FILE]\n"
            "              [--engine PATH] [--schemas-dir DIR] [--max-jobs N]\n"
            "              [--cores N] [--threads-per-job N] [--wall-limit S] [--max-particles N]\n"
            "              [--max-children N] [--body-limit BYTES] [--connection-limit N]\n"
            "              [--per-ip-limit N] [--connection-timeout S] [--header-timeout S]\n"
            "              [--body-timeout S] [--heavy-threads N] [--memory-limit-mb N]\n"
            "              [--kill-grace S] [--max-attempts N] [--token-file FILE]\n"
            "              [--min-free-mb N] [--max-output-mb N] [--disk-reserve-mb N]\n"
            "              [--executor local|slurm] [--shared-dir DIR] [--recover]\n"
            "defaults: --listen 127.0.0.1:8080, --data-dir $XDG_STATE_HOME/tlsphd or ./tlsphd-data,\n"
            "          --max-jobs 1, --cores <CPUs>, --threads-per-job <cores / max-jobs>,\n"
            "          --wall-limit 3600,\n"
            "          --max-particles %ld, --min-free-mb 256, --max-output-mb 16384,\n"
            "          --disk-reserve-mb 8.  Config file: 'key = value' lines with the\n"
            "          same names (underscores), plus 'token_sha256 = HEX' (repeatable).\n"
            "Tokens are required when listening on a non-loopback address.\n"
            "--recover: start on a data directory that fails the start-up checks (a\n"
            "corrupt database is moved aside; job directories without rows get rows).\n",
            TLSPH_DEFAULT_MAX_PARTICLES);
}

static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) {
        /* accept exponent notation for big counts (2e6) */
        double d = strtod(s, &end);
        if (end == s || *end || d != d || d < (double)lo || d > (double)hi || d != (double)(long)d)
            return -1;
        v = (long)d;
    }
    *out = v;
    return 0;
}

static int parse_double(const char *s, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !(v >= lo && v <= hi))
        return -1;
    *out = v;
    return 0;
}

static int set_str(char *dst, size_t size, const char *v)
{
    if (strlen(v) >= size || !*v)
        return -1;
    strcpy(dst, v);
    return 0;
}

/* ADDR:PORT, [V6]:PORT, or :PORT / PORT (loopback). */
static int parse_listen(struct tcfg *c, const char *v)
{
    char host[128];
    const char *colon;
    if (strlen(v) >= sizeof c->listen)
        return -1;
    if (v[0] == '[') {
        const char *rb = strchr(v, ']');
        if (!rb || rb[1] != ':' || (size_t)(rb - v - 1) >= sizeof host)
            return -1;
        memcpy(host, v + 1, (size_t)(rb - v - 1));
        host[rb - v - 1] = '\0';
        colon = rb + 1;
    } else {
        colon = strrchr(v, ':');
        if (!colon) {
            strcpy(host, "127.0.0.1");
            colon = v - 1; /* whole string is the port */
        } else {
            if ((size_t)(colon - v) >= sizeof host)
                return -1;
            memcpy(host, v, (size_t)(colon - v));
            host[colon - v] = '\0';
            if (!*host)
                strcpy(host, "127.0.0.1");
        }
    }
    long port;
    if (parse_long(colon + 1, 1, 65535, &port) != 0)
        return -1;
    memset(&c->addr, 0, sizeof c->addr);
    struct sockaddr_in *a4 = (struct sockaddr_in *)&c->addr;
    struct sockaddr_in6 *a6 = (struct sockaddr_in6 *)&c->addr;
    if (inet_pton(AF_INET, host, &a4->sin_addr) == 1) {
        a4->sin_family = AF_INET;
        a4->sin_port = htons((uint16_t)port);
        c->addrlen = sizeof *a4;
        c->loopback = (ntohl(a4->sin_addr.s_addr) >> 24) == 127;
    } else if (inet_pton(AF_INET6, host, &a6->sin6_addr) == 1) {
        a6->sin6_family = AF_INET6;
        a6->sin6_port = htons((uint16_t)port);
        c->addrlen = sizeof *a6;
        c->loopback = IN6_IS_ADDR_LOOPBACK(&a6->sin6_addr);
    } else {
        return -1;
    }
    strcpy(c->listen, v);
    return 0;
}

/* Every setting once: its name in the file, its flag, how its value is read,
 * the accepted range and where it goes.  Limits the engine also enforces come
 * from the engine's own constants. */
enum key_kind {
    K_LISTEN,     /* ADDR:PORT */
    K_STRING,     /* a char[] member, non-empty */
    K_INT,        /* an int member, integer in [lo, hi] */
    K_LONG,       /* a long member */
    K_SIZE,       /* a size_t member */
    K_DOUBLE,     /* a double member, number in [lo, hi] */
    K_TOKEN_HEX,  /* adds a token hash */
    K_TOKEN_FILE  /* adds the tokens of a file */
};

struct key {
    const char *name; /* in the config file */
    const char *flag; /* on the command line; NULL: file only */
    enum key_kind kind;
    double lo, hi;
    size_t offset, size; /* of the member in struct tcfg */
};

#define MEMBER(m) offsetof(struct tcfg, m), sizeof(((struct tcfg *)0)->m)

static const struct key keys[] = {
    {"listen", "--listen", K_LISTEN, 0, 0, 0, 0},
    {"data_dir", "--data-dir", K_STRING, 0, 0, MEMBER(data_dir)},
    {"engine", "--engine", K_STRING, 0, 0, MEMBER(engine)},
    {"schemas_dir", "--schemas-dir", K_STRING, 0, 0, MEMBER(schemas_dir)},
    {"max_jobs", "--max-jobs", K_INT, 1, 1024, MEMBER(max_jobs)},
    {"cores", "--cores", K_INT, 1, 4096, MEMBER(cores)},
    {"threads_per_job", "--threads-per-job", K_INT, 1, TLSPH_MAX_THREADS, MEMBER(threads_per_job)},
    {"wall_limit", "--wall-limit", K_DOUBLE, 1, 1e9, MEMBER(wall_limit)},
    {"max_particles", "--max-particles", K_LONG, 1, TLSPH_MAX_PARTICLES, MEMBER(max_particles)},
    {"max_children", "--max-children", K_LONG, 1, 100000, MEMBER(max_children)},
    {"body_limit", "--body-limit", K_SIZE, 1024, 1L << 30, MEMBER(body_limit)},
    {"connection_limit", "--connection-limit", K_INT, 4, 65536, MEMBER(connection_limit)},
    {"per_ip_limit", "--per-ip-limit", K_INT, 0, 65536, MEMBER(per_ip_limit)},
    {"connection_timeout", "--connection-timeout", K_INT, 1, 3600, MEMBER(connection_timeout)},
    {"header_timeout", "--header-timeout", K_INT, 1, 3600, MEMBER(header_timeout)},
    {"body_timeout", "--body-timeout", K_INT, 1, 86400, MEMBER(body_timeout)},
    {"heavy_threads", "--heavy-threads", K_INT, 1, 32, MEMBER(heavy_threads)},
    {"memory_limit_mb", "--memory-limit-mb", K_LONG, 0, 1L << 30, MEMBER(memory_limit_mb)},
    {"kill_grace", "--kill-grace", K_DOUBLE, 0, 3600, MEMBER(kill_grace)},
    {"max_attempts", "--max-attempts", K_INT, 1, 100, MEMBER(max_attempts)},
    {"min_free_mb", "--min-free-mb", K_LONG, 0, 1L << 40, MEMBER(min_free_mb)},
    {"max_output_mb", "--max-output-mb", K_LONG, 0, 1L << 40, MEMBER(max_output_mb)},
    {"disk_reserve_mb", "--disk-reserve-mb", K_LONG, 0, 1L << 20, MEMBER(disk_reserve_mb)},
    {"executor", "--executor", K_STRING, 0, 0, MEMBER(executor)},
    {"shared_dir", "--shared-dir", K_STRING, 0, 0, MEMBER(shared_dir)},
    {"slurm_partition", NULL, K_STRING, 0, 0, MEMBER(slurm_partition)},
    {"slurm_account", NULL, K_STRING, 0, 0, MEMBER(slurm_account)},
    {"slurm_options", NULL, K_STRING, 0, 0, MEMBER(slurm_options)},
    {"slurm_poll", NULL, K_DOUBLE, 0.1, 3600, MEMBER(slurm_poll)},
    {"slurm_particles_per_cpu", NULL, K_LONG, 1, 1L << 40, MEMBER(slurm_particles_per_cpu)},
    {"slurm_bytes_per_particle", NULL, K_DOUBLE, 1, 1e9, MEMBER(slurm_bytes_per_particle)},
    {"slurm_mem_margin", NULL, K_DOUBLE, 1, 100, MEMBER(slurm_mem_margin)},
    {"slurm_mem_base_mb", NULL, K_LONG, 0, 1L << 30, MEMBER(slurm_mem_base_mb)},
    {"slurm_array_limit", NULL, K_INT, 0, 1000000, MEMBER(slurm_array_limit)},
    {"test_hold_heavy", NULL, K_STRING, 0, 0, MEMBER(test_hold_heavy)},
    {"token_sha256", NULL, K_TOKEN_HEX, 0, 0, 0, 0},
    {"token_file", "--token-file", K_TOKEN_FILE, 0, 0, 0, 0},
};
#define NKEYS (sizeof keys / sizeof keys[0])

enum apply_rc {
    APPLY_OK,
    APPLY_BAD_VALUE,   /* the caller says which key and where */
    APPLY_UNKNOWN_KEY,
    APPLY_FAILED       /* err already says why (a token file) */
};

/* Sets one setting from its text; a bad value leaves the member as it was. */
static enum apply_rc apply_key(struct tcfg *c, const struct key *k, const char *v, char *err,
                               size_t errsize)
{
    void *dst = (char *)c + k->offset;
    long l = 0;
    double d = 0;
    switch (k->kind) {
    case K_LISTEN:
        return parse_listen(c, v) == 0 ? APPLY_OK : APPLY_BAD_VALUE;
    case K_STRING:
        return set_str(dst, k->size, v) == 0 ? APPLY_OK : APPLY_BAD_VALUE;
    case K_INT:
    case K_LONG:
    case K_SIZE:
        if (parse_long(v, (long)k->lo, (long)k->hi, &l) != 0)
            return APPLY_BAD_VALUE;
        if (k->kind == K_INT)
            *(int *)dst = (int)l;
        else if (k->kind == K_LONG)
            *(long *)dst = l;
        else
            *(size_t *)dst = (size_t)l;
        return APPLY_OK;
    case K_DOUBLE:
        if (parse_double(v, k->lo, k->hi, &d) != 0)
            return APPLY_BAD_VALUE;
        *(double *)dst = d;
        return APPLY_OK;
    case K_TOKEN_HEX:
        return tauth_add_hex(&c->auth, v) == 0 ? APPLY_OK : APPLY_BAD_VALUE;
    case K_TOKEN_FILE:
        return tauth_load_file(&c->auth, v, err, errsize) < 0 ? APPLY_FAILED : APPLY_OK;
    }
    return APPLY_BAD_VALUE;
}

static const struct key *key_named(const char *name)
{
    for (size_t k = 0; k < NKEYS; k++)
        if (!strcmp(keys[k].name, name))
            return &keys[k];
    return NULL;
}

static const struct key *key_of_flag(const char *flag)
{
    for (size_t k = 0; k < NKEYS; k++)
        if (keys[k].flag && !strcmp(keys[k].flag, flag))
            return &keys[k];
    return NULL;
}

static int load_file(struct tcfg *c, const char *path, char *err, size_t errsize)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errsize, "config %s: %s", path, strerror(errno));
        return -1;
    }
    char line[2048];
    int lineno = 0, rc = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *s = line, *e;
        while (isspace((unsigned char)*s))
            s++;
        if (*s == '#' || *s == '\0')
            continue;
        char *eq = strchr(s, '=');
        if (!eq) {
            snprintf(err, errsize, "config %s:%d: expected 'key = value'", path, lineno);
            rc = -1;
            break;
        }
        *eq = '\0';
        char *v = eq + 1;
        for (e = eq; e > s && isspace((unsigned char)e[-1]); e--)
            e[-1] = '\0';
        while (isspace((unsigned char)*v))
            v++;
        for (e = v + strlen(v); e > v && isspace((unsigned char)e[-1]); e--)
            e[-1] = '\0';
        for (char *k = s; *k; k++)
            if (*k == '-')
                *k = '_';
        const struct key *k = key_named(s);
        enum apply_rc r = k ? apply_key(c, k, v, err, errsize) : APPLY_UNKNOWN_KEY;
        if (r == APPLY_UNKNOWN_KEY)
            snprintf(err, errsize, "config %s:%d: unknown key '%s'", path, lineno, s);
        else if (r == APPLY_BAD_VALUE)
            snprintf(err, errsize, "config %s:%d: bad value for '%s'", path, lineno, s);
        if (r != APPLY_OK) {
            rc = -1;
            break;
        }
    }
    fclose(f);
    return rc;
}

static void default_engine(struct tcfg *c)
{
    char exe[896];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            slash[1] = '\0';
            if (strlen(exe) + sizeof "tlsph-run" < sizeof c->engine) {
                snprintf(c->engine, sizeof c->engine, "%stlsph-run", exe);
                if (access(c->engine, X_OK) == 0)
                    return;
            }
        }
    }
    snprintf(c->engine, sizeof c->engine, "%s", TLSPH_ENGINE_DEFAULT);
}

/* openapi.json: --schemas-dir, else TLSPH_SCHEMAS_DIR (install), else
 * <exe dir>/schemas (source tree), else <exe dir>/../share/tlsph/schemas. */
static void default_schemas(struct tcfg *c)
{
    char exe[896], cand[1024];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
#ifdef TLSPH_SCHEMAS_DIR
    snprintf(cand, sizeof cand, "%s/openapi.json", TLSPH_SCHEMAS_DIR);
    if (access(cand, R_OK) == 0) {
        snprintf(c->schemas_dir, sizeof c->schemas_dir, "%s", TLSPH_SCHEMAS_DIR);
        return;
    }
#endif
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            const char *rel[] = {"/schemas", "/../share/tlsph/schemas"};
            for (size_t i = 0; i < 2; i++) {
                snprintf(cand, sizeof cand, "%s%s/openapi.json", exe, rel[i]);
                size_t len = strlen(cand) - strlen("/openapi.json");
                if (access(cand, R_OK) == 0 && len < sizeof c->schemas_dir) {
                    memcpy(c->schemas_dir, cand, len);
                    c->schemas_dir[len] = '\0';
                    return;
                }
            }
        }
    }
    snprintf(c->schemas_dir, sizeof c->schemas_dir, "schemas");
}

enum tcfg_rc tcfg_load(struct tcfg *c, int argc, char **argv, char *err, size_t errsize)
{
    memset(c, 0, sizeof *c);
    tauth_init(&c->auth);
    parse_listen(c, "127.0.0.1:8080");
    const char *xdg = getenv("XDG_STATE_HOME");
    if (xdg && *xdg == '/' && strlen(xdg) + 16 < sizeof c->data_dir)
        snprintf(c->data_dir, sizeof c->data_dir, "%s/tlsphd", xdg);
    else
        snprintf(c->data_dir, sizeof c->data_dir, "./tlsphd-data");
    c->max_jobs = 1;
    c->threads_per_job = 0; /* settled below, once max_jobs and cores are known */
    c->wall_limit = 3600;
    c->max_particles = TLSPH_DEFAULT_MAX_PARTICLES;
    c->max_children = 1000;
    c->body_limit = 8u << 20;
    c->connection_limit = 512;
    c->per_ip_limit = 64;
    c->connection_timeout = 30;
    c->header_timeout = 10;
    c->body_timeout = 120;
    c->heavy_threads = 2;
    c->memory_limit_mb = 0;
    c->kill_grace = 5;
    c->max_attempts = 3;
    c->min_free_mb = 256;
    c->max_output_mb = 16384;
    c->disk_reserve_mb = 8;
    snprintf(c->executor, sizeof c->executor, "local");
    c->slurm_poll = 2;
    c->slurm_particles_per_cpu = 20000;
    c->slurm_bytes_per_particle = 4096;
    c->slurm_mem_margin = 1.5;
    c->slurm_mem_base_mb = 256;

    /* pass 1: --help, --config and --recover (a mode of this start, not a setting) */
    const char *config = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return TCFG_HELP;
        if (!strcmp(argv[i], "--config")) {
            if (i + 1 >= argc) {
                snprintf(err, errsize, "--config needs a value");
                return TCFG_ERROR;
            }
            config = argv[++i];
        } else if (!strcmp(argv[i], "--recover")) {
            c->recover = 1;
        }
    }
    if (config && load_file(c, config, err, errsize) != 0)
        return TCFG_ERROR;
    /* pass 2: flags override the file */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--config")) {
            i++;
            continue;
        }
        if (!strcmp(argv[i], "--recover"))
            continue;
        const struct key *k = key_of_flag(argv[i]);
        if (!k) {
            snprintf(err, errsize, "unknown argument '%s'", argv[i]);
            return TCFG_ERROR;
        }
        if (i + 1 >= argc) {
            snprintf(err, errsize, "%s needs a value", argv[i]);
            return TCFG_ERROR;
        }
        enum apply_rc r = apply_key(c, k, argv[++i], err, errsize);
        if (r == APPLY_BAD_VALUE)
            snprintf(err, errsize, "bad value for %s: '%s'", k->flag, argv[i]);
        if (r != APPLY_OK)
            return TCFG_ERROR;
    }
    if (!c->engine[0])
        default_engine(c);
    if (!c->schemas_dir[0])
        default_schemas(c);
    if (strcmp(c->executor, "local") != 0 && strcmp(c->executor, "slurm") != 0) {
        snprintf(err, errsize, "executor must be \"local\" or \"slurm\", not \"%s\"", c->executor);
        return TCFG_ERROR;
    }
    if (!c->cores)
        c->cores = tbudget_detect_cores();
    if (!strcmp(c->executor, "slurm")) /* Slurm allots cores: threads_per_job caps a task */
        c->threads_per_job = c->threads_per_job          ? c->threads_per_job
                             : c->cores < TLSPH_MAX_THREADS ? c->cores
                                                            : TLSPH_MAX_THREADS;
    else
        tbudget_configure(c->cores, c->max_jobs, &c->threads_per_job, c->budget_warning,
                          sizeof c->budget_warning);
    if (c->threads_per_job > TLSPH_MAX_THREADS) /* more cores than one engine takes */
        c->threads_per_job = TLSPH_MAX_THREADS;
    if (snprintf(c->db_path, sizeof c->db_path, "%s/tlsphd.sqlite", c->data_dir) >=
            (int)sizeof c->db_path ||
        (c->shared_dir[0] ? snprintf(c->jobs_dir, sizeof c->jobs_dir, "%s", c->shared_dir)
                          : snprintf(c->jobs_dir, sizeof c->jobs_dir, "%s/jobs", c->data_dir)) >=
            (int)sizeof c->jobs_dir) {
        snprintf(err, errsize, "data directory path too long");
        return TCFG_ERROR;
    }
    if (!c->loopback && !tauth_enabled(&c->auth)) {
        snprintf(err, errsize,
                 "refusing to listen on non-loopback address %s without tokens "
                 "(token_sha256 in the config file or --token-file)",
                 c->listen);
        return TCFG_ERROR;
    }
    return TCFG_OK;
}

void tcfg_free(struct tcfg *c)
{
    tauth_free(&c->auth);
}
