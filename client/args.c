/* The command-line pieces every subcommand shares: the usage error, the one
 * ID argument of a job or study command, and submitting a JSON file. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "jsonfile.h"
#include "urls.h"

int usage_error(const char *cmd, const char *msg, const char *arg)
{
    fprintf(stderr, "tlsph %s: %s%s%s\n(see tlsph --help)\n", cmd, msg, arg ? ": " : "", arg ? arg : "");
    return RC_USAGE;
}

int take_id(const char *cmd, const char *what, const char *arg, const char **id)
{
    if (arg[0] == '-')
        return usage_error(cmd, "unknown option", arg);
    if (*id) {
        char msg[64];
        snprintf(msg, sizeof msg, "more than one %s id", what);
        return usage_error(cmd, msg, arg);
    }
    *id = arg;
    return RC_OK;
}

int take_id_or_name(const char *cmd, const char *msg, const char *arg, const char **id, int *nnames)
{
    if (arg[0] == '-')
        return usage_error(cmd, msg, arg);
    if (!*id)
        *id = arg;
    else
        (*nnames)++;
    return RC_OK;
}

int need_id(const char *cmd, const char *what, const char *id)
{
    if (!id) {
        char msg[64];
        snprintf(msg, sizeof msg, "missing %s ID", what);
        return usage_error(cmd, msg, NULL);
    }
    return id_check(id);
}

int id_args(const char *cmd, const char *what, int argc, char **argv, const char *flag, int *given,
            const char **id)
{
    int rc;
    *id = NULL;
    for (int i = 1; i < argc; i++) {
        if (flag && strcmp(argv[i], flag) == 0)
            *given = 1;
        else if ((rc = take_id(cmd, what, argv[i], id)) != RC_OK)
            return rc;
    }
    return need_id(cmd, what, *id);
}

int submit_file(const settings *s, int argc, char **argv, const char *cmd, const char *file,
                const char *process, const char *key)
{
    if (argc != 2 || (argv[1][0] == '-' && argv[1][1])) {
        char msg[64];
        snprintf(msg, sizeof msg, "expected exactly one %s", file);
        return usage_error(cmd, msg, NULL);
    }
    json_t *doc;
    int rc = jsonfile_load(argv[1], &doc);
    if (rc != RC_OK)
        return rc;
    json_t *inputs = key ? json_pack("{s:o}", key, doc) : doc;
    if (!inputs) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    return submit_job(s, process, inputs);
}
