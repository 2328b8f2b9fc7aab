/* Model setup: particles from the scene's bodies, reference pairs, correction
 * matrices, boundary groups, the list of active modules, and the initial force
 * evaluation.  Teardown releases everything. */
#include "run/model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bc/boundary.h"
#include "contact/contact.h"
#include "crack/fibre.h"
#include "crack/crack_driver.h"
#include "crack/precrack.h"
#include "rigid/rigid.h"
#include "material/constitutive.h"
#include "material/damage/damage.h"
#include "material/eos/eos.h"
#include "material/strength/strength.h"
#include "run/integrate.h"
#include "sph/correction.h"
#include "sph/crack_treatment.h"
#include "sph/link_criterion.h"
#include "sph/kernel.h"
#include "sph/neighbors.h"
#include "util/parallel.h"

void *tlsph_alloc(struct tlsph_model *m, size_t count, size_t size)
{
    if (count == 0)
        count = 1;
    void *p = calloc(count, size);
    if (p)
        m->bytes_allocated += count * size;
    return p;
}

void tlsph_model_momentum(const struct tlsph_model *m, double out[3])
{
    double p0 = 0, p1 = 0, p2 = 0;
    const double *v = m->p.v, *mass = m->p.mass;
#pragma omp parallel for schedule(static) reduction(+ : p0, p1, p2) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++) {
        p0 += mass[i] * v[3 * i];
        p1 += mass[i] * v[3 * i + 1];
        p2 += mass[i] * v[3 * i + 2];
    }
    out[0] = p0;
    out[1] = p1;
    out[2] = p2;
    if (m->rigid)
        tlsph_rigid_momentum(m, out);
}

double tlsph_energy_balance(const struct tlsph_energy *e)
{
    return e->kinetic + e->internal + e->hourglass + e->viscous + e->contact - e->external_work -
           e->initial;
}

void tlsph_model_free(struct tlsph_model *m)
{
    if (!m)
        return;
    struct tlsph_particles *p = &m->p;
    free(p->id); free(p->body); free(p->X); free(p->x); free(p->v); free(p->f);
    free(p->vol0); free(p->mass); free(p->h); free(p->Linv); free(p->F); free(p->Fdot);
    free(p->P_tilde); free(p->sigma); free(p->e);
    free(p->f_hourglass); free(p->f_viscous);
    free(p->eps_p); free(p->plastic_strain); free(p->eps_p_rate); free(p->yield_stress);
    free(p->T); free(p->hg_scale); free(p->spacing);
    free(p->damage); free(p->damage_init); free(p->crack_gradient); free(p->void_fraction);
    free(p->void_fstar); free(p->void_nucleated); free(p->void_shear); free(p->F_carry);
    free(m->pairs.start); free(m->pairs.j); free(m->pairs.dw); free(m->pairs.w);
    free(m->body_begin); free(m->body_end);
    if (m->groups)
        for (size_t k = 0; k < m->scene.nbcs; k++) {
            free(m->groups[k].index);
            free(m->groups[k].area);
            free(m->groups[k].load);
        }
    free(m->groups);
    tlsph_contact_free(m);
    tlsph_rigid_free(m);
    if (m->crack && m->crack->release)
        m->crack->release(m);
    tlsph_crack_driver_release(m);
    tlsph_precrack_release(m);
    tlsph_model_fibres_release(m);
    tlsph_measures_free(&m->measures);
    tlsph_scene_free(&m->scene);
    free(m);
}

static void add_module(struct tlsph_model *m, const char *name)
{
    for (int k = 0; k < m->nmodules; k++)
        if (strcmp(m->modules[k], name) == 0)
            return;
    if (m->nmodules < TLSPH_MAX_MODULES)
        m->modules[m->nmodules++] = name;
}

/* The effects this scene calls for, in pipeline order. Names are static strings. */
static void select_modules(struct tlsph_model *m)
{
    const struct tlsph_scene *s = &m->scene;
    add_module(m, s->kernel == TLSPH_KERNEL_CUBIC_SPLINE ? "kernel:cubic_spline"
                                                         : "kernel:wendland_c2");
    add_module(m, "kinematics:corrected_gradient");
    if (m->crack_surface)
        add_module(m, "crack:precrack");
    if (m->fibres)
        add_module(m, "crack:fibres");
    if (m->crack_driver)
        add_module(m, "crack:growth");
    int plastic = 0, rate = 0, softening = 0, heating = 0, damage = 0, evolution = 0;
    for (size_t b = 0; b < s->nbodies; b++) {
        const struct tlsph_material *mat = &s->materials[s->bodies[b].material];
        add_module(m, mat->eos->module);
        add_module(m, mat->strength->module);
        plastic |= tlsph_material_is_plastic(mat);
        rate |= (mat->strength_terms & TLSPH_FLOW_RATE) != 0;
        softening |= (mat->strength_terms & TLSPH_FLOW_THERMAL) != 0;
        heating |= mat->thermal.enabled;
        const struct tlsph_damage_model *dm = mat->damage.model;
        if (dm) {
            add_module(m, dm->module);
            const char *extra[TLSPH_DAMAGE_MAX_MODULES];
            const int nextra = dm->modules ? dm->modules(mat, extra) : 0;
            for (int k = 0; k < nextra; k++)
                add_module(m, extra[k]);
            evolution |= dm->initiation != NULL; /* criteria grow D by eq. 45 */
            damage = 1;
        }
    }
    add_module(m, "stress_rate:green_naghdi_hencky");
    if (plastic)
        add_module(m, "plasticity:j2_radial_return");
    if (rate)
        add_module(m, "plasticity:strain_rate_hardening");
    if (heating)
        add_module(m, "thermal:adiabatic_heating");
    if (softening)
        add_module(m, "thermal:softening");
    if (evolution)
        add_module(m, "damage:evolution_linear");
    if (damage) {
        add_module(m, m->crack->module);
        add_module(m, s->failed_motion == TLSPH_FAILED_ARREST ? "failure:arrest" : "failure:free");
    }
    if (m->links) {
        add_module(m, m->crack->module);
        add_module(m, s->links.criterion->module);
    }
    add_module(m, "force:pk1_pair");
    if (s->hourglass)
        add_module(m, "hourglass:ganzenmuller");
    if (m->p.hg_scale)
        add_module(m, "hourglass:tangent_stiffness");
    if (s->viscosity)
        add_module(m, "viscosity:monaghan");
    if (m->contact)
        add_module(m, s->contact.law->module);
    if (m->rigid) {
        add_module(m, "rigid:penalty_hertz");
        int friction = 0, free_ = 0;
        for (size_t k = 0; k < s->nrigid; k++) {
            friction |= s->rigid[k].friction > 0.0;
            free_ |= s->rigid[k].motion == TLSPH_RIGID_FREE;
        }
        if (friction)
            add_module(m, "rigid:coulomb_friction");
        if (free_)
            add_module(m, "rigid:free_motion");
    }
    for (size_t k = 0; k < s->nbcs; k++)
        add_module(m, s->bcs[k].kind->module);
    add_module(m, "integrator:velocity_verlet");
    add_module(m, "stability:checks");
}

static int allocate_particles(struct tlsph_model *m, size_t n)
{
    struct tlsph_particles *p = &m->p;
    p->n = n;
    p->cap = n;
    p->id = tlsph_alloc(m, n, sizeof *p->id);
    p->body = tlsph_alloc(m, n, sizeof *p->body);
    p->X = tlsph_alloc(m, 3 * n, sizeof(double));
    p->x = tlsph_alloc(m, 3 * n, sizeof(double));
    p->v = tlsph_alloc(m, 3 * n, sizeof(double));
    p->f = tlsph_alloc(m, 3 * n, sizeof(double));
    p->vol0 = tlsph_alloc(m, n, sizeof(double));
    p->mass = tlsph_alloc(m, n, sizeof(double));
    p->h = tlsph_alloc(m, n, sizeof(double));
    p->Linv = tlsph_alloc(m, 9 * n, sizeof(double));
    p->F = tlsph_alloc(m, 9 * n, sizeof(double));
    p->Fdot = tlsph_alloc(m, 9 * n, sizeof(double));
    p->P_tilde = tlsph_alloc(m, 9 * n, sizeof(double));
    p->sigma = tlsph_alloc(m, 6 * n, sizeof(double));
    p->e = tlsph_alloc(m, n, sizeof(double));
    /* only the modules the scene asks for get their arrays */
    if (m->scene.hourglass && !(p->f_hourglass = tlsph_alloc(m, 3 * n, sizeof(double))))
        return -1;
    if (m->scene.viscosity && !(p->f_viscous = tlsph_alloc(m, 3 * n, sizeof(double))))
        return -1;
    int plastic = 0, thermal = 0, damage = 0;
    unsigned damage_fields = 0;
    for (size_t k = 0; k < m->scene.nmaterials; k++) {
        const struct tlsph_material *mat = &m->scene.materials[k];
        plastic |= tlsph_material_is_plastic(mat);
        thermal |= mat->thermal.enabled;
        damage |= mat->damage.model != NULL;
        damage_fields |= mat->damage.model ? mat->damage.model->fields : 0;
    }
    if ((damage_fields & TLSPH_DAMAGE_FIELD_VOID_FRACTION) &&
        !(p->void_fraction = tlsph_alloc(m, n, sizeof(double))))
        return -1;
    if ((damage_fields & TLSPH_DAMAGE_FIELD_POROUS) &&
        (!(p->void_fstar = tlsph_alloc(m, n, sizeof(double))) ||
         !(p->void_nucleated = tlsph_alloc(m, n, sizeof(double))) ||
         !(p->void_shear = tlsph_alloc(m, n, sizeof(double)))))
        return -1;
    if (damage && (!(p->damage = tlsph_alloc(m, n, sizeof(double))) ||
                   !(p->damage_init = tlsph_alloc(m, n, sizeof(double)))))
        return -1;
    if ((m->crack->fields & TLSPH_CRACK_FIELD_GRADIENT) &&
        !(p->crack_gradient = tlsph_alloc(m, 9 * n, sizeof(double))))
        return -1;
    /* F carried through splits (crack/split_carry.h); the pseudo-spring
     * recomputes L^-1 every step, so it cannot hold the carried part */
    if (m->scene.crack_growth.on && m->crack->variant != TLSPH_APPROX_PSEUDO_SPRING &&
        !(p->F_carry = tlsph_alloc(m, 9 * n, sizeof(double))))
        return -1;
    if (plastic && (!(p->eps_p = tlsph_alloc(m, n, sizeof(double))) ||
                    !(p->plastic_strain = tlsph_alloc(m, 6 * n, sizeof(double))) ||
                    !(p->eps_p_rate = tlsph_alloc(m, n, sizeof(double))) ||
                    !(p->yield_stress = tlsph_alloc(m, n, sizeof(double)))))
        return -1;
    if (thermal && !(p->T = tlsph_alloc(m, n, sizeof(double))))
        return -1;
    if (plastic && m->scene.hourglass && m->scene.hourglass_tangent) {
        if (!(p->hg_scale = tlsph_alloc(m, n, sizeof(double))))
            return -1;
        for (size_t i = 0; i < n; i++)
            p->hg_scale[i] = 1.0; /* elastic until a step says otherwise */
    }
    return p->id && p->body && p->X && p->x && p->v && p->f && p->vol0 && p->mass && p->h &&
                   p->Linv && p->F && p->Fdot && p->P_tilde && p->sigma && p->e
               ? 0
               : -1;
}

/* Generates every body's lattice, orders particles by reference cell within
 * each body (locality for the pair loops), and fills the reference data. */
static int generate(struct tlsph_model *m, struct tlsph_errors *err)
{
    struct tlsph_scene *s = &m->scene;
    double **pts = calloc(s->nbodies, sizeof *pts);
    double **vols = calloc(s->nbodies, sizeof *vols);
    double **sps = calloc(s->nbodies, sizeof *sps); /* refined bodies' spacings */
    size_t *counts = calloc(s->nbodies, sizeof *counts);
    m->body_begin = tlsph_alloc(m, s->nbodies, sizeof(size_t));
    m->body_end = tlsph_alloc(m, s->nbodies, sizeof(size_t));
    int rc = -1;
    size_t *order = NULL;
    double *Xall = NULL, *Vall = NULL, *Sall = NULL;
    int32_t *ball = NULL;
    int graded = 0;
    if (!pts || !vols || !sps || !counts || !m->body_begin || !m->body_end) {
        tlsph_errors_add(err, "", "out of memory");
        goto done;
    }
    size_t total = 0;
    for (size_t b = 0; b < s->nbodies; b++) {
        long left = s->max_particles - (long)total;
        graded |= s->bodies[b].nrefine > 0;
        if (tlsph_body_fill(s, b, left, &pts[b], &vols[b], s->bodies[b].nrefine ? &sps[b] : NULL,
                            &counts[b], err) != 0)
            goto done;
        if (counts[b] == 0) {
            char ptr[64];
            snprintf(ptr, sizeof ptr, "/bodies/%zu/geometry", b);
            tlsph_errors_add(err, ptr, "body '%s' contains no lattice point", s->bodies[b].name);
            goto done;
        }
        m->body_begin[b] = total;
        total += counts[b];
        m->body_end[b] = total;
    }
    if (total > (size_t)INT32_MAX) {
        tlsph_errors_add(err, "", "too many particles (%zu)", total);
        goto done;
    }
    order = malloc(total * sizeof *order);
    Xall = malloc(3 * total * sizeof *Xall);
    ball = malloc(total * sizeof *ball);
    Vall = malloc(total * sizeof *Vall);
    if (graded)
        Sall = malloc(total * sizeof *Sall);
    if (!order || !Xall || !ball || !Vall || (graded && !Sall) ||
        allocate_particles(m, total) != 0 ||
        (graded && !(m->p.spacing = tlsph_alloc(m, total, sizeof(double))))) {
        tlsph_errors_add(err, "", "out of memory for %zu particles", total);
        goto done;
    }
    double cell = 0.0;
    for (size_t b = 0; b < s->nbodies; b++) {
        memcpy(Xall + 3 * m->body_begin[b], pts[b], 3 * counts[b] * sizeof(double));
        memcpy(Vall + m->body_begin[b], vols[b], counts[b] * sizeof(double));
        for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++) {
            ball[i] = (int32_t)b;
            if (graded)
                Sall[i] = sps[b] ? sps[b][i - m->body_begin[b]] : s->bodies[b].spacing;
        }
        cell = fmax(cell, s->support_factor * s->bodies[b].spacing);
    }
    if (tlsph_cell_order(Xall, ball, total, cell, order) != 0) {
        tlsph_errors_add(err, "", "out of memory");
        goto done;
    }
    struct tlsph_particles *p = &m->p;
    for (size_t k = 0; k < total; k++) {
        const size_t o = order[k];
        struct tlsph_body *body = &s->bodies[ball[o]];
        const struct tlsph_material *mat = &s->materials[body->material];
        p->id[k] = (int64_t)o;
        p->body[k] = ball[o];
        for (int c = 0; c < 3; c++)
            p->X[3 * k + c] = p->x[3 * k + c] = Xall[3 * o + c];
        p->vol0[k] = Vall[o]; /* spacing^d on the lattice, per shell when conforming */
        p->mass[k] = mat->density * p->vol0[k];
        /* the particle's own spacing when graded (volume, mass and h follow it) */
        p->h[k] = 0.5 * s->support_factor * (graded ? Sall[o] : body->spacing);
        if (graded)
            p->spacing[k] = Sall[o];
        for (int c = 0; c < 3; c++) {
            struct tlsph_expr *ex = &body->initial_velocity[c];
            p->v[3 * k + c] = ex->evaluator ? tlsph_expr_eval(ex, p->X + 3 * k) : 0.0;
        }
        for (int c = 0; c < 9; c++)
            p->F[9 * k + c] = (c % 4 == 0);
        for (int c = 0; p->F_carry && c < 9; c++)
            p->F_carry[9 * k + c] = (c % 4 == 0);
        tlsph_constitutive_init_particle(m, k);
    }
    rc = 0;
done:
    for (size_t b = 0; b < s->nbodies; b++) {
        if (pts)
            free(pts[b]);
        if (vols)
            free(vols[b]);
        if (sps)
            free(sps[b]);
    }
    free(pts);
    free(vols);
    free(sps);
    free(Sall);
    free(Vall);
    free(counts);
    free(order);
    free(Xall);
    free(ball);
    return rc;
}

int tlsph_model_create(struct tlsph_scene *scene, struct tlsph_model **out,
                       struct tlsph_errors *err)
{
    *out = NULL;
    struct tlsph_model *m = calloc(1, sizeof *m);
    if (!m) {
        tlsph_errors_add(err, "", "out of memory");
        tlsph_scene_free(scene);
        return -1;
    }
    m->scene = *scene;
    memset(scene, 0, sizeof *scene);
    m->dim = m->scene.dimension;
    m->crack = tlsph_crack_select(&m->scene);

    if (generate(m, err) != 0)
        goto fail;
    for (size_t b = 0; b < m->scene.nbodies; b++)
        if (m->scene.bodies[b].thickness_axis >= 0) { /* some body is thin */
            if (tlsph_model_fibres_setup(m, err) != 0)
                goto fail;
            break;
        }

    if (tlsph_build_pairs(m->p.X, m->p.h, m->p.body, m->p.n, &m->pairs.start, &m->pairs.j) != 0) {
        tlsph_errors_add(err, "", "out of memory building the neighbour list");
        goto fail;
    }
    m->pairs.npairs = (size_t)m->pairs.start[m->p.n];
    m->bytes_allocated += (m->p.n + 1) * sizeof(int64_t) + m->pairs.npairs * sizeof(int32_t);
    if (m->scene.ncracks && tlsph_precrack_setup(m, err) != 0) /* cuts the pairs */
        goto fail;
    if (m->scene.crack_growth.on && tlsph_crack_driver_setup(m, err) != 0)
        goto fail;
    if (m->crack->setup && m->crack->setup(m, err) != 0) /* may narrow the pairs */
        goto fail;
    m->pairs.dw = tlsph_alloc(m, m->pairs.npairs, sizeof(double));
    if (m->scene.hourglass)
        m->pairs.w = tlsph_alloc(m, m->pairs.npairs, sizeof(double));
    if (!m->pairs.dw || (m->scene.hourglass && !m->pairs.w)) {
        tlsph_errors_add(err, "", "out of memory for %zu pairs", m->pairs.npairs);
        goto fail;
    }
    tlsph_correction_build(m);

    m->groups = tlsph_alloc(m, m->scene.nbcs, sizeof *m->groups);
    if (!m->groups) {
        tlsph_errors_add(err, "", "out of memory");
        goto fail;
    }
    if (tlsph_boundary_select(m, err) != 0 || tlsph_boundary_check(m, err) != 0 ||
        tlsph_measures_init(m, err) != 0)
        goto fail;
    /* only a scene where contact can act (parse_contact.c): the others allocate
     * and run nothing */
    if (m->scene.contact.law && tlsph_contact_create(m, err) != 0)
        goto fail;
    if (m->scene.nrigid && tlsph_rigid_create(m, err) != 0)
        goto fail;
    select_modules(m);

    tlsph_start(m);
    *out = m;
    return 0;
fail:
    tlsph_model_free(m);
    return -1;
}
