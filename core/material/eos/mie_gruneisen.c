/* Mie-Grueneisen EOS, paper 000 eq. 37 without damage (damage enters in the
 * damage issue):
 *
 *   p = rho0 c0^2 (eta-1) [eta - Gamma0/2 (eta-1)] / [eta - S (eta-1)]^2 + Gamma0 rho0 e,
 *   eta = rho/rho0 = 1/J.
 *
 * p is positive in compression.  e is the specific internal energy (J/kg); the
 * paper writes Gamma0 e with e per unit volume, which is rho0 times ours.
 * Parameters: c0 bulk sound speed (m/s), s Hugoniot slope (1), gamma0 (1).
 * The Hugoniot denominator vanishes at eta = S/(S-1); a particle compressed that
 * far is reported by the stability check (det F and NaN tests), never clamped. */
#include <math.h>

#include "scene/keys.h"
#include "material/eos/eos.h"

enum { C0, S, GAMMA0 };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "c0", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m/s", .offset = TLSPH_PARAM(C0),
     .description = "bulk sound speed c0"},
    {.name = "s", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "1",
     .offset = TLSPH_PARAM(S), .description = "Hugoniot slope S"},
    {.name = "gamma0", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "1", .def = 0.0,
     .offset = TLSPH_PARAM(GAMMA0), .description = "Grueneisen gamma Gamma0"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/eos", "mie_gruneisen", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = m->eos_params};
    return tlsph_keys_read(obj, &table, pointer, &to, err);
}

static void pressure(const struct tlsph_material *m, double J, double e, double *p, double *K_t)
{
    const double rho0 = m->density, c0 = m->eos_params[C0], s = m->eos_params[S];
    const double g0 = m->eos_params[GAMMA0];
    const double eta = 1.0 / J, mu = eta - 1.0;
    const double num = mu * (eta - 0.5 * g0 * mu);
    const double den = eta - s * mu;
    const double k = rho0 * c0 * c0;
    *p = k * num / (den * den) + g0 * rho0 * e;
    /* dp/deta of the Hugoniot part; -J dp/dJ = eta dp/deta. */
    const double dnum = (eta - 0.5 * g0 * mu) + mu * (1.0 - 0.5 * g0);
    const double dden = 1.0 - s;
    const double dp = k * (dnum * den - 2.0 * num * dden) / (den * den * den);
    *K_t = eta * dp;
}

const struct tlsph_eos_model tlsph_eos_mie_gruneisen = {
    .name = "mie_gruneisen",
    .module = "eos:mie_gruneisen",
    .keys = &table,
    .parse = parse,
    .pressure = pressure,
};
