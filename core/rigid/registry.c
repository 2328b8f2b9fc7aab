/* The table of rigid shapes (rigid.h). */
#include "rigid/rigid.h"
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
