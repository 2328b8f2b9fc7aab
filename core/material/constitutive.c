#include "material/constitutive.h"

#include <math.h>
#include <stdint.h>

#include "material/damage/damage.h"
#include "util/mat3.h"
#include "material/material_point.h"
#include "material/step_estimate.h"
#include "material/strength/strength.h"
#include "sph/kinematics.h"
#include "util/parallel.h"

/* The "tangent" hourglass stiffness: once a particle has flowed, its spring
 * uses the uniaxial elasto-plastic tangent E_t = E H / (E + H) (H = d sigma_y /
 * d eps_p at the current state, strain hardening only: the rate term's
 * derivative scales with 1/dt and is no stiffness), as a fraction of E, so the
 * hourglass modes meet the resistance the material itself offers instead of
 * the elastic one that stops a neck from forming.  The fraction never rises
 * again: a spring that stiffened on elastic unloading would push back the
 * hourglass error it let grow during flow with E, releasing energy that was
 * never stored (measured: a 2.4 % energy-balance error on a torn bar when the
 * scale followed each step's flow state). */
static double hourglass_scale(const struct tlsph_material *mat,
                              const struct tlsph_point_state *st, double previous)
{
    if (!(st->eps_p > 0.0))
        return previous;
    struct tlsph_flow fl;
    mat->strength->flow(mat, st->eps_p, st->rate, st->T, &fl);
    const double H = fmax(fl.d_strain, 0.0), E = mat->youngs_modulus;
    return isfinite(H) ? fmin(previous, H / (E + H)) : previous;
}

/* Which of the particle arrays the point updates of one body read and write. */
struct point_arrays {
    int plastic, thermal, damaging, voids, porous;
};

static struct point_arrays point_arrays_of(const struct tlsph_material *mat)
{
    const struct tlsph_damage_model *dm = mat->damage.model;
    return (struct point_arrays){
        .plastic = tlsph_material_is_plastic(mat),
        .thermal = mat->thermal.enabled,
        .damaging = dm != NULL,
        .voids = dm && (dm->fields & TLSPH_DAMAGE_FIELD_VOID_FRACTION),
        .porous = dm && (dm->fields & TLSPH_DAMAGE_FIELD_POROUS),
    };
}

/* The history of a plastic point (damage needs plasticity). */
static inline void load_state(const struct tlsph_particles *p, size_t i, struct point_arrays a,
                              struct tlsph_point_state *st)
{
    st->eps_p = p->eps_p[i];
    for (int c = 0; c < 6; c++)
        st->plastic_strain[c] = p->plastic_strain[6 * i + c];
    st->rate = p->eps_p_rate[i];
    st->yield = p->yield_stress[i];
    st->T = a.thermal ? p->T[i] : 0.0;
    st->damage = a.damaging ? p->damage[i] : 0.0;
    st->damage_init = a.damaging ? p->damage_init[i] : 0.0;
    st->void_fraction = a.voids ? p->void_fraction[i] : 0.0;
    if (a.porous) {
        st->void_fstar = p->void_fstar[i];
        st->void_nucleated = p->void_nucleated[i];
        st->void_shear = p->void_shear[i];
    }
}

static inline void store_damage(struct tlsph_particles *p, size_t i, struct point_arrays a,
                                const struct tlsph_point_state *st)
{
    p->damage[i] = st->damage;
    p->damage_init[i] = st->damage_init;
    if (a.voids)
        p->void_fraction[i] = st->void_fraction;
    if (a.porous) {
        p->void_fstar[i] = st->void_fstar;
        p->void_nucleated[i] = st->void_nucleated;
        p->void_shear[i] = st->void_shear;
    }
}

static inline void store_state(struct tlsph_particles *p, size_t i, struct point_arrays a,
                               const struct tlsph_point_state *st)
{
    p->eps_p[i] = st->eps_p;
    for (int c = 0; c < 6; c++)
        p->plastic_strain[6 * i + c] = st->plastic_strain[c];
    p->eps_p_rate[i] = st->rate;
    p->yield_stress[i] = st->yield;
    if (a.thermal)
        p->T[i] = st->T;
    if (a.damaging)
        store_damage(p, i, a, st);
}

void tlsph_constitutive_init_particle(struct tlsph_model *m, size_t i)
{
    struct tlsph_particles *p = &m->p;
    const struct tlsph_material *mat = &m->scene.materials[m->scene.bodies[p->body[i]].material];
    if (p->T)
        p->T[i] = mat->thermal.enabled ? mat->thermal.initial_temperature : NAN;
    const struct tlsph_damage_model *dm = mat->damage.model;
    if (dm && dm->point_init) {
        struct tlsph_point_state st = {0};
        dm->point_init(mat, &st);
        store_damage(p, i, point_arrays_of(mat), &st);
    }
}

/* The update of every body; with_kinematics: each thread first gathers the
 * kinematics of the particles it then updates (tlsph_kinematics_for), in the
 * same parallel region, so the phase pair costs one region and one barrier
 * instead of two.  Both take the thread's share of each body's range from
 * tlsph_static_share (the split of OpenMP's static loops), and the reductions
 * are those of separate loops, so the results are the same bit for bit. */
static void constitutive_pass(struct tlsph_model *m, double dt, int with_kinematics)
{
    struct tlsph_particles *p = &m->p;
    size_t inverted = 0, failures = 0;
    long long flowing = 0, iterations = 0;
    int64_t first_bad = INT64_MAX, first_failure = INT64_MAX;
    double min_detF = INFINITY, dt_min = INFINITY, cmax = 0.0, plastic_work = 0.0;
    double damage_work = 0.0;

    for (size_t b = 0; b < m->scene.nbodies; b++) {
        const struct tlsph_body *body = &m->scene.bodies[b];
        const struct tlsph_material *mat = &m->scene.materials[body->material];
        const struct point_arrays arrays = point_arrays_of(mat);
        const int plastic = arrays.plastic, damaging = arrays.damaging;
        const double G43 = 4.0 / 3.0 * mat->shear_modulus, rho0 = mat->density;
        const double spacing = body->spacing;
        /* the step estimate (material/step_estimate.h): "tangent" (the default)
         * takes the tangent's wave speed along each principal direction and the
         * viscous damping; "elastic" the elastic P-wave speed alone */
        const int tangent_step = m->scene.step_estimate;
        const int viscous_step = tangent_step && m->scene.viscosity;
        const double beta1 = m->scene.viscosity_linear, beta2 = m->scene.viscosity_quadratic;

        const size_t lo = m->body_begin[b], hi = m->body_end[b];
        /* one region per body: the optional gather, then the update; the
         * loop inside keeps the indentation it had as a `parallel for` */
#pragma omp parallel reduction(+ : inverted, failures, plastic_work, flowing, iterations, damage_work) \
    reduction(min : first_bad, first_failure, min_detF, dt_min) reduction(max : cmax)                 \
    if (hi - lo >= TLSPH_PARALLEL_MIN_ITEMS)
        { /* clang-format off */
        if (with_kinematics)
            tlsph_kinematics_for(m, lo, hi, dt);
        size_t share_lo, share_hi;
        tlsph_static_share(lo, hi, &share_lo, &share_hi);
        /* C = F^T F of SYM3_EIGEN_LANES particles decomposed at once
         * (sym3_eigen_batch: the same bits, ~40 % less time; a failed
         * particle's is computed and not used) */
        double lam[3 * SYM3_EIGEN_LANES], Q[9 * SYM3_EIGEN_LANES];
        for (size_t i = share_lo; i < share_hi; i++) {
            const size_t lane = (i - share_lo) % SYM3_EIGEN_LANES;
            if (lane == 0) {
                const size_t nb = share_hi - i < SYM3_EIGEN_LANES ? share_hi - i : SYM3_EIGEN_LANES;
                double C[9 * SYM3_EIGEN_LANES];
                for (size_t l = 0; l < nb; l++)
                    mat3_mul_at(p->F + 9 * (i + l), p->F + 9 * (i + l), C + 9 * l);
                sym3_eigen_batch((int)nb, C, lam, Q);
            }
            struct tlsph_point_state st = {0}, *sp = NULL;
            if (plastic) {
                load_state(p, i, arrays, &st);
                sp = &st;
            }
            struct tlsph_point_result r;
            tlsph_point_update_eigen(mat, p->F + 9 * i, lam + 3 * lane, Q + 9 * lane, p->e[i], dt,
                                     sp, &r);
            if (plastic) {
                store_state(p, i, arrays, &st);
                if (damaging)
                    damage_work += r.damage_work * p->vol0[i];
                plastic_work += r.plastic_work * p->vol0[i];
                if (p->hg_scale)
                    p->hg_scale[i] = hourglass_scale(mat, &st, p->hg_scale[i]);
                flowing += r.iterations > 0;
                iterations += r.iterations;
                if (!r.converged) {
                    failures++;
                    if (p->id[i] < first_failure)
                        first_failure = p->id[i];
                }
            }

            if (damaging && st.damage >= 1.0) {
                /* failed: no stress, no interaction (kinematics.c, forces.c); its F
                 * is no strain of material any more, so it is not checked, and it
                 * does not limit the step.  The failure phase (failure.c)
                 * releases the stress it carried. */
                continue;
            }
            const double J = r.J;
            if (!(J > 0.0) || !isfinite(J)) {
                inverted++;
                if (p->id[i] < first_bad)
                    first_bad = p->id[i];
            }
            min_detF = fmin(min_detF, J);
            for (int c = 0; c < 6; c++)
                p->sigma[6 * i + c] = r.sigma[c];

            const double *Fd = p->Fdot + 9 * i;
            double power = 0.0;
            for (int a = 0; a < 9; a++)
                power += r.P[a] * Fd[a];
            p->e[i] += 0.5 * dt * power * p->vol0[i] / p->mass[i];

            mat3_mul_bt(r.P, p->Linv + 9 * i, p->P_tilde + 9 * i);

            /* P-wave speed in the current state; the step shrinks with the
             * particle's principal stretch (material/step_estimate.h).  A
             * negative tangent bulk modulus (Mie-Grueneisen far in tension) is a
             * material instability, not a wave speed: the estimate falls back to
             * the shear part only and the stability checks report what follows. */
            const double c = sqrt(fmax(r.K_t + G43, G43) * J / rho0);
            const double *v = p->v + 3 * i;
            const double speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            cmax = fmax(cmax, c);
            /* the particle's own spacing when the body is graded */
            const double h_i = p->spacing ? p->spacing[i] : spacing;
            double dt_i = h_i * (tangent_step ? r.wave_stretch : r.min_stretch) / (c + speed);
            if (viscous_step)
                dt_i *= tlsph_viscous_step_factor(beta1, beta2, p->h[i], p->Fdot + 9 * i,
                                                  r.min_stretch, c);
            dt_min = fmin(dt_min, dt_i);
        }
        } /* clang-format on; the end of the region: the pair's one barrier */
    }
    m->inverted = inverted;
    m->first_inverted_id = inverted ? first_bad : -1;
    m->min_detF = min_detF;
    /* Sticky: the stability check runs every check_every steps, and a point
     * whose return failed in a step between two checks keeps its elastic trial
     * stress for that step; the run must still stop at the next check
     * (measured: an m_gurson block sheared to 3.8 mm passed one such step
     * silently when only the last evaluation counted). */
    if (failures && !m->return_failures)
        m->first_return_failure_id = first_failure;
    m->return_failures += failures;
    m->energy.plastic_work += plastic_work;
    m->energy.damage_work += damage_work;
    m->plastic_point_steps += flowing;
    m->return_iterations += iterations;
    m->dt_cfl = dt_min;
    m->max_wave_speed = cmax;
}

void tlsph_constitutive(struct tlsph_model *m, double dt)
{
    constitutive_pass(m, dt, 0);
}

void tlsph_constitutive_with_kinematics(struct tlsph_model *m, double dt)
{
    constitutive_pass(m, dt, 1);
}
