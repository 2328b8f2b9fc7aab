/* Particle splitting (paper 003 §3.2, eqs. 21-32): when the crack tip moves
 * on, every particle of the old tip fibre is split in two, one on each side of
 * the new crack segment, and the pairs whose sight line crosses the crack
 * surface are cut (crack/local_rebuild.h).  This is the engine side; the
 * crack driver decides when and what to split and adds the facets.
 *
 * The angles.  V1 (previous tip -> current tip) and V2 (current tip -> new
 * tip) divide the plane around the tip into two sectors: between the crack
 * already open behind the tip (direction -V1) and the new segment (V2), of
 * angle theta = angle(-V1, V2), and the rest, 2 pi - theta.  Half 1 sits at
 * +delta (delta normal to V2): it gets the sector on delta's side, phi1 =
 * theta when delta.(-V1) > 0 else 2 pi - theta; half 2 gets phi2 = 2 pi -
 * phi1.  A straight crack gives pi and pi.
 *
 * What each field of the pair gets (parent = the particle before the split;
 * half 1 keeps the parent's index, half 2 is appended at the end of the
 * body's range, local_rebuild.h):
 *   mass, vol0    eqs. 21-24: m1 = m phi1 / 2pi, m2 = m - m1 (and V alike), so
 *                 m1 + m2 = m to one rounding
 *   X             eqs. 25-26: X1 = X + delta, X2 = X - delta
 *   x             x1 = x + F delta, x2 = x - F delta: the current place of the
 *                 material points X +- delta (to first order), so the halves
 *                 sit where the deformed body has them.  Eqs. 27-28 add
 *                 +-delta to the "displacement": read as the current
 *                 position this is x +- delta, the same for F = I; read as
 *                 u = x - X it would put half 1 at x + 2 delta, a gap of
 *                 delta not caused by any motion
 *   v             eqs. 29-30: copied (momentum and kinetic energy conserved
 *                 to round-off: m1 v + m2 v = m v)
 *   f, f_hourglass, f_viscous
 *                 each the stored value minus the pair sums on the old
 *                 supports plus those on the new (crack/split_forces.h),
 *                 updated on the affected rows and their partners only; the
 *                 rest (contact, rigid bodies, loads, and the viscous force's
 *                 velocity lag: the stored one saw t_(n-1/2)) of a parent is
 *                 shared by mass (f1 = f m1/m, f2 = f - f1).  Eqs. 31-32 zero
 *                 the halves' acceleration (a central-difference code
 *                 recomputes it before using it); the velocity-Verlet step
 *                 here starts with a half kick by the stored force
 *                 (run/integrate.h), which must be the one the next energy
 *                 update is conjugate to, hourglass and viscous parts
 *                 included (their trapezoidal power takes the stored ones);
 *                 with zero for the halves momentum changes by dt/2
 *                 f_parent.  The changed pairs lie between recomputed rows,
 *                 so momentum is exact to round-off
 *   h, spacing    copied (the split cuts the support, it does not refine it)
 *   F, Fdot, sigma, e, eps_p, plastic_strain, eps_p_rate,
 *   yield_stress, hg_scale, T, damage, damage_init, void_*, crack_gradient,
 *   F_carry       copied: the same material point's state (intensive; e is
 *                 per kg, so the internal energy m e is conserved); F is
 *                 carried onto the new supports (crack/split_carry.h)
 *   Linv          recomputed from the new support (local_rebuild.h), times
 *                 the carried G (crack/split_carry.h)
 *   P_tilde       sigma cof(F) Linv^T with the new Linv (local_rebuild.h)
 *   id            two new ids, after the largest so far (half 1 of the s-th
 *                 parent: max + 1 + 2s, half 2: max + 2 + 2s); the parent's
 *                 id ends with the split
 *   body          the parent's
 * Energy account: kinetic and internal energy are unchanged by the split, no
 * term is booked.  P_tilde = P L^-T of the rebuilt rows is refolded with the
 * new L (local_rebuild.h) and the forces updated (above), so the next step
 * is conjugate again: its balance moves by velocity Verlet's dt^2/8 sum
 * |f|^2/m term alone, as a step without a split does (to 1e-15 J of 1.41 J in
 * tests/engine/test_split.c at the default step; the term is larger after a
 * split, the halves' forces at the new faces: docs/crack-growth.md).
 *
 * Index-holding structures: pairs (rebuilt, local_rebuild.h), body ranges
 * (the body grows by k, later bodies shift by k), boundary groups,
 * sections and probes (indices shifted; a half joins every group, section and
 * probe of its parent), fibres, the contact phase's and the rigid bodies' per-particle arrays and
 * candidate lists (crack/split_state.h).  A pressure group's reference area
 * vectors and stored loads are shared like the volume (half 1 the share
 * phi1 / 2 pi of the parent's vector, half 2 the rest; split.c share_vectors
 * says why), so the group's total area vector and force are kept to one
 * rounding.  Refused with an error, the model unchanged: virtual links (D_ij
 * per pair is not remapped yet).  Fibres (m->fibres) follow the split: the halves 2 form a
 * new fibre beside their parents' (crack/fibre.h tlsph_fibres_split_commit).
 * The result file of a run that splits needs the layout for changing counts
 * (io/output/output.h); one opened with one count per run refuses the next
 * frame with an error. */
#ifndef TLSPH_CRACK_SPLIT_H
#define TLSPH_CRACK_SPLIT_H

#include <stddef.h>

#include "crack/crack_surface.h"
#include "run/model.h"
#include "run/particles_grow.h"
#include "util/errors.h"

/* One split event. */
struct tlsph_split {
    const size_t *index; /* the particles to split (a fibre), distinct, one body */
    size_t n;
    double V1[3];        /* previous crack direction (reference frame), any length > 0 */
    double V2[3];        /* new crack direction, any length > 0 */
    double delta[3];     /* offset of the halves, m, normal to V2, |delta| > 0 */
};

/* phi[0], phi[1] (rad, summing to 2 pi) for half 1 (+delta) and half 2; 0, or
 * -1 when V1, V2 or delta is zero or not finite, or delta is not normal to V2
 * (|delta.V2| > 1e-9 |delta||V2|). */
int tlsph_split_angles(const double V1[3], const double V2[3], const double delta[3],
                       double phi[2]);

/* Splits the particles, rebuilds the pairs and corrections around them
 * against the crack surface cs (may be NULL; its facets from first_new_facet
 * on are the ones added for this split, which widen the rebuilt region).
 * 0, or -1 with err and the model unchanged (refusals above, bad input, out
 * of memory).  alloc/ctx: the growth's allocator (NULL: malloc; a test's to
 * inject a failure). */
int tlsph_split_particles(struct tlsph_model *m, const struct tlsph_split *sp,
                          const struct tlsph_crack_surface *cs, size_t first_new_facet,
                          tlsph_grow_alloc_fn alloc, void *ctx, struct tlsph_errors *err);

#endif
