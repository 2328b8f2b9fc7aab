#include "run/run.h"

#include <math.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "bc/boundary.h"
#include "contact/contact.h"
#include "crack/crack_driver.h"
#include "rigid/rigid.h"
#include "io/output/output.h"
#include "run/integrate.h"
#include "run/progress.h"
#include "util/clock.h"
#include "util/parallel.h"

static size_t peak_rss_bytes(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0;
    return (size_t)ru.ru_maxrss * 1024u; /* Linux reports KiB */
}

static void fill_cost(const struct tlsph_model *m, double wall, struct tlsph_cost *c)
{
    c->particles = m->p.n;
    c->pairs = m->pairs.npairs;
    c->steps = m->step;
    c->wall_seconds = wall;
    c->particle_steps_per_second = wall > 0 ? (double)m->p.n * (double)m->step / wall : 0.0;
    c->peak_memory_bytes = peak_rss_bytes();
    c->bytes_per_particle = m->p.n ? (double)m->bytes_allocated / (double)m->p.n : 0.0;
    c->threads = tlsph_threads();
    c->contact = m->contact != NULL;
    if (c->contact) {
        const struct tlsph_contact_cost cc = tlsph_contact_cost(m);
        c->contact_searches = cc.searches;
        c->contact_search_share = wall > 0 ? cc.search_seconds / wall : 0.0;
        c->contact_phase_share = wall > 0 ? cc.phase_seconds / wall : 0.0;
    }
    c->porous = m->p.void_fraction != NULL;
    if (c->porous)
        c->material_phase_share = wall > 0 ? m->material_seconds / wall : 0.0;
}

static json_t *cost_json(const struct tlsph_cost *c)
{
    json_t *o = json_pack(
        "{s:I, s:I, s:I, s:f, s:f, s:I, s:f}", "particles", (json_int_t)c->particles, "pairs",
        (json_int_t)c->pairs, "steps", (json_int_t)c->steps, "wall_seconds", c->wall_seconds,
        "particle_steps_per_second", c->particle_steps_per_second, "peak_memory_bytes",
        (json_int_t)c->peak_memory_bytes, "bytes_per_particle", c->bytes_per_particle);
    if (o)
        json_object_set_new(o, "threads", json_integer(c->threads));
    if (o && c->contact) {
        json_object_set_new(o, "contact_searches", json_integer(c->contact_searches));
        json_object_set_new(o, "contact_search_share", json_real(c->contact_search_share));
        json_object_set_new(o, "contact_phase_share", json_real(c->contact_phase_share));
    }
    if (o && c->porous)
        json_object_set_new(o, "material_phase_share", json_real(c->material_phase_share));
    return o;
}

static json_t *diagnostic_json(const struct tlsph_diagnostic *d)
{
    json_t *ids = json_array();
    for (size_t k = 0; ids && k < d->nids; k++)
        json_array_append_new(ids, json_integer(d->ids[k]));
    return json_pack("{s:I, s:f, s:s, s:f, s:f, s:o, s:s}", "step", (json_int_t)d->step, "time",
                     d->time, "quantity", d->quantity, "value", isfinite(d->value) ? d->value : -1.0,
                     "limit", d->limit, "particle_ids", ids ? ids : json_array(), "message",
                     d->message);
}

static void emit_started(const struct tlsph_model *m, int fd)
{
    json_t *mods = json_array();
    for (int k = 0; mods && k < m->nmodules; k++)
        json_array_append_new(mods, json_string(m->modules[k]));
    json_t *o = json_pack("{s:s, s:I, s:I, s:f, s:o, s:I, s:f}", "event", TLSPH_EVENT_STARTED, "particles",
                          (json_int_t)m->p.n, "pairs", (json_int_t)m->pairs.npairs, "end_time",
                          m->scene.end_time, "modules", mods ? mods : json_array(),
                          "deficient_supports", (json_int_t)m->deficient_supports, "dt", m->dt);
    tlsph_progress_emit(fd, o);
    json_decref(o);
}

static void emit_progress(const struct tlsph_model *m, int fd, double wall, long frames)
{
    const double frac = m->scene.end_time > 0 ? m->t / m->scene.end_time : 1.0;
    const double eta = frac > 0 ? wall * (1.0 - frac) / frac : -1.0;
    json_t *o = json_pack("{s:s, s:I, s:f, s:f, s:f, s:f, s:I}", "event", TLSPH_EVENT_PROGRESS, "step",
                          (json_int_t)m->step, "time", m->t, "end_time", m->scene.end_time,
                          "wall_seconds", wall, "eta_seconds", eta, "frames", (json_int_t)frames);
    if (o && m->crack_driver) { /* the growth: the count changes (progress.schema.json) */
        json_object_set_new(o, "particles", json_integer((json_int_t)m->p.n));
        json_object_set_new(o, "crack_tip_advances",
                            json_integer((json_int_t)m->crack_driver->nevents));
        json_object_set_new(o, "crack_length", json_real(tlsph_crack_driver_length(m)));
    }
    tlsph_progress_emit(fd, o);
    json_decref(o);
}

/* The final event; err adds the errors (io_error), d the diagnostic (unstable). */
static void emit_finished(const struct tlsph_model *m, int fd, enum tlsph_exit code,
                          const struct tlsph_cost *c, const struct tlsph_diagnostic *d,
                          const struct tlsph_errors *err)
{
    json_t *o = tlsph_progress_final(code, err);
    if (o) {
        json_object_set_new(o, "step", json_integer((json_int_t)m->step));
        json_object_set_new(o, "time", json_real(m->t));
        json_object_set_new(o, "cost", cost_json(c));
        if (d)
            json_object_set_new(o, "diagnostic", diagnostic_json(d));
    }
    tlsph_progress_emit(fd, o);
    json_decref(o);
}

/* The crack driver after a step (crack/crack_driver.h); a growth that
 * cannot go on (a split refused, out of memory) stops the run on a
 * diagnostic, since the pairs would no longer match the crack surface. */
static int grow_cracks(struct tlsph_model *m, FILE *log, struct tlsph_diagnostic *d)
{
    struct tlsph_errors e;
    tlsph_errors_init(&e);
    const int rc = tlsph_crack_driver_step(m, log, &e);
    if (rc != 0) {
        memset(d, 0, sizeof *d);
        d->step = m->step;
        d->time = m->t;
        snprintf(d->quantity, sizeof d->quantity, "crack_growth");
        snprintf(d->message, sizeof d->message, "crack growth stopped the run: %s",
                 e.count ? e.items[0].message : "out of memory");
    }
    tlsph_errors_free(&e);
    return rc;
}

/* What writing a frame or a sample came to; STOPPED: the run stops on the
 * diagnostic in d. */
enum written { WRITTEN, STOPPED, IO_FAILED };

/* The writer refused a value that is not finite: the run stops. */
static enum written refused(struct tlsph_model *m, const struct tlsph_output *out,
                            struct tlsph_diagnostic *d)
{
    const struct tlsph_output_refusal *r = tlsph_output_refusal(out);
    tlsph_refusal_diagnostic(m, r->dataset, r->value, r->ids, r->nids, d);
    return STOPPED;
}

static enum written write_frame(struct tlsph_output *out, struct tlsph_model *m, long *frames,
                                struct tlsph_diagnostic *d)
{
    const int rc = tlsph_output_frame(out, m);
    if (rc == TLSPH_OUTPUT_REFUSED)
        return refused(m, out, d);
    if (rc != 0)
        return IO_FAILED;
    (*frames)++;
    return WRITTEN;
}

static enum written write_series(struct tlsph_output *out, struct tlsph_model *m,
                                 struct tlsph_diagnostic *d)
{
    tlsph_boundary_displacements(m);
    const int rc = tlsph_output_series(out, m);
    if (rc == TLSPH_OUTPUT_REFUSED)
        return refused(m, out, d);
    return rc != 0 ? IO_FAILED : WRITTEN;
}

/* A frame with its series sample (a frame time, the start and the end). */
static enum written write_both(struct tlsph_output *out, struct tlsph_model *m, long *frames,
                               struct tlsph_diagnostic *d)
{
    tlsph_boundary_displacements(m);
    const enum written w = write_frame(out, m, frames, d);
    return w != WRITTEN ? w : write_series(out, m, d);
}

int tlsph_run(struct tlsph_model *m, const struct tlsph_run_options *o,
              struct tlsph_diagnostic *d, struct tlsph_errors *err)
{
    const double t0 = tlsph_monotonic_seconds();
    const struct tlsph_scene *s = &m->scene;
    const double frame_dt = s->end_time / (double)s->frames;
    m->frame_interval = frame_dt;
    m->next_frame_time = frame_dt;
    m->dt = tlsph_next_dt(m); /* the first step, now with the frame schedule */
    struct tlsph_output *out = tlsph_output_open(o->output_dir, m, err);
    if (!out) {
        struct tlsph_cost none;
        if (err->count == 0)
            tlsph_errors_add(err, "", "cannot create the result file");
        fill_cost(m, tlsph_monotonic_seconds() - t0, &none);
        emit_finished(m, o->progress_fd, TLSPH_EXIT_IO, &none, NULL, err);
        return TLSPH_EXIT_IO;
    }
    emit_started(m, o->progress_fd);
    if (o->log)
        fprintf(o->log,
                "tlsph: %zu particles, %zu pairs (%.1f per particle), %zu deficient supports, "
                "%zu isolated, dt = %.4g s\n",
                m->p.n, m->pairs.npairs, m->p.n ? (double)m->pairs.npairs / (double)m->p.n : 0.0,
                m->deficient_supports, m->isolated, m->dt);
    if (o->log && m->crack_surface && m->scene.ncracks)
        fprintf(o->log, "tlsph: the scene's cracks cut %zu reference pairs\n", m->cut_pairs);

    long frames = 0, next_frame = 1;
    enum tlsph_exit code = TLSPH_EXIT_SUCCESS;
    int have_diag = 0;
    double last_progress = t0;
    /* The initial state meets the contract too before it is written. */
    enum written w = tlsph_model_check(m, d) != 0 ? STOPPED : write_both(out, m, &frames, d);
    for (;;) {
        if (w == IO_FAILED)
            goto io_error;
        if (w == STOPPED) {
            have_diag = 1;
            break;
        }
        const int at_end = m->t >= s->end_time * (1.0 - 1e-12) ||
                           (s->max_steps > 0 && m->step >= s->max_steps);
        const int cancelled = o->cancel && *o->cancel;
        if (at_end || cancelled) {
            if (tlsph_model_check(m, d) != 0) {
                have_diag = 1;
                break;
            }
            w = write_both(out, m, &frames, d);
            if (w != WRITTEN)
                continue;
            if (cancelled && !at_end)
                code = TLSPH_EXIT_CANCELLED;
            break;
        }
        if (tlsph_time_check(m, d) != 0) {
            have_diag = 1;
            break;
        }
        tlsph_model_step(m);
        if (m->crack_driver && grow_cracks(m, o->log, d) != 0) {
            have_diag = 1;
            break;
        }
        const int frame_due = m->t >= (double)next_frame * frame_dt * (1.0 - 1e-12) &&
                              m->t < s->end_time * (1.0 - 1e-12);
        if (frame_due || m->step % s->check_every == 0) {
            if (tlsph_model_check(m, d) != 0) {
                have_diag = 1;
                break;
            }
        }
        if (m->step % s->series_every == 0 && (w = write_series(out, m, d)) != WRITTEN)
            continue;
        if (frame_due) {
            if ((w = write_frame(out, m, &frames, d)) != WRITTEN)
                continue;
            while ((double)next_frame * frame_dt <= m->t * (1.0 + 1e-12))
                next_frame++;
            m->next_frame_time = (double)next_frame * frame_dt;
        }
        const double wall = tlsph_monotonic_seconds();
        if (frame_due || wall - last_progress > 0.5) {
            emit_progress(m, o->progress_fd, wall - t0, frames);
            last_progress = wall;
        }
    }

    if (have_diag) {
        code = TLSPH_EXIT_UNSTABLE;
        if (o->log)
            fprintf(o->log, "tlsph: %s\n", d->message);
    }
    struct tlsph_cost cost;
    m->wall_seconds = tlsph_monotonic_seconds() - t0;
    fill_cost(m, m->wall_seconds, &cost);
    const char *status = tlsph_exit_status(code);
    if (tlsph_output_close(out, m, &cost, status, have_diag ? d : NULL) != 0) {
        tlsph_errors_add(err, "", "could not finish writing the result file");
        emit_finished(m, o->progress_fd, TLSPH_EXIT_IO, &cost, NULL, err);
        return TLSPH_EXIT_IO;
    }
    emit_finished(m, o->progress_fd, code, &cost, have_diag ? d : NULL, NULL);
    if (o->log && m->p.eps_p)
        fprintf(o->log,
                "tlsph: plasticity: %lld plastic point-steps (%.1f %% of all), %.2f return-mapping "
                "iterations each\n",
                m->plastic_point_steps,
                m->step ? 100.0 * (double)m->plastic_point_steps / ((double)m->step * (double)m->p.n)
                        : 0.0,
                m->plastic_point_steps
                    ? (double)m->return_iterations / (double)m->plastic_point_steps
                    : 0.0);
    if (o->log && m->p.eps_p)
        fprintf(o->log, "tlsph: material phase %.3f s (%.1f %% of the run)\n", m->material_seconds,
                cost.wall_seconds > 0 ? 100.0 * m->material_seconds / cost.wall_seconds : 0.0);
    if (o->log && m->contact) {
        const struct tlsph_contact_cost cc = tlsph_contact_cost(m);
        fprintf(o->log,
                "tlsph: contact: %ld searches (%.3f s, %.1f %% of the run), contact phase %.3f s "
                "(%.1f %%), %zu candidate pairs now\n",
                cc.searches, cc.search_seconds,
                cost.wall_seconds > 0 ? 100.0 * cc.search_seconds / cost.wall_seconds : 0.0,
                cc.phase_seconds,
                cost.wall_seconds > 0 ? 100.0 * cc.phase_seconds / cost.wall_seconds : 0.0,
                tlsph_contact_candidates(m) / 2);
    }
    if (o->log && m->crack_driver) {
        const struct tlsph_crack_driver *cd = m->crack_driver;
        fprintf(o->log,
                "tlsph: crack growth: %zu tip advances, %zu particles split, %zu particles "
                "now, grown %g m, driver %.3f s (%.2f %% of the run)\n",
                cd->nevents, cd->particles_split, m->p.n, tlsph_crack_driver_length(m),
                cd->seconds, cost.wall_seconds > 0 ? 100.0 * cd->seconds / cost.wall_seconds : 0.0);
    }
    if (o->log && m->rigid) {
        const struct tlsph_rigid_cost rc = tlsph_rigid_cost(m);
        const double share = cost.wall_seconds > 0 ? rc.phase_seconds / cost.wall_seconds : 0.0;
        fprintf(o->log,
                "tlsph: rigid bodies: %ld searches, rigid phase %.3f s (%.1f %% of the run)\n",
                rc.searches, rc.phase_seconds, 100.0 * share);
    }
    if (o->log)
        fprintf(o->log,
                "tlsph: %s after %ld steps, t = %.6g s, %.2f s wall (%d thread%s), %.3g "
                "particle-steps/s, %.0f bytes/particle, peak RSS %.1f MiB\n",
                status, m->step, m->t, cost.wall_seconds, cost.threads,
                cost.threads == 1 ? "" : "s", cost.particle_steps_per_second,
                cost.bytes_per_particle, (double)cost.peak_memory_bytes / 1048576.0);
    return code;

io_error:
    tlsph_output_abort(out);
    if (err->count == 0)
        tlsph_errors_add(err, "", "writing the result file failed");
    {
        struct tlsph_cost partial;
        fill_cost(m, tlsph_monotonic_seconds() - t0, &partial);
        emit_finished(m, o->progress_fd, TLSPH_EXIT_IO, &partial, NULL, err);
    }
    return TLSPH_EXIT_IO;
}
