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
 * The reference area vectors N dA_i, once at setup (prepare): the particle's
 * cell face V_i / s, scaled to the scene's "area" when given, along the
 * scene's "normal" or the layer's own fitted normal (core/bc/surface.h says
 * how and why). */
#include "bc/kind.h"
#include "bc/selector.h"
#include "bc/surface.h"
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

/* Setup: the reference area vectors (core/bc/surface.h) and the store for
 * the force of each evaluation. */
static int prepare(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                   const char *pointer, struct tlsph_errors *err)
{
    g->area = tlsph_alloc(m, 3 * g->n, sizeof(double));
    g->load = tlsph_alloc(m, 3 * g->n, sizeof(double));
    if (!g->area || !g->load) {
        tlsph_errors_add(err, pointer, "out of memory");
        return -1;
    }
    const double *normal = bc->params[HAS_NORMAL] != 0.0 ? bc->normal : NULL;
    return tlsph_surface_areas(m, g->index, g->n, normal, bc->params[AREA], g->area, bc->name,
                               pointer, err);
}

static void force(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g, double *power)
{
    (void)power; /* booked kick by kick in constrain */
    const double p = tlsph_expr_eval(&bc->expr[0], &m->t);
    for (size_t a = 0; a < g->n; a++) {
        const size_t i = (size_t)g->index[a];
        const double *F = m->p.F + 9 * i, *N = g->area + 3 * a;
        double *load = g->load + 3 * a, *f = m->p.f + 3 * i;
        /* cof(F) = J F^-T = adj(F)^T */
        double adj[9];
        mat3_adjugate(F, adj);
        for (int c = 0; c < 3; c++) {
            load[c] = -p * (adj[c] * N[0] + adj[3 + c] * N[1] + adj[6 + c] * N[2]);
            f[c] += load[c];
        }
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
