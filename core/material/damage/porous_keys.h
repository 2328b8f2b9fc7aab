/* The scene keys of the Gurson family (porous.h), one definition each, for
 * the rows' tables (gurson.c, gtn_aravas.c, sm_gurson.c, m_gurson.c).
 * Defaults: the calibrated set of paper 003's Table 1 (Normal Strength steel);
 * the fracture defaults are its crack criteria of §6.1 (f_p = 0.0135 for its
 * models 1-4, eps_p = 0.35 for the fifth). */
#ifndef TLSPH_DAMAGE_POROUS_KEYS_H
#define TLSPH_DAMAGE_POROUS_KEYS_H

#include "scene/keys.h"
#include "material/damage/damage.h"
#include "material/damage/porous.h"

/* clang-format off */
#define POROUS_NUMBER(key, lo, hi, lo_end, hi_end, default_, slot, text)                     \
    {.name = (key), .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,                      \
     .range = {(lo), (hi), (lo_end), (hi_end)}, .unit = "1", .def = (default_),               \
     .offset = TLSPH_PARAM(slot), .description = (text)}

#define POROUS_KEY_Q(key, default_, slot, text)                                                \
    POROUS_NUMBER(key, 0.0, 10.0, JC_OPEN, JC_CLOSED, default_, slot, text)

#define POROUS_KEY_F0                                                                          \
    POROUS_NUMBER("initial_void_fraction", 0.0, 1.0, JC_CLOSED, JC_OPEN, 0.0025, POR_F0,      \
                  "initial void volume fraction f0, below fracture_void_fraction (and "       \
                  "critical_void_fraction where the model has one); Table 1: 0.0025")

#define POROUS_KEY_COALESCENCE                                                                 \
    POROUS_NUMBER("critical_void_fraction", 0.0, 1.0, JC_OPEN, JC_OPEN, 0.021, POR_FC,       \
                  "void fraction f_c where coalescence starts (eq. 45), below "                \
                  "failure_void_fraction and 1/q1; Table 1: 0.021"),                           \
    POROUS_NUMBER("failure_void_fraction", 0.0, 1.0, JC_OPEN, JC_OPEN, 0.2109, POR_FF,       \
                  "void fraction f_f where f* reaches 1/q1 (eq. 45); Table 1: 0.2109")

#define POROUS_KEY_SHEAR                                                                       \
    POROUS_NUMBER("shear_coefficient", 0.0, 100.0, JC_CLOSED, JC_CLOSED, 1.0, POR_KW,        \
                  "shear growth coefficient k_w (eqs. 49, 52); Table 1: 1.0")

#define POROUS_KEY_FRACTURE                                                                    \
    {.name = "fracture_criterion", .kind = TLSPH_KEY_CHOICE, .flags = TLSPH_KEY_DEFAULT,       \
     .choices = tlsph_porous_criteria, .def = POROUS_FRACTURE_VOID_FRACTION, .size = 32,      \
     .noun = "fracture criterion", .offset = TLSPH_PARAM(POR_CRITERION),                      \
     .description = "what fails the point: void_fraction (f reaches fracture_void_fraction) "  \
                    "or plastic_strain (the matrix plastic strain reaches "                    \
                    "fracture_plastic_strain); either way it fails when the surface has "     \
                    "shrunk to 1e-3 of the matrix strength"},                                  \
    POROUS_NUMBER("fracture_void_fraction", 0.0, 1.0, JC_OPEN, JC_CLOSED, 0.0135, POR_FP,    \
                  "critical void fraction f_p of the void_fraction criterion; paper 003 "      \
                  "§6.1: 0.0135"),                                                             \
    POROUS_NUMBER("fracture_plastic_strain", 0.0, 100.0, JC_OPEN, JC_CLOSED, 0.35, POR_EC,   \
                  "critical matrix plastic strain of the plastic_strain criterion; paper "    \
                  "003 §6.1 (fifth variant): 0.35"),                                           \
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REFUSED,                \
     .description = "refused: the damage of a porous model comes from its void fraction"}
/* clang-format on */

/* clang-format off */
/* "nucleation": {amplitude, mean_strain, deviation} (eqs. 46-48), Table 1's
 * values when absent; its table, named `nucleation_table`, in the row's file
 * (each row's table names its model). */
#define POROUS_NUCLEATION_TABLE(model)                                                         \
    static const struct tlsph_key nucleation_keys[] = {                                        \
        POROUS_NUMBER("amplitude", 0.0, 1.0, JC_CLOSED, JC_OPEN, 0.02, POR_FN,                \
                      "nucleated void volume fraction f_N (eq. 48); 0 = no nucleation; "      \
                      "Table 1: 0.02"),                                                        \
        POROUS_NUMBER("mean_strain", 0.0, 10.0, JC_CLOSED, JC_CLOSED, 0.55, POR_EN,           \
                      "mean matrix plastic strain of nucleation eps_N; Table 1: 0.55"),        \
        POROUS_NUMBER("deviation", 0.0, 10.0, JC_OPEN, JC_CLOSED, 0.2, POR_SN,                \
                      "standard deviation s_N; Table 1: 0.2"),                                 \
    };                                                                                         \
    static const struct tlsph_key_table nucleation_table =                                     \
        TLSPH_KEY_TABLE("/materials/*/damage/nucleation", model, nucleation_keys)

#define POROUS_KEY_NUCLEATION                                                                  \
    {.name = "nucleation", .kind = TLSPH_KEY_OBJECT, .table = &nucleation_table,               \
     .description = "strain-controlled nucleation df = A_N d eps_M (eqs. 46-48); absent = "   \
                    "Table 1's values"}
/* clang-format on */

/* clang-format off */
/* The keys of the GTN-like rows (gtn_aravas, sm_gurson, m_gurson): the
 * surface's factors, f0, coalescence and nucleation (its table first, by
 * POROUS_NUCLEATION_TABLE). */
#define POROUS_KEYS_GTN                                                                        \
    POROUS_KEY_Q("q1", 2.5, POR_Q1, "yield-surface factor q1 (eq. 43); Table 1: 2.5"),          \
    POROUS_KEY_Q("q2", 1.0, POR_Q2, "yield-surface factor q2 (eq. 43); Table 1: 1.0"),          \
    POROUS_KEY_Q("q3", 3.25, POR_Q3, "yield-surface factor q3 (eq. 43); Table 1: 3.25"),        \
    POROUS_KEY_F0, POROUS_KEY_COALESCENCE, POROUS_KEY_NUCLEATION

/* The row of model `id` (its descriptor tlsph_damage_<id>) on the key table
 * `table` of its file, with the shear term `shear` (POROUS_SHEAR_*). */
#define POROUS_ROW(id, shear)                                                                  \
    static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,         \
                     struct tlsph_errors *err)                                                 \
    {                                                                                          \
        return tlsph_porous_parse(obj, m, pointer, &table, (shear), err);                      \
    }                                                                                          \
    const struct tlsph_damage_model tlsph_damage_##id = {                                      \
        .name = #id, .module = "damage:" #id, .keys = &table, .porous = 1,                     \
        .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION | TLSPH_DAMAGE_FIELD_POROUS,                \
        .parse = parse, .point_update = tlsph_porous_point_update,                             \
        .point_init = tlsph_porous_point_init}
/* clang-format on */

extern const struct tlsph_key_choice tlsph_porous_criteria[];

/* Reads a row's table into m->damage.params and makes the checks of
 * tlsph_porous_check; `shear` is the row's POROUS_SHEAR_*.  Returns 0 or -1. */
int tlsph_porous_parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                       const struct tlsph_key_table *table, int shear, struct tlsph_errors *err);

#endif
