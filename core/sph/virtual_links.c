/* Virtual links (paper 001 §3): the immediate-neighbour support, the links'
 * state and its row in the table of crack treatments.  The equations and the
 * choices are in virtual_links.h; the criteria in link_*.c. */
#include "sph/virtual_links.h"

#include <stdlib.h>
#include <string.h>

#include "sph/link_criterion.h"
#include "util/mat3.h"

/* Local spacing s_i = V_i^(1/d), m. */
static double local_spacing(const struct tlsph_model *m, size_t i)
{
    return m->dim == 2 ? sqrt(m->p.vol0[i]) : cbrt(m->p.vol0[i]);
}

/* Keeps the immediate neighbours of every particle (virtual_links.h), in
 * place.  The test is symmetric in i, j to the bit (the same squares and the
 * same sum either way), so the list stays symmetric. */
static void restrict_support(struct tlsph_model *m)
{
    const double *X = m->p.X;
    int64_t *start = m->pairs.start;
    int32_t *nbr = m->pairs.j;
    int64_t out = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        const int64_t lo = start[i], hi = start[i + 1];
        start[i] = out;
        const double si = local_spacing(m, i);
        for (int64_t k = lo; k < hi; k++) {
            const size_t j = (size_t)nbr[k];
            double r2 = 0.0;
            for (int a = 0; a < 3; a++)
                r2 += (X[3 * j + a] - X[3 * i + a]) * (X[3 * j + a] - X[3 * i + a]);
            const double reach = m->scene.links.reach * 0.5 * (si + local_spacing(m, j));
            if (r2 < reach * reach)
                nbr[out++] = (int32_t)j;
        }
    }
    const size_t dropped = m->pairs.npairs - (size_t)out;
    start[m->p.n] = out;
    m->pairs.npairs = (size_t)out;
    m->bytes_allocated -= dropped * sizeof(int32_t); /* the tail stays allocated, unused */
}

static void release(struct tlsph_model *m)
{
    if (!m->links)
        return;
    free(m->links->D);
    free(m->links->D_prev);
    free(m->links->mirror);
    free(m->links);
    m->links = NULL;
}

static int setup(struct tlsph_model *m, struct tlsph_errors *err)
{
    restrict_support(m);
    const size_t np = m->pairs.npairs;
    struct tlsph_links *L = tlsph_alloc(m, 1, sizeof *L);
    if (!L) {
        tlsph_errors_add(err, "", "out of memory for the virtual links");
        return -1;
    }
    m->links = L;
    L->D = tlsph_alloc(m, np, sizeof *L->D);
    L->D_prev = tlsph_alloc(m, np, sizeof *L->D_prev);
    L->mirror = tlsph_alloc(m, np, sizeof *L->mirror);
    if (!L->D || !L->D_prev || !L->mirror) {
        tlsph_errors_add(err, "", "out of memory for %zu virtual links", np);
        return -1;
    }
    const int64_t *start = m->pairs.start;
    const int32_t *nbr = m->pairs.j;
    for (size_t i = 0; i < m->p.n; i++)
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const size_t j = (size_t)nbr[k];
            L->D[k] = 0.0;
            L->mirror[k] = -1;
            for (int64_t q = start[j]; q < start[j + 1]; q++)
                if ((size_t)nbr[q] == i)
                    L->mirror[k] = q;
            if (L->mirror[k] < 0) { /* the pair list is symmetric by construction */
                tlsph_errors_add(err, "", "virtual links: pair %zu-%zu has no mirror", i, j);
                return -1;
            }
        }
    return 0;
}

/* The second half of this step's internal-energy update with the links' new
 * state (virtual_links.h): e_i loses dt/2 V_i/m_i sum_j (D_ij - D_ij,prev)
 * V_j dw_ij P~_i : (v_j - v_i) (x) (X_j - X_i), the part of P_i : Fdot_i the
 * grown damage no longer transmits.  Per particle, so each thread writes its
 * own e_i; the branch skips the links that did not change. */
static void rebook_half_step(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
    const int64_t *restrict start = m->pairs.start;
    const int32_t *restrict nbr = m->pairs.j;
    const double *restrict dw = m->pairs.dw, *restrict vol0 = m->p.vol0;
    const double *restrict D = m->links->D, *restrict D0 = m->links->D_prev;
    const double *restrict X = m->p.X, *restrict v = m->p.v, *restrict Pt = m->p.P_tilde;
    double *restrict e = m->p.e;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        double lost = 0.0;
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const double dD = D[k] - D0[k];
            if (dD == 0.0)
                continue;
            const size_t j = (size_t)nbr[k];
            const double s = dD * vol0[j] * dw[k];
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    lost += s * Pt[9 * i + 3 * a + b] * (v[3 * j + a] - v[3 * i + a]) *
                            (X[3 * j + b] - X[3 * i + b]);
        }
        e[i] -= 0.5 * dt * lost * vol0[i] / m->p.mass[i];
    }
}

static void update(struct tlsph_model *m)
{
    struct tlsph_links *L = m->links;
    memcpy(L->D_prev, L->D, m->pairs.npairs * sizeof *L->D);
    L->broken = m->scene.links.criterion->update(m);
    /* m->dt is this step's (0 at the start, where no half step was booked) */
    if (m->dt > 0.0)
        rebook_half_step(m, m->dt);
}

void tlsph_virtual_links_particle_damage(const struct tlsph_model *m, double *out)
{
    const int64_t *start = m->pairs.start;
    for (size_t i = 0; i < m->p.n; i++) {
        double sum = 0.0;
        for (int64_t k = start[i]; k < start[i + 1]; k++)
            sum += m->links->D[k];
        const int64_t n = start[i + 1] - start[i];
        out[i] = n > 0 ? sum / (double)n : 0.0;
    }
}

double tlsph_link_impedance(const struct tlsph_model *m, size_t i)
{
    const struct tlsph_material *mat =
        &m->scene.materials[m->scene.bodies[m->p.body[i]].material];
    const double J = mat3_det(m->p.F + 9 * i);
    return sqrt(mat->youngs_modulus * mat->density / (J > 0.0 ? J : 1.0));
}

const struct tlsph_crack_model tlsph_crack_virtual_links = {
    .name = "virtual_links",
    .module = "approximation:virtual_links",
    .scene = TLSPH_CRACK_VIRTUAL_LINKS,
    .variant = TLSPH_APPROX_VIRTUAL_LINKS,
    .fields = TLSPH_CRACK_FIELD_GRADIENT, /* F's history: what the links no longer transmit */
    .setup = setup,
    .update = update,
    .release = release,
};
