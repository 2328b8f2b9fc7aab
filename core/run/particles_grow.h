/* Growing the particle arrays during a run (particle splitting, paper 003
 * eqs. 21-32, core/crack/split.h).
 *
 * Capacity.  m->p.cap particles are allocated in every particle array that
 * exists (the optional ones, NULL when no module needs them, stay NULL); p.n
 * of them are in use.  Growing to more than cap doubles it (or takes the
 * number asked for when that is larger), so a run that adds particles one
 * split at a time reallocates O(log n) times.
 *
 * All or nothing.  A growth allocates every new array first; when one
 * allocation fails it frees the new ones and leaves the model exactly as it
 * was (same pointers, same cap, same bytes_allocated).  Only when all have
 * been allocated are the n used entries copied and the old arrays freed.  The
 * peak memory of a growth is the old plus the new arrays.
 *
 * Order.  Particles are ordered body by body (model.h); tlsph_particles_open
 * makes room for k particles at one index (the end of a body's range) by
 * moving the later particles up by k: the index map old -> new is
 * i -> i + k for i >= at, the identity below.  Cost: the moved particles'
 * bytes (O(n) per call, a memmove), no computation.
 *
 * Ownership: the arrays stay the model's; bytes_allocated follows every
 * growth. */
#ifndef TLSPH_PARTICLES_GROW_H
#define TLSPH_PARTICLES_GROW_H

#include <stddef.h>

#include "run/model.h"

/* One array to grow: where its pointer lives and its bytes per particle. */
struct tlsph_grow_array {
    void **ptr;
    size_t elem;
};

/* The allocator of a growth: malloc, or a test's allocator that fails on
 * demand (ctx is passed through). */
typedef void *(*tlsph_grow_alloc_fn)(size_t bytes, void *ctx);

/* The most arrays tlsph_particle_arrays lists. */
#define TLSPH_MAX_PARTICLE_ARRAYS 40

/* Lists every particle array of p that exists (non-NULL) into out
 * [TLSPH_MAX_PARTICLE_ARRAYS]; returns how many. */
size_t tlsph_particle_arrays(struct tlsph_particles *p, struct tlsph_grow_array *out);

/* Replaces each of the count arrays by a new one of cap entries holding its
 * first n entries (n <= cap), all or nothing: 0, or -1 when an allocation
 * failed, with every array untouched.  alloc NULL means malloc. */
int tlsph_grow_arrays(const struct tlsph_grow_array *a, size_t count, size_t n, size_t cap,
                      tlsph_grow_alloc_fn alloc, void *ctx);

/* Makes p.cap >= need (doubling); 0, or -1 out of memory with the model
 * unchanged.  alloc NULL means malloc. */
int tlsph_particles_reserve(struct tlsph_model *m, size_t need, tlsph_grow_alloc_fn alloc,
                            void *ctx);

/* Moves particles at .. n-1 up by k (needs cap >= n + k) and sets n += k;
 * the k entries from `at` keep stale values for the caller to fill. */
void tlsph_particles_open(struct tlsph_model *m, size_t at, size_t k);

#endif
