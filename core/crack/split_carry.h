/* The deformation gradient carried through a split.
 *
 * Why.  A total-Lagrangian particle reads F from its support: F_i = I +
 * [sum_j V_j (u_j - u_i) (x) grad W_i] L_i^-1.  A split cuts the pairs across
 * the new facets, so the rows around it (the halves, the new tip's fibre, the
 * rows along the cut) read F from one side only from then on.  Where the
 * opening ahead of the tip was smeared over the old support, the one-sided F
 * lost it in one step although no material moved: in the capped cylinder an
 * undamaged half went to det F = 0.42 and was launched at 4.4 km/s; in the
 * tearing plate a porous half went from J 1.011 to 0.901 (a trial pressure of
 * 15 GPa).  The opening the old support smeared over its particles is a real
 * gap now, between the faces; the material point's state did not change,
 * only its discretisation did.
 *
 * What.  When a split rebuilds row i (crack/local_rebuild.h), with F_old the
 * F the material sees (p.F, the last evaluation, at the current positions)
 * and F_raw = I + S_new L_new^-1 the new support's reading of the same
 * positions (with the damage-aware treatment S_new less the row's stored
 * crack gradient, as its gather takes it), the row keeps
 *     G_i = F_raw^-1 F_old,      p.Linv_i = L_new^-1 G_i,    p.F_carry_i = G_i,
 * so that the kinematics (sph/kinematics.h) give F_i = G_i + S L_new^-1 G_i =
 * F_raw G_i: equal to F_old at the split, and changed afterwards by the new
 * support's increments (Fdot_i = Sd L_new^-1 G_i, so the velocity gradient
 * Fdot F^-1 is the new support's).  Every material sees the F it saw (the
 * Hencky strain, J for the equation of state, the porous models' elastic
 * volume), so no stress jumps; the stress folding P_tilde = P (L^-1 G)^T
 * (constitutive.c, local_rebuild.c) is the one conjugate to this F, so the
 * energy account and the forces stay consistent.  A row rebuilt again
 * composes: F_old already holds the older G.
 *
 * Only crack-growth scenes allocate p.F_carry (identity at the start);
 * without it the kinematics read I and nothing changes.  Not with the
 * pseudo-spring treatment (it recomputes L^-1 every step): p.F_carry stays
 * NULL there and F jumps as before.  Units: dimensionless. */
#ifndef TLSPH_CRACK_SPLIT_CARRY_H
#define TLSPH_CRACK_SPLIT_CARRY_H

#include <stddef.h>

#include "run/model.h"

/* For row i whose pairs and p.Linv (the raw L_new^-1) were just rebuilt, while
 * p.F still holds F_old: sets p.F_carry_i and p.Linv_i as above.  Returns 1
 * when carried, 0 when p.F_carry is NULL, the point has failed (D >= 1: no
 * stress, its F no longer updated) or F_raw is singular or not finite;
 * then G_old is kept (p.Linv_i = L_new^-1 G_old) and F jumps as without the
 * carry.  An F_raw with det < 0 (a support the cut left inverted against the
 * old F) is carried too: F_raw G = F_old whatever det F_raw's sign, and
 * keeping G_old there handed the material an inverted F (the stiffened plate
 * of docs/crack-growth.md went non-finite 5 steps after such a row). */
int tlsph_split_carry_row(struct tlsph_model *m, size_t i);

/* Allocates p.F_carry (the identity for every particle; its capacity p.cap)
 * when the model has none: a model built from a scene without crack growth
 * that a caller splits (the unit tests).  0, or -1 out of memory (the model
 * unchanged). */
int tlsph_split_carry_enable(struct tlsph_model *m);

/* H = ln U of F = R U (row-major), as sym6 (xx, xy, xz, yy, yz, zz), the
 * material point's strain measure (material/material_point.h): what the
 * tests compare across a split. */
void tlsph_split_hencky(const double F[9], double H[6]);

#endif
