/* tlsphd configuration, see config.h. */
#include "config.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef TLSPH_ENGINE_DEFAULT
#define TLSPH_ENGINE_DEFAULT "tlsph-run"
#endif

void tcfg_usage(FILE *f)
{
    fprintf(f,
            "usage: tlsphd [--listen ADDR:PORT] [--data-dir DIR] [--config FILE]\n"
            "              [--engine PATH] [--schemas-dir DIR] [--max-jobs N]\n"
            "              [--threads-per-job N] [--wall-limit S] [--max-particles N]\n"
            "              [--max-children N] [--body-limit BYTES] [--connection-limit N]\n"
            "              [--per-ip-limit N] [--connection-timeout S] [--memory-limit-mb N]\n"
            "              [--kill-grace S] [--max-attempts N] [--token-file FILE]\n"
            "defaults: --listen 127.0.0.1:8080, --data-dir $XDG_STATE_HOME/tlsphd or ./tlsphd-data,\n"
            "          --max-jobs 1, --threads-per-job <cores>, --wall-limit 3600,\n"
            "          --max-particles 2000000.  Config file: 'key = value' lines with the\n"
            "          same names (underscores), plus 'token_sha256 = HEX' (repeatable).\n"
            "Tokens are required when listening on a non-loopback address.\n");
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

/* Applies one key = value.  Returns 0, -1 bad value, -2 unknown key. */
static int apply(struct tcfg *c, const char *key, const char *v, char *err, size_t errsize)
{
    long l = 0;
    double d = 0.0;
    int r = 0;
    if (!strcmp(key, "listen"))
        r = parse_listen(c, v);
    else if (!strcmp(key, "data_dir"))
        r = set_str(c->data_dir, sizeof c->data_dir, v);
    else if (!strcmp(key, "engine"))
        r = set_str(c->engine, sizeof c->engine, v);
    else if (!strcmp(key, "schemas_dir"))
        r = set_str(c->schemas_dir, sizeof c->schemas_dir, v);
    else if (!strcmp(key, "max_jobs"))
        r = parse_long(v, 1, 1024, &l), c->max_jobs = (int)l;
    else if (!strcmp(key, "threads_per_job"))
        r = parse_long(v, 1, 1024, &l), c->threads_per_job = (int)l;
    else if (!strcmp(key, "wall_limit"))
        r = parse_double(v, 1, 1e9, &d), c->wall_limit = d;
    else if (!strcmp(key, "max_particles"))
        r = parse_long(v, 1, 50000000L, &l), c->max_particles = l;
    else if (!strcmp(key, "max_children"))
        r = parse_long(v, 1, 100000, &l), c->max_children = l;
    else if (!strcmp(key, "body_limit"))
        r = parse_long(v, 1024, 1L << 30, &l), c->body_limit = (size_t)l;
    else if (!strcmp(key, "connection_limit"))
        r = parse_long(v, 4, 65536, &l), c->connection_limit = (int)l;
    else if (!strcmp(key, "per_ip_limit"))
        r = parse_long(v, 0, 65536, &l), c->per_ip_limit = (int)l;
    else if (!strcmp(key, "connection_timeout"))
        r = parse_long(v, 1, 3600, &l), c->connection_timeout = (int)l;
    else if (!strcmp(key, "memory_limit_mb"))
        r = parse_long(v, 0, 1L << 30, &l), c->memory_limit_mb = l;
    else if (!strcmp(key, "kill_grace"))
        r = parse_double(v, 0, 3600, &d), c->kill_grace = d;
    else if (!strcmp(key, "max_attempts"))
        r = parse_long(v, 1, 100, &l), c->max_attempts = (int)l;
    else if (!strcmp(key, "token_sha256"))
        r = tauth_add_hex(&c->auth, v);
    else if (!strcmp(key, "token_file"))
        return tauth_load_file(&c->auth, v, err, errsize) < 0 ? -3 : 0;
    else
        return -2;
    return r == 0 ? 0 : -1;
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
        int r = apply(c, s, v, err, errsize);
        if (r == -2)
            snprintf(err, errsize, "config %s:%d: unknown key '%s'", path, lineno, s);
        else if (r == -1)
            snprintf(err, errsize, "config %s:%d: bad value for '%s'", path, lineno, s);
        if (r < 0) {
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

static const struct {
    const char *flag, *key;
} flags[] = {
    {"--listen", "listen"},
    {"--data-dir", "data_dir"},
    {"--engine", "engine"},
    {"--schemas-dir", "schemas_dir"},
    {"--max-jobs", "max_jobs"},
    {"--threads-per-job", "threads_per_job"},
    {"--wall-limit", "wall_limit"},
    {"--max-particles", "max_particles"},
    {"--max-children", "max_children"},
    {"--body-limit", "body_limit"},
    {"--connection-limit", "connection_limit"},
    {"--per-ip-limit", "per_ip_limit"},
    {"--connection-timeout", "connection_timeout"},
    {"--memory-limit-mb", "memory_limit_mb"},
    {"--kill-grace", "kill_grace"},
    {"--max-attempts", "max_attempts"},
    {"--token-file", "token_file"},
};

int tcfg_load(struct tcfg *c, int argc, char **argv, char *err, size_t errsize)
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
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    c->threads_per_job = cores > 0 ? (int)cores : 1;
    c->wall_limit = 3600;
    c->max_particles = 2000000;
    c->max_children = 1000;
    c->body_limit = 8u << 20;
    c->connection_limit = 256;
    c->per_ip_limit = 64;
    c->connection_timeout = 30;
    c->memory_limit_mb = 0;
    c->kill_grace = 5;
    c->max_attempts = 3;

    /* pass 1: --help and --config */
    const char *config = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return 1;
        if (!strcmp(argv[i], "--config")) {
            if (i + 1 >= argc) {
                snprintf(err, errsize, "--config needs a value");
                return -1;
            }
            config = argv[++i];
        }
    }
    if (config && load_file(c, config, err, errsize) != 0)
        return -1;
    /* pass 2: flags override the file */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--config")) {
            i++;
            continue;
        }
        size_t k;
        for (k = 0; k < sizeof flags / sizeof flags[0]; k++)
            if (!strcmp(argv[i], flags[k].flag))
                break;
        if (k == sizeof flags / sizeof flags[0]) {
            snprintf(err, errsize, "unknown argument '%s'", argv[i]);
            return -1;
        }
        if (i + 1 >= argc) {
            snprintf(err, errsize, "%s needs a value", argv[i]);
            return -1;
        }
        int r = apply(c, flags[k].key, argv[++i], err, errsize);
        if (r == -1)
            snprintf(err, errsize, "bad value for %s: '%s'", flags[k].flag, argv[i]);
        if (r < 0)
            return -1;
    }
    if (!c->engine[0])
        default_engine(c);
    if (!c->schemas_dir[0])
        default_schemas(c);
    if (snprintf(c->db_path, sizeof c->db_path, "%s/tlsphd.sqlite", c->data_dir) >=
            (int)sizeof c->db_path ||
        snprintf(c->jobs_dir, sizeof c->jobs_dir, "%s/jobs", c->data_dir) >=
            (int)sizeof c->jobs_dir) {
        snprintf(err, errsize, "data directory path too long");
        return -1;
    }
    if (!c->loopback && !tauth_enabled(&c->auth)) {
        snprintf(err, errsize,
                 "refusing to listen on non-loopback address %s without tokens "
                 "(token_sha256 in the config file or --token-file)",
                 c->listen);
        return -1;
    }
    return 0;
}

void tcfg_free(struct tcfg *c)
{
    tauth_free(&c->auth);
}
