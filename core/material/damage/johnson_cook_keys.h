/* The scene keys and checks the two Johnson-Cook failure-strain criteria share:
 * paper 000's initiation criterion (johnson_cook.c, eqs. 43-44) and paper 003's
 * accumulated damage with a critical value (johnson_cook_accumulated.c, eq. 62).
 * Both read the parameters into m->damage.params in the layout below; they
 * differ in the rate factor and in what happens when the sum is reached
 * (docs/damage.md). */
#ifndef TLSPH_DAMAGE_JOHNSON_COOK_KEYS_H
#define TLSPH_DAMAGE_JOHNSON_COOK_KEYS_H

#include <math.h>

#include "scene/keys.h"
#include "material/damage/damage.h"

/* m->damage.params slots; JC_DC only for the accumulated criterion */
enum { JC_D1, JC_D2, JC_D3, JC_D4, JC_EPSDOT0, JC_D5, JC_TREF, JC_TMELT, JC_DC };

/* clang-format off */
#define JC_FAILURE_KEYS_D123                                                                   \
    {.name = "d1", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                     \
     .range = {0.0, 1e3, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "(dimensionless strain)", \
     .offset = TLSPH_PARAM(JC_D1), .description = "failure-strain constant D1"},              \
    {.name = "d2", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                     \
     .range = {0.0, 1e3, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "(dimensionless strain)", \
     .offset = TLSPH_PARAM(JC_D2),                                                             \
     .description = "failure-strain coefficient D2; d1 and d2 not both 0"},                   \
    {.name = "d3", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                     \
     .range = {-1e3, 1e3, JC_CLOSED, JC_CLOSED}, .unit = "1", .offset = TLSPH_PARAM(JC_D3),  \
     .description = "triaxiality exponent D3"}

#define JC_FAILURE_KEYS_RATE                                                                   \
    {.name = "d4", .kind = TLSPH_KEY_NUMBER, .range = {-10.0, 10.0, JC_CLOSED, JC_CLOSED},    \
     .unit = "1", .term = TLSPH_FLOW_RATE, .offset = TLSPH_PARAM(JC_D4),                      \
     .description = "strain-rate coefficient D4; absent = no rate term"},                     \
    {.name = "reference_strain_rate", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,  \
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "1/s", .with = "d4",                     \
     .offset = TLSPH_PARAM(JC_EPSDOT0), .description = "reference plastic strain rate epsdot_0"}

#define JC_FAILURE_KEYS_THERMAL                                                                \
    {.name = "d5", .kind = TLSPH_KEY_NUMBER, .range = {-1.0, 1e3, JC_OPEN, JC_CLOSED},        \
     .unit = "1", .term = TLSPH_FLOW_THERMAL, .offset = TLSPH_PARAM(JC_D5),                   \
     .description = "thermal coefficient D5; absent = no thermal term; needs the material's " \
                    "thermal block"},                                                          \
    {.name = "reference_temperature", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,  \
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "K", .with = "d5",                       \
     .offset = TLSPH_PARAM(JC_TREF), .description = "reference temperature T_ref of T*"},     \
    {.name = "melting_temperature", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,    \
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "K", .with = "d5",                       \
     .offset = TLSPH_PARAM(JC_TMELT),                                                          \
     .description = "melting temperature T_melt of T*, above T_ref"}
/* clang-format on */

/* Reads obj with table into m->damage and checks what the table cannot state:
 * d1 and d2 not both 0 (eps_f > 0 at every triaxiality), T_melt > T_ref and a
 * thermal block with d5.  Returns 0 or -1 (each problem reported). */
int tlsph_damage_jc_read(const json_t *obj, const struct tlsph_key_table *table,
                         struct tlsph_material *m, const char *pointer, struct tlsph_errors *err);

/* The homologous temperature T* = (T - T_ref)/(T_melt - T_ref) of the failure
 * strain's thermal factor, clamped to [0, 1] as the JC flow law's convention:
 * no effect below T_ref, T* = 1 at and above T_melt. */
static inline double tlsph_damage_jc_homologous(const double *q, double T)
{
    const double Ts = (T - q[JC_TREF]) / (q[JC_TMELT] - q[JC_TREF]);
    return fmin(fmax(Ts, 0.0), 1.0);
}

#endif
