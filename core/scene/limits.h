/* The scene's defaults and ceilings, named once.  The key tables
 * (core/scene/scene_keys.c) read them, and so may any program that must agree
 * with the engine about a scene (the daemon's particle limit, a client's
 * defaults).  Units as in the scene: SI, counts dimensionless. */
#ifndef TLSPH_SCENE_LIMITS_H
#define TLSPH_SCENE_LIMITS_H

#include "util/names.h" /* the naming rule and its length */

/* ---------------------------------------------------------------- ceilings */
#define TLSPH_NAME_MAX           (TLSPH_NAME_CHARS_MAX + 1) /* bytes of a name, with its NUL */
#define TLSPH_MAX_PARTICLES      50000000L /* absolute ceiling; the scene may set a lower one */
#define TLSPH_MAX_PARAMS         40        /* entries of "parameters" */
#define TLSPH_MAX_MATERIALS      1000      /* entries of "materials" */
#define TLSPH_MAX_BODIES         10000     /* items of "bodies" */
#define TLSPH_MAX_MEASURES       32        /* items of "output.gauges", "output.sections", "output.probes" */
#define TLSPH_MAX_RIGID_BODIES   32        /* items of "rigid_bodies" */
#define TLSPH_MAX_CRACKS         32        /* items of "cracks" */
#define TLSPH_MAX_CRACK_CORNERS  64        /* corners of one crack polygon */
#define TLSPH_MAX_GROWTH_TIPS    8         /* crack_growth.tips */
#define TLSPH_GEOMETRY_MAX_DEPTH 16        /* nesting of union / difference */
/* Objects (primitives, unions, differences) in one body's geometry: bounds the
 * lattice walk at (lattice points in the bounding box) x (objects) box tests */
#define TLSPH_GEOMETRY_MAX_OBJECTS 1000
/* Refinement regions of one body ("refine"), and the finest refined spacing as
 * body spacing / 2^TLSPH_MAX_REFINE_LEVELS (each level halves the cells). */
#define TLSPH_MAX_REFINE 16
#define TLSPH_MAX_REFINE_LEVELS 10
/* Smallest spacing / (largest |coordinate| of the body's geometry and origin):
 * positions are doubles (53 bits, ~16 digits), so at this ratio a position is
 * exact to ~1e-9 spacing and a step's displacement (~1e-3 spacing) to ~1e-6 of
 * itself; far below it particles coincide (1e16 m at 1 m spacing) */
#define TLSPH_MIN_RELATIVE_SPACING 1e-7
#define TLSPH_SCENE_FILE_MAX     (16L * 1024 * 1024) /* bytes of a scene file (16 MiB) */
/* Time steps of one run: the ceiling of time.max_steps, of the step count
 * validation estimates for a scene without max_steps (core/scene/check_steps.c),
 * and of the count a run projects while it goes (core/run/stability.c).  1e8
 * steps take days of wall time even for a thousand particles; a scene that needs
 * more has a step far below what its physics needs (cfl, spacing, a fixed step)
 * or an end time far beyond it. */
#define TLSPH_MAX_STEPS          100000000L
#define TLSPH_MAX_EVERY          1000000000L /* stability.check_every, output.series_every (steps) */
#define TLSPH_MAX_FRAMES         100000L     /* output.frames */

/* ---------------------------------------------------------------- physical ranges
 * Bounds that keep a scene's numbers inside what a solid can be and what a double
 * can hold through the step estimate (wave speed sqrt(E / rho) and the like). */
#define TLSPH_MIN_DENSITY        0.01   /* kg/m^3: below any solid (aerogels ~1) */
#define TLSPH_MAX_DENSITY        1e5    /* kg/m^3: above any solid (osmium 22 590) */
#define TLSPH_MIN_MODULUS        1.0    /* Pa: Young's modulus, below any gel */
#define TLSPH_MAX_MODULUS        1e13   /* Pa: Young's modulus, ten times diamond's */
#define TLSPH_MIN_CFL            1e-3   /* time.cfl: below it the step only adds round-off */
#define TLSPH_MIN_FIXED_STEP     1e-15  /* s: time.step, a femtosecond */
/* Samples of an expression of t over [0, end]: t = k end / N, k = 0..N
 * (core/scene/check_values.c). */
#define TLSPH_TIME_SAMPLES       1000

/* ---------------------------------------------------------------- defaults */
#define TLSPH_DEFAULT_NAME "scene"
/* "dimension" is required; validation goes on in 3-D when it is missing or invalid. */
#define TLSPH_DEFAULT_DIMENSION             3
/* time.cfl: the fraction of the estimated stable step a run takes.  The measured
 * leapfrog limit is 0.9-1.6x the estimate (docs/performance.md "The stable step"),
 * so 0.6 steps at most at 0.67 of it; 0.3 (the default before 2026-11-26) cost twice
 * the steps with the same answers on the cases measured there. */
#define TLSPH_DEFAULT_CFL                   0.6
#define TLSPH_DEFAULT_STEP_ESTIMATE         1
#define TLSPH_DEFAULT_SUPPORT_FACTOR        2.01
#define TLSPH_DEFAULT_HOURGLASS             1 /* enabled */
#define TLSPH_DEFAULT_HOURGLASS_COEFFICIENT 1.0
/* hourglass.stiffness: 1 = "tangent" (the spring follows the elasto-plastic
 * tangent where a particle has flowed).  Measured more accurate on the Taylor
 * bars (docs/performance.md); no effect on a scene without plasticity, whose
 * model never allocates the scale array (core/run/model.c). */
#define TLSPH_DEFAULT_HOURGLASS_TANGENT     1
#define TLSPH_DEFAULT_VISCOSITY             0 /* disabled */
#define TLSPH_DEFAULT_VISCOSITY_LINEAR      1.0
#define TLSPH_DEFAULT_VISCOSITY_QUADRATIC   0.0
#define TLSPH_DEFAULT_CHECK_EVERY           10L /* steps */
#define TLSPH_DEFAULT_ENERGY_TOLERANCE      0.05
#define TLSPH_DEFAULT_SPEED_LIMIT           1.0
#define TLSPH_DEFAULT_MAX_PARTICLES         2000000L
#define TLSPH_DEFAULT_FRAMES                20L
#define TLSPH_DEFAULT_SERIES_EVERY          10L /* steps */
#define TLSPH_DEFAULT_TAYLOR_QUINNEY        0.9
#define TLSPH_DEFAULT_CONTACT               1 /* enabled (where it can act) */
#define TLSPH_DEFAULT_CONTACT_SKIN          0.5 /* x the largest body spacing */
/* Deepest contact overlap / (R_i + R_j) the stability contract accepts: deeper,
 * two particles are about to pass through each other (tunnelling), so the run
 * stops (contact_penetration) instead of going on silently wrong.  The same
 * bound holds for a particle on a rigid body, overlap / R (rigid_penetration). */
#define TLSPH_CONTACT_MAX_OVERLAP           0.5
/* Body pairs with a contact-force series: all pairs of different bodies when
 * there are at most this many (12 bodies give 66: a 12-body scene has none);
 * beyond, only the per-body series (docs/output.md). */
#define TLSPH_MAX_CONTACT_PAIR_SERIES       66

#endif
