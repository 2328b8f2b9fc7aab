/* The key tables of the scene's own objects (see keys.h): the root, its
 * sections, a material's scalars and thermal block, a body, a gauge and a
 * section.  The models' parameter tables live next to their laws in
 * core/material/, the geometry primitives' next to their parsers
 * (core/scene/parse_geometry.c), each boundary-condition kind's in its file in
 * core/bc/. */
#include <stddef.h>
#include <string.h>

#include "bc/selector.h"
#include "scene/limits.h"
#include "scene/parse_internal.h"

/* One row per key, as in the docs' tables. */
/* clang-format off */

/* Choices are stored through an int. */
_Static_assert(sizeof(enum tlsph_kernel_type) == sizeof(int), "kernel choice stored as int");
_Static_assert(sizeof(enum tlsph_crack_treatment) == sizeof(int), "treatment stored as int");
_Static_assert(sizeof(enum tlsph_failed_motion) == sizeof(int), "motion stored as int");
_Static_assert(sizeof(enum tlsph_placement) == sizeof(int), "placement stored as int");

#define AT(member) offsetof(struct tlsph_scene, member)
#define NUMBER TLSPH_KEY_NUMBER
#define INTEGER TLSPH_KEY_INTEGER
#define BOOLEAN TLSPH_KEY_BOOLEAN
#define CHOICE TLSPH_KEY_CHOICE
#define REQUIRED TLSPH_KEY_REQUIRED
#define DEFAULT TLSPH_KEY_DEFAULT
#define CALLER TLSPH_KEY_CALLER

/* ------------------------------------------------------------------ time */

static const struct tlsph_key_choice step_estimates[] = {{"elastic", 0}, {"tangent", 1}, {0}};

static const struct tlsph_key time_keys[] = {
    {.name = "end", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "s", .offset = AT(end_time), .description = "end time"},
    {.name = "cfl", .kind = NUMBER, .flags = DEFAULT,
     .range = {TLSPH_MIN_CFL, 10.0, JC_CLOSED, JC_CLOSED},
     .unit = "1", .def = TLSPH_DEFAULT_CFL, .offset = AT(cfl),
     .description = "safety factor on the CFL time step"},
    {.name = "step", .kind = NUMBER, .range = {TLSPH_MIN_FIXED_STEP, 0.0, JC_CLOSED, JC_NONE},
     .unit = "s",
     .offset = AT(fixed_dt), .description = "fixed time step; absent = the CFL step"},
    {.name = "step_estimate", .kind = CHOICE, .flags = DEFAULT,
     .def = TLSPH_DEFAULT_STEP_ESTIMATE, .size = 16, .choices = step_estimates,
     .noun = "step estimate", .offset = AT(step_estimate),
     .description = "stable-step estimate: tangent (the wave speed of the elasto-plastic "
                    "tangent in flowing points, the viscous damping included) or elastic "
                    "(the elastic P-wave speed alone, the estimate before 2026-11-26)"},
    {.name = "max_steps", .kind = INTEGER, .flags = DEFAULT,
     .range = {0.0, (double)TLSPH_MAX_STEPS, JC_CLOSED, JC_CLOSED}, .unit = "1", .def = 0.0,
     .offset = AT(max_steps), .description = "step limit, 0 = unlimited"},
};
static const struct tlsph_key_table time_table = TLSPH_KEY_TABLE("/time", NULL, time_keys);

/* ------------------------------------------------------------------ discretization */

static const struct tlsph_key_choice kernels[] = {
    {"wendland_c2", TLSPH_KERNEL_WENDLAND_C2}, {"cubic_spline", TLSPH_KERNEL_CUBIC_SPLINE}, {0}};
static const struct tlsph_key_choice stiffnesses[] = {{"elastic", 0}, {"tangent", 1}, {0}};
static const struct tlsph_key_choice treatments[] = {
    {"damage_aware", TLSPH_CRACK_DAMAGE_AWARE}, {"pseudo_spring", TLSPH_CRACK_PSEUDO_SPRING},
    {"virtual_links", TLSPH_CRACK_VIRTUAL_LINKS}, {0}};
static const struct tlsph_key_choice motions[] = {
    {"free", TLSPH_FAILED_FREE}, {"arrest", TLSPH_FAILED_ARREST}, {0}};

static const struct tlsph_key hourglass_keys[] = {
    {.name = "enabled", .kind = BOOLEAN, .flags = DEFAULT, .def = TLSPH_DEFAULT_HOURGLASS,
     .offset = AT(hourglass), .description = "hourglass control on"},
    {.name = "coefficient", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 100.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_HOURGLASS_COEFFICIENT, .offset = AT(hourglass_coefficient),
     .description = "hourglass control coefficient alpha (Ganzenmueller 2015)"},
    {.name = "stiffness", .kind = CHOICE, .flags = DEFAULT,
     .def = TLSPH_DEFAULT_HOURGLASS_TANGENT, .size = 16, .choices = stiffnesses,
     .noun = "hourglass stiffness", .offset = AT(hourglass_tangent),
     .description = "modulus of the hourglass spring: tangent (default) = the elasto-plastic "
                    "tangent E H / (E + H) in particles that have flowed, never rising "
                    "again; elastic = Young's modulus everywhere (the former default); no "
                    "effect without plasticity"},
};
static const struct tlsph_key_table hourglass_table =
    TLSPH_KEY_TABLE("/discretization/hourglass", NULL, hourglass_keys);

static const struct tlsph_key viscosity_keys[] = {
    {.name = "enabled", .kind = BOOLEAN, .flags = DEFAULT, .def = TLSPH_DEFAULT_VISCOSITY,
     .offset = AT(viscosity), .description = "artificial viscosity on"},
    {.name = "linear", .kind = NUMBER, .flags = DEFAULT, .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED},
     .unit = "1", .def = TLSPH_DEFAULT_VISCOSITY_LINEAR, .offset = AT(viscosity_linear),
     .description = "linear artificial viscosity coefficient beta1 (paper 001 eq. 18)"},
    {.name = "quadratic", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_VISCOSITY_QUADRATIC, .offset = AT(viscosity_quadratic),
     .description = "quadratic artificial viscosity coefficient beta2"},
};
static const struct tlsph_key_table viscosity_table =
    TLSPH_KEY_TABLE("/discretization/viscosity", NULL, viscosity_keys);

static const struct tlsph_key treatment_keys[] = {
    {.name = "treatment", .kind = CHOICE, .flags = DEFAULT, .def = TLSPH_CRACK_DAMAGE_AWARE,
     .size = 32, .choices = treatments, .noun = "damage treatment", .offset = AT(crack_treatment),
     .description = "how damage enters the particle approximation: damage_aware (paper 000 "
                    "eqs. 33-35), pseudo_spring (for comparison only) or virtual_links (paper "
                    "001: links between immediate neighbours carry the damage)"},
    {.name = "failed_particles", .kind = CHOICE, .flags = DEFAULT, .def = TLSPH_FAILED_FREE,
     .size = 32, .choices = motions, .noun = "failed-particle motion", .offset = AT(failed_motion),
     .description = "what a failed particle does: free (keeps its velocity) or arrest (its "
                    "velocity is set to 0 when it fails)"},
    {.name = "links", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .description = "the virtual links' criterion: {\"type\": name, ...parameters}; required "
                    "with the virtual_links treatment (core/scene/parse_links.c)"},
};
static const struct tlsph_key_table treatment_table =
    TLSPH_KEY_TABLE("/discretization/damage", NULL, treatment_keys);

static const struct tlsph_key discretization_keys[] = {
    {.name = "kernel", .kind = CHOICE, .flags = DEFAULT, .def = TLSPH_KERNEL_WENDLAND_C2,
     .size = 32, .choices = kernels, .noun = "kernel", .offset = AT(kernel),
     .description = "SPH kernel"},
    {.name = "support_factor", .kind = NUMBER, .flags = DEFAULT,
     .range = {1.2, 4.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "(support radius / spacing)",
     .def = TLSPH_DEFAULT_SUPPORT_FACTOR, .offset = AT(support_factor),
     .description = "kernel support radius / lattice spacing"},
    {.name = "hourglass", .kind = TLSPH_KEY_OBJECT, .table = &hourglass_table,
     .description = "hourglass control"},
    {.name = "viscosity", .kind = TLSPH_KEY_OBJECT, .table = &viscosity_table,
     .description = "artificial viscosity"},
    {.name = "damage", .kind = TLSPH_KEY_OBJECT, .table = &treatment_table,
     .description = "damage treatment; read only when some material has a damage block, or "
                    "with virtual_links"},
};
static const struct tlsph_key_table discretization_table =
    TLSPH_KEY_TABLE("/discretization", NULL, discretization_keys);

/* ------------------------------------------------------------------ stability, limits */

static const struct tlsph_key stability_keys[] = {
    {.name = "check_every", .kind = INTEGER, .flags = DEFAULT,
     .range = {1.0, (double)TLSPH_MAX_EVERY, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_CHECK_EVERY, .offset = AT(check_every),
     .description = "steps between stability checks"},
    {.name = "energy_tolerance", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .said = "(relative to the energy scale)", .def = TLSPH_DEFAULT_ENERGY_TOLERANCE,
     .offset = AT(energy_tolerance),
     .description = "allowed energy-balance error relative to the energy scale"},
    {.name = "speed_limit", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 100.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .said = "(max speed / max wave speed)", .def = TLSPH_DEFAULT_SPEED_LIMIT,
     .offset = AT(speed_limit_factor), .description = "max particle speed / max wave speed"},
};
static const struct tlsph_key_table stability_table =
    TLSPH_KEY_TABLE("/stability", NULL, stability_keys);

static const struct tlsph_key limits_keys[] = {
    {.name = "max_particles", .kind = INTEGER, .flags = DEFAULT,
     .range = {1.0, (double)TLSPH_MAX_PARTICLES, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_MAX_PARTICLES, .offset = AT(max_particles),
     .description = "particle limit: scenes that would generate more are refused"},
};
static const struct tlsph_key_table limits_table = TLSPH_KEY_TABLE("/limits", NULL, limits_keys);

/* ------------------------------------------------------------------ output */

static const struct tlsph_key gauge_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .description = "unique among the gauges; names the output series"},
    {.name = "between", .kind = TLSPH_KEY_ARRAY, .flags = REQUIRED | CALLER,
     .description = "two different names of fixed or velocity boundary conditions"},
    {.name = "area", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "m^2", .offset = offsetof(struct tlsph_gauge, area),
     .description = "initial load-carrying area (m per metre of thickness in 2-D)"},
    {.name = "length", .kind = NUMBER, .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m",
     .offset = offsetof(struct tlsph_gauge, length),
     .description = "gauge length; absent = the distance of the two groups' reference "
                    "centroids"},
};
const struct tlsph_key_table tlsph_gauge_keys =
    TLSPH_KEY_TABLE("/output/gauges/*", NULL, gauge_keys);

static const struct tlsph_key section_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .description = "unique among the sections; names the output series"},
    TLSPH_KEY_POINT("point", "a point of the plane"),
    TLSPH_KEY_DIRECTION("normal", "normal of the plane, any non-zero length"),
    {.name = "thickness", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "m", .offset = offsetof(struct tlsph_section, thickness),
     .description = "slab thickness across the plane"},
};
const struct tlsph_key_table tlsph_section_keys =
    TLSPH_KEY_TABLE("/output/sections/*", NULL, section_keys);

static const struct tlsph_key probe_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .description = "unique among the probes; names the output series"},
    {.name = "select", .kind = TLSPH_KEY_OBJECT, .flags = REQUIRED | CALLER,
     .table = &tlsph_probe_selector_keys,
     .description = "the particles whose centre of mass the probe follows (by reference "
                    "position)"},
};
const struct tlsph_key_table tlsph_probe_keys =
    TLSPH_KEY_TABLE("/output/probes/*", NULL, probe_keys);

static const struct tlsph_key_choice radius_overs[] = {{"all", 0}, {"lowest_layer", 1}, {0}};
static const struct tlsph_key extent_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .description = "unique among the extents; names the output series"},
    {.name = "select", .kind = TLSPH_KEY_OBJECT, .flags = REQUIRED | CALLER,
     .table = &tlsph_extent_selector_keys,
     .description = "the particles whose extent is measured (by reference position)"},
    TLSPH_KEY_POINT("point", "a point of the axis"),
    TLSPH_KEY_DIRECTION("axis", "direction of the axis, any non-zero length"),
    {.name = "radius_over", .kind = CHOICE, .flags = DEFAULT, .def = 0.0, .size = 16,
     .choices = radius_overs, .noun = "radius selection",
     .offset = offsetof(struct tlsph_extent, lowest_layer),
     .description = "the particles the radius is taken over: all the selected ones, or "
                    "lowest_layer, those whose centre lies within half their spacing of the "
                    "lowest selected centre along the axis (a Taylor bar's foot)"},
};
const struct tlsph_key_table tlsph_extent_keys =
    TLSPH_KEY_TABLE("/output/extents/*", NULL, extent_keys);

static const struct tlsph_key output_keys[] = {
    {.name = "frames", .kind = INTEGER, .flags = DEFAULT,
     .range = {1.0, (double)TLSPH_MAX_FRAMES, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_FRAMES, .offset = AT(frames),
     .description = "field frames over [0, end]"},
    {.name = "series_every", .kind = INTEGER, .flags = DEFAULT,
     .range = {1.0, (double)TLSPH_MAX_EVERY, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .def = TLSPH_DEFAULT_SERIES_EVERY, .offset = AT(series_every),
     .description = "steps between time-series samples"},
    {.name = "gauges", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_gauge_keys,
     .description = "engineering stress-strain gauges"},
    {.name = "sections", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_section_keys,
     .description = "Lagrangian cross-sections"},
    {.name = "probes", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_probe_keys,
     .description = "displacement and velocity of selected particles' centre of mass"},
    {.name = "extents", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_extent_keys,
     .description = "how far selected particles reach about and along an axis"},
};
static const struct tlsph_key_table output_table = TLSPH_KEY_TABLE("/output", NULL, output_keys);

/* ------------------------------------------------------------------ materials */

#define MAT(member) offsetof(struct tlsph_material, member)

static const struct tlsph_key thermal_keys[] = {
    {.name = "specific_heat", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 1e6, JC_OPEN, JC_CLOSED}, .unit = "J/(kg K)",
     .offset = offsetof(struct tlsph_thermal, specific_heat),
     .description = "specific heat capacity C_p"},
    {.name = "initial_temperature", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 1e5, JC_OPEN, JC_CLOSED}, .unit = "K",
     .offset = offsetof(struct tlsph_thermal, initial_temperature),
     .description = "temperature at t = 0"},
    {.name = "taylor_quinney", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 1.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .said = "(fraction of plastic work turned into heat)", .def = TLSPH_DEFAULT_TAYLOR_QUINNEY,
     .offset = offsetof(struct tlsph_thermal, taylor_quinney),
     .description = "Taylor-Quinney coefficient chi, fraction of plastic work turned into heat"},
    {.name = "expansion_coefficient", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 1e-3, JC_CLOSED, JC_CLOSED}, .unit = "1/K", .def = 0.0,
     .offset = offsetof(struct tlsph_thermal, expansion),
     .description = "linear thermal expansion coefficient gamma: thermal strain rate "
                    "gamma dT/dt I (paper 003 eq. 58); 0 = none"},
};
static const struct tlsph_key_table thermal_table =
    TLSPH_KEY_TABLE("/materials/*/thermal", NULL, thermal_keys);

static const struct tlsph_key material_keys[] = {
    {.name = "density", .kind = NUMBER, .flags = REQUIRED,
     .range = {TLSPH_MIN_DENSITY, TLSPH_MAX_DENSITY, JC_CLOSED, JC_CLOSED},
     .unit = "kg/m^3", .offset = MAT(density), .description = "reference density rho0"},
    {.name = "youngs_modulus", .kind = NUMBER, .flags = REQUIRED,
     .range = {TLSPH_MIN_MODULUS, TLSPH_MAX_MODULUS, JC_CLOSED, JC_CLOSED}, .unit = "Pa",
     .offset = MAT(youngs_modulus),
     .description = "Young's modulus E"},
    {.name = "poisson_ratio", .kind = NUMBER, .flags = REQUIRED,
     .range = {-1.0, 0.5, JC_OPEN, JC_OPEN}, .unit = "1",
     .above_max = "incompressible (nu = 0.5) and nu > 0.5 materials are not supported",
     .offset = MAT(poisson_ratio), .description = "Poisson's ratio nu"},
    {.name = "eos", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .description = "equation of state: {\"type\": name, ...parameters}; absent = linear"},
    {.name = "strength", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .description = "deviatoric response: {\"type\": name, ...parameters}; absent = elastic"},
    {.name = "thermal", .kind = TLSPH_KEY_OBJECT, .flags = CALLER, .table = &thermal_table,
     .description = "adiabatic heating by plastic work; needs a plastic strength model"},
    {.name = "damage", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .description = "ductile damage and failure: {\"type\": name, ...parameters}; needs a "
                    "plastic strength model"},
};
const struct tlsph_key_table tlsph_material_keys =
    TLSPH_KEY_TABLE("/materials/*", NULL, material_keys);

/* ------------------------------------------------------------------ bodies */

static const struct tlsph_key_choice lattices[] = {{"simple_cubic", 0}, {0}};
static const struct tlsph_key_choice placements[] = {
    {"lattice", TLSPH_PLACEMENT_LATTICE}, {"conforming", TLSPH_PLACEMENT_CONFORMING}, {0}};

static const struct tlsph_key_choice axes[] = {
    {"none", -1}, {"x", 0}, {"y", 1}, {"z", 2}, {"radial", 3}, {0}};

static const struct tlsph_key body_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .description = "unique body name"},
    {.name = "material", .kind = TLSPH_KEY_STRING, .flags = REQUIRED | CALLER,
     .size = TLSPH_NAME_MAX, .description = "a key of /materials"},
    {.name = "spacing", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "m", .offset = offsetof(struct tlsph_body, spacing),
     .description = "lattice spacing h"},
    {.name = "lattice", .kind = CHOICE, .flags = DEFAULT, .def = 0, .size = 32,
     .choices = lattices, .noun = "lattice", .offset = TLSPH_KEY_NOWHERE,
     .description = "lattice type"},
    {.name = "placement", .kind = CHOICE, .size = 32, .choices = placements, .noun = "placement",
     .offset = offsetof(struct tlsph_body, placement),
     .description = "lattice = the simple cubic lattice; conforming = concentric shells of "
                    "thickness and arc spacing about h that follow the surface of a sphere (a "
                    "disc in 2-D) or a cylinder (the geometry one of them, or a difference "
                    "whose first object is one; origin unused), each particle its shell's "
                    "volume / count; absent = conforming for a sphere without an origin, "
                    "lattice otherwise"},
    {.name = "origin", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .unit = "m",
     .description = "lattice origin: points sit at origin + (i + 1/2) h; absent = the minimum "
                    "corner of the geometry's bounding box"},
    {.name = "geometry", .kind = TLSPH_KEY_OBJECT, .flags = REQUIRED | CALLER,
     .table = &tlsph_geometry_keys, .description = "the region the particles fill"},
    {.name = "initial_velocity", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .unit = "m/s",
     .description = "3 items, each a number or an expression of x, y, z; absent = 0"},
    {.name = "refine", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_refine_keys,
     .description = "regions filled at a finer spacing, graded back to the body's spacing "
                    "(lattice placement only); absent = uniform"},
    {.name = "thickness_axis", .kind = CHOICE, .flags = DEFAULT, .def = -1, .size = 32,
     .choices = axes, .noun = "thickness axis", .offset = offsetof(struct tlsph_body, thickness_axis),
     .description = "a thin body (a plate; 3-D, uniform lattice): its thickness direction, "
                    "along which its particles stack into fibres for the crack-tip search; "
                    "radial = a cylindrical shell's wall (conforming placement of a cylinder, "
                    "the same count on every shell); none = not thin"},
    {.name = "thickness_regions", .kind = TLSPH_KEY_ARRAY, .flags = CALLER,
     .table = &tlsph_thickness_region_keys,
     .description = "a thin body whose parts are thin in different directions (a plate and "
                    "its stiffeners; 3-D, uniform lattice): 1 to 8 regions, each a box and the "
                    "axis its particles stack along into fibres; a particle in no region is in "
                    "no fibre, one in two is refused; not with thickness_axis"},
};
const struct tlsph_key_table tlsph_body_keys = TLSPH_KEY_TABLE("/bodies/*", NULL, body_keys);

/* ------------------------------------------------------------------ contact */

static const struct tlsph_key contact_keys[] = {
    {.name = "enabled", .kind = BOOLEAN, .flags = DEFAULT, .def = TLSPH_DEFAULT_CONTACT,
     .offset = AT(contact.enabled),
     .description = "false: no contact, bodies and fragments pass through each other; "
                    "default true (contact is on in every scene of more than one body or "
                    "with a damage model)"},
    {.name = "law", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .description = "the contact law: {\"type\": name, ...parameters}; absent = penalty with "
                    "its defaults"},
    {.name = "skin", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .said = "(relative to the largest body spacing)", .def = TLSPH_DEFAULT_CONTACT_SKIN,
     .offset = AT(contact.skin),
     .description = "search skin relative to the largest body spacing: the search runs again "
                    "when a particle has moved half of it"},
};
const struct tlsph_key_table tlsph_contact_keys = TLSPH_KEY_TABLE("/contact", NULL, contact_keys);

/* ------------------------------------------------------------------ root */

static const struct tlsph_key scene_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = DEFAULT, .def_text = TLSPH_DEFAULT_NAME,
     .size = TLSPH_NAME_MAX, .offset = AT(name), .description = "label stored in the output"},
    {.name = "dimension", .kind = INTEGER, .flags = REQUIRED | DEFAULT,
     .range = {2.0, 3.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .def = TLSPH_DEFAULT_DIMENSION,
     .size = sizeof(int), .offset = AT(dimension),
     .description = "2 = plane strain in the x-y plane, unit thickness; 3 = 3-D"},
    {.name = "parameters", .kind = TLSPH_KEY_OBJECT, .flags = CALLER | TLSPH_KEY_MAP,
     .description = "named constants for expressions"},
    {.name = "time", .kind = TLSPH_KEY_OBJECT, .flags = REQUIRED | CALLER, .table = &time_table,
     .description = "time span and stepping"},
    {.name = "discretization", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .table = &discretization_table,
     .description = "kernel, support, hourglass control, viscosity, damage treatment"},
    {.name = "stability", .kind = TLSPH_KEY_OBJECT, .flags = CALLER, .table = &stability_table,
     .description = "stability checks"},
    {.name = "limits", .kind = TLSPH_KEY_OBJECT, .flags = CALLER, .table = &limits_table,
     .description = "particle limit"},
    {.name = "output", .kind = TLSPH_KEY_OBJECT, .flags = CALLER, .table = &output_table,
     .description = "frames, time-series sampling, gauges and sections"},
    {.name = "materials", .kind = TLSPH_KEY_OBJECT,
     .flags = REQUIRED | CALLER | TLSPH_KEY_MAP | TLSPH_KEY_NAME,
     .table = &tlsph_material_keys, .description = "material name -> material"},
    {.name = "bodies", .kind = TLSPH_KEY_ARRAY, .flags = REQUIRED | CALLER,
     .table = &tlsph_body_keys, .description = "bodies of particles"},
    {.name = "boundary_conditions", .kind = TLSPH_KEY_ARRAY, .flags = CALLER,
     .description = "supports and loads"},
    {.name = "contact", .kind = TLSPH_KEY_OBJECT, .flags = CALLER, .table = &tlsph_contact_keys,
     .description = "contact between bodies and fragments; absent = the default contact "
                    "(penalty) when the scene has more than one body or a damage model"},
    {.name = "rigid_bodies", .kind = TLSPH_KEY_ARRAY, .flags = CALLER,
     .table = &tlsph_rigid_body_keys,
     .description = "rigid bodies (plane, box, sphere, cylinder, cone), prescribed or free"},
    {.name = "cracks", .kind = TLSPH_KEY_ARRAY, .flags = CALLER, .table = &tlsph_crack_keys,
     .description = "initial cracks: reference pairs whose sight line crosses one are not "
                    "created"},
    {.name = "crack_growth", .kind = TLSPH_KEY_OBJECT, .flags = CALLER,
     .table = &tlsph_crack_growth_keys,
     .description = "cracks that grow from fibre to fibre (paper 003 eq. 20); absent = none "
                    "grows"},
};
const struct tlsph_key_table tlsph_scene_keys = TLSPH_KEY_TABLE("", NULL, scene_keys);

/* clang-format on */

void tlsph_scene_defaults(struct tlsph_scene *s)
{
    memset(s, 0, sizeof *s);
    tlsph_keys_defaults(&tlsph_scene_keys, s);
    for (size_t i = 0; i < tlsph_scene_keys.nkeys; i++) { /* the sections stored in s */
        const struct tlsph_key *k = &tlsph_scene_keys.keys[i];
        if (k->kind == TLSPH_KEY_OBJECT && k->table && !(k->flags & TLSPH_KEY_MAP))
            tlsph_keys_defaults(k->table, s);
    }
}
