/* The daemon's thread budget; see thread_budget.h. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "thread_budget.h"

#include <sched.h>
#include <stdio.h>
#include <unistd.h>

int tbudget_detect_cores(void)
{
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) {
        const int n = CPU_COUNT(&set);
        if (n > 0)
            return n;
    }
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

int tbudget_configure(int cores, int max_jobs, int *threads_per_job, char *warn, size_t warnsize)
{
    if (cores < 1)
        cores = 1;
    if (max_jobs < 1)
        max_jobs = 1;
    int share = cores / max_jobs;
    if (share < 1)
        share = 1;
    if (warnsize > 0)
        warn[0] = '\0';
    const int asked = *threads_per_job;
    if (asked < 1 || (long)asked * max_jobs > cores)
        *threads_per_job = share; /* asked > cores / max_jobs >= share */
    if (max_jobs > cores) {
        snprintf(warn, warnsize,
                 "max_jobs %d > cores %d: at most %d engines run at once, each on one thread, "
                 "and the other jobs wait (set cores to share cores on purpose)",
                 max_jobs, cores, cores);
        return 1;
    }
    if (asked >= 1 && *threads_per_job != asked) {
        snprintf(warn, warnsize,
                 "threads_per_job %d x max_jobs %d > cores %d: lowered threads_per_job to %d, so "
                 "that the engines running at once never want more threads than there are cores",
                 asked, max_jobs, cores, *threads_per_job);
        return 1;
    }
    return 0;
}

int tbudget_grant(const struct tbudget *b, int want)
{
    const int free_cores = b->cores - b->used;
    if (free_cores < 1)
        return 0;
    if (want < 1)
        want = 1;
    return want < free_cores ? want : free_cores;
}

void tbudget_take(struct tbudget *b, int n)
{
    b->used += n;
}

void tbudget_give(struct tbudget *b, int n)
{
    b->used -= n;
    if (b->used < 0)
        b->used = 0;
}
