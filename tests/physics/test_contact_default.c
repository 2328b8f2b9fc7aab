/* Contact on by default (core/scene/parse_contact.c, docs/contact.md).
 *
 * - Two bodies without a "contact" block get the default contact (penalty
 *   law, its module listed; "contact": {"enabled": false} switches it off:
 *   test_contact); a one-body scene without damage has no contact phase at
 *   all (m->contact NULL).
 * - The t = 0 touching rule: particles of different bodies are accepted when
 *   r >= (1 - 1e-6)(s_i + s_j)/2.  Two 4 x 4 mm blocks face to face, 1 mm
 *   spacing: exactly one spacing apart, and closer by 1e-13 m (the round-off
 *   of a lattice origin), are accepted; 0.1 spacing into each other is refused
 *   with the pointer of the later body (/bodies/1); the same overlap with
 *   contact off is accepted (bodies that pass through each other may start
 *   overlapped).
 * - The validation's first-step estimate includes the contact step
 *   (core/contact/estimate.c): two 3-D steel blocks with a stiff pin-ball law
 *   (radius_factor 1, K_p = 1e4): the estimate is cfl x sqrt(m_eff / k) with, by
 *   hand, R = k h = support_factor x spacing / 2, the overlap delta =
 *   max(0.5 (2R), 2R - spacing), k = K_p 3/2 (G/2) sqrt(R/2 delta),
 *   m_eff = rho spacing^3 / 2, to 1e-12, and it is shorter than the material step
 *   (cfl x spacing / c); with the default penalty law between equal steel
 *   blocks the contact does not bind (line form: 1.13 spacing / c for nu = 0,
 *   longer than the material step for any nu) and the estimate is the
 *   material step, the same as with contact off.
 * - A damaging body with a pin-ball of radius factor 1.2 (balls of 1.2 h,
 *   reaching past the nearest non-neighbours at 2 spacings): its surface
 *   pairs start without contact (no pair overlapping, no contact force at
 *   setup) because their reach factors were lowered to their distance
 *   (contact/touch.c tlsph_contact_settle); some factor is below 1, so the
 *   rule acted. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact.h"
#include "contact/state.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

/* One or two steel blocks of 4 x 4 mm, the second's lattice origin at x =
 * origin (m), and the given contact block (or none: NULL). */
static void blocks(char *out, size_t size, int two, double origin, const char *contact)
{
    char second[512] = "";
    if (two)
        snprintf(second, sizeof second,
                 ",{\"name\":\"b\",\"material\":\"steel\",\"spacing\":0.001,"
                 "\"origin\":[%.17g,0,0],"
                 "\"geometry\":{\"box\":{\"min\":[%.17g,0,0],\"max\":[0.008,0.004,0]}}}",
                 origin, origin);
    snprintf(out, size,
             "{\"dimension\":2,\"time\":{\"end\":1e-6},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3}},"
             "\"bodies\":[{\"name\":\"a\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.004,0.004,0]}}}%s]%s%s}",
             second, contact ? ",\"contact\":" : "", contact ? contact : "");
}

START_TEST(two_bodies_get_contact_by_default)
{
    char json[2048];
    blocks(json, sizeof json, 1, 0.004, NULL);
    struct tlsph_model *m = build_model(json);
    ck_assert(m->contact != NULL);
    ck_assert(model_has_module(m, "contact:penalty_hertz"));
    tlsph_model_free(m);
    /* "enabled": false: test_contact, no_contact_block_no_contact_state */
}
END_TEST

START_TEST(one_body_without_damage_has_no_contact)
{
    char json[2048];
    blocks(json, sizeof json, 0, 0.0, NULL);
    struct tlsph_model *m = build_model(json);
    ck_assert(m->contact == NULL);
    tlsph_model_free(m);
}
END_TEST

START_TEST(touching_bodies_accepted_overlapping_refused)
{
    char json[2048], ptr[256];
    /* exactly one spacing apart, and 1e-13 m closer (round-off) */
    const double touching[] = {0.004, 0.004 - 1e-13};
    for (size_t k = 0; k < 2; k++) {
        blocks(json, sizeof json, 1, touching[k], NULL);
        struct tlsph_model *m = try_build_model(json, ptr, sizeof ptr);
        ck_assert_msg(m != NULL, "face-to-face blocks (origin %.17g) refused at %s", touching[k],
                      ptr);
        ck_assert(m->contact != NULL);
        tlsph_model_free(m);
    }
    /* 0.1 spacing into each other */
    blocks(json, sizeof json, 1, 0.0039, NULL);
    struct tlsph_model *m = try_build_model(json, ptr, sizeof ptr);
    ck_assert(m == NULL);
    ck_assert_str_eq(ptr, "/bodies/1");
    /* without contact the overlap is the user's business */
    blocks(json, sizeof json, 1, 0.0039, "{\"enabled\":false}");
    m = try_build_model(json, ptr, sizeof ptr);
    ck_assert(m != NULL);
    tlsph_model_free(m);
}
END_TEST

/* Two 3-D steel blocks of 4 x 4 x 4 mm, face to face, with the given contact
 * block (or none); returns the validation's first step. */
static double validated_step(const char *contact, struct tlsph_scene *out)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":1e-6,\"cfl\":0.3},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3}},"
             "\"bodies\":[{\"name\":\"a\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.004,0.004,0.004]}}},"
             "{\"name\":\"b\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0.004,0,0],\"max\":[0.008,0.004,0.004]}}}]"
             "%s%s}",
             contact ? ",\"contact\":" : "", contact ? contact : "");
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    const int rc = tlsph_scene_parse(json, strlen(json), out, &err);
    for (size_t k = 0; k < err.count; k++)
        fprintf(stderr, "scene error: %s: %s\n", err.items[k].pointer, err.items[k].message);
    tlsph_errors_free(&err);
    ck_assert_int_eq(rc, 0);
    return out->estimated_dt;
}

START_TEST(validation_estimates_the_contact_step)
{
    struct tlsph_scene s;
    const double off = validated_step("{\"enabled\":false}", &s);
    const struct tlsph_material *mat = &s.materials[0];
    const double material = s.cfl * 0.001 / mat->wave_speed;
    const double G = mat->shear_modulus, rho = mat->density, support = s.support_factor;
    tlsph_scene_free(&s);
    ck_assert_msg(fabs(off / material - 1.0) < 1e-12, "no contact: %.15g, material %.15g", off,
                  material);
    const double penalty = validated_step(NULL, &s);
    tlsph_scene_free(&s);
    ck_assert_msg(penalty == off, "default penalty binds: %.15g vs %.15g", penalty, off);

    const double est = validated_step(
        "{\"law\":{\"type\":\"pinball\",\"radius_factor\":1,\"scale_factor\":1e4}}", &s);
    const double cfl = s.cfl;
    tlsph_scene_free(&s);
    const double R = 0.5 * support * 0.001, delta = fmax(0.5 * 2.0 * R, 2.0 * R - 0.001);
    const double k = 1e4 * 1.5 * (G / 2.0) * sqrt(R / 2.0 * delta);
    const double expect = cfl * sqrt(0.5 * rho * 1e-9 / k);
    fprintf(stderr, "validation step: pin-ball K_p 1e4 %.6e s (by hand %.6e s), material %.6e s\n",
            est, expect, material);
    ck_assert_msg(fabs(est / expect - 1.0) < 1e-12, "estimate %.15g, by hand %.15g", est, expect);
    ck_assert(est < material);
}
END_TEST

START_TEST(a_body_does_not_start_in_contact_with_itself)
{
    const char *json =
        "{\"dimension\":2,\"time\":{\"end\":1e-6},"
        "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2e11,"
        "\"poisson_ratio\":0.3,\"strength\":{\"type\":\"linear_hardening\","
        "\"yield_stress\":3e8,\"hardening_modulus\":5e8},"
        "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.05,\"d2\":0,\"d3\":0}}},"
        "\"bodies\":[{\"name\":\"a\",\"material\":\"steel\",\"spacing\":0.001,"
        "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.008,0.004,0]}}}],"
        "\"contact\":{\"law\":{\"type\":\"pinball\",\"radius_factor\":1.2,"
        "\"scale_factor\":100}}}";
    struct tlsph_model *m = build_model(json);
    const struct tlsph_contact *c = m->contact;
    ck_assert(c != NULL && c->touch != NULL);
    double lowest = 1.0, force = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        lowest = fmin(lowest, c->reach[i]);
        force = fmax(force, fabs(c->f_old[3 * i]) + fabs(c->f_old[3 * i + 1]));
    }
    fprintf(stderr, "pin-ball 1.2 h in one body: %zu candidates, lowest reach factor %.4f, "
                    "%zu pairs in contact, largest contact force %g N/m\n",
            tlsph_contact_candidates(m), lowest, tlsph_contact_active(m), force);
    ck_assert(tlsph_contact_candidates(m) > 0);
    ck_assert(lowest < 1.0);
    ck_assert_uint_eq(tlsph_contact_active(m), 0);
    ck_assert(force == 0.0);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("contact_default", 120, two_bodies_get_contact_by_default,
                 one_body_without_damage_has_no_contact,
                 touching_bodies_accepted_overlapping_refused,
                 validation_estimates_the_contact_step,
                 a_body_does_not_start_in_contact_with_itself)
