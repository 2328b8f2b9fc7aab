/* posix_spawn attributes for a helper, see spawn_attr.h. */
#include "spawn_attr.h"

#include <signal.h>

int spawn_attr_defaults(posix_spawnattr_t *at)
{
    int e = posix_spawnattr_init(at);
    if (e)
        return e;
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    sigdelset(&all, SIGKILL);
    sigdelset(&all, SIGSTOP);
    e = posix_spawnattr_setsigmask(at, &none);
    e = e ? e : posix_spawnattr_setsigdefault(at, &all);
    e = e ? e : posix_spawnattr_setflags(at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    if (e)
        posix_spawnattr_destroy(at);
    return e;
}
