#include "run/progress.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void tlsph_progress_emit(int fd, const json_t *obj)
{
    if (fd < 0 || !obj)
        return;
    char *text = json_dumps(obj, JSON_COMPACT);
    if (!text)
        return;
    size_t len = strlen(text);
    text[len] = '\0';
    /* write the line in one buffer so concurrent readers never see half a line */
    char *line = malloc(len + 2);
    if (line) {
        memcpy(line, text, len);
        line[len] = '\n';
        size_t off = 0;
        while (off < len + 1) {
            ssize_t w = write(fd, line + off, len + 1 - off);
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0)
                break;
            off += (size_t)w;
        }
        free(line);
    }
    free(text);
}

json_t *tlsph_progress_final(enum tlsph_exit code, const struct tlsph_errors *err)
{
    const char *status = tlsph_exit_status(code);
    if (!status)
        return NULL;
    json_t *o = json_pack("{s:s, s:s}", "event", TLSPH_EVENT_FINISHED, "status", status);
    if (o && err && err->count > 0) {
        json_t *list = tlsph_errors_to_json(err);
        if (!list || json_object_set_new(o, "errors", list) != 0) {
            json_decref(o);
            return NULL;
        }
    }
    return o;
}
