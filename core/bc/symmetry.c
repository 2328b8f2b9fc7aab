/* "symmetry": the selected particles keep zero velocity along the plane's
 * normal (a roller condition; the kernel is not mirrored).  Without a
 * selector, the particles within half a lattice spacing of the plane.  The
 * plane does not move: its impulse does no work. */
#include <math.h>

#include "bc/kind.h"
#include "bc/plane.h"
#include "bc/selector.h"
#include "run/model.h"

static int parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                 const char *pointer, struct tlsph_errors *err)
{
    int bad = tlsph_plane_parse(obj, s, bc, pointer, err) != 0;
    bad |= tlsph_selector_parse(obj, s, bc, pointer, err) != 0;
    return bad ? -1 : 0;
}

static size_t select_on_plane(const struct tlsph_model *m, struct tlsph_bc *bc, int32_t *index)
{
    if (tlsph_selector_given(&bc->select))
        return tlsph_selector_pick(m, &bc->select, index);
    size_t count = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double d = tlsph_plane_distance(bc, m->p.X + 3 * i);
        const double h = tlsph_particle_spacing(m, i);
        if (fabs(d) <= 0.5 * h * (1.0 + 1e-9)) {
            if (index)
                index[count] = (int32_t)i;
            count++;
        }
    }
    return count;
}

static void constrain(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                      double t, double t_mid, double *work)
{
    (void)t, (void)t_mid, (void)work;
    const double *nn = bc->normal;
    for (size_t a = 0; a < g->n; a++) {
        const size_t i = (size_t)g->index[a];
        double *v = m->p.v + 3 * i;
        const double vn = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
        const double mi = m->p.mass[i];
        for (int c = 0; c < 3; c++) {
            g->impulse[c] -= mi * vn * nn[c];
            v[c] -= vn * nn[c];
        }
    }
}

/* v.n = 0: for a plane normal to an axis, that axis' component held at 0.  An
 * oblique plane is taken as holding at 0 every component along which its
 * normal has a share (what the check compares; the projection itself mixes
 * them). */
static enum tlsph_bc_prescription prescribes(struct tlsph_bc *bc, int c, double *value)
{
    if (fabs(bc->normal[c]) < 1e-12)
        return TLSPH_BC_FREE;
    *value = 0.0;
    return TLSPH_BC_CONSTANT;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    TLSPH_KEY_POINT("point", "a point of the symmetry plane"),
    TLSPH_KEY_DIRECTION("normal", "normal of the plane, any non-zero length"),
    TLSPH_BC_SELECT(0, "the particles held on the plane; absent = those within half a lattice "
                       "spacing of it"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "symmetry", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_symmetry = {
    .name = "symmetry",
    .module = "bc:symmetry",
    .carries_load = 0,
    .keys = &table,
    .parse = parse,
    .select = select_on_plane,
    .prescribes = prescribes,
    .constrain = constrain,
};
