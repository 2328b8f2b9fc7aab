#include "constitutive.h"

#include <math.h>
#include <stdint.h>

#include "eos/eos.h"
#include "mat3.h"
#include "strength/strength.h"

void tlsph_constitutive(struct tlsph_model *m, double dt)
{
    struct tlsph_particles *p = &m->p;
    size_t inverted = 0;
    int64_t first_bad = INT64_MAX;
    double min_detF = INFINITY, dt_min = INFINITY, cmax = 0.0;

    for (size_t b = 0; b < m->scene.nbodies; b++) {
        const struct tlsph_body *body = &m->scene.bodies[b];
        const struct tlsph_material *mat = &m->scene.materials[body->material];
        const struct tlsph_eos_model *eos = mat->eos;
        const struct tlsph_strength_model *str = mat->strength;
        const double G43 = 4.0 / 3.0 * mat->shear_modulus, rho0 = mat->density;
        const double spacing = body->spacing;

#pragma omp parallel for schedule(static) reduction(+ : inverted) reduction(min : first_bad,     \
                                                                                min_detF, dt_min) \
    reduction(max : cmax)
        for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++) {
            const double *F = p->F + 9 * i;
            const double J = mat3_det(F);
            if (!(J > 0.0) || !isfinite(J)) {
                inverted++;
                if (p->id[i] < first_bad)
                    first_bad = p->id[i];
            }
            min_detF = fmin(min_detF, J);

            double C[9], lam[3], Q[9];
            mat3_mul_at(F, F, C);
            sym3_eigen(C, lam, Q);
            double lns[3], sinv[3], smin = INFINITY;
            for (int a = 0; a < 3; a++) {
                const double s = sqrt(lam[a]);
                lns[a] = log(s);
                sinv[a] = 1.0 / s;
                smin = fmin(smin, s);
            }
            const double lnJ = lns[0] + lns[1] + lns[2];
            const double dev[3] = {lns[0] - lnJ / 3.0, lns[1] - lnJ / 3.0, lns[2] - lnJ / 3.0};
            double eps_dev[6], tau[6], Uinv6[6];
            sym3_compose(Q, dev, eps_dev);
            sym3_compose(Q, sinv, Uinv6);
            str->deviatoric(mat, eps_dev, tau);

            double pressure, K_t;
            eos->pressure(mat, J, p->e[i], &pressure, &K_t);
            const double Jp = J * pressure;
            tau[0] -= Jp;
            tau[3] -= Jp;
            tau[5] -= Jp;

            double T[9], Ui[9], A[9], S[9], P[9];
            sym6_to_mat3(tau, T);
            sym6_to_mat3(Uinv6, Ui);
            mat3_mul(Ui, T, A);
            mat3_mul(A, Ui, S);
            mat3_mul(F, S, P);

            double sig[9];
            mat3_mul_bt(P, F, sig);
            const double rJ = 1.0 / J;
            double *sg = p->sigma + 6 * i;
            sg[0] = sig[0] * rJ;
            sg[1] = 0.5 * (sig[1] + sig[3]) * rJ;
            sg[2] = 0.5 * (sig[2] + sig[6]) * rJ;
            sg[3] = sig[4] * rJ;
            sg[4] = 0.5 * (sig[5] + sig[7]) * rJ;
            sg[5] = sig[8] * rJ;

            const double *Fd = p->Fdot + 9 * i;
            double power = 0.0;
            for (int a = 0; a < 9; a++)
                power += P[a] * Fd[a];
            p->e[i] += 0.5 * dt * power * p->vol0[i] / p->mass[i];

            mat3_mul_bt(P, p->Linv + 9 * i, p->P_tilde + 9 * i);

            /* P-wave speed in the current state; the step shrinks with the
             * particle's smallest principal stretch.  A negative tangent bulk
             * modulus (Mie-Grueneisen far in tension) is a material instability,
             * not a wave speed: the estimate falls back to the shear part only
             * and the stability checks report what follows. */
            const double c = sqrt(fmax(K_t + G43, G43) * J / rho0);
            const double *v = p->v + 3 * i;
            const double speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            cmax = fmax(cmax, c);
            dt_min = fmin(dt_min, spacing * smin / (c + speed));
        }
    }
    m->inverted = inverted;
    m->first_inverted_id = inverted ? first_bad : -1;
    m->min_detF = min_detF;
    m->dt_cfl = dt_min;
    m->max_wave_speed = cmax;
}
