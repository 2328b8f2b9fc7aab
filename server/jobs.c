/* The jobs service, see jobs.h. */
#include "jobs.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "jobdir.h"
#include "scene/scene.h"
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

/* The engine's validation of a scene (the same parser tlsph-run runs). */
static bool scene_valid(const char *text, struct tlsph_errors *err)
{
    struct tlsph_scene sc;
    memset(&sc, 0, sizeof sc);
    if (tlsph_scene_parse(text, strlen(text), &sc, err) != 0)
        return false;
    tlsph_scene_free(&sc);
    return true;
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
    char *text = json_dumps(scene, JSON_COMPACT);
    if (!text)
        return JOBS_NO_MEMORY;
    struct tlsph_errors scene_err;
    tlsph_errors_init(&scene_err);
    enum jobs_rc rc = JOBS_OK;
    if (!scene_valid(text, &scene_err)) {
        add_prefixed(err, "/scene", &scene_err);
        rc = JOBS_INVALID;
        goto done;
    }
    struct tq_job j;
    new_row(env, &j, "run", text);
    if (job_id_new(j.id) != 0) {
        errmsg_set(out->why, sizeof out->why, "no random id: %s", strerror(errno));
        rc = JOBS_NO_DIRECTORY;
        goto done;
    }
    if (jobdir_create(env->cfg->jobs_dir, j.id, text, out->why, sizeof out->why) != 0) {
        rc = JOBS_NO_DIRECTORY;
        goto done;
    }
    if (tq_insert(env->q, &j) != TQ_OK) {
        errmsg_set(out->why, sizeof out->why, "tq_insert: %s", tq_last_error(env->q));
        jobdir_remove(env->cfg->jobs_dir, j.id);
        rc = JOBS_NOT_QUEUED;
        goto done;
    }
    tsup_wake(env->sup);
    memcpy(out->id, j.id, JOB_ID_LEN + 1);
done:
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
 * the sweep parameter whose values caused them (naming the child). */
static void check_child(const struct jobs_env *env, const json_t *params,
                        const struct tstudy_child *kid, size_t i, struct tlsph_errors *err)
{
    struct tlsph_errors errs;
    tlsph_errors_init(&errs);
    json_t *mp = tstudy_pointer_get(kid->scene, "/limits/max_particles");
    if (json_is_number(mp) && json_number_value(mp) > (double)env->cfg->max_particles) {
        tlsph_errors_add(&errs, "/limits/max_particles",
                         "exceeds this server's limit of %ld particles per job",
                         env->cfg->max_particles);
    } else {
        char *text = json_dumps(kid->scene, JSON_COMPACT);
        if (text)
            scene_valid(text, &errs);
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
                char *vals = json_dumps(kid->params, JSON_COMPACT);
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

/* Expands and validates the study; JOBS_OK with the children, or JOBS_INVALID. */
static enum jobs_rc expand_study(const struct jobs_env *env, json_t *inputs,
                                 struct tstudy_child **kids, size_t *nk, struct tlsph_errors *err)
{
    json_t *base = json_object_get(inputs, "base");
    if (json_is_object(base) &&
        !apply_particle_limit(env, base, err, "/base/limits/max_particles"))
        return JOBS_INVALID;
    struct tlsph_errors errs;
    tlsph_errors_init(&errs);
    int rc = tstudy_expand(inputs, (size_t)env->cfg->max_children, kids, nk, &errs);
    if (rc != 0)
        add_prefixed(err, "", &errs);
    tlsph_errors_free(&errs);
    if (rc != 0)
        return JOBS_INVALID;
    if (*nk == 0) {
        tlsph_errors_add(err, "/sweep", "the sweep yields no child");
        return JOBS_INVALID;
    }
    const json_t *params = json_object_get(json_object_get(inputs, "sweep"), "parameters");
    for (size_t i = 0; i < *nk && err->count < JOBS_MAX_REPORTED_ERRORS; i++)
        check_child(env, params, &(*kids)[i], i, err);
    return err->count > 0 ? JOBS_INVALID : JOBS_OK;
}

/* Directories first, then the rows in one transaction; on failure the
 * directories made so far are removed. */
static enum jobs_rc queue_study(const struct jobs_env *env, json_t *inputs,
                                const struct tstudy_child *kids, size_t nk,
                                struct jobs_submitted *out)
{
    char *study_text = json_dumps(inputs, JSON_COMPACT);
    struct tq_job study;
    new_row(env, &study, "study", study_text);
    struct tq_job *rows = calloc(nk, sizeof *rows);
    enum jobs_rc rc = JOBS_OK;
    size_t i = 0;
    if (!study_text || !rows || job_id_new(study.id) != 0) {
        rc = JOBS_NO_MEMORY;
        goto done;
    }
    for (i = 0; i < nk; i++) {
        new_row(env, &rows[i], "run", json_dumps(kids[i].scene, JSON_COMPACT));
        rows[i].params = json_dumps(kids[i].params, JSON_COMPACT);
        rows[i].seq = (long)i;
        strcpy(rows[i].study_id, study.id);
        if (!rows[i].input || !rows[i].params || job_id_new(rows[i].id) != 0 ||
            jobdir_create(env->cfg->jobs_dir, rows[i].id, rows[i].input, out->why,
                          sizeof out->why) != 0)
            break;
    }
    const bool queued = i == nk && tq_insert_study(env->q, &study, rows, nk) == TQ_OK;
    if (!queued) {
        if (i == nk)
            errmsg_set(out->why, sizeof out->why, "tq_insert_study: %s", tq_last_error(env->q));
        else if (!out->why[0])
            errmsg_set(out->why, sizeof out->why, "child %zu: out of memory or no random id", i);
        for (size_t k = 0; k < nk && k <= i; k++)
            if (rows[k].id[0])
                jobdir_remove(env->cfg->jobs_dir, rows[k].id);
        rc = JOBS_NOT_QUEUED;
        goto done;
    }
    tsup_wake(env->sup);
    memcpy(out->id, study.id, JOB_ID_LEN + 1);
done:
    if (rows)
        for (size_t k = 0; k < nk; k++) {
            free(rows[k].input);
            free(rows[k].params);
        }
    free(rows);
    free(study_text);
    return rc;
}

enum jobs_rc jobs_submit_study(const struct jobs_env *env, json_t *inputs,
                               struct jobs_submitted *out)
{
    struct tstudy_child *kids = NULL;
    size_t nk = 0;
    enum jobs_rc rc = expand_study(env, inputs, &kids, &nk, &out->errors);
    if (rc == JOBS_OK)
        rc = queue_study(env, inputs, kids, nk, out);
    tstudy_children_free(kids, nk);
    return rc;
}

/* ------------------------------------------------------------------ cancel, remove */

enum jobs_rc jobs_cancel(const struct jobs_env *env, const char *id)
{
    if (tq_request_cancel(env->q, id) == TQ_ERROR)
        return JOBS_BUSY;
    tsup_wake(env->sup);
    return JOBS_OK;
}

enum jobs_rc jobs_remove(const struct jobs_env *env, const struct tq_job *job)
{
    struct tq_job *kids = NULL;
    size_t nk = 0;
    if (!strcmp(job->process, "study") && jobs_study_children(env, job->id, &kids, &nk) != 0)
        return JOBS_BUSY;
    enum jobs_rc rc;
    switch (tq_delete(env->q, job->id)) {
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
        rc = JOBS_BUSY;
        break;
    }
    tq_jobs_free(kids, nk);
    return rc;
}
