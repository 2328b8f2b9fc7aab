/* Unit tests of the Slurm executor's parts that need no Slurm:
 * server/slurm_state.c (the state table of Slurm 22.05's job_state_string
 * names, the end decisions, squeue's output), server/slurm_submit.c (the batch script, run here
 * by bash with a stand-in engine: the progress stream on fd 3 lands in
 * progress.jsonl, the exit status in exit_status, renamed into place),
 * server/slurm_cmd.c (stdin, stdout, a deadline) and
 * server/slurm_resources.c (the rules of slurm_resources.h on
 * examples/elastic-strip.json: 400 particles). */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../../server/config.h" /* not the build's config.h */
#include "slurm_cmd.h"
#include "slurm_resources.h"
#include "slurm_state.h"
#include "slurm_submit.h"
#include "strbuf.h"
#include "support/check_main.h"

START_TEST(state_table)
{
    ck_assert_int_eq(slurm_state_of("PENDING")->phase, SLURM_WAITING);
    ck_assert_int_eq(slurm_state_of("RUNNING")->phase, SLURM_RUNNING);
    ck_assert_int_eq(slurm_state_of("COMPLETING")->phase, SLURM_RUNNING);
    ck_assert_int_eq(slurm_state_of("COMPLETED")->phase, SLURM_ENDED);
    ck_assert_int_eq(slurm_state_of("FAILED")->phase, SLURM_ENDED);
    ck_assert_int_eq(slurm_state_of("TIMEOUT")->phase, SLURM_FAILED);
    ck_assert_str_eq(slurm_state_of("TIMEOUT")->outcome, "timed_out");
    ck_assert_str_eq(slurm_state_of("OUT_OF_MEMORY")->outcome, "crashed");
    ck_assert_int_eq(slurm_state_of("CANCELLED")->phase, SLURM_CANCELLED);
    ck_assert_int_eq(slurm_state_of("NODE_FAIL")->phase, SLURM_REQUEUE);
    ck_assert_int_eq(slurm_state_of("PREEMPTED")->phase, SLURM_REQUEUE);
    ck_assert_int_eq(slurm_state_of("SOMETHING_NEW")->phase, SLURM_UNKNOWN);
    ck_assert_int_eq(slurm_state_of(NULL)->phase, SLURM_UNKNOWN);
}
END_TEST

/* The end decisions of slurm_state.h's table. */
START_TEST(verdicts)
{
    const struct slurm_state *run = slurm_state_of("RUNNING"), *pend = slurm_state_of("PENDING"),
                             *done = slurm_state_of("COMPLETED"), *tmo = slurm_state_of("TIMEOUT"),
                             *node = slurm_state_of("NODE_FAIL"), *canc = slurm_state_of("CANCELLED");
    ck_assert_int_eq(slurm_verdict(-1, pend, false), SLURM_WATCH);
    ck_assert_int_eq(slurm_verdict(-1, run, true), SLURM_WATCH);
    ck_assert_int_eq(slurm_verdict(0, run, false), SLURM_END_BY_EXIT);  /* the engine's end: at once */
    ck_assert_int_eq(slurm_verdict(3, run, false), SLURM_END_BY_EXIT);
    ck_assert_int_eq(slurm_verdict(5, run, false), SLURM_WAIT);         /* SIGTERM: a TIMEOUT coming? */
    ck_assert_int_eq(slurm_verdict(137, run, false), SLURM_WAIT);
    ck_assert_int_eq(slurm_verdict(137, run, true), SLURM_END_BY_EXIT);
    ck_assert_int_eq(slurm_verdict(5, tmo, false), SLURM_END_BY_SLURM); /* Slurm's word wins */
    ck_assert_int_eq(slurm_verdict(-1, tmo, false), SLURM_END_BY_SLURM);
    ck_assert_int_eq(slurm_verdict(-1, canc, false), SLURM_END_BY_SLURM);
    ck_assert_int_eq(slurm_verdict(-1, node, false), SLURM_REQUEUE_NODE);
    ck_assert_int_eq(slurm_verdict(1, done, false), SLURM_END_BY_EXIT);
    ck_assert_int_eq(slurm_verdict(-1, done, false), SLURM_WAIT);       /* the status over NFS */
    ck_assert_int_eq(slurm_verdict(-1, done, true), SLURM_END_NO_STATUS);
    ck_assert_int_eq(slurm_verdict(5, NULL, false), SLURM_END_BY_EXIT); /* Slurm forgot it */
    ck_assert_int_eq(slurm_verdict(-1, NULL, false), SLURM_WAIT);
    ck_assert_int_eq(slurm_verdict(-1, NULL, true), SLURM_REQUEUE_GONE);
}
END_TEST

START_TEST(squeue_lines)
{
    const char *text = "12|RUNNING|None|node1|tlsph-a-1\n"
                       "\n"
                       "13_4|PENDING|Resources||tlsph-b-2\n"
                       "garbage\n"
                       "14|TIMEOUT|TimeLimit|node2|tlsph-c-1"; /* no final newline */
    struct slurm_queue_row *rows;
    size_t n;
    ck_assert_int_eq(slurm_queue_parse(text, &rows, &n), 0);
    ck_assert_uint_eq(n, 3);
    ck_assert_str_eq(rows[1].id, "13_4");
    ck_assert_str_eq(rows[1].reason, "Resources");
    ck_assert_str_eq(rows[1].nodes, "");
    ck_assert_str_eq(rows[1].name, "tlsph-b-2");
    ck_assert_ptr_nonnull(slurm_queue_find(rows, n, "14"));
    ck_assert_str_eq(slurm_queue_find(rows, n, "14")->state, "TIMEOUT");
    ck_assert_ptr_null(slurm_queue_find(rows, n, "13"));
    free(rows);
}
END_TEST

static void write_file(const char *path, const char *text, mode_t mode)
{
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
    chmod(path, mode);
}

START_TEST(batch_script_runs)
{
    char base[] = "/tmp/test_slurm.XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(base));
    char jobs[512], path[700], cmd[1200];
    snprintf(jobs, sizeof jobs, "%s/it's jobs", base); /* a quote in the path */
    ck_assert_int_eq(mkdir(jobs, 0700), 0);
    snprintf(path, sizeof path, "%s/bbb", jobs);
    ck_assert_int_eq(mkdir(path, 0700), 0);
    /* the stand-in engine: its arguments on stdout, a progress line on fd 3, exit 3 */
    char engine[600];
    snprintf(engine, sizeof engine, "%s/engine", base);
    write_file(engine, "#!/bin/bash\necho \"$@\"\necho '{\"event\":\"finished\"}' >&3\nexit 3\n", 0700);
    const char *ids[] = {"aaa", "bbb"};
    struct tcfg cfg;
    memset(&cfg, 0, sizeof cfg);
    const struct slurm_submission s = {.name = "tlsph-aaa-1", .jobs_dir = jobs, .engine = engine,
                                       .ids = ids, .n = 2, .array = true, .cfg = &cfg};
    char *script = slurm_script(&s);
    ck_assert_ptr_nonnull(script);
    snprintf(path, sizeof path, "%s/script.sh", base);
    write_file(path, script, 0600);
    free(script);
    snprintf(cmd, sizeof cmd, "SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=3 bash '%s'", path);
    const int st = system(cmd);
    ck_assert(WIFEXITED(st) && WEXITSTATUS(st) == 3);
    snprintf(path, sizeof path, "%s/bbb/exit_status", jobs);
    char *text = strbuf_read_file(path, NULL);
    ck_assert_ptr_nonnull(text);
    ck_assert_str_eq(text, "3\n");
    free(text);
    snprintf(path, sizeof path, "%s/bbb/progress.jsonl", jobs);
    text = strbuf_read_file(path, NULL);
    ck_assert_ptr_nonnull(text);
    ck_assert_str_eq(text, "{\"event\":\"finished\"}\n");
    free(text);
    snprintf(path, sizeof path, "%s/bbb/log.txt", jobs);
    text = strbuf_read_file(path, NULL);
    ck_assert_ptr_nonnull(text);
    ck_assert_ptr_nonnull(strstr(text, "bbb/scene.json -o "));
    ck_assert_ptr_nonnull(strstr(text, "--progress-fd 3 --threads 3"));
    free(text);
    snprintf(path, sizeof path, "%s/bbb/exit_status.tmp", jobs);
    ck_assert_int_ne(access(path, F_OK), 0);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", base);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

START_TEST(commands)
{
    struct slurm_cmd_result r;
    char *cat[] = {(char *)"cat", NULL};
    ck_assert_int_eq(slurm_cmd_run(cat, "12;cluster\n", 10, &r), 0);
    ck_assert_str_eq(r.out.p, "12;cluster\n");
    slurm_cmd_free(&r);
    char *hang[] = {(char *)"sleep", (char *)"30", NULL};
    ck_assert_int_eq(slurm_cmd_run(hang, NULL, 0.2, &r), -1);
    char why[200];
    ck_assert_ptr_nonnull(strstr(slurm_cmd_why(&r, why, sizeof why), "did not answer"));
    slurm_cmd_free(&r);
    char *missing[] = {(char *)"no-such-command-tlsph", NULL};
    ck_assert_int_ne(slurm_cmd_run(missing, NULL, 10, &r), 0);
    slurm_cmd_free(&r);
}
END_TEST

START_TEST(resources)
{
    const char *top = getenv("top_srcdir");
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/elastic-strip.json", top ? top : ".");
    char *scene = strbuf_read_file(path, NULL);
    ck_assert_ptr_nonnull(scene);
    struct tcfg cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.slurm_particles_per_cpu = 150;
    cfg.slurm_bytes_per_particle = 4096;
    cfg.slurm_mem_margin = 1.5;
    cfg.slurm_mem_base_mb = 256;
    struct slurm_resources r;
    char err[300];
    ck_assert_int_eq(slurm_resources_of(scene, &cfg, 8, 61, &r, err, sizeof err), 0);
    ck_assert_uint_eq(r.particles, 400);
    ck_assert_int_eq(r.cpus, 3);          /* ceil(400 / 150) */
    ck_assert_int_eq(r.mem_mb, 3 + 256);  /* ceil(1.5 x 400 x 4096 B / MiB) = ceil(2.34) */
    ck_assert_int_eq(r.time_min, 2);      /* 61 s: 2 min */
    ck_assert_int_eq(slurm_resources_of(scene, &cfg, 2, 60, &r, err, sizeof err), 0);
    ck_assert_int_eq(r.cpus, 2);          /* at most the threads */
    ck_assert_int_eq(r.time_min, 1);
    ck_assert_int_eq(slurm_resources_of("{\"bodies\": 1}", &cfg, 2, 60, &r, err, sizeof err), -1);
    free(scene);
}
END_TEST

TLSPH_CHECK_MAIN("slurm", 0, state_table, verdicts, squeue_lines, batch_script_runs, commands, resources)
