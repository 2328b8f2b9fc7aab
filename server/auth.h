/* Bearer-token authentication (server/auth.c).
 *
 * Only SHA-256 hashes of tokens are kept in memory (GnuTLS gnutls_hash_fast).
 * Tokens come as hex hashes from the config file (token_sha256 = HEX) or as
 * plaintext lines of a token file, hashed at load and wiped.  A request's
 * token is hashed and compared with every stored hash in constant time. */
#ifndef TLSPHD_AUTH_H
#define TLSPHD_AUTH_H

#include <stddef.h>
#include <stdio.h>

#define TAUTH_HASH_LEN 32

struct tauth {
    unsigned char (*hashes)[TAUTH_HASH_LEN];
    size_t n, cap;
};

void tauth_init(struct tauth *a);
void tauth_free(struct tauth *a);
/* Adds a hash given as 64 hex digits. 0 or -1 (bad hex). */
int tauth_add_hex(struct tauth *a, const char *hex);
/* Hashes and adds a plaintext token (>= 16 chars). 0 or -1. */
int tauth_add_token(struct tauth *a, const char *token, size_t len);
/* Reads plaintext tokens (one per line, '#' comments, blank lines ignored).
 * A file that other users may read, or anyone but its owner may write, is
 * refused (group-readable is fine, for a service group).
 * Returns the number of tokens added or -1 with err. */
int tauth_load_file(struct tauth *a, const char *path, char *err, size_t errsize);
/* 1 when authentication is configured (at least one token). */
int tauth_enabled(const struct tauth *a);
/* Checks an Authorization header value ("Bearer <token>"). 1 accepted, 0 not. */
int tauth_check_header(const struct tauth *a, const char *authorization);

#endif
