/* Bearer-token authentication, see auth.h. */
#include "auth.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <gnutls/crypto.h>
#include <gnutls/gnutls.h>

#define MIN_TOKEN_LEN 16

void tauth_init(struct tauth *a)
{
    memset(a, 0, sizeof *a);
}

void tauth_free(struct tauth *a)
{
    if (a->hashes)
        explicit_bzero(a->hashes, a->cap * TAUTH_HASH_LEN);
    free(a->hashes);
    memset(a, 0, sizeof *a);
}

static int add_hash(struct tauth *a, const unsigned char h[TAUTH_HASH_LEN])
{
    if (a->n == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 4;
        void *p = realloc(a->hashes, cap * TAUTH_HASH_LEN);
        if (!p)
            return -1;
        a->hashes = p;
        a->cap = cap;
    }
    memcpy(a->hashes[a->n++], h, TAUTH_HASH_LEN);
    return 0;
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = tolower(c);
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

int tauth_add_hex(struct tauth *a, const char *hex)
{
    unsigned char h[TAUTH_HASH_LEN];
    if (strlen(hex) != 2 * TAUTH_HASH_LEN)
        return -1;
    for (size_t i = 0; i < TAUTH_HASH_LEN; i++) {
        int hi = hexval((unsigned char)hex[2 * i]), lo = hexval((unsigned char)hex[2 * i + 1]);
        if (hi < 0 || lo < 0)
            return -1;
        h[i] = (unsigned char)(hi << 4 | lo);
    }
    return add_hash(a, h);
}

static int sha256(const char *data, size_t len, unsigned char out[TAUTH_HASH_LEN])
{
    return gnutls_hash_fast(GNUTLS_DIG_SHA256, data, len, out) == 0 ? 0 : -1;
}

int tauth_add_token(struct tauth *a, const char *token, size_t len)
{
    unsigned char h[TAUTH_HASH_LEN];
    if (len < MIN_TOKEN_LEN || sha256(token, len, h) != 0)
        return -1;
    int r = add_hash(a, h);
    explicit_bzero(h, sizeof h);
    return r;
}

int tauth_load_file(struct tauth *a, const char *path, char *err, size_t errsize)
{
    FILE *f = fopen(path, "re");
    if (!f) {
        snprintf(err, errsize, "token file %s: %s", path, strerror(errno));
        return -1;
    }
    /* Refused, not warned about: tokens that every local user can read (or
     * anyone but the owner can change) protect nothing, like an ssh key. */
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, errsize, "token file %s is not a regular file", path);
        fclose(f);
        return -1;
    }
    if (st.st_mode & (S_IROTH | S_IWOTH | S_IWGRP)) {
        snprintf(err, errsize,
                 "token file %s is %s by other users (mode %04o); refusing it: "
                 "chmod 600 (or 640 for a service group) and start again",
                 path, st.st_mode & S_IROTH ? "readable" : "writable",
                 (unsigned)(st.st_mode & 07777));
        fclose(f);
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int added = 0, lineno = 0, rc = 0;
    while ((len = getline(&line, &cap, f)) >= 0) {
        lineno++;
        char *s = line;
        while (len > 0 && isspace((unsigned char)s[len - 1]))
            s[--len] = '\0';
        while (*s && isspace((unsigned char)*s))
            s++, len--;
        if (*s == '\0' || *s == '#')
            continue;
        if (tauth_add_token(a, s, (size_t)len) != 0) {
            snprintf(err, errsize, "token file %s line %d: tokens need at least %d characters",
                     path, lineno, MIN_TOKEN_LEN);
            rc = -1;
            break;
        }
        added++;
    }
    if (line) {
        explicit_bzero(line, cap);
        free(line);
    }
    fclose(f);
    if (rc == 0 && added == 0) {
        snprintf(err, errsize, "token file %s holds no token", path);
        return -1;
    }
    return rc < 0 ? -1 : added;
}

int tauth_enabled(const struct tauth *a)
{
    return a->n > 0;
}

int tauth_check_header(const struct tauth *a, const char *authorization)
{
    if (!authorization)
        return 0;
    while (*authorization == ' ')
        authorization++;
    if (strncasecmp(authorization, "Bearer ", 7) != 0)
        return 0;
    const char *tok = authorization + 7;
    while (*tok == ' ')
        tok++;
    size_t len = strlen(tok);
    while (len > 0 && tok[len - 1] == ' ')
        len--;
    if (len == 0 || len > 4096)
        return 0;
    unsigned char h[TAUTH_HASH_LEN];
    if (sha256(tok, len, h) != 0)
        return 0;
    /* constant time over every stored hash: no early exit */
    unsigned match = 0;
    for (size_t i = 0; i < a->n; i++) {
        unsigned diff = 0;
        for (size_t k = 0; k < TAUTH_HASH_LEN; k++)
            diff |= (unsigned)(h[k] ^ a->hashes[i][k]);
        match |= (unsigned)(diff == 0);
    }
    explicit_bzero(h, sizeof h);
    return match != 0;
}
