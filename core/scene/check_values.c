/* The scene's expressions give finite numbers wherever the engine evaluates
 * them.  An Inf or NaN from `1/0`, `0/0`, `log(0)` or an overflowing constant
 * would go straight into the initial state or a prescribed velocity, and from
 * there into frame 0 of the result; no dataset of a result may hold one
 * (docs/output.md), so the scene is refused instead.
 *
 *   - A body's initial velocity (expressions of x, y, z in m) is evaluated at
 *     every lattice point of the body, which is exactly where the engine
 *     evaluates it (core/run/model.c); a constant one once.  The walk runs after
 *     the particle counts, so it is bounded by the particle limit, and it
 *     visits only bodies with a component that depends on x, y or z.
 *   - An expression of t (a prescribed velocity, core/bc/velocity.c) is
 *     evaluated at t = k end / N, k = 0..N (N = TLSPH_TIME_SAMPLES): the engine
 *     evaluates it at step ends and mid-steps it cannot know in advance, so a
 *     singularity between two samples passes here and is stopped by the
 *     stability contract at run time (core/run/stability.c), never written.
 *
 * Selector expressions only choose particles (non-zero = chosen) and are not
 * checked. */
#include <math.h>
#include <string.h>

#include "scene/parse_internal.h"

static const char *const axis[3] = {"x", "y", "z"};

/* How a message names a value that is not finite. */
static const char *nonfinite(double v)
{
    return isnan(v) ? "NaN" : v > 0 ? "+Inf" : "-Inf";
}

/* Where one velocity component first failed. */
struct component_failure {
    int failed;
    double value;
    double X[3];
};

struct velocity_walk {
    struct tlsph_expr *ex[3]; /* the components that depend on x, y, z; NULL otherwise */
    double constant[3];       /* the others' values (0 when absent) */
    struct component_failure bad[3];
    int pending; /* components still finite everywhere */
    struct tlsph_initial_speed *fastest;
};

static int visit_point(const double X[3], void *ctx)
{
    struct velocity_walk *w = ctx;
    double v[3];
    for (int c = 0; c < 3; c++) {
        v[c] = w->ex[c] ? tlsph_expr_eval(w->ex[c], X) : w->constant[c];
        if (w->ex[c] && !isfinite(v[c]) && !w->bad[c].failed) {
            w->bad[c] = (struct component_failure){1, v[c], {X[0], X[1], X[2]}};
            w->pending--;
        }
    }
    const double speed = hypot(hypot(v[0], v[1]), v[2]);
    if (speed > w->fastest->speed) { /* false for NaN: those are reported above */
        w->fastest->speed = speed;
        memcpy(w->fastest->X, X, sizeof w->fastest->X);
    }
    return w->pending == 0; /* every component already failed: nothing more to learn */
}

static void report(struct tlsph_errors *err, const char *body_pointer, int c,
                   const struct tlsph_expr *ex, const char *body, const struct component_failure *f,
                   int constant)
{
    char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, body_pointer, "initial_velocity");
    tlsph_pointer_index(q, sizeof q, p, (size_t)c);
    if (constant)
        tlsph_errors_add(err, q,
                         "initial %s velocity '%s' of body '%s' is %s, not a finite number of "
                         "m/s",
                         axis[c], tlsph_expr_text(ex), body, nonfinite(f->value));
    else
        tlsph_errors_add(err, q,
                         "initial %s velocity '%s' of body '%s' is %s at its particle x = %g, "
                         "y = %g, z = %g m; it must be a finite number of m/s at every particle",
                         axis[c], tlsph_expr_text(ex), body, nonfinite(f->value), f->X[0], f->X[1],
                         f->X[2]);
}

int tlsph_check_initial_velocities(struct tlsph_scene *s, struct tlsph_initial_speed *fastest,
                                   struct tlsph_errors *err)
{
    int bad = 0;
    for (size_t b = 0; b < s->nbodies; b++) {
        struct tlsph_body *body = &s->bodies[b];
        char P[TLSPH_POINTER_MAX];
        tlsph_pointer_index(P, sizeof P, "/bodies", b);
        struct velocity_walk w = {.fastest = &fastest[b]};
        memset(&fastest[b], 0, sizeof fastest[b]);
        int body_bad = 0;
        for (int c = 0; c < 3; c++) {
            struct tlsph_expr *ex = &body->initial_velocity[c];
            if (!ex->evaluator)
                continue;
            if (!ex->constant) {
                w.ex[c] = ex;
                w.pending++;
                continue;
            }
            const double origin[3] = {0.0, 0.0, 0.0};
            w.constant[c] = tlsph_expr_eval(ex, origin);
            if (!isfinite(w.constant[c])) {
                report(err, P, c, ex, body->name,
                       &(struct component_failure){1, w.constant[c], {0, 0, 0}}, 1);
                body_bad = 1;
            }
        }
        bad |= body_bad;
        if (body_bad)
            continue; /* a constant failed: the speeds are not needed */
        long lo[3], hi[3];
        const double candidates = tlsph_lattice_range(s, b, lo, hi);
        if (w.pending == 0 || !(candidates > 0.0)) { /* uniform: one point says it all */
            fastest[b].speed = hypot(hypot(w.constant[0], w.constant[1]), w.constant[2]);
            continue;
        }
        if (tlsph_lattice_visit(s, b, lo, hi, visit_point, &w) < 0) {
            tlsph_errors_add(err, P, "out of memory for the geometry of body '%s'", body->name);
            bad = 1;
            continue;
        }
        for (int c = 0; c < 3; c++)
            if (w.bad[c].failed) {
                report(err, P, c, w.ex[c], body->name, &w.bad[c], 0);
                bad = 1;
            }
    }
    return bad ? -1 : 0;
}

int tlsph_check_expr_of_time(struct tlsph_expr *ex, const struct tlsph_scene *s, const char *what,
                             const char *pointer, struct tlsph_errors *err)
{
    const double end = s->end_time;
    /* An invalid end time is reported with /time; t = 0 is still checked. */
    const int n = end > 0.0 && isfinite(end) ? TLSPH_TIME_SAMPLES : 0;
    for (int k = 0; k <= n; k++) {
        const double t = n ? end * (double)k / (double)n : 0.0;
        const double v = tlsph_expr_eval(ex, &t);
        if (isfinite(v))
            continue;
        if (ex->constant)
            tlsph_errors_add(err, pointer, "%s '%s' is %s, not a finite number", what,
                             tlsph_expr_text(ex), nonfinite(v));
        else
            tlsph_errors_add(err, pointer,
                             "%s '%s' is %s at t = %g s; it must be finite over [0, end] "
                             "(checked at t = k end / %d, k = 0..%d)",
                             what, tlsph_expr_text(ex), nonfinite(v), t, TLSPH_TIME_SAMPLES,
                             TLSPH_TIME_SAMPLES);
        return -1;
    }
    return 0;
}
