/* "pressure": a pressure p(t) (Pa, a number or an expression of t) on a
 * surface of a body, given as the particles of its outermost layer (the
 * selector).  It pushes into the body: each particle i gets the force
 *
 *     f_i = -p(t) n da_i,   n da_i = J F_i^-T N dA_i = cof(F_i) N dA_i   (Nanson)
 *
 * with N dA_i the particle's reference area vector (outward) and F_i its
 * deformation gradient of the current evaluation, so the load follows the
 * surface as it rotates, stretches and thins.  A negative p pulls (suction).
 *
 * Work: each half kick v_b = v_a + (dt/2) F/m changes the kinetic energy by
 * exactly (dt/2) f . (v_a + v_b) / 2 for each force f of that kick, so the
 * constrain hook (after every half kick) books that for the pressure force of
 * the kick, kept from the force hook.  The power at the half-step velocities
 * (a body force's booking) lags a ramped load by half a step: with p(0) = 0
 * its first step books no work for kinetic energy that is already there, and
 * the balance starts at 100 % of its scale.
 *
 * The reference area vectors, once at setup (prepare):
 *  - magnitude dA_i = V_i / s, V_i the particle's reference volume and s its
 *    body's spacing: the particle's cell face.  On a lattice face every
 *    particle holds s^2 (s in 2-D) and a face of n x m cells sums to its area
 *    exactly; on conforming shells V_i / s is the arc (times dz) at the
 *    particle's middle radius, half a spacing off the surface (the relative
 *    error on a curved face is s / 2R), which the optional "area" corrects:
 *    the magnitudes are scaled so that they sum to the surface's true area.
 *  - direction: the scene's "normal" (a flat face), or each particle's own
 *    outward normal: the normal of the plane (line in 2-D) fitted through the
 *    selected particles within its support (the smallest principal direction
 *    of their scatter about their centroid), refined by a quadric through the
 *    particle (quadric_normal: a one-sided patch of a curved surface tilts the
 *    plane), oriented outwards by the colour gradient
 *    c_i = sum_j V_j |W'| (X_i - X_j) / |X_i - X_j|, which points away from
 *    the body's particles.  The fit is exact on a flat face up to its edges
 *    and corners (where the colour gradient alone tilts by 45 degrees and the
 *    load would lose 1 - cos 45 of its share), radial on conforming shells,
 *    and within 1e-4 rad of radial at the ends of a loaded cylinder wall (the
 *    plane alone: 0.05 rad); where the fit is undetermined (a lone particle, a
 *    single row in 3-D) the colour gradient's direction is used.
 * A selected particle whose colour gradient vanishes (its neighbours surround
 * it: not on the surface) is refused, and so is a "normal" that points into
 * the body (against the colour gradient summed over the group). */
#include <math.h>
#include <stdlib.h>

#include "bc/kind.h"
#include "bc/selector.h"
#include "run/model.h"
#include "scene/parse_internal.h"
#include "util/mat3.h"

/* Where the numbers live in struct tlsph_bc (scene.h): the normal in
 * bc->normal, these two in bc->params. */
#define HAS_NORMAL 6 /* 1: bc->normal is the outward normal of every particle */
#define AREA       7 /* the surface's reference area (m^2, m in 2-D); 0: sum of V_i / s */

static const char *const tvar[] = {"t"};

static int parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc, const char *P,
                 struct tlsph_errors *err)
{
    int bad = tlsph_selector_parse(obj, s, bc, P, err) != 0;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "pressure");
    const json_t *v = json_object_get(obj, "pressure");
    if (!v) {
        tlsph_errors_add(err, p,
                         "required field 'pressure' (Pa: a number or an expression of t) "
                         "is missing");
        bad = 1;
    } else if (!json_is_number(v) && !json_is_string(v)) {
        tlsph_errors_add(err, p,
                         "'pressure' must be a number (Pa) or an expression string of t (s) "
                         "giving Pa, got %s",
                         jc_type_name(v));
        bad = 1;
    } else if (tlsph_scene_expr(&bc->expr[0], v, tvar, 1, 0, s, p, err) != 0 ||
               tlsph_check_expr_of_time(&bc->expr[0], s, "pressure", p, err) != 0) {
        bad = 1;
    }
    bc->params[HAS_NORMAL] = 0.0;
    if (json_object_get(obj, "normal")) {
        double n[3];
        if (tlsph_parse_direction(obj, "normal", s->dimension, P, n, err) != 0) {
            bad = 1;
        } else {
            for (int c = 0; c < 3; c++)
                bc->normal[c] = n[c];
            bc->params[HAS_NORMAL] = 1.0;
        }
    }
    double area = 0.0;
    if (jc_number(obj, "area", 0, JC_POSITIVE, s->dimension == 2 ? "m" : "m^2", P, &area, err) < 0)
        bad = 1;
    bc->params[AREA] = area;
    return bad ? -1 : 0;
}

/* Outward colour gradient of particle i: away from its neighbours, 1/m. */
static void colour_gradient(const struct tlsph_model *m, size_t i, double c[3])
{
    const double *Xi = m->p.X + 3 * i;
    c[0] = c[1] = c[2] = 0.0;
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        const double *Xj = m->p.X + 3 * j;
        /* dw = W'/r < 0: -dw (Xi - Xj) points from j to i */
        const double w = -m->pairs.dw[k] * m->p.vol0[j];
        for (int d = 0; d < 3; d++)
            c[d] += w * (Xi[d] - Xj[d]);
    }
}

/* Refines n, the normal of the plane fitted at particle i (tangents t1, t2;
 * t2 unused in 2-D), to the surface's normal at i: the least-squares quadric
 * through i,  w = c1 u + c2 v + c3 u^2 + c4 u v + c5 v^2  (2-D: c1 u + c3 u^2),
 * over the group's particles in i's support, (u, v, w) their offsets from i
 * along t1, t2, n in spacings; then n ~ n - c1 t1 - c2 t2.  A plane through a
 * one-sided patch of a curved surface (near the edge of the loaded region)
 * tilts with the sag it cannot follow; the quadric follows it.  On a flat
 * face w = 0 and n stays.  Leaves n when the system is singular. */
static void quadric_normal(const struct tlsph_model *m, size_t i, const unsigned char *mark,
                           const double t1[3], const double t2[3], double n[3])
{
    const int nb = m->dim == 2 ? 2 : 5;
    double M[5][6] = {{0}}; /* normal equations, the right-hand side in column 5 */
    const double *X = m->p.X;
    const double s = m->scene.bodies[m->p.body[i]].spacing;
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        if (!mark[j])
            continue;
        double d[3];
        for (int c = 0; c < 3; c++)
            d[c] = (X[3 * j + c] - X[3 * i + c]) / s;
        const double u = d[0] * t1[0] + d[1] * t1[1] + d[2] * t1[2];
        const double v = nb == 5 ? d[0] * t2[0] + d[1] * t2[1] + d[2] * t2[2] : 0.0;
        const double w = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        const double phi2[2] = {u, u * u}, phi5[5] = {u, v, u * u, u * v, v * v};
        const double *phi = nb == 5 ? phi5 : phi2;
        for (int a = 0; a < nb; a++) {
            for (int b = 0; b < nb; b++)
                M[a][b] += phi[a] * phi[b];
            M[a][5] += phi[a] * w;
        }
    }
    double big = 0.0;
    for (int a = 0; a < nb; a++)
        big = fmax(big, M[a][a]);
    for (int col = 0; col < nb; col++) { /* Gauss-Jordan, partial pivoting */
        int piv = col;
        for (int r = col + 1; r < nb; r++)
            if (fabs(M[r][col]) > fabs(M[piv][col]))
                piv = r;
        if (!(fabs(M[piv][col]) > 1e-9 * big))
            return;
        for (int c = 0; c < 6; c++) {
            const double tmp = M[col][c];
            M[col][c] = M[piv][c];
            M[piv][c] = tmp;
        }
        for (int r = 0; r < nb; r++) {
            if (r == col)
                continue;
            const double f = M[r][col] / M[col][col];
            for (int c = col; c < 6; c++)
                M[r][c] -= f * M[col][c];
        }
    }
    const double c1 = M[0][5] / M[0][0], c2 = nb == 5 ? M[1][5] / M[1][1] : 0.0;
    double len = 0.0;
    for (int c = 0; c < 3; c++) {
        n[c] -= c1 * t1[c] + c2 * (nb == 5 ? t2[c] : 0.0);
        len += n[c] * n[c];
    }
    len = sqrt(len);
    for (int c = 0; c < 3; c++)
        n[c] /= len;
}

/* Unit normal of the surface through the group's particles in i's support
 * (mark[j]: j is in the group), i included, into n: the normal of their
 * plane (2-D: line), refined by quadric_normal; 0, or -1 when undetermined. */
static int fitted_normal(const struct tlsph_model *m, size_t i, const unsigned char *mark,
                         double n[3])
{
    const int64_t k0 = m->pairs.start[i], k1 = m->pairs.start[i + 1];
    const double *X = m->p.X;
    double cen[3] = {X[3 * i], X[3 * i + 1], X[3 * i + 2]};
    size_t count = 1;
    for (int64_t k = k0; k < k1; k++)
        if (mark[m->pairs.j[k]]) {
            for (int d = 0; d < 3; d++)
                cen[d] += X[3 * (size_t)m->pairs.j[k] + d];
            count++;
        }
    for (int d = 0; d < 3; d++)
        cen[d] /= (double)count;
    /* the scatter about the centroid, i's own term first */
    double C[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            C[3 * a + b] = (X[3 * i + a] - cen[a]) * (X[3 * i + b] - cen[b]);
    for (int64_t k = k0; k < k1; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        if (!mark[j])
            continue;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                C[3 * a + b] += (X[3 * j + a] - cen[a]) * (X[3 * j + b] - cen[b]);
    }
    if (m->dim == 2) /* the normal lies in the x-y plane: z is never the smallest */
        C[8] = 2.0 * (C[0] + C[4]);
    double lam[3], Q[9];
    sym3_eigen(C, lam, Q);
    int lo = 0;
    for (int k = 1; k < 3; k++)
        if (lam[k] < lam[lo])
            lo = k;
    /* the next smallest, mi: the surface's spread along it (in 2-D the
     * in-plane tangent); hi the third */
    const int mi = lam[(lo + 1) % 3] <= lam[(lo + 2) % 3] ? (lo + 1) % 3 : (lo + 2) % 3;
    const int hi = 3 - lo - mi;
    /* a plane needs spread in d - 1 directions, well above the sag across it */
    if (!(lam[mi] > 0.0) || lam[lo] > 0.25 * lam[mi])
        return -1;
    double t1[3], t2[3];
    for (int d = 0; d < 3; d++) {
        n[d] = Q[3 * d + lo];
        t1[d] = Q[3 * d + mi];
        t2[d] = Q[3 * d + hi];
    }
    quadric_normal(m, i, mark, t1, t2, n);
    return 0;
}

static int prepare(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                   const char *pointer, struct tlsph_errors *err)
{
    g->area = tlsph_alloc(m, 3 * g->n, sizeof(double));
    g->load = tlsph_alloc(m, 3 * g->n, sizeof(double));
    unsigned char *mark = calloc(m->p.n, 1);
    if (!g->area || !g->load || !mark) {
        free(mark);
        tlsph_errors_add(err, pointer, "out of memory");
        return -1;
    }
    for (size_t a = 0; a < g->n; a++)
        mark[g->index[a]] = 1;
    const int given = bc->params[HAS_NORMAL] != 0.0;
    double outward = 0.0, sum = 0.0;
    int rc = 0;
    for (size_t a = 0; a < g->n && rc == 0; a++) {
        const size_t i = (size_t)g->index[a];
        double c[3], n[3];
        colour_gradient(m, i, c);
        const double cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const double s = m->scene.bodies[m->p.body[i]].spacing;
        /* interior particles: c is round-off of a sum of terms ~ 1/s */
        if (!(cn * s > 1e-6)) {
            tlsph_errors_add(err, pointer,
                             "boundary condition '%s' selects particle %lld at (%g, %g, %g) m, "
                             "which is not on the surface of its body (its neighbours surround "
                             "it): select only the loaded surface's outermost layer",
                             bc->name, (long long)m->p.id[i], m->p.X[3 * i], m->p.X[3 * i + 1],
                             m->p.X[3 * i + 2]);
            rc = -1;
            break;
        }
        if (given) {
            for (int d = 0; d < 3; d++)
                n[d] = bc->normal[d];
            outward += (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / cn;
        } else if (fitted_normal(m, i, mark, n) == 0) {
            if (n[0] * c[0] + n[1] * c[1] + n[2] * c[2] < 0.0)
                for (int d = 0; d < 3; d++)
                    n[d] = -n[d];
        } else {
            for (int d = 0; d < 3; d++)
                n[d] = c[d] / cn;
        }
        const double dA = m->p.vol0[i] / s;
        for (int d = 0; d < 3; d++)
            g->area[3 * a + d] = dA * n[d];
        sum += dA;
    }
    free(mark);
    if (rc != 0)
        return rc;
    if (given && !(outward > 0.0)) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_join(q, sizeof q, pointer, "normal");
        tlsph_errors_add(err, q,
                         "boundary condition '%s': 'normal' (%g, %g, %g) points into the body "
                         "at the selected particles; give the loaded surface's outward normal "
                         "(a positive pressure pushes against it, into the body)",
                         bc->name, bc->normal[0], bc->normal[1], bc->normal[2]);
        return -1;
    }
    if (bc->params[AREA] > 0.0) {
        const double scale = bc->params[AREA] / sum;
        for (size_t k = 0; k < 3 * g->n; k++)
            g->area[k] *= scale;
    }
    return 0;
}

static void force(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g, double *power)
{
    (void)power; /* booked kick by kick in constrain */
    const double p = tlsph_expr_eval(&bc->expr[0], &m->t);
    for (size_t a = 0; a < g->n; a++) {
        const size_t i = (size_t)g->index[a];
        const double *F = m->p.F + 9 * i, *N = g->area + 3 * a;
        double *load = g->load + 3 * a, *f = m->p.f + 3 * i;
        /* cof(F) = J F^-T, row by row: the current area vector without 1 / J */
        load[0] = -p * ((F[4] * F[8] - F[5] * F[7]) * N[0] + (F[5] * F[6] - F[3] * F[8]) * N[1] +
                        (F[3] * F[7] - F[4] * F[6]) * N[2]);
        load[1] = -p * ((F[2] * F[7] - F[1] * F[8]) * N[0] + (F[0] * F[8] - F[2] * F[6]) * N[1] +
                        (F[1] * F[6] - F[0] * F[7]) * N[2]);
        load[2] = -p * ((F[1] * F[5] - F[2] * F[4]) * N[0] + (F[2] * F[3] - F[0] * F[5]) * N[1] +
                        (F[0] * F[4] - F[1] * F[3]) * N[2]);
        for (int c = 0; c < 3; c++)
            f[c] += load[c];
    }
}

/* After a half kick of m->dt / 2 (0 at setup) with the forces m->p.f: the
 * pressure's work over it, at the mean velocity of the kick. */
static void constrain(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g, double t,
                      double t_mid, double *work)
{
    (void)bc, (void)t, (void)t_mid;
    const double half = 0.5 * m->dt;
    double w = *work; /* a local: nothing stored here can alias it */
    for (size_t a = 0; a < g->n; a++) {
        const size_t i = (size_t)g->index[a];
        const double *load = g->load + 3 * a, *v = m->p.v + 3 * i, *f = m->p.f + 3 * i;
        const double back = 0.5 * half / m->p.mass[i]; /* v_b - mean = (dt/4) F / m */
        w += half * (load[0] * (v[0] - back * f[0]) + load[1] * (v[1] - back * f[1]) +
                     load[2] * (v[2] - back * f[2]));
    }
    *work = w;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    TLSPH_BC_SELECT(TLSPH_KEY_REQUIRED, "the loaded surface's outermost particle layer"),
    {.name = "pressure", .kind = TLSPH_KEY_EXPRESSION,
     .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER, .unit = "Pa",
     .description = "a number or an expression of t (s); positive pushes into the body"},
    {.name = "normal", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER, .unit = "1",
     .description = "outward normal of a flat loaded face, any non-zero length; absent = each "
                    "particle's own, fitted"},
    {.name = "area", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_CALLER,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m^2",
     .description = "reference area of the loaded surface (m per metre of thickness in 2-D); "
                    "absent = the sum of the particles' volume / spacing"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "pressure", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_pressure = {
    .name = "pressure",
    .module = "bc:pressure",
    .carries_load = 0,
    .keys = &table,
    .parse = parse,
    .select = tlsph_selector_select,
    .prepare = prepare,
    .constrain = constrain,
    .force = force,
};
