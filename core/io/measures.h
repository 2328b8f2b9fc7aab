/* Scene measurements sampled as time series (scene "output.gauges",
 * "output.sections" and "output.probes", see core/scene/scene.h): engineering
 * stress and strain between two loaded groups, averages over a Lagrangian
 * cross-section (the quantities tensile tests report (paper 000 §6: engineering stress-strain of
 * smooth bars, principal stress vs plastic strain averaged over the notch
 * section of notched bars), the motion of selected particles' centre of mass,
 * and how far selected particles reach about and along an axis (a Taylor
 * bar's foot diameter and length). */
#ifndef TLSPH_MEASURES_H
#define TLSPH_MEASURES_H

#include <stddef.h>
#include <stdint.h>

#include "util/errors.h"
#include "scene/scene.h"

struct tlsph_model;

/* Per-run state of the measurements; owned by the model. */
struct tlsph_measures {
    double gauge_axis[TLSPH_MAX_MEASURES][3];   /* unit, group 0 -> group 1 centroid (reference) */
    double gauge_length[TLSPH_MAX_MEASURES];    /* m */
    int32_t *section_index[TLSPH_MAX_MEASURES]; /* particles of each section (owned) */
    size_t section_count[TLSPH_MAX_MEASURES];
    double section_volume[TLSPH_MAX_MEASURES];  /* reference volume of the section, m^3 */
    int32_t *probe_index[TLSPH_MAX_MEASURES];   /* particles of each probe (owned) */
    size_t probe_count[TLSPH_MAX_MEASURES];
    double probe_mass[TLSPH_MAX_MEASURES];      /* their mass, kg */
    int32_t *extent_index[TLSPH_MAX_MEASURES];  /* particles of each extent (owned) */
    size_t extent_count[TLSPH_MAX_MEASURES];
};

/* Values of one section, in this order; the output keeps the present ones. */
enum tlsph_section_value {
    TLSPH_SECTION_MAX_PRINCIPAL, /* mean largest principal Cauchy stress, Pa */
    TLSPH_SECTION_NORMAL,        /* mean normal stress n.sigma.n, Pa */
    TLSPH_SECTION_PLASTIC,       /* mean equivalent plastic strain, 1 */
    TLSPH_SECTION_DAMAGE,        /* mean damage, 1 */
    TLSPH_SECTION_NVALUES
};

/* Sets up the gauges (axis, length), sections and probes (particle lists) from
 * the reference configuration; needs the boundary groups.  A section or probe
 * that holds no particle, or a gauge whose groups share a centroid, is an
 * error naming the scene field.  Returns 0 or -1 with err. */
int tlsph_measures_init(struct tlsph_model *m, struct tlsph_errors *err);
void tlsph_measures_free(struct tlsph_measures *ms);

/* Engineering stress (Pa, positive in tension) and strain (1) of gauge k. */
void tlsph_gauge_values(const struct tlsph_model *m, size_t k, double out[2]);
/* Reference-volume-weighted means over section k (enum tlsph_section_value);
 * entries whose module is absent (plasticity, damage) are 0. */
void tlsph_section_values(const struct tlsph_model *m, size_t k,
                          double out[TLSPH_SECTION_NVALUES]);
/* Probe k: the mass-weighted mean displacement x - X (m) of its particles in
 * out[0..2] and their mean velocity (m/s: momentum / mass) in out[3..5]. */
void tlsph_probe_values(const struct tlsph_model *m, size_t k, double out[6]);

/* Values of one extent, in this order (m).  Each particle counts with its outer
 * edge: its centre plus or minus half its spacing (the body's, or its own where
 * the body refines), the same edge bench/taylor_metrics.py's extent measure uses. */
enum tlsph_extent_value {
    TLSPH_EXTENT_RADIUS,   /* largest distance of a centre from the axis line, + half spacing,
                              over the radius_over particles */
    TLSPH_EXTENT_DIAMETER, /* twice that */
    TLSPH_EXTENT_LOWER,    /* lowest coordinate along the axis (from point), - half spacing */
    TLSPH_EXTENT_UPPER,    /* highest coordinate along the axis, + half spacing */
    TLSPH_EXTENT_LENGTH,   /* upper - lower */
    TLSPH_EXTENT_NVALUES
};
/* Extent k at the current positions (enum tlsph_extent_value). */
void tlsph_extent_values(const struct tlsph_model *m, size_t k, double *out);

#endif
