/* Growing the particle arrays all or nothing (particles_grow.h). */
#include "run/particles_grow.h"

#include <stdlib.h>
#include <string.h>

/* Every pointer member of struct tlsph_particles must be listed below: a new
 * field changes the size and stops the build here until it is added. */
_Static_assert(sizeof(struct tlsph_particles) == 2 * sizeof(size_t) + 32 * sizeof(void *),
               "struct tlsph_particles changed: list the new array in tlsph_particle_arrays");

size_t tlsph_particle_arrays(struct tlsph_particles *p, struct tlsph_grow_array *out)
{
    const struct tlsph_grow_array all[] = {
        {(void **)&p->id, sizeof *p->id},
        {(void **)&p->body, sizeof *p->body},
        {(void **)&p->X, 3 * sizeof(double)},
        {(void **)&p->x, 3 * sizeof(double)},
        {(void **)&p->v, 3 * sizeof(double)},
        {(void **)&p->f, 3 * sizeof(double)},
        {(void **)&p->vol0, sizeof(double)},
        {(void **)&p->mass, sizeof(double)},
        {(void **)&p->h, sizeof(double)},
        {(void **)&p->Linv, 9 * sizeof(double)},
        {(void **)&p->F, 9 * sizeof(double)},
        {(void **)&p->Fdot, 9 * sizeof(double)},
        {(void **)&p->P_tilde, 9 * sizeof(double)},
        {(void **)&p->sigma, 6 * sizeof(double)},
        {(void **)&p->e, sizeof(double)},
        {(void **)&p->f_hourglass, 3 * sizeof(double)},
        {(void **)&p->f_viscous, 3 * sizeof(double)},
        {(void **)&p->eps_p, sizeof(double)},
        {(void **)&p->plastic_strain, 6 * sizeof(double)},
        {(void **)&p->eps_p_rate, sizeof(double)},
        {(void **)&p->yield_stress, sizeof(double)},
        {(void **)&p->hg_scale, sizeof(double)},
        {(void **)&p->T, sizeof(double)},
        {(void **)&p->spacing, sizeof(double)},
        {(void **)&p->damage, sizeof(double)},
        {(void **)&p->damage_init, sizeof(double)},
        {(void **)&p->void_fraction, sizeof(double)},
        {(void **)&p->void_fstar, sizeof(double)},
        {(void **)&p->void_nucleated, sizeof(double)},
        {(void **)&p->void_shear, sizeof(double)},
        {(void **)&p->crack_gradient, 9 * sizeof(double)},
        {(void **)&p->F_carry, 9 * sizeof(double)},
    };
    _Static_assert(sizeof all / sizeof all[0] == 32, "one row per array");
    size_t count = 0;
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (*all[k].ptr)
            out[count++] = all[k];
    return count;
}

static void *plain_malloc(size_t bytes, void *ctx)
{
    (void)ctx;
    return malloc(bytes);
}

int tlsph_grow_arrays(const struct tlsph_grow_array *a, size_t count, size_t n, size_t cap,
                      tlsph_grow_alloc_fn alloc, void *ctx)
{
    if (!alloc)
        alloc = plain_malloc;
    if (n > cap || count > TLSPH_MAX_PARTICLE_ARRAYS)
        return -1;
    void *fresh[TLSPH_MAX_PARTICLE_ARRAYS];
    for (size_t k = 0; k < count; k++) {
        if (cap > SIZE_MAX / a[k].elem || !(fresh[k] = alloc((cap ? cap : 1) * a[k].elem, ctx))) {
            for (size_t q = 0; q < k; q++)
                free(fresh[q]);
            return -1;
        }
    }
    /* all allocated: nothing can fail from here */
    for (size_t k = 0; k < count; k++) {
        if (n)
            memcpy(fresh[k], *a[k].ptr, n * a[k].elem);
        free(*a[k].ptr);
        *a[k].ptr = fresh[k];
    }
    return 0;
}

int tlsph_particles_reserve(struct tlsph_model *m, size_t need, tlsph_grow_alloc_fn alloc,
                            void *ctx)
{
    struct tlsph_particles *p = &m->p;
    if (need <= p->cap)
        return 0;
    size_t cap = p->cap > SIZE_MAX / 2 ? need : 2 * p->cap;
    if (cap < need)
        cap = need;
    struct tlsph_grow_array a[TLSPH_MAX_PARTICLE_ARRAYS];
    const size_t count = tlsph_particle_arrays(p, a);
    if (tlsph_grow_arrays(a, count, p->n, cap, alloc, ctx) != 0)
        return -1;
    for (size_t k = 0; k < count; k++)
        m->bytes_allocated += (cap - p->cap) * a[k].elem;
    p->cap = cap;
    return 0;
}

void tlsph_particles_open(struct tlsph_model *m, size_t at, size_t k)
{
    struct tlsph_particles *p = &m->p;
    struct tlsph_grow_array a[TLSPH_MAX_PARTICLE_ARRAYS];
    const size_t count = tlsph_particle_arrays(p, a);
    for (size_t q = 0; q < count; q++) {
        char *base = *a[q].ptr;
        memmove(base + (at + k) * a[q].elem, base + at * a[q].elem, (p->n - at) * a[q].elem);
    }
    p->n += k;
}
