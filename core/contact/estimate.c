/* The contact step in the validation's first-step estimate (contact.h),
 * before any particle exists.
 *
 * The engine lowers each evaluation's step to sqrt(m* / k) over the pairs in
 * contact (forces.c), k the law's tangent stiffness at the pair's overlap.
 * Before the run the overlaps are unknown, so the estimate takes the stiffest
 * contact the run may see: for every pair of bodies that can meet (different
 * bodies; a body with itself when its material damages or has virtual links), two of their
 * particles (mass rho V0, V0 = spacing^d, per metre in 2-D) at the deepest
 * overlap the stability contract accepts, TLSPH_CONTACT_MAX_OVERLAP x
 * (R_a + R_b), or at the overlap two touching lattice cells already have when
 * the law's radii exceed half the spacings, whichever is deeper.  For the
 * penalty law's line form k does not depend on the overlap and the estimate
 * is the engine's step while bodies touch; for the point form and the
 * pin-ball (k ~ overlap^(1/2)) it is a lower bound, reached only by a contact
 * as deep as the contract allows. */
#include <math.h>
#include <stdlib.h>

#include "contact/penalty.h"
#include "contact/pinball.h"
#include "scene/limits.h"

static double particle_mass(const struct tlsph_scene *s, size_t b)
{
    const struct tlsph_body *bd = &s->bodies[b];
    const double v0 = s->dimension == 3 ? bd->spacing * bd->spacing * bd->spacing
                                        : bd->spacing * bd->spacing; /* x 1 m */
    return s->materials[bd->material].density * v0;
}

double tlsph_contact_step_estimate(const struct tlsph_scene *s, size_t pair[2])
{
    const struct tlsph_contact_law *law = s->contact.law;
    if (!law || s->nbodies == 0)
        return INFINITY;
    struct tlsph_contact_body *cb = calloc(s->nbodies, sizeof *cb);
    if (!cb)
        return INFINITY; /* an estimate only: the run itself still limits its step */
    for (size_t b = 0; b < s->nbodies; b++)
        law->body(s, b, &cb[b]);
    const enum tlsph_contact_variant variant = law->variant(s);
    double best = INFINITY;
    for (size_t a = 0; a < s->nbodies; a++)
        for (size_t b = a; b < s->nbodies; b++) {
            if (a == b && !s->materials[s->bodies[a].material].damage.model &&
                s->crack_treatment != TLSPH_CRACK_VIRTUAL_LINKS)
                continue;
            const double reach = cb[a].radius + cb[b].radius;
            const double cells = 0.5 * (s->bodies[a].spacing + s->bodies[b].spacing);
            const double delta = fmax(TLSPH_CONTACT_MAX_OVERLAP * reach, reach - cells);
            const double ma = particle_mass(s, a), mb = particle_mass(s, b);
            struct tlsph_contact_pair p;
            if (variant == TLSPH_CONTACT_PINBALL)
                p = tlsph_pinball_pair(&cb[a], &cb[b], delta, 0, 0.0, 0.0,
                                       s->contact.params[TLSPH_PINBALL_SCALE_FACTOR]);
            else
                p = tlsph_penalty_pair(variant == TLSPH_CONTACT_PENALTY_POINT, &cb[a], &cb[b], ma,
                                       mb, delta, 0.0, 0.0);
            if (!(p.stiffness > 0.0))
                continue;
            const double t = sqrt(ma * mb / (ma + mb) / p.stiffness);
            if (t < best) {
                best = t;
                pair[0] = a;
                pair[1] = b;
            }
        }
    free(cb);
    return best;
}
