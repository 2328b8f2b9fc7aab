/* Where the daemon is and how to authenticate: flags > env > config file > default. */
#ifndef TLSPH_CLIENT_SETTINGS_H
#define TLSPH_CLIENT_SETTINGS_H

#define SETTINGS_DEFAULT_URL "http://127.0.0.1:8080"

typedef struct {
    char url[1024];   /* base URL without trailing slash */
    char token[1024]; /* bearer token, "" for none */
} settings;

/* Fills *s.  flag_* and config_path may be NULL.  Returns an RC_* code (message printed). */
int settings_load(settings *s, const char *flag_url, const char *flag_token, const char *config_path);

#endif
