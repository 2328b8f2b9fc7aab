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

#include "scene/json_check.h"
#include "material/eos/eos.h"

enum { C0, S, GAMMA0 };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "c0", "s", "gamma0", NULL};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    double c0 = 0, s = 0, g = 0;
    bad |= jc_number(obj, "c0", 1, JC_POSITIVE, "m/s", pointer, &c0, err) < 0;
    bad |= jc_number(obj, "s", 1, JC_BETWEEN(0.0, 10.0), "1", pointer, &s, err) < 0;
    bad |= jc_number(obj, "gamma0", 0, JC_BETWEEN(0.0, 10.0), "1", pointer, &g, err) < 0;
    m->eos_params[C0] = c0;
    m->eos_params[S] = s;
    m->eos_params[GAMMA0] = g;
    return bad ? -1 : 0;
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
    .parse = parse,
    .pressure = pressure,
};
