/* The jobs service, see jobs.h. */
#include "jobs.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "convergence.h"
#include "errmsg.h"
#include "intent.h"
#include "jobdir.h"
#include "numtext.h"
#include "output_size.h"
#include "run/protocol.h"
#include "scene/scene.h"
#include "storage.h"
#include "study.h"
#include "supervisor.h"

/* ------------------------------------------------------------------ helpers */

/* Appends every error of in to out with prefix before its pointer. */
static void add_prefixed(struct tlsph_errors *out, const char *prefix,
                         const struct tlsph_errors *in)
{
    char pointer[1024];
    for (size_t i = 0; i < in->count; i++) {
        snprintf(pointer, sizeof pointer, "%s%s", prefix, in->items[i].pointer);
        tlsph_errors_add(out, pointer, "%s", in->items[i].message);
    }
    if (in->out_of_memory)
        tlsph_errors_add(out, prefix, "more errors (out of memory)");
}

static bool has_error(const struct tlsph_errors *e, const char *pointer, const char *message)
{
    for (size_t i = 0; i < e->count; i++)
        if (!strcmp(e->items[i].pointer, pointer) && !strcmp(e->items[i].message, message))
            return true;
    return false;
}

/* The daemon's particle limit on a scene object: injected when the scene sets
 * none, an error at pointer when it sets a larger one (false). */
static bool apply_particle_limit(const struct jobs_env *env, json_t *scene,
                                 struct tlsph_errors *err, const char *pointer)
{
    const long limit = env->cfg->max_particles;
    json_t *lim = json_object_get(scene, "limits");
    if (!lim) {
        json_object_set_new(scene, "limits", json_pack("{s:I}", "max_particles", (json_int_t)limit));
        return true;
    }
    if (!json_is_object(lim))
        return true; /* the scene validator reports it */
    json_t *mp = json_object_get(lim, "max_particles");
    if (!mp) {
        json_object_set_new(lim, "max_particles", json_integer(limit));
        return true;
    }
    if (json_is_number(mp) && json_number_value(mp) > (double)limit) {
        tlsph_errors_add(err, pointer, "exceeds this server's limit of %ld particles per job", limit);
        return false;
    }
    return true;
}

/* The engine's validation of a scene (the same parser tlsph-run runs), and
 * the estimate of its result file. */
static bool scene_valid(const char *text, struct tlsph_errors *err, struct output_size *size)
{
    struct tlsph_scene sc;
    memset(&sc, 0, sizeof sc);
    if (tlsph_scene_parse(text, strlen(text), &sc, err) != 0)
        return false;
    const int rc = output_size_estimate(&sc, size, err);
    tlsph_scene_free(&sc);
    return rc == 0;
}

/* A job's estimate against the per-job quota: false with an error at
 * pointer (who names the child of a study, "" for a run). */
static bool within_quota(const struct jobs_env *env, const struct output_size *size,
                         const char *pointer, const char *who, struct jobs_submitted *out)
{
    const double quota = (double)env->cfg->max_output_mb * 1024.0 * 1024.0;
    if (env->cfg->max_output_mb <= 0 || size->bytes <= quota)
        return true;
    char est[32], lim[32];
    output_size_text(est, sizeof est, size->bytes);
    output_size_text(lim, sizeof lim, quota);
    tlsph_errors_add(&out->errors, pointer,
                     "%sthe result file is estimated at %s (%zu particles x (%.0f B + %ld "
                     "frames x %.0f B), an upper bound: docs/api.md), above this server's "
                     "quota of %s per job (max_output_mb); write fewer frames or use fewer "
                     "particles",
                     who, est, size->particles, size->reference_bytes, size->records,
                     size->frame_bytes, lim);
    if (!out->detail[0])
        errmsg_set(out->detail, sizeof out->detail,
                   "%sthe estimated result file of %s is above the quota of %s per job",
                   who, est, lim);
    return false;
}

/* The free space of the data directory against the floor plus the
 * estimate of everything submitted (out->output_bytes): JOBS_OK or
 * JOBS_NO_SPACE with the detail. */
static enum jobs_rc check_space(const struct jobs_env *env, struct jobs_submitted *out)
{
    const int64_t free_bytes = storage_free_bytes(env->cfg);
    if (free_bytes < 0)
        return JOBS_OK; /* unknown: the writes themselves will tell */
    const double floor_bytes = (double)storage_floor_bytes(env->cfg);
    if ((double)free_bytes >= floor_bytes + out->output_bytes)
        return JOBS_OK;
    char est[32], fr[32], fl[32];
    output_size_text(est, sizeof est, out->output_bytes);
    output_size_text(fr, sizeof fr, (double)free_bytes);
    output_size_text(fl, sizeof fl, floor_bytes);
    if ((double)free_bytes < floor_bytes)
        errmsg_set(out->detail, sizeof out->detail,
                   "the data directory has %s free, below the floor of %s (min_free_mb): no new "
                   "job is taken until space is freed",
                   fr, fl);
    else
        errmsg_set(out->detail, sizeof out->detail,
                   "the result files are estimated at %s, but the data directory has %s free "
                   "above the floor of %s (min_free_mb)",
                   est, fr, fl);
    return JOBS_NO_SPACE;
}

/* Why creating directories or rows failed: a full disk, or something else. */
static enum jobs_rc write_failure(const struct jobs_env *env, bool queue_full,
                                  enum jobs_rc otherwise, struct jobs_submitted *out)
{
    const int64_t free_bytes = storage_free_bytes(env->cfg);
    if (!queue_full && (free_bytes < 0 || (uint64_t)free_bytes >= storage_floor_bytes(env->cfg)))
        return otherwise;
    errmsg_set(out->detail, sizeof out->detail,
               "the data directory's disk is full or below its free-space floor: %s",
               out->why[0] ? out->why : "no space");
    return JOBS_NO_SPACE;
}

static void new_row(const struct jobs_env *env, struct tq_job *j, const char *process, char *input)
{
    memset(j, 0, sizeof *j);
    snprintf(j->process, sizeof j->process, "%s", process);
    strcpy(j->status, TQ_ACCEPTED);
    j->seq = -1;
    j->input = input;
    j->eta = -1;
    j->threads = env->cfg->threads_per_job;
    j->wall_limit = env->cfg->wall_limit;
}

static int cmp_seq(const void *x, const void *y)
{
    const struct tq_job *a = x, *b = y;
    return (a->seq > b->seq) - (a->seq < b->seq);
}

int jobs_study_children(const struct jobs_env *env, const char *id, struct tq_job **out,
                        size_t *n)
{
    if (tq_list(env->q, NULL, id, NULL, env->cfg->max_children + 1, 0, out, n) != TQ_OK)
        return -1;
    qsort(*out, *n, sizeof **out, cmp_seq);
    return 0;
}

void jobs_submitted_init(struct jobs_submitted *s)
{
    memset(s, 0, sizeof *s);
    tlsph_errors_init(&s->errors);
}

void jobs_submitted_free(struct jobs_submitted *s)
{
    tlsph_errors_free(&s->errors);
}

/* ------------------------------------------------------------------ runs */

/* The run's optional "threads" input: the OpenMP threads it asks for, at
 * most the cores of the thread budget (thread_budget.h; with Slurm,
 * threads_per_job, the cap of --cpus-per-task).  0 when absent (the
 * configured threads_per_job), -1 with an error at /threads. */
static long requested_threads(const struct jobs_env *env, const json_t *inputs,
                              struct tlsph_errors *err)
{
    const json_t *t = json_object_get(inputs, "threads");
    if (!t)
        return 0;
    const int slurm = !strcmp(env->cfg->executor, "slurm");
    long most = slurm ? env->cfg->threads_per_job : env->cfg->cores;
    if (most > TLSPH_MAX_THREADS)
        most = TLSPH_MAX_THREADS; /* the engine's own ceiling (run/protocol.h) */
    if (!json_is_integer(t) || json_integer_value(t) < 1 || json_integer_value(t) > most) {
        tlsph_errors_add(err, "/threads",
                         "must be an integer from 1 to %ld, the %s of this server (OpenMP "
                         "threads of the run; omit it for the default, %d)",
                         most, slurm ? "threads_per_job" : "cores", env->cfg->threads_per_job);
        return -1;
    }
    return (long)json_integer_value(t);
}

enum jobs_rc jobs_submit_run(const struct jobs_env *env, json_t *inputs, struct jobs_submitted *out)
{
    struct tlsph_errors *err = &out->errors;
    json_t *scene = json_object_get(inputs, "scene");
    if (!json_is_object(scene)) {
        tlsph_errors_add(err, "/scene", "%s", scene ? "must be an object (a scene document)" : "required");
        return JOBS_INVALID;
    }
    if (!apply_particle_limit(env, scene, err, "/scene/limits/max_particles"))
        return JOBS_INVALID;
    const long threads = requested_threads(env, inputs, err);
    if (threads < 0)
        return JOBS_INVALID;
    char *text = numtext_json_dumps(scene, JSON_COMPACT);
    if (!text)
        return JOBS_NO_MEMORY;
    struct tlsph_errors scene_err;
    tlsph_errors_init(&scene_err);
    struct intent intent = {""};
    enum jobs_rc rc = JOBS_OK;
    struct output_size size;
    if (!scene_valid(text, &scene_err, &size)) {
        add_prefixed(err, "/scene", &scene_err);
        rc = JOBS_INVALID;
        goto done;
    }
    out->output_bytes = size.bytes;
    if (!within_quota(env, &size, "/scene/output/frames", "", out)) {
        rc = JOBS_OVER_QUOTA;
        goto done;
    }
    if ((rc = check_space(env, out)) != JOBS_OK)
        goto done;
    struct tq_job j;
    new_row(env, &j, "run", text);
    if (threads > 0)
        j.threads = threads;
    if (job_id_new(j.id) != 0) {
        errmsg_set(out->why, sizeof out->why, "no random id: %s", strerror(errno));
        rc = JOBS_NO_DIRECTORY;
        goto done;
    }
    const char *ids[] = {j.id};
    if (intent_begin(&intent, env->cfg->jobs_dir, ids, 1, out->why, sizeof out->why) != 0 ||
        jobdir_create(env->cfg->jobs_dir, j.id, text, out->why, sizeof out->why) != 0) {
        out->errnum = errno;
        rc = write_failure(env, false, JOBS_NO_DIRECTORY, out);
        goto done;
    }
    if (tq_insert(env->q, &j) != TQ_OK) {
        errmsg_set(out->why, sizeof out->why, "tq_insert: %s", tq_last_error(env->q));
        jobdir_remove(env->cfg->jobs_dir, j.id);
        rc = write_failure(env, tq_disk_full(env->q), JOBS_NOT_QUEUED, out);
        goto done;
    }
    tsup_wake(env->sup);
    memcpy(out->id, j.id, JOB_ID_LEN + 1);
done:
    intent_end(&intent);
    tlsph_errors_free(&scene_err);
    free(text);
    return rc;
}

/* ------------------------------------------------------------------ studies */

/* Is error pointer p inside (or equal to) swept pointer s? */
static bool pointer_under(const char *p, const char *s)
{
    size_t n = strlen(s);
    return !strncmp(p, s, n) && (p[n] == '\0' || p[n] == '/');
}

/* Validates child i; its errors go to err, pointed at the base scene, or at
 * the sweep parameter whose values caused them (naming the child).  size
 * gets the estimate of its result file (valid when no error was added). */
static void check_child(const struct jobs_env *env, const json_t *params,
                        const struct tstudy_child *kid, size_t i, struct tlsph_errors *err,
                        struct output_size *size)
{
    struct tlsph_errors errs;
    tlsph_errors_init(&errs);
    memset(size, 0, sizeof *size);
    json_t *mp = tstudy_pointer_get(kid->scene, "/limits/max_particles");
    if (json_is_number(mp) && json_number_value(mp) > (double)env->cfg->max_particles) {
        tlsph_errors_add(&errs, "/limits/max_particles",
                         "exceeds this server's limit of %ld particles per job",
                         env->cfg->max_particles);
    } else {
        char *text = numtext_json_dumps(kid->scene, JSON_COMPACT);
        if (text)
            scene_valid(text, &errs, size);
        free(text);
    }
    for (size_t k = 0; k < errs.count && err->count < JOBS_MAX_REPORTED_ERRORS; k++) {
        const char *ep = errs.items[k].pointer;
        char pointer[600], detail[1200];
        snprintf(pointer, sizeof pointer, "/base%s", ep);
        snprintf(detail, sizeof detail, "%s", errs.items[k].message);
        const json_t *pp;
        size_t pi;
        json_array_foreach(params, pi, pp) {
            const char *sp = json_string_value(json_object_get(pp, "pointer"));
            if (sp && pointer_under(ep, sp)) {
                char *vals = numtext_json_dumps(kid->params, JSON_COMPACT);
                snprintf(pointer, sizeof pointer, "/sweep/parameters/%zu", pi);
                snprintf(detail, sizeof detail, "child %zu %s: %s", i, vals ? vals : "",
                         errs.items[k].message);
                free(vals);
                break;
            }
        }
        if (!has_error(err, pointer, detail))
            tlsph_errors_add(err, pointer, "%s", detail);
    }
    tlsph_errors_free(&errs);
}

/* Expands and validates the study; JOBS_OK with the children, or
 * JOBS_INVALID; then the quota of each child (JOBS_OVER_QUOTA) and the space
 * for all (JOBS_NO_SPACE). */
static enum jobs_rc expand_study(const struct jobs_env *env, json_t *inputs,
                                 struct tstudy_child **kids, size_t *nk, struct jobs_submitted *out)
{
    struct tlsph_errors *err = &out->errors;
    json_t *base = json_object_get(inputs, "base");
    if (json_is_object(base) &&
        !apply_particle_limit(env, base, err, "/base/limits/max_particles"))
        return JOBS_INVALID;
    struct tlsph_errors errs;
    tlsph_errors_init(&errs);
    const int expanded = tstudy_expand(inputs, (size_t)env->cfg->max_children, kids, nk, &errs);
    if (expanded != 0)
        add_prefixed(err, "", &errs);
    tlsph_errors_free(&errs);
    if (expanded != 0)
        return JOBS_INVALID;
    if (*nk == 0) {
        tlsph_errors_add(err, "/sweep", "the sweep yields no child");
        return JOBS_INVALID;
    }
    const json_t *params = json_object_get(json_object_get(inputs, "sweep"), "parameters");
    struct output_size *sizes = calloc(*nk, sizeof *sizes);
    if (!sizes)
        return JOBS_NO_MEMORY;
    for (size_t i = 0; i < *nk && err->count < JOBS_MAX_REPORTED_ERRORS; i++)
        check_child(env, params, &(*kids)[i], i, err, &sizes[i]);
    enum jobs_rc rc = err->count > 0 ? JOBS_INVALID : JOBS_OK;
    for (size_t i = 0; rc != JOBS_INVALID && i < *nk; i++) {
        if (env->cfg->max_output_mb <= 0) {
            out->output_bytes += sizes[i].bytes;
            continue;
        }
        char who[1100];
        char *vals = numtext_json_dumps((*kids)[i].params, JSON_COMPACT);
        snprintf(who, sizeof who, "child %zu %s: ", i, vals ? vals : "");
        free(vals);
        out->output_bytes += sizes[i].bytes;
        if (err->count < JOBS_MAX_REPORTED_ERRORS &&
            !within_quota(env, &sizes[i], "/base/output/frames", who, out))
            rc = JOBS_OVER_QUOTA;
    }
    free(sizes);
    return rc == JOBS_OK ? check_space(env, out) : rc;
}

/* Ids and rows first, then the intent file, the directories, and the rows in
 * one transaction; on failure the directories made so far are removed. */
static enum jobs_rc queue_study(const struct jobs_env *env, json_t *inputs,
                                const struct tstudy_child *kids, size_t nk,
                                struct jobs_submitted *out)
{
    char *study_text = numtext_json_dumps(inputs, JSON_COMPACT);
    struct tq_job study;
    new_row(env, &study, "study", study_text);
    struct tq_job *rows = calloc(nk, sizeof *rows);
    const char **ids = calloc(nk + 1, sizeof *ids);
    struct intent intent = {""};
    enum jobs_rc rc = JOBS_OK;
    size_t made = 0;
    if (!study_text || !rows || !ids || job_id_new(study.id) != 0) {
        rc = JOBS_NO_MEMORY;
        goto done;
    }
    ids[0] = study.id;
    for (size_t i = 0; i < nk; i++) {
        new_row(env, &rows[i], "run", numtext_json_dumps(kids[i].scene, JSON_COMPACT));
        rows[i].params = numtext_json_dumps(kids[i].params, JSON_COMPACT);
        rows[i].seq = (long)i;
        strcpy(rows[i].study_id, study.id);
        if (!rows[i].input || !rows[i].params || job_id_new(rows[i].id) != 0) {
            rc = JOBS_NO_MEMORY;
            goto done;
        }
        ids[i + 1] = rows[i].id;
    }
    if (intent_begin(&intent, env->cfg->jobs_dir, ids, nk + 1, out->why, sizeof out->why) != 0) {
        out->errnum = errno;
        rc = write_failure(env, false, JOBS_NOT_QUEUED, out);
        goto done;
    }
    while (made < nk && jobdir_create(env->cfg->jobs_dir, rows[made].id, rows[made].input,
                                      out->why, sizeof out->why) == 0)
        made++;
    if (made < nk)
        out->errnum = errno;
    const bool queued = made == nk && tq_insert_study(env->q, &study, rows, nk) == TQ_OK;
    if (!queued) {
        const bool full = made == nk && tq_disk_full(env->q);
        if (made == nk)
            errmsg_set(out->why, sizeof out->why, "tq_insert_study: %s", tq_last_error(env->q));
        for (size_t k = 0; k < nk && k <= made; k++)
            jobdir_remove(env->cfg->jobs_dir, rows[k].id);
        rc = write_failure(env, full, JOBS_NOT_QUEUED, out);
        goto done;
    }
    tsup_wake(env->sup);
    memcpy(out->id, study.id, JOB_ID_LEN + 1);
done:
    intent_end(&intent);
    if (rows)
        for (size_t k = 0; k < nk; k++) {
            free(rows[k].input);
            free(rows[k].params);
        }
    free(rows);
    free(ids);
    free(study_text);
    return rc;
}

enum jobs_rc jobs_submit_study(const struct jobs_env *env, json_t *inputs,
                               struct jobs_submitted *out)
{
    struct tstudy_child *kids = NULL;
    size_t nk = 0;
    enum jobs_rc rc = expand_study(env, inputs, &kids, &nk, out);
    if (rc == JOBS_OK)
        rc = queue_study(env, inputs, kids, nk, out);
    tstudy_children_free(kids, nk);
    return rc;
}

enum jobs_rc jobs_submit_convergence(const struct jobs_env *env, json_t *inputs,
                                     struct jobs_submitted *out)
{
    json_t *study = tconv_study(inputs, &out->errors);
    if (!study)
        return out->errors.out_of_memory ? JOBS_NO_MEMORY : JOBS_INVALID;
    /* the study machinery sees the study without the request it came from
     * (a shallow copy: the particle limit lands in the stored base too) */
    json_t *plain = json_copy(study);
    struct tstudy_child *kids = NULL;
    size_t nk = 0;
    enum jobs_rc rc = JOBS_NO_MEMORY;
    if (plain && json_object_del(plain, "convergence") == 0) {
        rc = expand_study(env, plain, &kids, &nk, out);
        if (rc == JOBS_OK)
            rc = queue_study(env, study, kids, nk, out);
    }
    /* the user sent a ladder, not a sweep: a child refused for its spacing
     * (the particle limit, a quota) is reported at the ladder */
    for (size_t i = 0; i < out->errors.count; i++) {
        char *ptr = out->errors.items[i].pointer, *ladder;
        if (ptr && !strncmp(ptr, "/sweep", 6) && (ptr[6] == '\0' || ptr[6] == '/') &&
            (ladder = strdup("/ladder")) != NULL) {
            free(ptr);
            out->errors.items[i].pointer = ladder;
        }
    }
    tstudy_children_free(kids, nk);
    json_decref(plain);
    json_decref(study);
    return rc;
}

/* ------------------------------------------------------------------ cancel, remove */

/* After a write the full disk refused: frees the reserve (storage.h) so that
 * it can be tried once more, and says whether that is worth it.  Cancelling
 * and removing are what a user does to get out of a full disk. */
static bool room_made(const struct jobs_env *env)
{
    return tq_disk_full(env->q) && storage_release_reserve(env->cfg);
}

enum jobs_rc jobs_cancel(const struct jobs_env *env, const char *id)
{
    enum tq_rc rc = tq_request_cancel(env->q, id);
    if (rc == TQ_ERROR && room_made(env))
        rc = tq_request_cancel(env->q, id);
    if (rc == TQ_ERROR)
        return tq_disk_full(env->q) ? JOBS_NO_SPACE : JOBS_BUSY;
    tsup_wake(env->sup);
    return JOBS_OK;
}

/* The intent of removing job and its children (intent.h), so that a crash
 * between the rows and the directories leaves no directory behind.  Best
 * effort: a removal is what frees a full disk, so it goes on without one. */
static void intend_removal(const struct jobs_env *env, const struct tq_job *job,
                           const struct tq_job *kids, size_t nk, struct intent *intent)
{
    const char **ids = calloc(nk + 1, sizeof *ids);
    size_t n = 0;
    char why[256];
    if (ids && job_id_valid(job->id))
        ids[n++] = job->id;
    for (size_t i = 0; ids && i < nk; i++)
        if (job_id_valid(kids[i].id))
            ids[n++] = kids[i].id;
    if (ids)
        intent_begin(intent, env->cfg->jobs_dir, ids, n, why, sizeof why);
    free(ids);
}

enum jobs_rc jobs_remove(const struct jobs_env *env, const struct tq_job *job)
{
    struct tq_job *kids = NULL;
    size_t nk = 0;
    if (job->study_id[0])
        return JOBS_STUDY_CHILD;
    if (!strcmp(job->process, "study") && jobs_study_children(env, job->id, &kids, &nk) != 0)
        return JOBS_BUSY;
    struct intent intent = {""};
    intend_removal(env, job, kids, nk, &intent);
    enum jobs_rc rc;
    enum tq_rc deleted = tq_delete(env->q, job->id);
    if (deleted == TQ_ERROR && room_made(env))
        deleted = tq_delete(env->q, job->id);
    switch (deleted) {
    case TQ_OK:
        for (size_t i = 0; i < nk; i++)
            if (job_id_valid(kids[i].id))
                jobdir_remove(env->cfg->jobs_dir, kids[i].id);
        jobdir_remove(env->cfg->jobs_dir, job->id);
        rc = JOBS_OK;
        break;
    case TQ_NOT_FOUND:
        rc = JOBS_NO_SUCH_JOB;
        break;
    case TQ_NOT_FINAL:
        rc = JOBS_NOT_FINAL;
        break;
    default:
        rc = tq_disk_full(env->q) ? JOBS_NO_SPACE : JOBS_BUSY;
        break;
    }
    intent_end(&intent);
    tq_jobs_free(kids, nk);
    return rc;
}
