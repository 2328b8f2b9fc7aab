/* A split keeps the elastic state of the porous points (split_elastic.h). */
#include "crack/split_elastic.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "material/damage/damage.h"
#include "sph/kinematics.h"
#include "util/mat3.h"

void tlsph_split_hencky(const double F[9], double H[6])
{
    double C[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            C[3 * r + c] = F[r] * F[c] + F[3 + r] * F[3 + c] + F[6 + r] * F[6 + c];
    double lam[3], Q[9], d[3];
    sym3_eigen(C, lam, Q);
    for (int a = 0; a < 3; a++)
        d[a] = 0.5 * log(lam[a]);
    sym3_compose(Q, d, H);
}

static int porous_body(const struct tlsph_model *m, int32_t b)
{
    const struct tlsph_material *mat = &m->scene.materials[m->scene.bodies[b].material];
    return mat->damage.model && (mat->damage.model->fields & TLSPH_DAMAGE_FIELD_VOID_FRACTION);
}

int tlsph_split_keep_elastic_state(struct tlsph_model *m, size_t *changed,
                                   struct tlsph_errors *err)
{
    if (changed)
        *changed = 0;
    struct tlsph_particles *p = &m->p;
    if (!p->void_fraction || !p->plastic_strain)
        return 0;
    const size_t n = p->n;
    double *F0 = malloc(9 * n * sizeof *F0), *Fd0 = malloc(9 * n * sizeof *Fd0);
    if (!F0 || !Fd0) {
        free(F0);
        free(Fd0);
        tlsph_errors_add(err, "", "crack growth: out of memory");
        return -1;
    }
    memcpy(F0, p->F, 9 * n * sizeof *F0);
    memcpy(Fd0, p->Fdot, 9 * n * sizeof *Fd0);
    tlsph_kinematics(m, 0.0);
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        const double *Fo = F0 + 9 * i, *Fn = p->F + 9 * i;
        int same = 1;
        for (int a = 0; a < 9 && same; a++)
            same = Fo[a] == Fn[a];
        if (same || !porous_body(m, p->body[i]) || (p->damage && p->damage[i] >= 1.0))
            continue;
        double Ho[6], Hn[6];
        tlsph_split_hencky(Fo, Ho);
        tlsph_split_hencky(Fn, Hn);
        for (int a = 0; a < 6; a++)
            p->plastic_strain[6 * i + a] += Hn[a] - Ho[a];
        count++;
    }
    memcpy(p->Fdot, Fd0, 9 * n * sizeof *Fd0);
    free(F0);
    free(Fd0);
    if (changed)
        *changed = count;
    return 0;
}
