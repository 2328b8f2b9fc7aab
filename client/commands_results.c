/* Result commands: fetch (resumable download), series (JSON/CSV). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "urls.h"

/* mkdir -p */
static int make_dirs(const char *dir)
{
    char *p = strdup(dir);
    if (!p) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    int rc = RC_OK;
    for (char *q = p + 1;; q++) {
        if (*q == '/' || *q == '\0') {
            char c = *q;
            *q = '\0';
            if (mkdir(p, 0777) != 0 && errno != EEXIST) {
                fprintf(stderr, "tlsph: cannot create directory %s: %s\n", p, strerror(errno));
                rc = RC_IO;
                break;
            }
            *q = c;
            if (c == '\0')
                break;
        }
    }
    free(p);
    struct stat st;
    if (rc == RC_OK && (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))) {
        fprintf(stderr, "tlsph: %s is not a directory\n", dir);
        rc = RC_IO;
    }
    return rc;
}

int cmd_fetch(const settings *s, int argc, char **argv)
{
    const char *id = NULL, *dir = NULL;
    int rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if ((rc = take_id("fetch", "job", argv[i], &id)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("fetch", "job", id)) != RC_OK)
        return rc;
    if (!dir || !*dir)
        dir = id;
    if ((rc = make_dirs(dir)) != RC_OK)
        return rc;
    const char *files[] = {"result.h5", "result.xmf"};
    for (int k = 0; k < 2 && rc == RC_OK; k++) {
        char path[128], dest[4096];
        snprintf(path, sizeof path, "/jobs/%s/results/%s", id, files[k]);
        if ((size_t)snprintf(dest, sizeof dest, "%s/%s", dir, files[k]) >= sizeof dest)
            return usage_error("fetch", "directory name too long", dir);
        rc = http_download(s, path, dest);
        if (rc == RC_OK)
            printf("%s\n", dest);
    }
    if (fflush(stdout) != 0)
        rc = RC_IO;
    return rc;
}

static int write_out(const char *d, size_t n)
{
    if (fwrite(d, 1, n, stdout) != n) {
        fprintf(stderr, "tlsph: cannot write the output: %s\n", strerror(errno));
        return RC_IO;
    }
    return RC_OK;
}

static int list_series(const settings *s, const char *id)
{
    char path[96];
    snprintf(path, sizeof path, "/jobs/%s/results/series", id);
    json_t *doc;
    int rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &doc);
    if (rc != RC_OK)
        return rc;
    size_t i;
    json_t *e;
    int w = 4;
    json_array_foreach(json_object_get(doc, "series"), i, e)
    {
        const char *nm = json_string_value(json_object_get(e, "name"));
        if (nm && (int)strlen(nm) > w && strlen(nm) < 80)
            w = (int)strlen(nm);
    }
    printf("%-*s  %-8s  %s\n", w, "NAME", "UNITS", "COMPONENTS");
    json_array_foreach(json_object_get(doc, "series"), i, e)
    {
        const char *nm = json_string_value(json_object_get(e, "name"));
        const char *un = json_string_value(json_object_get(e, "units"));
        json_t *comps = json_object_get(e, "components");
        printf("%-*s  %-8s  ", w, nm ? nm : "?", un && *un ? un : "-");
        if (json_is_array(comps)) {
            size_t k;
            json_t *c;
            json_array_foreach(comps, k, c) printf("%s%s", k ? "," : "", json_string_value(c) ? json_string_value(c) : "?");
        } else {
            fputs("-", stdout);
        }
        putchar('\n');
    }
    json_decref(doc);
    return RC_OK;
}

int cmd_series(const settings *s, int argc, char **argv)
{
    const char *id = NULL;
    int csv = 0, nnames = 0, rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0)
            csv = 1;
        else if ((rc = take_id_or_name("series", "unknown option", argv[i], &id, &nnames)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("series", "job", id)) != RC_OK)
        return rc;
    if (nnames == 0)
        return list_series(s, id);
    int k = 0;
    if (!csv && nnames > 1)
        rc = write_out("[", 1);
    for (int i = 1; i < argc && rc == RC_OK; i++) {
        if (argv[i][0] == '-' || argv[i] == id)
            continue;
        char *path = url_series_path(id, argv[i], csv);
        if (!path) {
            fprintf(stderr, "tlsph: out of memory\n");
            return RC_IO;
        }
        http_response r;
        rc = http_text(s, path, &r);
        free(path);
        if (rc != RC_OK)
            break;
        if (k > 0)
            rc = write_out(csv ? "\n" : ",", 1);
        size_t len = r.len;
        if (!csv && nnames > 1)
            while (len > 0 && (r.body[len - 1] == '\n' || r.body[len - 1] == '\r'))
                len--;
        if (rc == RC_OK)
            rc = write_out(r.body, len);
        http_response_free(&r);
        k++;
    }
    if (rc == RC_OK && !csv && nnames > 1)
        rc = write_out("]\n", 2);
    if (fflush(stdout) != 0 && rc == RC_OK)
        rc = RC_IO;
    return rc;
}
