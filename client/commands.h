/* The subcommands.  Each takes argv with argv[0] = the command name and returns
 * an RC_* exit code. */
#ifndef TLSPH_CLIENT_COMMANDS_H
#define TLSPH_CLIENT_COMMANDS_H

#include <jansson.h>

#include "settings.h"

int cmd_submit(const settings *s, int argc, char **argv);
int cmd_status(const settings *s, int argc, char **argv);
int cmd_wait(const settings *s, int argc, char **argv);
int cmd_cancel(const settings *s, int argc, char **argv);
int cmd_list(const settings *s, int argc, char **argv);
int cmd_watch(const settings *s, int argc, char **argv);
int cmd_fetch(const settings *s, int argc, char **argv);
int cmd_series(const settings *s, int argc, char **argv);
int cmd_plot(const settings *s, int argc, char **argv);
int cmd_study(const settings *s, int argc, char **argv);
int cmd_convergence(const settings *s, int argc, char **argv);

/* GET /jobs/ID?wait=wait_s (long-poll; wait_s <= 0: no wait).  *out is the statusInfo. */
int job_poll(const settings *s, const char *id, double wait_s, json_t **out);

/* POSTs {"inputs": inputs} (reference stolen) to /processes/PROCESS/execution and
 * prints the new job id. */
int submit_job(const settings *s, const char *process, json_t *inputs);

/* client/args.c: usage error helper: prints "tlsph CMD: msg[: arg]" and returns RC_USAGE. */
int usage_error(const char *cmd, const char *msg, const char *arg);
/* The last case of a command's argument loop, for arg that is none of its
 * options: the ID of a `what` ("job", "study") when none was seen yet (RC_OK),
 * else a usage error ("unknown option", "more than one job id"). */
int take_id(const char *cmd, const char *what, const char *arg, const char **id);
/* The same for `tlsph CMD ID NAME...`: the first argument that is no option is
 * the job ID, the others are names (counted in *nnames); an option is a usage
 * error (msg). */
int take_id_or_name(const char *cmd, const char *msg, const char *arg, const char **id, int *nnames);
/* After the loop: a usage error when no ID was given ("missing job ID"), else
 * id_check's answer. */
int need_id(const char *cmd, const char *what, const char *id);
/* `tlsph CMD [FLAG] ID`: argv[1..] hold one ID of a `what` and, when flag is
 * given, maybe that flag (*given = 1 then); RC_OK, or an error already reported. */
int id_args(const char *cmd, const char *what, int argc, char **argv, const char *flag, int *given,
            const char **id);
/* `tlsph CMD FILE`: loads the one JSON file argv[1] ("-": stdin) and submits it
 * to PROCESS, as the inputs or, with key, wrapped as {key: document}. */
int submit_file(const settings *s, int argc, char **argv, const char *cmd, const char *file,
                const char *process, const char *key);

#endif
