/* What a fibre's D sums (paper 003 §3.1 and §6.1): crack_growth.criterion.
 *
 * The paper: "we first choose either the volume fraction of voids, or the
 * effective plastic strain as the damage measure D", and a fibre's D_J is the
 * sum of its particles' D (D_j = sum_{i=1}^{M} D_ji, M = 3).  Its tearing runs
 * use f with D_c = f_p = 0.0135 (the four Gurson variants) and the plastic
 * strain with D_c = 0.35 (GTN, the fifth run); its Johnson-Cook cylinder (§6.4)
 * uses the accumulated damage of eq. 62 with D_c = 0.1.  Each is a particle
 * field the fibre search (crack/fibre.h) sums as it sums D:
 *
 *   damage          p.damage: the damage variable D of any damage model (the
 *                   default; Johnson-Cook's eq. 62);
 *   void_fraction   p.void_fraction: f of a porous damage model (gtn and the
 *                   Gurson family), not f* (eq. 45): the paper's f_p is a
 *                   value of f, as the family's own fracture_void_fraction;
 *   plastic_strain  p.eps_p: the equivalent plastic strain (for the Gurson
 *                   family the matrix strain eps_M, the one its own
 *                   fracture_plastic_strain reads).
 *
 * The sum over the fibre is kept for all three (one meaning of D_c per
 * number of layers, as the paper writes it): with three layers D_c = 0.0135
 * is reached at a mean f of 0.0045 over the thickness (each particle starts at
 * f0 = 0.0025 in Table 1, so the sum starts at 0.0075), and D_c = 0.35 at a
 * mean plastic strain of 0.117.  A scene that wants the per-particle reading
 * sets D_c = M x f_p.
 *
 * Units: dimensionless.  No state: the field is read from the model each
 * search. */
#ifndef TLSPH_CRACK_FIBRE_CRITERION_H
#define TLSPH_CRACK_FIBRE_CRITERION_H

#include <stddef.h>

#include "run/model.h"
#include "util/errors.h"

/* The per-particle array the scene's criterion sums (owned by the model; may
 * be NULL only when tlsph_crack_criterion_check was not called). */
const double *tlsph_crack_criterion_field(const struct tlsph_model *m);

/* Does body b's material have the criterion's quantity?  0, or -1 with an
 * error at /crack_growth/criterion naming the body and its material (a void
 * fraction needs a porous damage model, a plastic strain a plastic strength
 * model). */
int tlsph_crack_criterion_check(const struct tlsph_model *m, size_t b, struct tlsph_errors *err);

/* The criterion's name as the scene writes it ("damage", ...). */
const char *tlsph_crack_criterion_name(int criterion);

#endif
