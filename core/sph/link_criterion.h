/* Link criteria of the virtual-link treatment (paper 001 §3, §5.2-5.3): how a
 * link's damage D_ij in [0, 1] follows the state of its two particles.  A table
 * of descriptors in sph/link_registry.c, one file per criterion:
 *   plastic_strain            eqs. 37-39: the particles' plastic strain projected
 *                             on the link, impedance-averaged; D = 1 at the threshold
 *   plastic_strain_softening  the same link strain; D grows linearly past the
 *                             threshold and reaches 1 after `softening` more
 *   rankine                   eq. 40: the link's stretch; D = 1 at the threshold
 * The scene names a row in /discretization/damage/links {"type": name, ...}.
 *
 * A criterion's `update` runs once per force evaluation over every link (its
 * own loop: no function pointer per link), after the stress update, so it sees
 * this step's plastic strain and positions.  Damage never heals: it writes
 * max(D_ij, its value) to both entries of the link (tlsph_links, virtual_links.h),
 * so D_ij = D_ji exactly and the pair forces stay antisymmetric. */
#ifndef TLSPH_LINK_CRITERION_H
#define TLSPH_LINK_CRITERION_H

#include <math.h>
#include <stddef.h>

#include "scene/keys.h"
#include "scene/scene.h"

struct tlsph_model;

/* A criterion's parameter i, as a key offset: the keys of /discretization/damage/links
 * are read into struct tlsph_link_settings (parse_links.c). */
#define TLSPH_LINK_PARAM(i) (offsetof(struct tlsph_link_settings, params) + TLSPH_PARAM(i))

/* The key every criterion's table lists: the reach of the immediate-neighbour
 * support (sph/virtual_links.h), in mean local spacings.  Above 1 (the nearest
 * lattice shell lies at 1 spacing); up to 3 (the kernel's support, support_factor
 * spacings, cuts it anyway).  1.85 keeps the unit cell around a particle: 8 links
 * on the 2-D square lattice, 26 on the 3-D cubic one; 1.2 keeps the nearest shell
 * only: 4 and 6. */
#define TLSPH_LINK_KEY_REACH                                                                   \
    {.name = "reach", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,                    \
     .range = {1.0, 3.0, JC_OPEN, JC_CLOSED}, .unit = "1", .def = 1.85,                        \
     .offset = offsetof(struct tlsph_link_settings, reach),                                     \
     .description = "immediate neighbours: the particles closer than reach x the mean local "   \
                    "spacing of the two, in spacings; 1.85 keeps the unit cell (8 links in "    \
                    "2-D, 26 in 3-D), 1.2 the nearest shell (4, 6); the kernel's support "      \
                    "(support_factor spacings) cuts it too"}

struct tlsph_link_criterion {
    const char *name;   /* as written in the scene */
    const char *module; /* "link:<name>" for the run's list of modules */
    /* its parameters, at /discretization/damage/links, into tlsph_link_settings.params
     * (read by core/scene/parse_links.c: no criterion needs a cross-field check) */
    const struct tlsph_key_table *keys;
    int needs_plasticity; /* reads the plastic strain tensor: some material must be plastic */
    /* Raises every link's D_ij to the criterion's value; returns the number of
     * links (each counted once) broken (D_ij = 1) after the update. */
    size_t (*update)(struct tlsph_model *m);
};

/* "plastic_strain, plastic_strain_softening, rankine" */
const char *tlsph_link_criterion_names(void);
/* The row named name, or NULL. */
const struct tlsph_link_criterion *tlsph_link_criterion_find(const char *name);

/* Eq. 37: the plastic strain tensor E (6 doubles, xx xy xz yy yz zz: the
 * engine's unrotated frame, which is the reference frame up to the rotation of
 * the polar decomposition) projected on the link's reference direction
 * d = X_j - X_i: N.E.N with N = d/|d|.  Quadratic in d, so the same for d and
 * -d.  The paper writes it with the current x_ij and a Cauchy-frame strain;
 * N.E.N in the unrotated frame is the same quantity with both taken in one
 * frame (n = R N).  The paper's T_R divides by |d|^2 where a unit vector needs
 * |d|; the fraction it prints (numerator over |d|^2) is the one used. */
static inline double tlsph_link_projected_strain(const double E[6], const double d[3])
{
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    return (E[0] * d[0] * d[0] + E[3] * d[1] * d[1] + E[5] * d[2] * d[2] +
            2.0 * (E[1] * d[0] * d[1] + E[2] * d[0] * d[2] + E[4] * d[1] * d[2])) /
           dd;
}

/* Eq. 38: the link's value of the two projections, each weighted by the other
 * particle's acoustic impedance Z = rho C = sqrt(E rho0 / J) (C = sqrt(E/rho),
 * rho = rho0 / J, as the paper's section 2 defines them).  Symmetric in i, j. */
static inline double tlsph_link_average(double Zi, double ei, double Zj, double ej)
{
    return (Zi * ej + Zj * ei) / (Zi + Zj);
}

/* The link plastic strain of eqs. 37-38 for the link i-j (the plastic strain
 * criteria's measure; link_plastic_strain.c).  Needs p.plastic_strain. */
double tlsph_link_plastic_strain_of(const struct tlsph_model *m, size_t i, size_t j);

/* The link's stretch of eq. 40, (r_t - r_0) / r_0, from the current and the
 * reference separations (either orientation). */
static inline double tlsph_link_stretch(const double dx[3], const double dX[3])
{
    const double r = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    const double r0 = sqrt(dX[0] * dX[0] + dX[1] * dX[1] + dX[2] * dX[2]);
    return (r - r0) / r0;
}

#endif
