/* libcurl wrapper.  Every request: connect timeout 5 s, a total timeout (long-poll
 * aware, given by the caller), no redirects (the token stays with the configured
 * server), http/https only, bodies capped at HTTP_MAX_BODY. */
#ifdef HAVE_CONFIG_H
#include <config.h>
#endif
#include "http.h"

#include <curl/curl.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "exitcodes.h"
#include "fetch_bar.h"

#ifndef PACKAGE_VERSION
#define PACKAGE_VERSION "dev"
#endif

int http_global_init(void)
{
    if (curl_global_init(CURL_GLOBAL_DEFAULT) != CURLE_OK) {
        fprintf(stderr, "tlsph: cannot initialise libcurl\n");
        return RC_NETWORK;
    }
    return RC_OK;
}

void http_global_cleanup(void)
{
    curl_global_cleanup();
}

/* ------------------------------------------------------------ buffers, headers */
typedef struct {
    char *p;
    size_t len, cap;
    int overflow;
} membuf;

static int membuf_add(membuf *b, const char *d, size_t k)
{
    if (k > HTTP_MAX_BODY - b->len) {
        b->overflow = 1;
        return -1;
    }
    if (b->len + k + 1 > b->cap) {
        size_t nc = b->cap ? b->cap : 4096;
        while (nc < b->len + k + 1)
            nc *= 2;
        char *np = realloc(b->p, nc);
        if (!np) {
            b->overflow = 1;
            return -1;
        }
        b->p = np;
        b->cap = nc;
    }
    memcpy(b->p + b->len, d, k);
    b->len += k;
    b->p[b->len] = '\0';
    return 0;
}

static size_t write_mem(char *d, size_t sz, size_t n, void *u)
{
    return membuf_add(u, d, sz * n) == 0 ? sz * n : 0;
}

typedef struct {
    long status;
    char etag[256];
    char content_type[128];
    long long content_length; /* -1 unknown */
    long long range_start;    /* from Content-Range, -1 unknown */
    long long range_total;    /* from Content-Range, -1 unknown */
} headers;

static void headers_reset(headers *h)
{
    memset(h, 0, sizeof *h);
    h->content_length = h->range_start = h->range_total = -1;
}

static void copy_trimmed(char *dst, size_t cap, const char *v, size_t n)
{
    while (n > 0 && (*v == ' ' || *v == '\t')) {
        v++;
        n--;
    }
    while (n > 0 && (v[n - 1] == '\r' || v[n - 1] == '\n' || v[n - 1] == ' '))
        n--;
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, v, n);
    dst[n] = '\0';
}

static size_t header_cb(char *d, size_t sz, size_t n, void *u)
{
    headers *h = u;
    size_t k = sz * n;
    char line[512];
    copy_trimmed(line, sizeof line, d, k);
    if (strncmp(line, "HTTP/", 5) == 0) {
        headers_reset(h);
        const char *sp = strchr(line, ' ');
        if (sp)
            h->status = strtol(sp + 1, NULL, 10);
        return k;
    }
    char *colon = strchr(line, ':');
    if (!colon)
        return k;
    *colon = '\0';
    const char *v = colon + 1;
    while (*v == ' ')
        v++;
    if (strcasecmp(line, "ETag") == 0)
        snprintf(h->etag, sizeof h->etag, "%s", v);
    else if (strcasecmp(line, "Content-Type") == 0)
        snprintf(h->content_type, sizeof h->content_type, "%s", v);
    else if (strcasecmp(line, "Content-Length") == 0)
        h->content_length = strtoll(v, NULL, 10);
    else if (strcasecmp(line, "Content-Range") == 0) {
        long long a, b, t;
        if (sscanf(v, "bytes %lld-%lld/%lld", &a, &b, &t) == 3) {
            h->range_start = a;
            h->range_total = t;
        } else if (sscanf(v, "bytes */%lld", &t) == 1) {
            h->range_total = t;
        }
    }
    return k;
}

/* ------------------------------------------------------------ handle setup */
typedef struct {
    CURL *c;
    struct curl_slist *hdrs;
    char err[CURL_ERROR_SIZE];
} request;

#define SETOPT(r, opt, val)                                                                    \
    do {                                                                                       \
        if (curl_easy_setopt((r)->c, opt, val) != CURLE_OK) {                                  \
            fprintf(stderr, "tlsph: libcurl rejected option %s\n", #opt);                     \
            return RC_NETWORK;                                                                 \
        }                                                                                      \
    } while (0)

static int add_header(request *r, const char *h)
{
    struct curl_slist *n = curl_slist_append(r->hdrs, h);
    if (!n) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    r->hdrs = n;
    return RC_OK;
}

static void request_free(request *r)
{
    curl_slist_free_all(r->hdrs);
    if (r->c)
        curl_easy_cleanup(r->c);
    r->hdrs = NULL;
    r->c = NULL;
}

/* Creates the handle for METHOD url; timeout_s 0 = no total timeout (downloads use
 * a low-speed limit instead). */
static int request_init(request *r, const settings *s, const char *method, const char *path,
                        long timeout_s, const char *accept)
{
    memset(r, 0, sizeof *r);
    size_t n = strlen(s->url) + strlen(path) + 1;
    char *url = malloc(n);
    if (!url) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    snprintf(url, n, "%s%s", s->url, path);
    r->c = curl_easy_init();
    if (!r->c) {
        free(url);
        fprintf(stderr, "tlsph: cannot create a libcurl handle\n");
        return RC_NETWORK;
    }
    int rc = RC_OK;
    if (curl_easy_setopt(r->c, CURLOPT_URL, url) != CURLE_OK) {
        fprintf(stderr, "tlsph: invalid URL %s\n", url);
        rc = RC_USAGE;
    }
    free(url);
    if (rc != RC_OK)
        return rc;
    SETOPT(r, CURLOPT_ERRORBUFFER, r->err);
    SETOPT(r, CURLOPT_NOSIGNAL, 1L);
    SETOPT(r, CURLOPT_CONNECTTIMEOUT, 5L);
    if (timeout_s > 0) {
        SETOPT(r, CURLOPT_TIMEOUT, timeout_s);
    } else {
        SETOPT(r, CURLOPT_LOW_SPEED_LIMIT, 1L);
        SETOPT(r, CURLOPT_LOW_SPEED_TIME, 60L);
    }
    SETOPT(r, CURLOPT_FOLLOWLOCATION, 0L);
#if LIBCURL_VERSION_NUM >= 0x075500
    SETOPT(r, CURLOPT_PROTOCOLS_STR, "http,https");
#endif
    SETOPT(r, CURLOPT_USERAGENT, "tlsph/" PACKAGE_VERSION);
    if (strcmp(method, "GET") != 0)
        SETOPT(r, CURLOPT_CUSTOMREQUEST, method);
    if (s->token[0]) {
        char auth[1100];
        snprintf(auth, sizeof auth, "Authorization: Bearer %s", s->token);
        if ((rc = add_header(r, auth)) != RC_OK)
            return rc;
    }
    if (accept) {
        char a[200];
        snprintf(a, sizeof a, "Accept: %s", accept);
        if ((rc = add_header(r, a)) != RC_OK)
            return rc;
    }
    return RC_OK;
}

/* Runs the request; maps transport failures to an RC_* code with a message. */
static int request_perform(request *r, const settings *s, int overflow)
{
    if (r->hdrs && curl_easy_setopt(r->c, CURLOPT_HTTPHEADER, r->hdrs) != CURLE_OK) {
        fprintf(stderr, "tlsph: libcurl rejected the headers\n");
        return RC_NETWORK;
    }
    CURLcode cc = curl_easy_perform(r->c);
    if (cc == CURLE_OK)
        return RC_OK;
    long oserr = 0;
    if (curl_easy_getinfo(r->c, CURLINFO_OS_ERRNO, &oserr) != CURLE_OK)
        oserr = 0;
    const char *why = r->err[0] ? r->err : curl_easy_strerror(cc);
    switch (cc) {
    case CURLE_COULDNT_CONNECT:
        fprintf(stderr, "tlsph: cannot connect to %s: %s\n", s->url, oserr ? strerror((int)oserr) : why);
        return RC_NETWORK;
    case CURLE_COULDNT_RESOLVE_HOST:
    case CURLE_COULDNT_RESOLVE_PROXY:
        fprintf(stderr, "tlsph: cannot connect to %s: cannot resolve host (%s)\n", s->url, why);
        return RC_NETWORK;
    case CURLE_OPERATION_TIMEDOUT:
        fprintf(stderr, "tlsph: %s did not answer in time: %s\n", s->url, why);
        return RC_NETWORK;
    case CURLE_WRITE_ERROR:
        if (overflow) {
            fprintf(stderr, "tlsph: the response from %s is larger than %zu MiB\n", s->url,
                    HTTP_MAX_BODY >> 20);
            return RC_NETWORK;
        }
        fprintf(stderr, "tlsph: cannot write the response: %s\n", why);
        return RC_IO;
    default:
        fprintf(stderr, "tlsph: request to %s failed: %s\n", s->url, why);
        return RC_NETWORK;
    }
}

/* ------------------------------------------------------------ in-memory exchanges */
int http_exchange(const settings *s, const char *method, const char *path, const char *json_body,
                  long timeout_s, http_response *r)
{
    memset(r, 0, sizeof *r);
    request q;
    membuf b = {0};
    headers h;
    headers_reset(&h);
    int rc = request_init(&q, s, method, path, timeout_s, "application/json, text/csv;q=0.9, */*;q=0.1");
    if (rc == RC_OK && json_body) {
        rc = add_header(&q, "Content-Type: application/json");
        if (rc == RC_OK && (curl_easy_setopt(q.c, CURLOPT_POSTFIELDS, json_body) != CURLE_OK ||
                            curl_easy_setopt(q.c, CURLOPT_POSTFIELDSIZE_LARGE,
                                             (curl_off_t)strlen(json_body)) != CURLE_OK)) {
            fprintf(stderr, "tlsph: libcurl rejected the request body\n");
            rc = RC_NETWORK;
        }
    }
    if (rc == RC_OK && (curl_easy_setopt(q.c, CURLOPT_WRITEFUNCTION, write_mem) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_WRITEDATA, &b) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_HEADERFUNCTION, header_cb) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_HEADERDATA, &h) != CURLE_OK)) {
        fprintf(stderr, "tlsph: libcurl rejected the callbacks\n");
        rc = RC_NETWORK;
    }
    if (rc == RC_OK)
        rc = request_perform(&q, s, b.overflow);
    if (rc == RC_OK && curl_easy_getinfo(q.c, CURLINFO_RESPONSE_CODE, &r->status) != CURLE_OK)
        r->status = h.status;
    request_free(&q);
    if (rc != RC_OK) {
        free(b.p);
        return rc;
    }
    if (!b.p) {
        b.p = calloc(1, 1);
        if (!b.p) {
            fprintf(stderr, "tlsph: out of memory\n");
            return RC_IO;
        }
    }
    r->body = b.p;
    r->len = b.len;
    snprintf(r->content_type, sizeof r->content_type, "%s", h.content_type);
    return RC_OK;
}

void http_response_free(http_response *r)
{
    free(r->body);
    r->body = NULL;
    r->len = 0;
}

/* Prints text from the server without terminal control characters. */
static void print_clean(FILE *f, const char *t, size_t max)
{
    for (size_t i = 0; t[i] && i < max; i++) {
        unsigned char c = (unsigned char)t[i];
        fputc(c < 0x20 && c != '\n' && c != '\t' ? '?' : (c == 0x7f ? '?' : c), f);
    }
}

int http_report_error(const settings *s, const http_response *r)
{
    int rc = (r->status == 401 || r->status == 403) ? RC_AUTH : RC_REJECTED;
    json_t *p = NULL;
    if (r->len > 0 && strstr(r->content_type, "json"))
        p = json_loadb(r->body, r->len, 0, NULL);
    const char *title = p ? json_string_value(json_object_get(p, "title")) : NULL;
    const char *detail = p ? json_string_value(json_object_get(p, "detail")) : NULL;
    if (rc == RC_AUTH)
        fprintf(stderr, "tlsph: authentication failed (HTTP %ld) at %s", r->status, s->url);
    else
        fprintf(stderr, "tlsph: the server rejected the request (HTTP %ld)", r->status);
    if (title) {
        fputs(": ", stderr);
        print_clean(stderr, title, 500);
    }
    if (detail) {
        fputs(": ", stderr);
        print_clean(stderr, detail, 2000);
    }
    if (!p && r->len > 0) {
        fputs(": ", stderr);
        print_clean(stderr, r->body, 300);
    }
    fputc('\n', stderr);
    json_t *errs = p ? json_object_get(p, "errors") : NULL;
    size_t i;
    json_t *e;
    json_array_foreach(errs, i, e)
    {
        const char *ptr = json_string_value(json_object_get(e, "pointer"));
        const char *d = json_string_value(json_object_get(e, "detail"));
        fputs("  ", stderr);
        print_clean(stderr, ptr ? ptr : "#", 1000);
        fputs(": ", stderr);
        print_clean(stderr, d ? d : "(no detail)", 2000);
        fputc('\n', stderr);
    }
    if (rc == RC_AUTH)
        fprintf(stderr, "tlsph: check --token, TLSPH_TOKEN or the config file\n");
    json_decref(p);
    return rc;
}

int http_json(const settings *s, const char *method, const char *path, const json_t *body,
              long timeout_s, json_t **out)
{
    *out = NULL;
    char *text = NULL;
    if (body) {
        text = json_dumps(body, JSON_COMPACT);
        if (!text) {
            fprintf(stderr, "tlsph: cannot encode the request body\n");
            return RC_IO;
        }
    }
    http_response r;
    int rc = http_exchange(s, method, path, text, timeout_s, &r);
    free(text);
    if (rc != RC_OK)
        return rc;
    if (r.status < 200 || r.status > 299) {
        rc = http_report_error(s, &r);
    } else {
        json_error_t err;
        *out = json_loadb(r.body, r.len, 0, &err);
        if (!*out) {
            fprintf(stderr, "tlsph: the server sent invalid JSON for %s: %s\n", path, err.text);
            rc = RC_NETWORK;
        }
    }
    http_response_free(&r);
    return rc;
}

int http_text(const settings *s, const char *path, http_response *r)
{
    int rc = http_exchange(s, "GET", path, NULL, HTTP_TIMEOUT, r);
    if (rc != RC_OK)
        return rc;
    if (r->status < 200 || r->status > 299) {
        rc = http_report_error(s, r);
        http_response_free(r);
    }
    return rc;
}

/* ------------------------------------------------------------ resumable download */
typedef struct {
    FILE *f;
    const char *etag_path;
    long long offset; /* bytes already in the .part file */
    headers h;
    membuf err;       /* body of a non-2xx answer */
    int mode;         /* 0 undecided, 1 to file, 2 to err */
    int bad_range;    /* 206 that does not start at offset */
    int io_error;
} download;

static size_t write_dl(char *d, size_t sz, size_t n, void *u)
{
    download *dl = u;
    size_t k = sz * n;
    if (dl->mode == 0) {
        if (dl->h.status == 200) {
            /* the whole file (no range, or If-Range did not match): restart from 0 */
            if (fflush(dl->f) != 0 || ftruncate(fileno(dl->f), 0) != 0) {
                dl->io_error = errno ? errno : EIO;
                return 0;
            }
            dl->offset = 0;
            dl->mode = 1;
        } else if (dl->h.status == 206) {
            if (dl->h.range_start != dl->offset) {
                dl->bad_range = 1;
                return 0;
            }
            dl->mode = 1;
        } else {
            dl->mode = 2;
        }
        if (dl->mode == 1 && dl->h.etag[0]) {
            FILE *e = fopen(dl->etag_path, "w");
            if (!e || fprintf(e, "%s\n", dl->h.etag) < 0 || fclose(e) != 0) {
                dl->io_error = errno ? errno : EIO;
                return 0;
            }
        }
    }
    if (dl->mode == 2)
        return membuf_add(&dl->err, d, k) == 0 ? k : 0;
    if (fwrite(d, 1, k, dl->f) != k) {
        dl->io_error = errno ? errno : EIO;
        return 0;
    }
    return k;
}

static long long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long long)st.st_size : -1;
}

/* One attempt.  *restart is set when the partial file must be discarded. */
static int download_once(const settings *s, const char *path, const char *dest, const char *part,
                         const char *etag_path, int *restart)
{
    *restart = 0;
    download dl;
    memset(&dl, 0, sizeof dl);
    headers_reset(&dl.h);
    dl.etag_path = etag_path;
    long long have = file_size(part);
    if (have < 0)
        have = 0;
    dl.offset = have;
    char etag[256] = "";
    if (have > 0) {
        FILE *e = fopen(etag_path, "r");
        if (e) {
            if (fgets(etag, sizeof etag, e))
                etag[strcspn(etag, "\r\n")] = '\0';
            fclose(e);
        }
    }
    dl.f = fopen(part, "ab");
    if (!dl.f) {
        fprintf(stderr, "tlsph: cannot write %s: %s\n", part, strerror(errno));
        return RC_IO;
    }
    request q;
    int rc = request_init(&q, s, "GET", path, 0, "*/*");
    if (rc == RC_OK && have > 0) {
        char range[64];
        snprintf(range, sizeof range, "Range: bytes=%lld-", have);
        rc = add_header(&q, range);
        if (rc == RC_OK && etag[0]) {
            char ifr[300];
            snprintf(ifr, sizeof ifr, "If-Range: %s", etag);
            rc = add_header(&q, ifr);
        }
    }
    if (rc == RC_OK && (curl_easy_setopt(q.c, CURLOPT_WRITEFUNCTION, write_dl) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_WRITEDATA, &dl) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_HEADERFUNCTION, header_cb) != CURLE_OK ||
                        curl_easy_setopt(q.c, CURLOPT_HEADERDATA, &dl.h) != CURLE_OK)) {
        fprintf(stderr, "tlsph: libcurl rejected the callbacks\n");
        rc = RC_NETWORK;
    }
    fetch_bar bar;
    const char *slash = strrchr(dest, '/');
    fetch_bar_init(&bar, slash ? slash + 1 : dest, &dl.h.status, &dl.offset);
    if (rc == RC_OK && fetch_bar_attach(&bar, q.c) != 0) {
        fprintf(stderr, "tlsph: libcurl rejected the progress callback\n");
        rc = RC_NETWORK;
    }
    if (rc == RC_OK) {
        rc = request_perform(&q, s, dl.err.overflow);
        fetch_bar_end(&bar);
        if (dl.io_error) {
            fprintf(stderr, "tlsph: cannot write %s: %s\n", part, strerror(dl.io_error));
            rc = RC_IO;
        } else if (dl.bad_range) {
            fprintf(stderr, "tlsph: the server answered a different range; restarting the download\n");
            *restart = 1;
            rc = RC_NETWORK;
        }
    }
    request_free(&q);
    if (fclose(dl.f) != 0 && rc == RC_OK) {
        fprintf(stderr, "tlsph: cannot write %s: %s\n", part, strerror(errno));
        rc = RC_IO;
    }
    if (rc != RC_OK) {
        free(dl.err.p);
        if (rc == RC_NETWORK && !*restart)
            fprintf(stderr, "tlsph: %s kept; run the same command again to resume\n", part);
        return rc;
    }

    long long size = file_size(part), total = -1;
    if (dl.h.status == 200) {
        total = dl.h.content_length;
    } else if (dl.h.status == 206) {
        total = dl.h.range_total;
    } else if (dl.h.status == 416 && dl.h.range_total >= 0 && size == dl.h.range_total) {
        total = size; /* the partial file was already complete */
    } else if (dl.h.status == 416) {
        free(dl.err.p);
        *restart = 1;
        return RC_NETWORK;
    } else {
        http_response er = {.status = dl.h.status, .body = dl.err.p ? dl.err.p : "", .len = dl.err.len};
        snprintf(er.content_type, sizeof er.content_type, "%s", dl.h.content_type);
        rc = http_report_error(s, &er);
        free(dl.err.p);
        /* nothing was written for this answer: drop an empty .part */
        if (file_size(part) == 0)
            unlink(part);
        return rc;
    }
    free(dl.err.p);
    if (total >= 0 && size != total) {
        fprintf(stderr, "tlsph: incomplete download of %s: %lld of %lld bytes; run again to resume\n",
                dest, size, total);
        return RC_NETWORK;
    }
    if (rename(part, dest) != 0) {
        fprintf(stderr, "tlsph: cannot rename %s to %s: %s\n", part, dest, strerror(errno));
        return RC_IO;
    }
    unlink(etag_path);
    if (dl.h.status == 206 && have > 0)
        fprintf(stderr, "%s: %lld bytes (resumed at %lld)\n", dest, size, have);
    else
        fprintf(stderr, "%s: %lld bytes\n", dest, size);
    return RC_OK;
}

int http_download(const settings *s, const char *path, const char *dest)
{
    size_t n = strlen(dest) + 16;
    char *part = malloc(n), *etag_path = malloc(n);
    if (!part || !etag_path) {
        free(part);
        free(etag_path);
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    snprintf(part, n, "%s.part", dest);
    snprintf(etag_path, n, "%s.part.etag", dest);
    int restart = 0, rc = RC_OK;
    for (int attempt = 0; attempt < 2; attempt++) {
        rc = download_once(s, path, dest, part, etag_path, &restart);
        if (!restart)
            break;
        unlink(part);
        unlink(etag_path);
    }
    free(part);
    free(etag_path);
    return rc;
}
