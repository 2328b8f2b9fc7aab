#include "util/name_list.h"

#include <string.h>

int tlsph_name_list_index(const char *list, const char *name)
{
    const size_t len = strlen(name);
    for (int k = 0;; k++) {
        const char *sep = strstr(list, ", ");
        const size_t n = sep ? (size_t)(sep - list) : strlen(list);
        if (n == len && memcmp(list, name, len) == 0)
            return k;
        if (!sep)
            return -1;
        list = sep + 2;
    }
}
