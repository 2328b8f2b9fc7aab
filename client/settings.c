/* Settings: --url/--token flags > TLSPH_URL/TLSPH_TOKEN > config file > default.
 * Config file: --config FILE, else $XDG_CONFIG_HOME/tlsph/client.conf, else
 * ~/.config/tlsph/client.conf; lines "url = ..." / "token = ...", '#' comments. */
#include "settings.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exitcodes.h"

static char *trim(char *p)
{
    while (*p && isspace((unsigned char)*p))
        p++;
    size_t n = strlen(p);
    while (n > 0 && isspace((unsigned char)p[n - 1]))
        p[--n] = '\0';
    return p;
}

static int copy_value(char *dst, size_t cap, const char *src, const char *what)
{
    size_t n = strlen(src);
    if (n >= cap) {
        fprintf(stderr, "tlsph: %s is too long (%zu bytes, at most %zu)\n", what, n, cap - 1);
        return RC_USAGE;
    }
    memcpy(dst, src, n + 1);
    return RC_OK;
}

/* Reads url/token from a config file into url/token (only where still empty). */
static int read_config(const char *path, int required, char *url, size_t ucap, char *token, size_t tcap)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        if (!required && errno == ENOENT)
            return RC_OK;
        fprintf(stderr, "tlsph: cannot read config file %s: %s\n", path, strerror(errno));
        return RC_IO;
    }
    char line[4096];
    int lineno = 0, rc = RC_OK;
    while (rc == RC_OK && fgets(line, sizeof line, f)) {
        lineno++;
        char *p = trim(line);
        if (*p == '\0' || *p == '#')
            continue;
        char *eq = strchr(p, '=');
        if (!eq) {
            fprintf(stderr, "tlsph: %s:%d: expected 'key = value'\n", path, lineno);
            rc = RC_USAGE;
            break;
        }
        *eq = '\0';
        char *key = trim(p), *val = trim(eq + 1);
        size_t vn = strlen(val);
        if (vn >= 2 && (val[0] == '"' || val[0] == '\'') && val[vn - 1] == val[0]) {
            val[vn - 1] = '\0';
            val++;
        }
        if (strcmp(key, "url") == 0) {
            if (!url[0])
                rc = copy_value(url, ucap, val, "url");
        } else if (strcmp(key, "token") == 0) {
            if (!token[0])
                rc = copy_value(token, tcap, val, "token");
        } else {
            fprintf(stderr, "tlsph: %s:%d: unknown key '%s' ignored\n", path, lineno, key);
        }
    }
    if (ferror(f)) {
        fprintf(stderr, "tlsph: error reading %s\n", path);
        rc = RC_IO;
    }
    fclose(f);
    return rc;
}

int settings_load(settings *s, const char *flag_url, const char *flag_token, const char *config_path)
{
    int rc;
    s->url[0] = s->token[0] = '\0';
    const char *env_url = getenv("TLSPH_URL"), *env_token = getenv("TLSPH_TOKEN");
    const char *u = flag_url ? flag_url : (env_url && *env_url ? env_url : NULL);
    const char *t = flag_token ? flag_token : (env_token && *env_token ? env_token : NULL);
    if (u && (rc = copy_value(s->url, sizeof s->url, u, "URL")) != RC_OK)
        return rc;
    if (t && (rc = copy_value(s->token, sizeof s->token, t, "token")) != RC_OK)
        return rc;

    if (config_path) {
        rc = read_config(config_path, 1, s->url, sizeof s->url, s->token, sizeof s->token);
    } else {
        char path[4096];
        const char *xdg = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
        int n = -1;
        if (xdg && *xdg)
            n = snprintf(path, sizeof path, "%s/tlsph/client.conf", xdg);
        else if (home && *home)
            n = snprintf(path, sizeof path, "%s/.config/tlsph/client.conf", home);
        rc = RC_OK;
        if (n > 0 && (size_t)n < sizeof path)
            rc = read_config(path, 0, s->url, sizeof s->url, s->token, sizeof s->token);
    }
    if (rc != RC_OK)
        return rc;
    if (!s->url[0])
        memcpy(s->url, SETTINGS_DEFAULT_URL, sizeof SETTINGS_DEFAULT_URL);

    if (strncmp(s->url, "http://", 7) != 0 && strncmp(s->url, "https://", 8) != 0) {
        fprintf(stderr, "tlsph: the URL must start with http:// or https:// (got '%s')\n", s->url);
        return RC_USAGE;
    }
    size_t n = strlen(s->url);
    while (n > 0 && s->url[n - 1] == '/')
        s->url[--n] = '\0';
    for (const char *p = s->token; *p; p++)
        if ((unsigned char)*p < 0x21 || (unsigned char)*p > 0x7e) {
            fprintf(stderr, "tlsph: the token contains whitespace or control characters\n");
            return RC_USAGE;
        }
    return RC_OK;
}
