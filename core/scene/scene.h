/* The validated, typed scene: what the engine runs.  Produced only by
 * tlsph_scene_parse (core/scene/parse.c) from the JSON text; every field here
 * has passed range and consistency checks, so the engine does not re-check.
 *
 * Units are SI everywhere: m, kg, s, Pa, K, J/kg.
 * Ownership: the scene owns everything it points to; tlsph_scene_free releases it. */
#ifndef TLSPH_SCENE_H
#define TLSPH_SCENE_H

#include <stddef.h>
#include <jansson.h>

#include "util/errors.h"
#include "util/expr.h"
#include "scene/limits.h" /* TLSPH_NAME_MAX, TLSPH_MAX_PARTICLES, the defaults */

struct tlsph_eos_model;      /* core/material/eos/eos.h */
struct tlsph_strength_model; /* core/material/strength/strength.h */
struct tlsph_damage_model;   /* core/material/damage/damage.h */
struct tlsph_contact_law;    /* core/contact/contact.h */
struct tlsph_rigid_spec;     /* core/rigid/rigid.h */

enum tlsph_kernel_type { TLSPH_KERNEL_CUBIC_SPLINE, TLSPH_KERNEL_WENDLAND_C2 };

/* How damage enters the particle approximation (paper 000 §3.1). */
enum tlsph_crack_treatment {
    TLSPH_CRACK_DAMAGE_AWARE, /* eqs. 33-35: velocity differences scaled by (1 - D_j) */
    TLSPH_CRACK_PSEUDO_SPRING, /* kernel scaled per pair by (1 - D_i)(1 - D_j); comparison only */
    TLSPH_CRACK_VIRTUAL_LINKS  /* paper 001: immediate-neighbour links with their own damage
                                  D_ij (sph/virtual_links.h); needs /discretization/damage/links */
};

struct tlsph_link_criterion; /* core/sph/link_criterion.h */

/* The virtual links' criterion (/discretization/damage/links), read only with
 * the virtual_links treatment. */
struct tlsph_link_settings {
    const struct tlsph_link_criterion *criterion; /* NULL: no links */
    double params[4];             /* the criterion's parameters, meaning fixed by it */
    double reach; /* immediate neighbours: |X_ij| < reach x the mean local spacing, in
                     spacings (sph/virtual_links.h; key "reach", default 1.85) */
};

/* What a failed particle (D = 1: no stress, no interaction) does next. */
enum tlsph_failed_motion {
    TLSPH_FAILED_FREE,  /* keeps its momentum and flies on: total momentum is conserved */
    TLSPH_FAILED_ARREST /* the paper's choice: velocity set to 0 when it fails (the
                           lost kinetic energy is booked as external work) */
};

/* Optional terms of a flow-stress law, each active only when the scene gives
 * its parameters (core/material/strength/johnson_cook.c). */
#define TLSPH_FLOW_RATE 1u    /* strain-rate hardening */
#define TLSPH_FLOW_THERMAL 2u /* thermal softening: needs the material's temperature */

/* Adiabatic heating by plastic work (paper 003 eq. 58): rho C_p dT = chi sigma : d^p.
 * A material has a temperature only when its scene entry has a "thermal" block. */
struct tlsph_thermal {
    int enabled;
    double specific_heat;       /* C_p, J/(kg K) */
    double taylor_quinney;      /* chi, fraction of plastic work turned into heat, 1 */
    double initial_temperature; /* K */
    /* gamma of paper 003 eq. 58, 1/K; 0 = none: the heat expands the point by the
     * thermal strain d^t = gamma dT I (the EOS sees J exp(-3 gamma (T - T0))) */
    double expansion;
};

/* Ductile damage and failure (paper 000 §5): present when the material's scene
 * entry has a "damage" block (model != NULL).  Needs a plastic strength model. */
struct tlsph_damage {
    const struct tlsph_damage_model *model; /* NULL: the material does not damage */
    double params[16];        /* meaning fixed by the model */
    unsigned terms;           /* TLSPH_FLOW_RATE / TLSPH_FLOW_THERMAL terms of the criterion */
    double evolution_factor;  /* eq. 45: D = factor (D_init - 1) once D_init >= 1, 1 */
};

struct tlsph_material {
    char name[TLSPH_NAME_MAX];
    double density;       /* rho0, kg/m^3 */
    double youngs_modulus; /* E, Pa */
    double poisson_ratio;  /* nu, 1, in (-1, 0.5) */
    double shear_modulus;  /* G = E/(2(1+nu)), Pa (derived) */
    double bulk_modulus;   /* K = E/(3(1-2nu)), Pa (derived) */
    double wave_speed;     /* sqrt((K+4G/3)/rho0), m/s (derived, P-wave) */
    const struct tlsph_eos_model *eos;
    double eos_params[8];  /* meaning fixed by the EOS model */
    const struct tlsph_strength_model *strength;
    double strength_params[8];  /* meaning fixed by the strength model */
    unsigned strength_terms;    /* TLSPH_FLOW_* terms the scene switched on */
    struct tlsph_thermal thermal;
    struct tlsph_damage damage;
};

enum tlsph_geometry_type {
    TLSPH_GEOM_BOX,        /* a[0..2] min corner, a[3..5] max corner */
    TLSPH_GEOM_CYLINDER,   /* a[0..2] base centre, a[3..5] unit axis, a[6] radius, a[7] length */
    TLSPH_GEOM_SPHERE,     /* a[0..2] centre, a[3] radius */
    TLSPH_GEOM_PLATE,      /* a[0..2] centre, a[3..5] unit normal, a[6] thickness,
                              a[7],a[8] in-plane sizes along u and w = n x u,
                              a[9..11] unit in-plane axis u (set by the parser, see parse_geometry.c) */
    TLSPH_GEOM_NOTCHED_BAR, /* round bar with a circumferential notch of radius R:
                              a[0..2] base centre, a[3..5] unit axis, a[6] bar radius,
                              a[7] length, a[8] notch root radius (bar radius at the notch),
                              a[9] notch radius R (a U-notch with flanks 2R apart when the
                              notch is deeper than R), a[10] notch position along the axis */
    TLSPH_GEOM_UNION,      /* children[0..n-1] */
    TLSPH_GEOM_DIFFERENCE  /* children[0] minus children[1..n-1] */
};

struct tlsph_geometry {
    enum tlsph_geometry_type type;
    double a[12];
    struct tlsph_geometry *children; /* owned array of nchildren */
    size_t nchildren;
};

/* How a body's geometry becomes particles (core/scene/lattice.c, conforming.c). */
enum tlsph_placement {
    TLSPH_PLACEMENT_AUTO,      /* absent in the scene: the parser resolves it to one of */
    TLSPH_PLACEMENT_LATTICE,   /* simple cubic lattice, every particle spacing^d */
    TLSPH_PLACEMENT_CONFORMING /* shells following a sphere's or cylinder's surface,
                                  volume per shell */
};

/* A region of a body filled at a finer spacing (core/scene/refine.c, graded.c):
 * the target spacing at X is spacing + (grading - 1) d(X) for d the distance of
 * X from the region, so the spacing grows by the factor `grading` per spacing
 * of distance away from it, up to the body's spacing. */
struct tlsph_refine {
    struct tlsph_geometry region; /* a box, cylinder or sphere (owned) */
    double spacing;               /* finest spacing in the region, m (< the body's) */
    double grading;               /* growth of the spacing per spacing of distance, 1 (> 1) */
};

/* A region of a thin body with its own thickness direction ("thickness_regions",
 * core/scene/thickness_regions.c; crack/fibre.h tlsph_fibres_build_regions): the
 * particles whose reference position lies in the closed box min..max form fibres
 * along axis. */
#define TLSPH_MAX_THICKNESS_REGIONS 8 /* = TLSPH_FIBRE_MAX_REGIONS */
#define TLSPH_THICKNESS_REGIONS 4     /* thickness_axis of a body with regions */
struct tlsph_thickness_region {
    int axis;                   /* 0 = x, 1 = y, 2 = z */
    double min[3], max[3];      /* m */
};

struct tlsph_body {
    char name[TLSPH_NAME_MAX];
    int material;       /* index into scene->materials */
    double spacing;     /* lattice spacing (conforming: shell thickness and arc spacing), m */
    enum tlsph_placement placement;
    double origin[3];   /* lattice origin (a lattice point sits at origin + (i+1/2)*spacing), m */
    struct tlsph_geometry geometry;
    struct tlsph_expr initial_velocity[3]; /* expressions of x, y, z (m) -> m/s; evaluator NULL = 0 */
    struct tlsph_refine *refine; /* owned array of nrefine; none = the uniform lattice */
    size_t nrefine;
    int thickness_axis; /* a thin body's thickness direction (0 = x, 1 = y, 2 = z, 3 =
                           radial: a conforming cylinder's wall): its particles form
                           fibres (crack/fibre.h); -1 = not thin;
                           TLSPH_THICKNESS_REGIONS: per region, below */
    int nthickness_regions; /* 0, or the regions of "thickness_regions" */
    struct tlsph_thickness_region thickness_region[TLSPH_MAX_THICKNESS_REGIONS];
};

/* Which particles a boundary condition applies to.  A particle is selected when it
 * belongs to the body (or any body when body < 0), lies inside the box (when
 * has_box) and the expression (when present) is non-zero; all tests use the
 * reference position. */
struct tlsph_selector {
    int body;            /* index into scene->bodies, -1 = all bodies */
    int has_box;
    double box_min[3], box_max[3]; /* m */
    struct tlsph_expr expression;  /* of x, y, z; evaluator NULL = none */
};

struct tlsph_bc_kind; /* core/bc/kind.h */

/* One boundary condition.  Its kind (core/bc/<type>.c) reads and uses the
 * fields below; a new kind keeps its numbers in params and its expressions in
 * expr unless it adds a named view to the unions. */
struct tlsph_bc {
    const struct tlsph_bc_kind *kind; /* what the condition does: the scene's "type" */
    char name[TLSPH_NAME_MAX];      /* used for output series names */
    struct tlsph_selector select;   /* kinds with a particle group (all but wall) */
    union {                         /* expressions, freed with the scene */
        struct tlsph_expr velocity[3]; /* velocity: m/s; evaluator NULL = free component */
        struct tlsph_expr expr[3];
    };
    int velocity_set[3];            /* velocity: the component is prescribed */
    union {                         /* numbers, meaning fixed by the kind */
        struct {
            double point[3];        /* wall, symmetry: a point of the plane, m */
            double normal[3];       /* wall, symmetry: unit normal (into the solid for walls) */
        };
        double acceleration[3];     /* body_force, m/s^2 */
        /* pressure: normal (outward, unit), params[6] 1 when it is given,
         * params[7] the surface's area (m^2, 0 = none); p(t) in expr[0] */
        double params[12];
    };
};

/* An engineering stress-strain gauge between two load-carrying groups (fixed or
 * velocity conditions): along the unit axis a from group[0]'s reference
 * centroid to group[1]'s, engineering stress = (R_1 - R_0).a / (2 area) (the
 * mean axial load, positive in tension) and engineering strain =
 * (u_1 - u_0).a / length, with R the reaction and u the mean displacement of a
 * group. */
struct tlsph_gauge {
    char name[TLSPH_NAME_MAX];
    int group[2];                 /* indices into scene->bcs */
    double area;                  /* initial load-carrying area, m^2 (m per metre of thickness in 2-D) */
    double length;                /* gauge length, m; 0 = initial distance of the two centroids */
};

/* A Lagrangian cross-section: the particles whose reference position lies
 * within thickness/2 of the plane through point with unit normal normal. */
struct tlsph_section {
    char name[TLSPH_NAME_MAX];
    double point[3];              /* m */
    double normal[3];             /* unit */
    double thickness;             /* m */
};

/* An initial crack ("cracks", core/scene/parse_cracks.c): in 3-D a planar
 * convex polygon of ncorners >= 3 corners, in 2-D a segment (ncorners = 2,
 * z = 0) that the engine extrudes through the plane (core/crack/precrack.h).
 * Reference pairs whose sight line crosses it are not created. */
struct tlsph_crack_spec {
    int ncorners;
    double corner[TLSPH_MAX_CRACK_CORNERS][3]; /* m */
};

/* How cracks grow ("crack_growth", core/scene/parse_cracks.c;
 * core/crack/crack_driver.h): the tips that grow, each the end of a crack's
 * trace in a body with fibres, and eq. 20's constants.  on = 0: no crack grows
 * (nothing allocated or run). */
struct tlsph_crack_growth {
    int on;
    double tip[TLSPH_MAX_GROWTH_TIPS][3]; /* m */
    size_t ntips;
    double critical_damage; /* D_c: the fibre's summed damage, 1 */
    double fan_angle;       /* theta_c, degrees */
    double search_radius;   /* R, in spacings of the tip's body */
    int criterion;          /* the particle quantity D_c is compared with, summed
                               over a fibre: TLSPH_CRACK_CRITERION_* */
    int initiate;           /* 1: cracks also start at fibres reaching D_c away from any
                               crack (crack_driver.h "Initiation") */
};
/* crack_growth.criterion (core/crack/fibre_criterion.h). */
enum {
    TLSPH_CRACK_CRITERION_DAMAGE = 0,        /* the damage variable D (the default) */
    TLSPH_CRACK_CRITERION_VOID_FRACTION = 1, /* the void volume fraction f */
    TLSPH_CRACK_CRITERION_PLASTIC_STRAIN = 2 /* the equivalent plastic strain */
};

/* A probe: the centre of mass of the particles a selector picks (by reference
 * position, once at setup), followed through the run: its displacement and
 * velocity, the point measurements a test reads from a dial gauge or a laser
 * (a beam's deflection, a bar's end). */
struct tlsph_probe {
    char name[TLSPH_NAME_MAX];
    struct tlsph_selector select;  /* the expression is freed with the scene */
};

/* An extent: how far the particles a selector picks (by reference position,
 * once at setup) reach, measured at their outer edges (centre +- half the
 * particle's spacing) about an axis through a point: the largest distance
 * from the axis line and the lowest and highest coordinate along it (a
 * Taylor bar's foot radius and its length, core/io/measures.h). */
struct tlsph_extent {
    char name[TLSPH_NAME_MAX];
    struct tlsph_selector select;  /* the expression is freed with the scene */
    double point[3];               /* a point of the axis, m */
    double axis[3];                /* its direction, unit */
    int lowest_layer;              /* "radius_over": 1 = "lowest_layer" (the particles whose
                                      centre lies within half their spacing of the lowest
                                      centre along the axis); 0 = "all" (the default) */
};

/* Contact between bodies and between the separated parts of a body
 * ("contact" block, core/contact/): on when law != NULL.  On by default
 * (without the block) in a scene of more than one body or with a damage
 * model; "enabled": false switches it off. */
struct tlsph_contact_settings {
    const struct tlsph_contact_law *law; /* NULL: no contact */
    int enabled;                  /* "enabled" (default 1); 0 leaves law NULL */
    double params[4];             /* the law's parameters, meaning fixed by the law */
    int choice;                   /* the law's choice key, meaning fixed by the law
                                     (penalty: its form, enum tlsph_penalty_form) */
    double skin;                  /* search skin / largest body spacing, 1 */
};

struct tlsph_scene {
    int dimension;                /* 2 (plane strain, x-y, unit thickness) or 3 */
    char name[TLSPH_NAME_MAX];

    /* time */
    double end_time;              /* s */
    double cfl;                   /* safety factor on the CFL step, [TLSPH_MIN_CFL, 10] */
    double fixed_dt;              /* s; 0 = use the CFL step */
    int step_estimate;            /* 1 ("tangent", the default): the wave speed of the
                                     tangent the return has in flowing points and the
                                     viscous damping in the step; 0 ("elastic"): the
                                     elastic P-wave speed alone (before 2026-11-26) */
    long max_steps;               /* 0 = unlimited */
    /* derived at validation (core/scene/check_steps.c) */
    double estimated_dt;          /* the first time step, s */
    double estimated_steps;       /* steps to reach end_time at that step (or max_steps), 1 */

    /* discretisation */
    enum tlsph_kernel_type kernel;
    double support_factor;        /* kernel support radius / spacing, 1.2..4 */
    int hourglass;                /* enabled */
    double hourglass_coefficient; /* alpha (Ganzenmueller 2015), 1 */
    int hourglass_tangent;        /* spring modulus: 0 = Young's modulus everywhere; 1 (the
                                     default) = the elasto-plastic tangent E H / (E + H)
                                     where the pair's particles have flowed plastically */
    int viscosity;                /* enabled */
    double viscosity_linear;      /* beta1 (paper 001 eq. 18), 1 */
    double viscosity_quadratic;   /* beta2, 1 */
    enum tlsph_crack_treatment crack_treatment; /* only read when some material damages */
    enum tlsph_failed_motion failed_motion;
    struct tlsph_link_settings links; /* virtual_links only */

    /* stability contract */
    long check_every;             /* steps between stability checks, >= 1 */
    double energy_tolerance;      /* max |energy balance| / energy scale, 1 */
    double speed_limit_factor;    /* max speed / max wave speed, 1 */
    long max_particles;           /* refuse scenes that would generate more */

    /* output */
    long frames;                  /* number of field frames over [0, end_time], >= 1 */
    long series_every;            /* steps between time-series samples, >= 1 */
    struct tlsph_gauge gauges[TLSPH_MAX_MEASURES];     size_t ngauges;
    struct tlsph_section sections[TLSPH_MAX_MEASURES]; size_t nsections;
    struct tlsph_probe probes[TLSPH_MAX_MEASURES];     size_t nprobes;
    struct tlsph_extent extents[TLSPH_MAX_MEASURES];   size_t nextents;

    struct tlsph_param *params;   size_t nparams;
    struct tlsph_material *materials; size_t nmaterials;
    struct tlsph_body *bodies;    size_t nbodies;
    struct tlsph_bc *bcs;         size_t nbcs;
    struct tlsph_contact_settings contact;
    struct tlsph_rigid_spec *rigid; size_t nrigid; /* "rigid_bodies" (core/rigid/) */
    struct tlsph_crack_spec *cracks; size_t ncracks; /* "cracks": initial cracks */
    struct tlsph_crack_growth crack_growth;

    char *json_text;              /* the scene as submitted, compact JSON, for the output file */
};

/* Parses and validates.  Returns 0 on success; otherwise -1 with every problem
 * found in err (JSON pointer + message) and *scene left empty. */
int tlsph_scene_parse(const char *text, size_t len, struct tlsph_scene *scene,
                      struct tlsph_errors *err);
/* A scene holding only the defaults of its own sections (time, discretization,
 * stability, limits, output; scene/limits.h): no materials, bodies or conditions. */
void tlsph_scene_defaults(struct tlsph_scene *scene);
int tlsph_scene_load_file(const char *path, struct tlsph_scene *scene, struct tlsph_errors *err);
void tlsph_scene_free(struct tlsph_scene *scene);

/* Geometry (core/scene/geometry.c). */
int tlsph_geometry_contains(const struct tlsph_geometry *g, const double X[3]);
/* Axis-aligned bounding box of g (m). */
void tlsph_geometry_bounds(const struct tlsph_geometry *g, double lo[3], double hi[3]);
/* The particle positions of body b (its lattice points inside its geometry, or
 * its conforming shells, by its placement): *out gets 3*n doubles (z = 0 in
 * 2-D), owned by the caller.  Counts first and refuses more than max_points. */
int tlsph_body_lattice(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                       size_t *n, struct tlsph_errors *err);
/* The particles of body b by its placement: *out gets 3*n positions (m) and,
 * when vol is non-NULL, *vol gets n reference volumes (m^3; m^2 per metre in
 * 2-D): spacing^d on the lattice, the shell's volume / count when conforming.
 * Both arrays owned by the caller (NULL when n = 0).  Refuses more than
 * max_points like tlsph_body_lattice. */
int tlsph_body_particles(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                         double **vol, size_t *n, struct tlsph_errors *err);
/* tlsph_body_particles with, when spacing is non-NULL, each particle's own
 * spacing (m; the body's spacing unless the body refines, see struct
 * tlsph_refine) in *spacing, owned by the caller. */
int tlsph_body_fill(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                    double **vol, double **spacing, size_t *n, struct tlsph_errors *err);

#endif
