/* A split keeps the elastic state of the porous points around it.
 *
 * Why.  A total-Lagrangian particle's F is read from its support: F_i = I +
 * sum_j V_j (u_j - u_i) (x) grad W L_i^-1.  A split cuts the pairs across the
 * new facets, so the particles beside them (the split halves, the new tip's
 * fibre, the rows along the cut) read F from one side only.  Where the
 * opening ahead of the tip was smeared over the support (a necking band
 * narrower than a spacing), the one-sided F loses it at once: in the tearing
 * plate (M-Gurson, 20 mm spacing) a split half went from F_yy 1.202, J 1.011
 * to F_yy 1.003, J 0.901 in one step, a trial pressure of 15 GPa that
 * crushed its voids (f 0.004 -> 0) and defeated the porous return
 * (return_mapping, the run stopped two steps after its second split).  The
 * material did not change: its discretisation did.
 *
 * What.  Right after a split, for every point of a porous damage model
 * (p.void_fraction; gtn and the Gurson family, whose plastic strain has a
 * trace and whose pressure reads the elastic volume J exp(-tr Ep)) that has
 * not failed and whose F the new supports change, the plastic strain takes
 * the jump of the Hencky strain H = ln U:
 *     Ep <- Ep + (H(F_new) - H(F_old)),
 * so H - Ep, the elastic strain, and with it the stress and the elastic
 * volume, are what they were (the state is carried across the
 * re-discretisation, as a remap carries it across a new mesh).  eps_p, f and
 * every other history variable are kept: no plastic flow happened.  F_new is
 * the kinematics of the current positions on the new supports (a gather with
 * dt = 0: no energy and no crack-gradient increment); Fdot is restored.
 *
 * J2 materials are left alone: their Ep is traceless and their pressure
 * reads J, so a volumetric jump cannot be carried in Ep (and scenes without a
 * porous model stay bit-identical).  Units: dimensionless strains. */
#ifndef TLSPH_CRACK_SPLIT_ELASTIC_H
#define TLSPH_CRACK_SPLIT_ELASTIC_H

#include "run/model.h"
#include "util/errors.h"

/* H = ln U of F = R U (row-major), as sym6 (xx, xy, xz, yy, yz, zz), the
 * material point's strain measure (material/material_point.h). */
void tlsph_split_hencky(const double F[9], double H[6]);

/* After tlsph_split_particles (the halves hold their parents' F): the above.
 * Sets *changed (may be NULL) to the points re-referenced.  0, or -1 out of
 * memory (err). */
int tlsph_split_keep_elastic_state(struct tlsph_model *m, size_t *changed,
                                   struct tlsph_errors *err);

#endif
