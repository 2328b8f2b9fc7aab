/* The damage-aware approximation (paper 000 eqs. 33-35): its row in the table
 * of crack treatments.  The per-pair pieces and the paper's equations are in
 * damage_aware.h. */
#include "sph/damage_aware.h"

const struct tlsph_crack_model tlsph_crack_damage_aware = {
    .name = "damage_aware",
    .module = "approximation:damage_aware",
    .scene = TLSPH_CRACK_DAMAGE_AWARE,
    .variant = TLSPH_APPROX_DAMAGE_AWARE,
    .fields = TLSPH_CRACK_FIELD_GRADIENT, /* the untransmitted gradient of eq. 34 */
};
