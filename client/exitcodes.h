/* Exit codes of the tlsph client: scripts rely on them (see docs/client.md). */
#ifndef TLSPH_CLIENT_EXITCODES_H
#define TLSPH_CLIENT_EXITCODES_H

enum {
    RC_OK = 0,        /* success; job successful */
    RC_USAGE = 1,     /* bad command line or input file that is not JSON */
    RC_REJECTED = 2,  /* the server answered an HTTP error (4xx/5xx) */
    RC_FAILED = 3,    /* the job finished "failed" */
    RC_DISMISSED = 4, /* the job was dismissed (cancelled) */
    RC_NETWORK = 5,   /* cannot reach the server, network or protocol error */
    RC_AUTH = 6,      /* authentication failed (401/403) */
    RC_IO = 7,        /* local I/O error */
    RC_TIMEOUT = 8    /* wait --timeout expired */
};

#endif
