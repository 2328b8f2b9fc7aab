/* The table of rigid shapes (rigid.h). */
#include "rigid/rigid.h"
#include "scene/parse_internal.h"
#include "util/name_list.h"

/* One row per shape: ROW(name) stands for tlsph_rigid_<name>, whose .name is
 * "name". */
#define RIGID_SHAPES(ROW) ROW(plane) ROW(box) ROW(sphere) ROW(cylinder) ROW(cone)

#define DECLARE(id) extern const struct tlsph_rigid_shape tlsph_rigid_##id;
RIGID_SHAPES(DECLARE)

#define ENTRY(id) &tlsph_rigid_##id,
static const struct tlsph_rigid_shape *const shapes[] = {RIGID_SHAPES(ENTRY)};

/* "plane, box, sphere, cylinder, cone" */
const char *tlsph_rigid_shape_names(void)
{
    return RIGID_SHAPES(TLSPH_LISTED) + 2;
}

const struct tlsph_rigid_shape *tlsph_rigid_shape_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_rigid_shape_names(), name);
    return k < 0 ? NULL : shapes[k];
}

int tlsph_rigid_read_shape(const json_t *obj, const struct tlsph_key_table *t, const char *key,
                           double point[3], struct tlsph_rigid_spec *r, const char *pointer,
                           struct tlsph_errors *err)
{
    int bad = tlsph_keys_unknown(obj, t, pointer, err) != 0;
    bad |= jc_vector(obj, key, 1, 3, "m", pointer, point, err) != 0;
    bad |=
        tlsph_keys_values(obj, t, pointer, &(struct tlsph_key_target){.base = r->size}, err) != 0;
    return bad ? -1 : 0;
}
