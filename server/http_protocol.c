/* The request checks libmicrohttpd 0.9.75 leaves to the daemon, see http_protocol.h. */
#include "http_protocol.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

#include <microhttpd.h>

size_t http_protocol_trim_query(char *uri)
{
    char *q = uri ? strchr(uri, '?') : NULL;
    if (!q || !q[1])
        return 0;
    size_t n = 1;
    for (const char *p = q + 1; *p; p++)
        n += *p == '&' || *p == ';';
    if (n <= HTTP_MAX_QUERY_PARAMS)
        return 0;
    q[1] = '\0';
    return n;
}

struct header_scan {
    int content_length, host, transfer_encoding;
    const char *te;    /* the (first) Transfer-Encoding */
    char bad_name[64]; /* a header name with white space, printable */
};

static enum MHD_Result scan_header(void *cls, enum MHD_ValueKind kind, const char *key,
                                   const char *value)
{
    struct header_scan *s = cls;
    (void)kind;
    if (!key)
        return MHD_YES;
    if (!*key || strpbrk(key, " \t")) {
        size_t i = 0;
        for (const char *k = key; *k && i + 1 < sizeof s->bad_name; k++)
            s->bad_name[i++] = (*k > 0x20 && *k < 0x7f) ? *k : ' ';
        s->bad_name[i] = '\0';
        if (!i)
            snprintf(s->bad_name, sizeof s->bad_name, "(empty)");
    } else if (!strcasecmp(key, MHD_HTTP_HEADER_CONTENT_LENGTH)) {
        s->content_length++;
    } else if (!strcasecmp(key, MHD_HTTP_HEADER_HOST)) {
        s->host++;
    } else if (!strcasecmp(key, MHD_HTTP_HEADER_TRANSFER_ENCODING)) {
        if (!s->transfer_encoding++)
            s->te = value;
    }
    return MHD_YES;
}

int http_protocol_check(struct MHD_Connection *conn, const char *version, enum problem_kind *kind,
                        char *detail, size_t size)
{
    struct header_scan s = {0};
    MHD_get_connection_values(conn, MHD_HEADER_KIND, scan_header, &s);
    *kind = PROBLEM_BAD_REQUEST;
    if (s.bad_name[0]) {
        snprintf(detail, size, "header name '%s' contains white space (RFC 9112 5.1)", s.bad_name);
        return -1;
    }
    if (s.transfer_encoding && s.content_length) {
        snprintf(detail, size,
                 "a request must not carry both Content-Length and "
                 "Transfer-Encoding (RFC 9112 6.1)");
        return -1;
    }
    if (s.content_length > 1) {
        snprintf(detail, size, "Content-Length is given %d times", s.content_length);
        return -1;
    }
    if (s.transfer_encoding > 1 || (s.te && strcasecmp(s.te, "chunked") != 0)) {
        *kind = PROBLEM_NOT_IMPLEMENTED;
        snprintf(detail, size, "Transfer-Encoding: only 'chunked' is supported");
        return -1;
    }
    if (version && !strcmp(version, MHD_HTTP_VERSION_1_1) && s.host != 1) {
        if (s.host)
            snprintf(detail, size, "Host is given %d times", s.host);
        else
            snprintf(detail, size, "an HTTP/1.1 request needs a Host header (RFC 9112 3.2)");
        return -1;
    }
    return 0;
}
