/* A rigid body's "motion" (rigid.h): "prescribed" (velocity and angular
 * velocity as expressions of t; the default, at rest) or "free" (mass or
 * density, initial velocities, inertia from the shape or given). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rigid/rigid.h"
#include "scene/parse_internal.h"
#include "util/mat3.h"
#include "util/name_list.h"

/* clang-format off */
static const struct tlsph_key prescribed_keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_RIGID_VECTOR("velocity", "m/s", "velocity of the reference point, 3 items, each a "
                                          "number or an expression of t (s); absent = at rest"),
    TLSPH_RIGID_VECTOR("angular_velocity", "rad/s", "angular velocity about the reference point, "
                                                    "3 items, each a number or an expression of "
                                                    "t (s); absent = 0"),
};
static const struct tlsph_key free_keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "mass", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "kg", .said = "kg (kg/m in 2-D)", .offset = offsetof(struct tlsph_rigid_spec, mass),
     .description = "mass (per metre of thickness in 2-D); exactly one of mass and density"},
    {.name = "density", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "kg/m^3", .offset = TLSPH_KEY_NOWHERE,
     .description = "density: mass = density x the shape's volume; exactly one of mass and "
                    "density"},
    TLSPH_RIGID_VECTOR("velocity", "m/s", "initial velocity of the centroid, 3 numbers; absent "
                                          "= 0"),
    TLSPH_RIGID_VECTOR("angular_velocity", "rad/s", "initial angular velocity, 3 numbers (2-D: "
                                                    "about z only); absent = 0"),
    TLSPH_RIGID_VECTOR("inertia", "kg m^2", "inertia tensor about the centroid at t = 0, [xx, "
                                            "yy, zz, xy, xz, yz], positive definite (2-D: zz > "
                                            "0, per metre, the others ignored); absent = the "
                                            "shape's, of uniform density"),
};
static const struct tlsph_key_table prescribed_table =
    TLSPH_KEY_TABLE("/rigid_bodies/*/motion", "prescribed", prescribed_keys);
static const struct tlsph_key_table free_table =
    TLSPH_KEY_TABLE("/rigid_bodies/*/motion", "free", free_keys);
/* clang-format on */

#define MOTIONS(ROW) ROW(prescribed) ROW(free)
static const struct tlsph_rigid_motion_type motions[] = {
    {"prescribed", &prescribed_table},
    {"free", &free_table},
};

const char *tlsph_rigid_motion_names(void)
{
    return MOTIONS(TLSPH_LISTED) + 2;
}

const struct tlsph_rigid_motion_type *tlsph_rigid_motion_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_rigid_motion_names(), name);
    return k < 0 ? NULL : &motions[k];
}

/* Prescribed "velocity" or "angular_velocity" (key) into ex[], set[]; in 2-D
 * the components off the plane's motion (off_plane[c]) must be null or 0. */
static int parse_expressions(const json_t *obj, const char *key, const char *unit,
                             const int off_plane[3], const struct tlsph_scene *s,
                             struct tlsph_expr *ex, int *set, const char *P,
                             struct tlsph_errors *err)
{
    if (!json_object_get(obj, key))
        return 0;
    return tlsph_scene_time_vector(obj, key, unit, "taken as 0", off_plane, s, ex, set, P, err) < 0 ? -1
                                                                                          : 0;
}

/* A free body's constant vector (velocity, angular_velocity). */
static int parse_vector(const json_t *obj, const char *key, const char *unit, const int skip[3],
                        double out[3], const char *P, struct tlsph_errors *err)
{
    const int rc = jc_vector(obj, key, 0, 3, unit, P, out, err);
    if (rc != 0)
        return rc < 0 ? -1 : 0;
    for (int k = 0; k < 3; k++)
        if (skip[k] && out[k] != 0.0) {
            char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, P, key);
            tlsph_pointer_index(q, sizeof q, p, (size_t)k);
            tlsph_errors_add(err, q,
                             "in a 2-D scene this component of '%s' must be 0 (%s): "
                             "the motion stays in the x-y plane",
                             key, unit);
            return -1;
        }
    return 0;
}

/* The inertia of a free body: given, or the shape's (uniform density),
 * rotated into the t = 0 frame: I = A diag A^T. */
static int free_inertia(const json_t *obj, const struct tlsph_scene *s, struct tlsph_rigid_spec *r,
                        const char *P, struct tlsph_errors *err)
{
    double g[6];
    const int rc = jc_vector(obj, "inertia", 0, 6, "kg m^2", P, g, err);
    if (rc < 0)
        return -1;
    memset(r->inertia, 0, sizeof r->inertia);
    if (rc == 0) {
        const double I[9] = {g[0], g[3], g[4], g[3], g[1], g[5], g[4], g[5], g[2]};
        double lam[3], Q[9];
        sym3_eigen(I, lam, Q);
        const int ok =
            s->dimension == 2 ? g[2] > 0.0 : lam[0] > 0.0 && lam[1] > 0.0 && lam[2] > 0.0;
        if (!ok) {
            char p[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, P, "inertia");
            tlsph_errors_add(err, p, "the inertia tensor must be %s (kg m^2)",
                             s->dimension == 2 ? "given with zz > 0" : "positive definite");
            return -1;
        }
        if (s->dimension == 2)
            r->inertia[8] = g[2];
        else
            memcpy(r->inertia, I, sizeof I);
        return 0;
    }
    double d[3];
    r->shape->mass_properties(r, s->dimension, d);
    if (s->dimension == 2) {
        r->inertia[8] = r->mass * d[2];
        return 0;
    }
    const double *A = r->axes;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                r->inertia[3 * i + j] += A[3 * i + k] * r->mass * d[k] * A[3 * j + k];
    return 0;
}

static int parse_free(const json_t *obj, const struct tlsph_scene *s, struct tlsph_rigid_spec *r,
                      const int vskip[3], const int wskip[3], const char *P,
                      struct tlsph_errors *err)
{
    if (!r->shape->has_volume) {
        tlsph_key_error(err, P, "type",
                        "a %s has no volume and cannot move freely: use "
                        "\"prescribed\" motion",
                        r->shape->name);
        return -1;
    }
    int bad = tlsph_keys_read(obj, &free_table, P, &(struct tlsph_key_target){.base = r}, err) != 0;
    const json_t *mass = json_object_get(obj, "mass"), *rho = json_object_get(obj, "density");
    if (!mass == !rho) {
        tlsph_errors_add(err, P,
                         "a free rigid body needs exactly one of 'mass' (kg; kg/m in 2-D) "
                         "and 'density' (kg/m^3), got %s",
                         mass ? "both" : "neither");
        return -1;
    }
    bad |= parse_vector(obj, "velocity", "m/s", vskip, r->v0, P, err) != 0;
    bad |= parse_vector(obj, "angular_velocity", "rad/s", wskip, r->w0, P, err) != 0;
    if (bad)
        return -1;
    if (rho) {
        double d[3];
        r->mass = json_number_value(rho) * r->shape->mass_properties(r, s->dimension, d);
    }
    return free_inertia(obj, s, r, P, err);
}

int tlsph_rigid_parse_motion(const json_t *entry, const struct tlsph_scene *s,
                             struct tlsph_rigid_spec *r, const char *pointer,
                             struct tlsph_errors *err)
{
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "motion");
    r->motion = TLSPH_RIGID_PRESCRIBED;
    const json_t *obj = json_object_get(entry, "motion");
    if (!obj)
        return 0; /* at rest */
    if (!json_is_object(obj)) {
        tlsph_errors_add(err, P,
                         "'motion' must be an object {\"type\": \"prescribed\" | \"free\", "
                         "...}, got %s",
                         jc_type_name(obj));
        return -1;
    }
    char type[64];
    if (jc_string(obj, "type", 1, P, type, sizeof type, err) != 0)
        return -1;
    const struct tlsph_rigid_motion_type *mt = tlsph_rigid_motion_find(type);
    if (!mt) {
        tlsph_key_error(err, P, "type", "unknown motion type '%s' (accepted: %s)", type,
                        tlsph_rigid_motion_names());
        return -1;
    }
    const int two = s->dimension == 2;
    const int vskip[3] = {0, 0, two}, wskip[3] = {two, two, 0};
    if (mt == &motions[1]) {
        r->motion = TLSPH_RIGID_FREE;
        return parse_free(obj, s, r, vskip, wskip, P, err);
    }
    int bad = tlsph_keys_unknown(obj, &prescribed_table, P, err) != 0;
    bad |= parse_expressions(obj, "velocity", "m/s", vskip, s, r->velocity, r->velocity_set, P,
                             err) != 0;
    bad |= parse_expressions(obj, "angular_velocity", "rad/s", wskip, s, r->angular_velocity,
                             r->angular_set, P, err) != 0;
    return bad ? -1 : 0;
}

void tlsph_rigid_specs_free(struct tlsph_rigid_spec *r, size_t n)
{
    for (size_t k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            tlsph_expr_free(&r[k].velocity[c]);
            tlsph_expr_free(&r[k].angular_velocity[c]);
        }
    free(r);
}
