/* The table of link criteria (link_criterion.h). */
#include "sph/link_criterion.h"
#include "util/name_list.h"

/* One row per criterion: ROW(name) stands for tlsph_link_<name>, whose .name is
 * "name". */
#define LINK_CRITERIA(ROW) ROW(plastic_strain) ROW(plastic_strain_softening) ROW(rankine)

#define DECLARE(id) extern const struct tlsph_link_criterion tlsph_link_##id;
LINK_CRITERIA(DECLARE)

#define ENTRY(id) &tlsph_link_##id,
static const struct tlsph_link_criterion *const criteria[] = {LINK_CRITERIA(ENTRY)};

const char *tlsph_link_criterion_names(void)
{
    return LINK_CRITERIA(TLSPH_LISTED) + 2;
}

const struct tlsph_link_criterion *tlsph_link_criterion_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_link_criterion_names(), name);
    return k < 0 ? NULL : criteria[k];
}
