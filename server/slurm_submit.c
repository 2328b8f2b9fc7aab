/* Handing runs to Slurm, see slurm_submit.h. */
#include "slurm_submit.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "config.h"
#include "errmsg.h"
#include "slurm_cmd.h"
#include "strbuf.h"

#define SBATCH_TIMEOUT 60.0 /* s: a controller that takes longer is down */
#define MAX_ARGS 64

/* s in single quotes for bash ('\'' for a quote inside). */
static void add_quoted(struct strbuf *b, const char *s)
{
    strbuf_adds(b, "'");
    for (; *s; s++)
        strbuf_adds(b, *s == '\'' ? "'\\''" : (char[]){*s, '\0'});
    strbuf_adds(b, "'");
}

char *slurm_script(const struct slurm_submission *s)
{
    struct strbuf b = {0};
    strbuf_adds(&b, "#!/bin/bash\n"
                    "# tlsphd: one tlsph-run per task (server/slurm_submit.h)\n"
                    "ids=(");
    for (size_t i = 0; i < s->n; i++) /* job ids are [0-9A-Za-z_-]: no quoting needed */
        strbuf_printf(&b, "%s%s", i ? " " : "", s->ids[i]);
    strbuf_adds(&b, ")\nid=${ids[${SLURM_ARRAY_TASK_ID:-0}]}\ndir=");
    add_quoted(&b, s->jobs_dir);
    strbuf_adds(&b, "/$id\n"
                    "if [ -z \"$id\" ] || ! cd \"$dir\"; then\n"
                    "    echo \"tlsphd: no job directory for task ${SLURM_ARRAY_TASK_ID:-0}\" >&2\n"
                    "    exit 1\n"
                    "fi\n"
                    "rm -f exit_status exit_status.tmp\n");
    add_quoted(&b, s->engine);
    strbuf_adds(&b, " \"$dir/scene.json\" -o \"$dir\" --progress-fd 3 --threads "
                    "\"${SLURM_CPUS_PER_TASK:-1}\" 3>\"$dir/progress.jsonl\" "
                    ">\"$dir/log.txt\" 2>&1\n"
                    "rc=$?\n"
                    "printf '%s\\n' \"$rc\" >exit_status.tmp && mv -f exit_status.tmp exit_status\n"
                    "exit \"$rc\"\n");
    return b.oom ? (strbuf_free(&b), NULL) : strbuf_take(&b);
}

/* Appends the blank-separated words of opts to argv (at most MAX_ARGS - 1 in
 * all); words points into the copy *buf (freed by the caller). */
static int split_options(const char *opts, char **buf, char **argv, int *argc)
{
    *buf = strdup(opts ? opts : "");
    if (!*buf)
        return -1;
    for (char *p = *buf; *p;) {
        while (isspace((unsigned char)*p))
            *p++ = '\0';
        if (!*p)
            break;
        if (*argc >= MAX_ARGS - 1)
            return -1;
        argv[(*argc)++] = p;
        while (*p && !isspace((unsigned char)*p))
            p++;
    }
    return 0;
}

int slurm_submit(const struct slurm_submission *s, char *slurm_id, size_t size, char *err,
                 size_t errsize)
{
    char opt[12][1200];
    int k = 0;
    char *argv[MAX_ARGS];
    int argc = 0;
    argv[argc++] = (char *)"sbatch";
    argv[argc++] = (char *)"--parsable";
    argv[argc++] = (char *)"--no-requeue";
    argv[argc++] = (char *)"--nodes=1";
    argv[argc++] = (char *)"--ntasks=1";
#define OPT(...) (snprintf(opt[k], sizeof opt[k], __VA_ARGS__), argv[argc++] = opt[k++])
    OPT("--job-name=%s", s->name);
    OPT("--output=%s/.slurm/%%j.out", s->jobs_dir);
    OPT("--chdir=%s", s->jobs_dir);
    OPT("--cpus-per-task=%ld", s->res.cpus);
    OPT("--mem=%ldM", s->res.mem_mb);
    OPT("--time=%ld", s->res.time_min);
    if (s->array && s->array_limit > 0)
        OPT("--array=0-%zu%%%ld", s->n - 1, s->array_limit);
    else if (s->array)
        OPT("--array=0-%zu", s->n - 1);
    if (s->cfg->slurm_partition[0])
        OPT("--partition=%s", s->cfg->slurm_partition);
    if (s->cfg->slurm_account[0])
        OPT("--account=%s", s->cfg->slurm_account);
#undef OPT
    char *words = NULL;
    if (split_options(s->cfg->slurm_options, &words, argv, &argc) < 0) {
        free(words);
        errmsg_set(err, errsize, "slurm_options: too many words (or out of memory)");
        return -1;
    }
    argv[argc] = NULL;

    char logdir[1200];
    snprintf(logdir, sizeof logdir, "%s/.slurm", s->jobs_dir);
    if (mkdir(logdir, 0750) < 0 && errno != EEXIST) {
        errmsg_set(err, errsize, "cannot create %s: %s", logdir, strerror(errno));
        free(words);
        return -1;
    }
    char *script = slurm_script(s);
    if (!script) {
        errmsg_set(err, errsize, "out of memory");
        free(words);
        return -1;
    }
    struct slurm_cmd_result r;
    const int st = slurm_cmd_run(argv, script, SBATCH_TIMEOUT, &r);
    free(script);
    free(words);
    int rc = -1;
    /* --parsable: "jobid" or "jobid;cluster" */
    const char *out = r.out.p ? r.out.p : "";
    size_t len = strspn(out, "0123456789");
    if (st == 0 && len > 0 && len < size) {
        snprintf(slurm_id, size, "%.*s", (int)len, out);
        rc = 0;
    } else {
        char why[300];
        errmsg_set(err, errsize, "sbatch: %s", slurm_cmd_why(&r, why, sizeof why));
    }
    slurm_cmd_free(&r);
    return rc;
}
