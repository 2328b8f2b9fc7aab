/* How long a scene's run is, estimated before any particle exists.
 *
 * The engine's step is dt = cfl x min_i spacing_i s_min,i / (c_i + |v_i|)
 * (core/material/constitutive.c), or the fixed time.step.  At t = 0 every
 * particle is unstrained (s_min = 1, J = 1, e = 0), so the first step is known
 * from the scene alone: c_b is the P-wave speed of body b's material at its
 * reference state (the EOS's tangent bulk modulus at J = 1 plus 4G/3, over
 * rho0) and |v| its fastest initial speed (check_values.c); with viscosity and
 * the "tangent" estimate the step has the damping factor of its linear term
 * (material/step_estimate.h; the quadratic term needs a rate of F, zero here).
 * The run needs about end / dt steps; validation refuses a scene that needs more than
 * TLSPH_MAX_STEPS (scene/limits.h) and has no time.max_steps to end it sooner.
 * With contact the engine also keeps the step below sqrt(m* / k) of every
 * pair in contact (core/contact/forces.c); the estimate includes the stiffest
 * contact the run may see (core/contact/estimate.c), so a stiff law (a
 * pin-ball with a large K_p) is counted before the run.
 * The step changes as the bodies deform, so this is an estimate: the run
 * itself stops when its own projection passes the limit (core/run/stability.c).
 *
 * Two more things the first step decides:
 *   - a body that starts faster than the stability contract's speed limit
 *     (stability.speed_limit x the largest wave speed) would be stopped at the
 *     first check, so it is refused now;
 *   - a fixed step longer than the frame interval end / frames would pass frame
 *     times without writing them (docs/output.md: a step never spans more than
 *     one frame time; a CFL step is shortened for that, a fixed one is not). */
#include <math.h>
#include <stdlib.h>

#include "contact/contact.h"
#include "material/eos/eos.h"
#include "material/step_estimate.h"
#include "scene/parse_internal.h"

double tlsph_reference_wave_speed(const struct tlsph_material *m)
{
    double p, K_t;
    m->eos->pressure(m, 1.0, 0.0, &p, &K_t);
    const double G43 = 4.0 / 3.0 * m->shear_modulus;
    return sqrt(fmax(K_t + G43, G43) / m->density); /* as the engine's, at J = 1 */
}

static int check_speeds(const struct tlsph_scene *s, const struct tlsph_initial_speed *fastest,
                        struct tlsph_errors *err)
{
    double cmax = 0.0;
    for (size_t b = 0; b < s->nbodies; b++)
        cmax = fmax(cmax, tlsph_reference_wave_speed(&s->materials[s->bodies[b].material]));
    const double limit = s->speed_limit_factor * cmax;
    int bad = 0;
    for (size_t b = 0; b < s->nbodies; b++) {
        const struct tlsph_initial_speed *f = &fastest[b];
        if (!(f->speed > limit))
            continue;
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_index(p, sizeof p, "/bodies", b);
        tlsph_key_error(err, p, "initial_velocity",
                        "body '%s' starts at %g m/s (at x = %g, y = %g, z = %g m), above the "
                        "stability contract's speed limit of %g m/s (/stability/speed_limit %g "
                        "x the largest wave speed %g m/s): the run would stop at its first "
                        "check",
                        s->bodies[b].name, f->speed, f->X[0], f->X[1], f->X[2], limit,
                        s->speed_limit_factor, cmax);
        bad = 1;
    }
    return bad ? -1 : 0;
}

int tlsph_check_steps(struct tlsph_scene *s, const struct tlsph_initial_speed *fastest,
                      struct tlsph_errors *err)
{
    if (check_speeds(s, fastest, err) != 0)
        return -1;
    const double end = s->end_time, frame_interval = end / (double)s->frames;
    if (s->fixed_dt > 0.0 && s->fixed_dt > frame_interval * (1.0 + 1e-12)) {
        tlsph_errors_add(err, "/time/step",
                         "'step' = %g s is longer than the frame interval /time/end / "
                         "/output/frames = %g s, so frames would be skipped: use a step of at "
                         "most %g s, or at most %.0f frames",
                         s->fixed_dt, frame_interval, frame_interval, floor(end / s->fixed_dt));
        return -1;
    }
    /* The first step, and the body that limits it. */
    size_t limiting = 0;
    double dt_cfl = INFINITY, c_limiting = 0.0;
    for (size_t b = 0; b < s->nbodies; b++) {
        const double c = tlsph_reference_wave_speed(&s->materials[s->bodies[b].material]);
        /* a graded body's step is set by its finest particles */
        double dt_b = tlsph_graded_finest(&s->bodies[b]) / (c + fastest[b].speed);
        if (s->step_estimate && s->viscosity)
            dt_b *= tlsph_damped_step_factor(TLSPH_VISCOUS_XI * s->viscosity_linear);
        if (dt_b < dt_cfl) {
            dt_cfl = dt_b;
            limiting = b;
            c_limiting = c;
        }
    }
    size_t pair[2] = {0, 0};
    const double dt_contact = tlsph_contact_step_estimate(s, pair);
    const int contact_limits = dt_contact < dt_cfl;
    if (contact_limits)
        dt_cfl = dt_contact;
    const double dt = s->fixed_dt > 0.0 ? s->fixed_dt : s->cfl * dt_cfl;
    /* A step longer than the frame interval ends at the next frame time instead. */
    const double steps = end / fmin(dt, frame_interval);
    s->estimated_dt = dt;
    s->estimated_steps = s->max_steps > 0 ? fmin(steps, (double)s->max_steps) : steps;
    if (s->max_steps > 0 || (dt > 0.0 && steps <= (double)TLSPH_MAX_STEPS))
        return 0;
    if (s->fixed_dt > 0.0) {
        tlsph_errors_add(err, "/time/end",
                         "'end' = %g s needs %.3g time steps of the fixed step %g s "
                         "(/time/step), above the limit of %ld steps; shorten the end time, "
                         "lengthen the step, or set /time/max_steps to end the run sooner",
                         end, steps, dt, TLSPH_MAX_STEPS);
        return -1;
    }
    if (contact_limits) {
        tlsph_errors_add(err, "/time/end",
                         "'end' = %g s needs about %.3g time steps of about %g s, above the limit "
                         "of %ld steps: the step is /time/cfl %g x the contact step %g s between "
                         "bodies '%s' and '%s' (sqrt(m*/k) of two particles at the deepest overlap "
                         "the stability contract accepts; /contact/law: a softer law or a smaller "
                         "scale factor lengthens it); shorten the end time, or set "
                         "/time/max_steps to end the run sooner",
                         end, steps, dt, TLSPH_MAX_STEPS, s->cfl, dt_contact,
                         s->bodies[pair[0]].name, s->bodies[pair[1]].name);
        return -1;
    }
    const struct tlsph_body *body = &s->bodies[limiting];
    const struct tlsph_material *mat = &s->materials[body->material];
    char mp[TLSPH_POINTER_MAX];
    tlsph_pointer_join(mp, sizeof mp, "/materials", mat->name);
    tlsph_errors_add(err, "/time/end",
                     "'end' = %g s needs about %.3g time steps of about %g s, above the limit "
                     "of %ld steps: the step is /time/cfl %g x the spacing %g m of body '%s' "
                     "(/bodies/%zu/spacing) / (the wave speed %g m/s of material '%s' (%s: "
                     "density, youngs_modulus, poisson_ratio, eos) + its initial speed %g m/s); "
                     "shorten the end time, raise cfl or the spacing, or set /time/max_steps to "
                     "end the run sooner",
                     end, steps, dt, TLSPH_MAX_STEPS, s->cfl, body->spacing, body->name, limiting,
                     c_limiting, mat->name, mp, fastest[limiting].speed);
    return -1;
}

int tlsph_check_run_start(struct tlsph_scene *s, struct tlsph_errors *err)
{
    struct tlsph_initial_speed *fastest = calloc(s->nbodies, sizeof *fastest);
    if (!fastest) {
        tlsph_errors_add(err, "/bodies", "out of memory");
        return -1;
    }
    int rc = tlsph_check_initial_velocities(s, fastest, err);
    if (rc == 0)
        rc = tlsph_check_steps(s, fastest, err);
    free(fastest);
    return rc;
}
