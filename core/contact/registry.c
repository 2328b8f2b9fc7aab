/* The table of contact laws (contact.h). */
#include "contact/contact.h"
#include "util/name_list.h"

/* One row per law: ROW(name) stands for tlsph_contact_<name>, whose .name is
 * "name".  The first row is the default. */
#define CONTACT_LAWS(ROW) ROW(penalty) ROW(pinball)

#define DECLARE(id) extern const struct tlsph_contact_law tlsph_contact_##id;
CONTACT_LAWS(DECLARE)

#define ENTRY(id) &tlsph_contact_##id,
static const struct tlsph_contact_law *const laws[] = {CONTACT_LAWS(ENTRY)};

/* "penalty, pinball" */
const char *tlsph_contact_names(void)
{
    return CONTACT_LAWS(TLSPH_LISTED) + 2;
}

const struct tlsph_contact_law *tlsph_contact_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_contact_names(), name);
    return k < 0 ? NULL : laws[k];
}

const struct tlsph_contact_law *tlsph_contact_default(void)
{
    return laws[0];
}
