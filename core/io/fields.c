/* The tables behind core/io/fields.h.  Adding an output field is one extractor
 * and one row here. */
#include "io/fields.h"

#include <math.h>
#include <string.h>

#include "bc/kind.h"
#include "contact/contact.h"
#include "crack/crack_driver.h"
#include "rigid/rigid.h"
#include "sph/virtual_links.h"
#include "util/mat3.h"

static void ex_id(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.id, m->p.n * sizeof(int64_t));
}

static void ex_body(const struct tlsph_model *m, void *out)
{
    int64_t *o = out;
    for (size_t i = 0; i < m->p.n; i++)
        o[i] = m->p.body[i];
}

static void ex_X(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.X, 3 * m->p.n * sizeof(double));
}

static void ex_volume(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.vol0, m->p.n * sizeof(double));
}

static void ex_mass(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.mass, m->p.n * sizeof(double));
}

static void ex_x(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.x, 3 * m->p.n * sizeof(double));
}

static void ex_v(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.v, 3 * m->p.n * sizeof(double));
}

static void ex_u(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t k = 0; k < 3 * m->p.n; k++)
        o[k] = m->p.x[k] - m->p.X[k];
}

static void ex_stress(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.sigma, 6 * m->p.n * sizeof(double));
}

static void ex_pressure(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *s = m->p.sigma + 6 * i;
        o[i] = -(s[0] + s[3] + s[5]) / 3.0;
    }
}

/* Von Mises equivalent of a symmetric tensor (xx xy xz yy yz zz). */
static double von_mises(const double *s)
{
    const double a = s[0] - s[3], b = s[3] - s[5], c = s[5] - s[0];
    return sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[1] * s[1] + s[2] * s[2] + s[4] * s[4]));
}

static void ex_von_mises(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++)
        o[i] = von_mises(m->p.sigma + 6 * i);
}

static void ex_detF(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *F = m->p.F + 9 * i;
        o[i] = mat3_det(F);
    }
}

static void ex_e(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.e, m->p.n * sizeof(double));
}

static int has_plasticity(const struct tlsph_model *m)
{
    return m->p.eps_p != NULL;
}

static int has_temperature(const struct tlsph_model *m)
{
    return m->p.T != NULL;
}

static void ex_eps_p(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.eps_p, m->p.n * sizeof(double));
}

static void ex_eps_p_rate(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.eps_p_rate, m->p.n * sizeof(double));
}

/* A particle whose material has no thermal block has no temperature (NaN in
 * m->p.T); the file holds 0 there, since no dataset holds a non-finite value. */
static void ex_T(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++) {
        const struct tlsph_body *b = &m->scene.bodies[m->p.body[i]];
        o[i] = m->scene.materials[b->material].thermal.enabled ? m->p.T[i] : 0.0;
    }
}

static int has_damage(const struct tlsph_model *m)
{
    return m->p.damage != NULL;
}

static void ex_damage(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.damage, m->p.n * sizeof(double));
}

/* Virtual links only (sph/virtual_links.h): D_i = sum_j D_ij / n_i. */
static int has_links(const struct tlsph_model *m)
{
    return m->links != NULL;
}

static void ex_link_damage(const struct tlsph_model *m, void *out)
{
    tlsph_virtual_links_particle_damage(m, out);
}

static void ex_damage_init(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.damage_init, m->p.n * sizeof(double));
}

static int has_voids(const struct tlsph_model *m)
{
    return m->p.void_fraction != NULL;
}

static void ex_void_fraction(const struct tlsph_model *m, void *out)
{
    memcpy(out, m->p.void_fraction, m->p.n * sizeof(double));
}

static void ex_triaxiality(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *s = m->p.sigma + 6 * i;
        const double q = von_mises(s);
        o[i] = q > 0.0 ? (s[0] + s[3] + s[5]) / (3.0 * q) : 0.0; /* finite: see the row */
    }
}

/* The Gurson family's own fields (material/damage/porous.h). */
static int has_porous(const struct tlsph_model *m)
{
    return m->p.void_fstar != NULL;
}

/* f*, the nucleated and the shear part of f: copies of their arrays */
#define COPY_EXTRACTOR(fn, array)                                                                  \
    static void fn(const struct tlsph_model *m, void *out)                                         \
    {                                                                                              \
        memcpy(out, m->p.array, m->p.n * sizeof(double));                                          \
    }
COPY_EXTRACTOR(ex_void_fstar, void_fstar)
COPY_EXTRACTOR(ex_void_nucleated, void_nucleated)
COPY_EXTRACTOR(ex_void_shear, void_shear)
#undef COPY_EXTRACTOR

/* xi = 27 J3 / (2 sigma_eq^3) of the Cauchy deviator, in [-1, 1]. */
static void ex_lode(const struct tlsph_model *m, void *out)
{
    double *o = out;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *s = m->p.sigma + 6 * i;
        const double q = von_mises(s), mean = (s[0] + s[3] + s[5]) / 3.0;
        const double a = s[0] - mean, d = s[3] - mean, f = s[5] - mean;
        const double J3 = a * (d * f - s[4] * s[4]) - s[1] * (s[1] * f - s[4] * s[2]) +
                          s[2] * (s[1] * s[4] - d * s[2]);
        o[i] = q > 0.0 ? fmin(fmax(13.5 * J3 / (q * q * q), -1.0), 1.0) : 0.0;
    }
}

const struct tlsph_field tlsph_fields[] = {
    {"id", TLSPH_FIELD_REFERENCE, TLSPH_INT64, 1, "1", NULL,
     "stable particle id (generation order, body by body)", NULL, ex_id},
    {"body", TLSPH_FIELD_REFERENCE, TLSPH_INT32, 1, "1", NULL,
     "index of the body in the scene's bodies array", NULL, ex_body},
    {"reference_position", TLSPH_FIELD_REFERENCE, TLSPH_FLOAT64, 3, "m", "x y z",
     "position in the reference configuration X", NULL, ex_X},
    {"volume", TLSPH_FIELD_REFERENCE, TLSPH_FLOAT64, 1, "m^3", NULL,
     "reference volume V0 (m^2 per metre of thickness in 2-D)", NULL, ex_volume},
    {"mass", TLSPH_FIELD_REFERENCE, TLSPH_FLOAT64, 1, "kg", NULL, "particle mass", NULL, ex_mass},
    {"position", TLSPH_FIELD_FRAME, TLSPH_FLOAT64, 3, "m", "x y z", "current position x", NULL,
     ex_x},
    {"velocity", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 3, "m/s", "x y z", "velocity", NULL, ex_v},
    {"displacement", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 3, "m", "x y z", "x - X", NULL, ex_u},
    {"stress", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 6, "Pa", "xx xy xz yy yz zz",
     "Cauchy stress", NULL, ex_stress},
    {"pressure", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "Pa", NULL,
     "pressure -tr(sigma)/3 (positive in compression)", NULL, ex_pressure},
    {"von_mises", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "Pa", NULL, "von Mises equivalent stress",
     NULL, ex_von_mises},
    {"det_F", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "volume ratio J = det F", NULL, ex_detF},
    {"internal_energy", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "J/kg", NULL,
     "specific internal energy", NULL, ex_e},
    {"plastic_strain", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "equivalent (von Mises) plastic strain, logarithmic; 0 in elastic bodies", has_plasticity,
     ex_eps_p},
    {"plastic_strain_rate", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1/s", NULL,
     "equivalent plastic strain rate of the last step", has_plasticity, ex_eps_p_rate},
    {"temperature", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "K", NULL,
     "temperature (adiabatic heating by plastic work); 0 where the material has no "
     "thermal block",
     has_temperature, ex_T},
    {"damage", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "damage D (0 intact, 1 failed: no stress); 0 in bodies without a damage model", has_damage,
     ex_damage},
    {"link_damage", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "virtual links: the particle's mean link damage sum_j D_ij / n (paper 001 §5.3; 1 = every "
     "link broken)",
     has_links, ex_link_damage},
    {"damage_initiation", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "damage-initiation variable D_init (damage starts at 1; GTN: f / f_c, coalescence "
     "starts at 1; johnson_cook_accumulated: D / D_c, the particle fails at 1)",
     has_damage, ex_damage_init},
    {"void_fraction", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "GTN void volume fraction f (damage D = q1 f*); 0 in bodies of other materials",
     has_voids, ex_void_fraction},
    {"triaxiality", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "stress triaxiality sigma_m / sigma_eq of the Cauchy stress; 0 where sigma_eq = 0 "
     "(unstressed or failed particles)",
     has_damage, ex_triaxiality},
    {"void_fraction_effective", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "Gurson family: f* of the yield surface (coalescence, paper 003 eq. 45; f* = f "
     "below critical_void_fraction); 0 in bodies of other materials",
     has_porous, ex_void_fstar},
    {"void_fraction_nucleated", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "Gurson family: the part of f nucleated so far (eqs. 46-48)", has_porous,
     ex_void_nucleated},
    {"void_fraction_shear", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "Gurson family: the part of f grown by the shear term so far (eqs. 49-54)", has_porous,
     ex_void_shear},
    {"lode_parameter", TLSPH_FIELD_FRAME, TLSPH_FLOAT32, 1, "1", NULL,
     "normalised third invariant xi = 27 J3 / (2 sigma_eq^3) of the Cauchy deviator: 1 "
     "axisymmetric tension, 0 pure shear, -1 axisymmetric compression (the shear term's "
     "omega = 1 - xi^2, eq. 50); 0 where sigma_eq = 0; with a Gurson-family model only",
     has_porous, ex_lode},
};
const size_t tlsph_nfields = sizeof tlsph_fields / sizeof *tlsph_fields;

static void sv_kinetic(const struct tlsph_model *m, double *o) { o[0] = m->energy.kinetic; }
static void sv_internal(const struct tlsph_model *m, double *o) { o[0] = m->energy.internal; }
static void sv_external(const struct tlsph_model *m, double *o) { o[0] = m->energy.external_work; }
static void sv_hourglass(const struct tlsph_model *m, double *o) { o[0] = m->energy.hourglass; }
static void sv_viscous(const struct tlsph_model *m, double *o) { o[0] = m->energy.viscous; }
static void sv_plastic(const struct tlsph_model *m, double *o) { o[0] = m->energy.plastic_work; }
static void sv_damage_work(const struct tlsph_model *m, double *o) { o[0] = m->energy.damage_work; }
static void sv_failed(const struct tlsph_model *m, double *o) { o[0] = (double)m->failed; }
static int has_crack_growth(const struct tlsph_model *m)
{
    return m->crack_driver != NULL;
}
static void sv_crack_length(const struct tlsph_model *m, double *o)
{
    o[0] = tlsph_crack_driver_length(m);
}
static void sv_crack_advances(const struct tlsph_model *m, double *o)
{
    o[0] = (double)m->crack_driver->nevents;
}
static void sv_particle_count(const struct tlsph_model *m, double *o)
{
    o[0] = (double)m->p.n;
}
static void sv_broken_links(const struct tlsph_model *m, double *o)
{
    o[0] = (double)m->links->broken;
}
static void sv_initiated(const struct tlsph_model *m, double *o)
{
    size_t n = 0;
    for (size_t i = 0; i < m->p.n; i++)
        n += m->p.damage_init[i] >= 1.0 ? 1 : 0;
    o[0] = (double)n;
}

static void sv_dt(const struct tlsph_model *m, double *o) { o[0] = m->dt; }

static int has_contact(const struct tlsph_model *m) { return m->contact != NULL; }
/* contact between bodies or with rigid bodies: both book contact_energy */
static int has_contact_work(const struct tlsph_model *m)
{
    return m->contact != NULL || m->rigid != NULL;
}
static int has_rigid(const struct tlsph_model *m) { return m->rigid != NULL; }
static void sv_rigid_contacts(const struct tlsph_model *m, double *o)
{
    o[0] = (double)tlsph_rigid_active(m);
}
static void sv_contact(const struct tlsph_model *m, double *o) { o[0] = m->energy.contact; }
static void sv_contact_pairs(const struct tlsph_model *m, double *o)
{
    o[0] = (double)tlsph_contact_active(m);
}

static void sv_balance(const struct tlsph_model *m, double *o)
{
    o[0] = tlsph_energy_balance(&m->energy);
}

static void sv_momentum(const struct tlsph_model *m, double *o)
{
    tlsph_model_momentum(m, o);
}

static void sv_max_temperature(const struct tlsph_model *m, double *o)
{
    double tmax = -INFINITY;
    for (size_t i = 0; i < m->p.n; i++)
        tmax = fmax(tmax, m->p.T[i]); /* fmax skips the NaN of bodies without temperature */
    o[0] = tmax;
}

const struct tlsph_series_column tlsph_global_series[] = {
    {"kinetic_energy", 1, "J", "sum of m v^2 / 2", NULL, sv_kinetic},
    {"internal_energy", 1, "J",
     "internal energy, sum of m e: stored (strain) energy plus plastic work and damage "
     "dissipation", NULL, sv_internal},
    {"external_work", 1, "J", "work done on the bodies by boundary conditions and body forces",
     NULL, sv_external},
    {"hourglass_energy", 1, "J", "work done against hourglass-control forces", NULL, sv_hourglass},
    {"viscous_energy", 1, "J", "work done against artificial-viscosity forces", NULL, sv_viscous},
    {"energy_balance", 1, "J",
     "kinetic + internal + hourglass + viscous - external work - initial energy (0 when energy "
     "is conserved)",
     NULL, sv_balance},
    {"linear_momentum", 3, "kg m/s", "total linear momentum", NULL, sv_momentum},
    {"time_step", 1, "s", "time step used for the last step", NULL, sv_dt},
    {"plastic_work", 1, "J",
     "plastic dissipation, sum over particles of the integral of sigma : d^p dV (part of "
     "internal_energy)",
     has_plasticity, sv_plastic},
    {"max_temperature", 1, "K", "highest particle temperature", has_temperature,
     sv_max_temperature},
    {"initiated_particles", 1, "1",
     "number of particles whose damage-initiation variable has reached 1 (JC/CL: damage "
     "grows; GTN: f >= f_c, coalescence)",
     has_damage, sv_initiated},
    {"failed_particles", 1, "1", "number of failed particles (D = 1)", has_damage, sv_failed},
    {"broken_links", 1, "1", "virtual links: number of broken links (D_ij = 1), each counted once",
     has_links, sv_broken_links},
    {"damage_energy", 1, "J",
     "energy dissipated by damage: stored energy released as D grows, sum over particles of "
     "psi_eff dD V0 (part of internal_energy)",
     has_damage, sv_damage_work},
    {"contact_energy", 1, "J",
     "work done against contact forces: energy stored in the overlaps plus what contact "
     "dissipated; enters energy_balance like hourglass_energy",
     has_contact_work, sv_contact},
    {"contact_pairs", 1, "1", "number of particle pairs in contact (overlapping)", has_contact,
     sv_contact_pairs},
    {"rigid_contacts", 1, "1", "number of particles in contact with a rigid body (overlapping)",
     has_rigid, sv_rigid_contacts},
    {"crack_length", 1, "m",
     "growing cracks: in-plane length of the crack surface added since the start, summed over "
     "the tips (where the pairs are cut; docs/crack-growth.md)",
     has_crack_growth, sv_crack_length},
    {"crack_tip_advances", 1, "1", "growing cracks: tip advances so far, summed over the tips",
     has_crack_growth, sv_crack_advances},
    {"particle_count", 1, "1", "growing cracks: number of particles (splitting adds them)",
     has_crack_growth, sv_particle_count},
};
const size_t tlsph_nglobal_series = sizeof tlsph_global_series / sizeof *tlsph_global_series;

static const struct tlsph_series_column group_columns[] = {
    {"reaction_force", 3, "N", "force exerted by the constraint on the group's particles", NULL,
     NULL},
    {"displacement", 3, "m", "mean displacement of the group's particles", NULL, NULL},
};

static const struct tlsph_series_column gauge_columns[] = {
    {"engineering_stress", 1, "Pa",
     "mean axial reaction of the two groups / area, positive in tension", NULL, NULL},
    {"engineering_strain", 1, "1", "change of the distance between the groups' mean "
     "positions along the gauge axis / gauge length", NULL, NULL},
};

/* In enum tlsph_section_value order. */
static const struct tlsph_series_column section_columns[] = {
    {"max_principal_stress", 1, "Pa",
     "mean over the section's particles (reference-volume weighted) of the largest "
     "principal Cauchy stress", NULL, NULL},
    {"normal_stress", 1, "Pa", "mean of n.sigma.n over the section's particles", NULL, NULL},
    {"plastic_strain", 1, "1", "mean equivalent plastic strain over the section's particles",
     has_plasticity, NULL},
    {"damage", 1, "1", "mean damage over the section's particles", has_damage, NULL},
};

/* Rigid surfaces (walls): the reaction is the momentum their stops give the
 * bodies over a step, divided by the step (core/bc/wall.c). */
static const struct tlsph_series_column wall_columns[] = {
    {"reaction_force", 3, "N",
     "force exerted by the wall on the bodies: the momentum its stops gave them during the "
     "last step / the step", NULL, NULL},
    {"torque", 3, "N m", "torque of that force about the wall's point", NULL, NULL},
};

/* Items: every body (the force from the other bodies), then the body pairs
 * "<a>--<b>" (the force on a from b; contact.h tlsph_contact_pairs). */
static const struct tlsph_series_column contact_columns[] = {
    {"force", 3, "N",
     "contact force on the body from the other bodies, or for a pair <a>--<b> on body a from "
     "body b (last force evaluation)",
     NULL, NULL},
};

/* Rigid bodies (core/rigid/): their motion and what the particles exert on them. */
static const struct tlsph_series_column rigid_columns[] = {
    {"position", 3, "m", "the body's reference point (centroid; a plane: its point)", NULL, NULL},
    {"velocity", 3, "m/s", "velocity of the reference point", NULL, NULL},
    {"angular_velocity", 3, "rad/s", "angular velocity", NULL, NULL},
    {"force", 3, "N", "contact force the particles exert on the body (last force evaluation)",
     NULL, NULL},
    {"torque", 3, "N m", "torque of those forces about the reference point", NULL, NULL},
};

/* Probes (output.probes): the centre of mass of the particles they picked. */
static const struct tlsph_series_column probe_columns[] = {
    {"displacement", 3, "m",
     "displacement of the centre of mass of the probe's particles (mass-weighted mean of x - X)",
     NULL, NULL},
    {"velocity", 3, "m/s", "velocity of that centre of mass (momentum / mass)", NULL, NULL},
};

/* Extents (output.extents): how far their particles reach, at the outer edges
 * (centre +- half the spacing); in the order of enum tlsph_extent_value. */
static const struct tlsph_series_column extent_columns[] = {
    {"radius", 1, "m", "largest distance from the axis line of a centre, plus half its spacing "
     "(over the lowest layer with radius_over lowest_layer)", NULL, NULL},
    {"diameter", 1, "m", "twice the radius (a Taylor bar's foot diameter)", NULL, NULL},
    {"lower", 1, "m", "lowest coordinate along the axis from its point, minus half the spacing",
     NULL, NULL},
    {"upper", 1, "m", "highest coordinate along the axis, plus half the spacing", NULL, NULL},
    {"length", 1, "m", "upper - lower (a free body's length)", NULL, NULL},
};

/* Growing crack tips (crack_growth.tips, core/crack/crack_driver.h), named
 * tip0, tip1, ... in the scene's order. */
static const struct tlsph_series_column crack_tip_columns[] = {
    {"position", 3, "m", "the tip (reference configuration): the pre-crack's end, then the "
     "centre of the tip fibre", NULL, NULL},
    {"advances", 1, "1", "tip advances so far", NULL, NULL},
    {"length", 1, "m", "in-plane length of the crack surface this tip added", NULL, NULL},
};

static size_t crack_tip_count(const struct tlsph_model *m)
{
    return m->crack_driver ? m->crack_driver->ntips : 0;
}
static const char *crack_tip_item(const struct tlsph_model *m, size_t k)
{
    static const char *const names[TLSPH_MAX_GROWTH_TIPS] = {"tip0", "tip1", "tip2", "tip3",
                                                             "tip4", "tip5", "tip6", "tip7"};
    (void)m;
    return k < TLSPH_MAX_GROWTH_TIPS ? names[k] : NULL;
}
static void crack_tip_values(const struct tlsph_model *m, size_t k, double *out)
{
    const struct tlsph_crack_tip *t = &m->crack_driver->tip[k];
    for (int c = 0; c < 3; c++)
        out[c] = t->T[c];
    out[3] = (double)t->advances;
    out[4] = t->length;
}

static size_t probe_count(const struct tlsph_model *m) { return m->scene.nprobes; }
static const char *probe_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.probes[k].name;
}

static size_t extent_count(const struct tlsph_model *m) { return m->scene.nextents; }
static const char *extent_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.extents[k].name;
}

static size_t rigid_count(const struct tlsph_model *m)
{
    return m->rigid ? m->scene.nrigid : 0;
}
static const char *rigid_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.rigid[k].name;
}
static void rigid_values(const struct tlsph_model *m, size_t k, double *out)
{
    struct tlsph_rigid_report r;
    tlsph_rigid_report(m, k, &r);
    for (int c = 0; c < 3; c++) {
        out[c] = r.position[c];
        out[3 + c] = r.velocity[c];
        out[6 + c] = r.angular_velocity[c];
        out[9 + c] = r.force[c];
        out[12 + c] = r.torque[c];
    }
}

static size_t group_count(const struct tlsph_model *m) { return m->scene.nbcs; }
static size_t contact_count(const struct tlsph_model *m)
{
    return m->contact ? m->scene.nbodies + tlsph_contact_pairs(m) : 0;
}
static const char *contact_item(const struct tlsph_model *m, size_t k)
{
    const size_t nb = m->scene.nbodies;
    return k < nb ? m->scene.bodies[k].name : tlsph_contact_pair_name(m, k - nb);
}
static void contact_values(const struct tlsph_model *m, size_t k, double *out)
{
    const size_t nb = m->scene.nbodies;
    if (k < nb)
        tlsph_contact_body_force(m, k, out);
    else
        tlsph_contact_pair_force(m, k - nb, out);
}
static size_t gauge_count(const struct tlsph_model *m) { return m->scene.ngauges; }
static size_t section_count(const struct tlsph_model *m) { return m->scene.nsections; }

/* Only conditions that carry load (fixed, velocity) have a reaction to report. */
static const char *group_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.bcs[k].kind->carries_load ? m->scene.bcs[k].name : NULL;
}

static const char *wall_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.bcs[k].kind->reports_torque ? m->scene.bcs[k].name : NULL;
}

static const char *gauge_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.gauges[k].name;
}

static const char *section_item(const struct tlsph_model *m, size_t k)
{
    return m->scene.sections[k].name;
}

static void group_values(const struct tlsph_model *m, size_t k, double *out)
{
    const struct tlsph_group *g = &m->groups[k];
    for (int c = 0; c < 3; c++) {
        out[c] = g->reaction[c];
        out[3 + c] = g->displacement[c];
    }
}

static void wall_values(const struct tlsph_model *m, size_t k, double *out)
{
    const struct tlsph_group *g = &m->groups[k];
    for (int c = 0; c < 3; c++) {
        out[c] = g->reaction[c];
        out[3 + c] = g->torque[c];
    }
}

static void section_values(const struct tlsph_model *m, size_t k, double *out)
{
    double v[TLSPH_SECTION_NVALUES];
    tlsph_section_values(m, k, v);
    for (size_t c = 0; c < TLSPH_SECTION_NVALUES; c++)
        if (tlsph_series_present(&section_columns[c], m))
            *out++ = v[c];
}

const struct tlsph_series_family tlsph_series_families[] = {
    [TLSPH_FAMILY_GROUPS] = {"groups", 1, group_columns,
                             sizeof group_columns / sizeof *group_columns, group_count,
                             group_item, group_values},
    [TLSPH_FAMILY_GAUGES] = {"gauges", 0, gauge_columns,
                             sizeof gauge_columns / sizeof *gauge_columns, gauge_count,
                             gauge_item, tlsph_gauge_values},
    [TLSPH_FAMILY_SECTIONS] = {"sections", 0, section_columns,
                               sizeof section_columns / sizeof *section_columns, section_count,
                               section_item, section_values},
    [TLSPH_FAMILY_WALLS] = {"walls", 0, wall_columns, sizeof wall_columns / sizeof *wall_columns,
                            group_count, wall_item, wall_values},
    [TLSPH_FAMILY_CONTACTS] = {"contacts", 0, contact_columns,
                               sizeof contact_columns / sizeof *contact_columns, contact_count,
                               contact_item, contact_values},
    [TLSPH_FAMILY_RIGID] = {"rigid", 0, rigid_columns, sizeof rigid_columns / sizeof *rigid_columns,
                            rigid_count, rigid_item, rigid_values},
    [TLSPH_FAMILY_PROBES] = {"probes", 0, probe_columns,
                             sizeof probe_columns / sizeof *probe_columns, probe_count,
                             probe_item, tlsph_probe_values},
    [TLSPH_FAMILY_CRACK_TIPS] = {"crack_tips", 0, crack_tip_columns,
                                 sizeof crack_tip_columns / sizeof *crack_tip_columns,
                                 crack_tip_count, crack_tip_item, crack_tip_values},
    [TLSPH_FAMILY_EXTENTS] = {"extents", 0, extent_columns,
                              sizeof extent_columns / sizeof *extent_columns, extent_count,
                              extent_item, tlsph_extent_values},
};

int tlsph_series_present(const struct tlsph_series_column *c, const struct tlsph_model *m)
{
    return c->present == NULL || c->present(m);
}

size_t tlsph_global_series_width(const struct tlsph_model *m)
{
    size_t w = 0;
    for (size_t c = 0; c < tlsph_nglobal_series; c++)
        if (tlsph_series_present(&tlsph_global_series[c], m))
            w += (size_t)tlsph_global_series[c].ncomp;
    return w;
}

size_t tlsph_family_width(const struct tlsph_series_family *f, const struct tlsph_model *m)
{
    size_t w = 0;
    for (size_t c = 0; c < f->ncolumns; c++)
        if (tlsph_series_present(&f->columns[c], m))
            w += (size_t)f->columns[c].ncomp;
    return w;
}

void tlsph_global_series_values(const struct tlsph_model *m, double *out)
{
    for (size_t c = 0; c < tlsph_nglobal_series; c++) {
        const struct tlsph_series_column *col = &tlsph_global_series[c];
        if (!tlsph_series_present(col, m))
            continue;
        col->value(m, out);
        out += col->ncomp;
    }
}
