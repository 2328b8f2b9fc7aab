/* Scene parser, top level: JSON text -> validated struct tlsph_scene.
 *
 * Every problem found is reported (JSON pointer + message naming the field, the
 * accepted range and its unit); parsing goes on after an error so that one run
 * of the validator lists them all.  The sections are read in dependency order:
 * dimension, parameters (used by expressions), scalar settings, materials,
 * bodies (need materials), boundary conditions (need bodies), then the
 * particle counts (need limits and valid bodies).  Bodies and BCs live in
 * parse_bodies.c and parse_bcs.c, geometry objects in parse_geometry.c. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "material/eos/eos.h"
#include "material/strength/strength.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

int tlsph_scene_find_body(const struct tlsph_scene *s, const char *name)
{
    for (size_t i = 0; i < s->nbodies; i++)
        if (strcmp(s->bodies[i].name, name) == 0)
            return (int)i;
    return -1;
}

int tlsph_scene_expr(struct tlsph_expr *ex, const json_t *v, const char *const *free_vars,
                     int nfree, int allow_conditions, const struct tlsph_scene *s,
                     const char *pointer, struct tlsph_errors *err)
{
    memset(ex, 0, sizeof *ex);
    char num[64];
    const char *text;
    if (json_is_number(v)) {
        if (!isfinite(json_number_value(v))) {
            tlsph_errors_add(err, pointer, "number must be finite");
            return -1;
        }
        snprintf(num, sizeof num, "%.17g", json_number_value(v));
        text = num;
    } else if (json_is_string(v)) {
        text = json_string_value(v);
        if (strlen(text) != json_string_length(v)) {
            tlsph_errors_add(err, pointer, "expression contains a NUL character");
            return -1;
        }
    } else {
        tlsph_errors_add(err, pointer,
                         "must be a number or an expression string of %s, got %s",
                         nfree == 1 ? free_vars[0] : "x, y, z", jc_type_name(v));
        return -1;
    }
    char *rewritten = NULL;
    if (allow_conditions) {
        char msg[256];
        rewritten = tlsph_condition_rewrite(text, msg, sizeof msg);
        if (!rewritten) {
            tlsph_errors_add(err, pointer, "invalid condition '%s': %s", text,
                             msg[0] ? msg : "out of memory");
            return -1;
        }
    }
    const char *compiled = rewritten ? rewritten : text;
    int rc;
    if (rewritten) {
        /* Report problems against the text the user wrote. */
        struct tlsph_errors tmp;
        tlsph_errors_init(&tmp);
        rc = tlsph_expr_compile(ex, compiled, free_vars, nfree, s->params, s->nparams, pointer,
                                &tmp);
        for (size_t i = 0; i < tmp.count; i++)
            tlsph_errors_add(err, pointer, "in condition '%s': %s", text, tmp.items[i].message);
        if (tmp.out_of_memory)
            err->out_of_memory = 1;
        tlsph_errors_free(&tmp);
        free(rewritten);
    } else {
        rc = tlsph_expr_compile(ex, compiled, free_vars, nfree, s->params, s->nparams, pointer,
                                err);
    }
    return rc;
}

/* ------------------------------------------------------------------ sections */

static int valid_identifier(const char *s)
{
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '_'))
        return 0;
    for (s++; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
              *s == '_'))
            return 0;
    return 1;
}

static int parse_parameters(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *obj = jc_object(root, "parameters", 0, "", err);
    if (!obj)
        return json_object_get(root, "parameters") ? -1 : 0;
    int bad = 0;
    size_t n = json_object_size(obj);
    if (n > TLSPH_MAX_PARAMS) {
        tlsph_errors_add(err, "/parameters", "at most %d parameters are allowed, got %zu",
                         TLSPH_MAX_PARAMS, n);
        return -1;
    }
    if (n == 0)
        return 0;
    s->params = calloc(n, sizeof *s->params);
    if (!s->params) {
        tlsph_errors_add(err, "/parameters", "out of memory");
        return -1;
    }
    const char *key;
    json_t *val;
    json_object_foreach((json_t *)obj, key, val) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, "/parameters", key);
        int ok = 1;
        if (!valid_identifier(key) || strlen(key) >= sizeof s->params[0].name) {
            tlsph_errors_add(err, p,
                             "parameter name '%s' must match [A-Za-z_][A-Za-z0-9_]* and have at "
                             "most %zu characters",
                             key, sizeof s->params[0].name - 1);
            ok = 0;
        } else {
            if (tlsph_expr_reserved(key) || strcmp(key, "x") == 0 || strcmp(key, "y") == 0 ||
                strcmp(key, "z") == 0 || strcmp(key, "t") == 0) {
                tlsph_errors_add(err, p,
                                 "parameter name '%s' is reserved (a variable x, y, z, t or a "
                                 "built-in constant or function of the expression language)",
                                 key);
                ok = 0;
            }
        }
        if (!json_is_number(val) || !isfinite(json_number_value(val))) {
            tlsph_errors_add(err, p, "parameter '%s' must be a finite number, got %s", key,
                             jc_type_name(val));
            ok = 0;
        }
        if (!ok) {
            bad = 1;
            continue;
        }
        memcpy(s->params[s->nparams].name, key, strlen(key) + 1);
        s->params[s->nparams].value = json_number_value(val);
        s->nparams++;
    }
    return bad ? -1 : 0;
}

/* time, discretization, stability, limits and output: the scene's own scalars,
 * read by their tables (scene_keys.c) in the order of the scene's keys.
 * *limits_bad tells the particle count whether the limit is known. */
static int parse_sections(const json_t *root, struct tlsph_scene *s, int *limits_bad,
                          struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = s};
    int bad = tlsph_keys_member(root, &tlsph_scene_keys, "time", "", &to, err) < 0;
    bad |= tlsph_keys_member(root, &tlsph_scene_keys, "discretization", "", &to, err) < 0;
    bad |= tlsph_keys_member(root, &tlsph_scene_keys, "stability", "", &to, err) < 0;
    *limits_bad = tlsph_keys_member(root, &tlsph_scene_keys, "limits", "", &to, err) < 0;
    bad |= *limits_bad;
    bad |= tlsph_keys_member(root, &tlsph_scene_keys, "output", "", &to, err) < 0;
    return bad ? -1 : 0;
}

/* "eos" / "strength": {"type": NAME, ...model parameters}. */
static int parse_model_ref(const json_t *mat, const char *key, const char *pointer,
                           char *type, size_t size, const json_t **obj, struct tlsph_errors *err)
{
    *obj = jc_object(mat, key, 0, pointer, err);
    if (!*obj)
        return json_object_get(mat, key) ? -1 : 1;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    return jc_string(*obj, "type", 1, p, type, size, err) == 0 ? 0 : -1;
}

/* "thermal": the material gets a temperature, raised by plastic work
 * (adiabatic heating). */
static int parse_thermal(const json_t *mat, struct tlsph_material *m, const char *pointer,
                         struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = &m->thermal};
    const int r = tlsph_keys_member(mat, &tlsph_material_keys, "thermal", pointer, &to, err);
    /* a block, even an invalid one: the strength model must not ask for it again */
    m->thermal.enabled = json_is_object(json_object_get(mat, "thermal"));
    return r < 0 ? -1 : 0;
}

int tlsph_require_plastic(const struct tlsph_material *m, const char *block, const char *why,
                          const char *pointer, struct tlsph_errors *err)
{
    if (!m->strength || tlsph_material_is_plastic(m))
        return 0;
    tlsph_errors_add(err, pointer,
                     "material '%s' has a %s block but strength '%s' is not plastic: %s (use a "
                     "plastic strength model: %s)",
                     m->name, block, m->strength->name, why, tlsph_strength_plastic_names());
    return 1;
}

static int parse_material(const char *name, const json_t *mat, struct tlsph_material *m,
                          struct tlsph_errors *err)
{
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, "/materials", name);
    if (!json_is_object(mat)) {
        tlsph_errors_add(err, P, "material '%s' must be an object, got %s", name,
                         jc_type_name(mat));
        return -1;
    }
    const int name_bad = tlsph_scene_check_name(name, "material name", P, err) != 0;
    if (strlen(name) >= sizeof m->name) /* reported by the check above */
        return -1;
    /* kept even when invalid, for body lookups */
    memcpy(m->name, name, strlen(name) + 1);
    const struct tlsph_key_target to = {.base = m};
    int bad = name_bad | (tlsph_keys_read(mat, &tlsph_material_keys, P, &to, err) != 0);
    if (!bad) { /* derived constants of a valid material; nothing reads those of another */
        const double nu = m->poisson_ratio;
        m->shear_modulus = m->youngs_modulus / (2.0 * (1.0 + nu));
        m->bulk_modulus = m->youngs_modulus / (3.0 * (1.0 - 2.0 * nu));
        m->wave_speed = sqrt((m->bulk_modulus + 4.0 * m->shear_modulus / 3.0) / m->density);
    }

    char type[64], p[TLSPH_POINTER_MAX];
    const json_t *obj;
    m->eos = &tlsph_eos_linear;
    int r = parse_model_ref(mat, "eos", P, type, sizeof type, &obj, err);
    tlsph_pointer_join(p, sizeof p, P, "eos");
    if (r < 0) {
        bad = 1;
    } else if (r == 0) {
        m->eos = tlsph_eos_find(type);
        if (!m->eos) {
            tlsph_key_error(err, p, "type", "unknown equation of state '%s' (accepted: %s)", type,
                            tlsph_eos_names());
            bad = 1;
        } else if (m->eos->parse(obj, m, p, err) != 0) {
            bad = 1;
        }
    }
    bad |= parse_thermal(mat, m, P, err) != 0;
    m->strength = &tlsph_strength_elastic;
    r = parse_model_ref(mat, "strength", P, type, sizeof type, &obj, err);
    tlsph_pointer_join(p, sizeof p, P, "strength");
    if (r < 0) {
        bad = 1;
    } else if (r == 0) {
        m->strength = tlsph_strength_find(type);
        if (!m->strength) {
            tlsph_key_error(err, p, "type", "unknown strength model '%s' (accepted: %s)", type,
                            tlsph_strength_names());
            bad = 1;
        } else if (m->strength->parse(obj, m, p, err) != 0) {
            bad = 1;
        }
    }
    if (m->thermal.enabled) {
        tlsph_pointer_join(p, sizeof p, P, "thermal");
        bad |= tlsph_require_plastic(m, "thermal", "adiabatic heating comes from plastic work",
                                     p, err);
    }
    bad |= tlsph_parse_material_damage(mat, m, P, err) != 0;
    return bad ? -1 : 0;
}

static int parse_materials(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *mats = jc_object(root, "materials", 1, "", err);
    if (!mats)
        return -1;
    size_t n = json_object_size(mats);
    if (n == 0) {
        tlsph_errors_add(err, "/materials", "'materials' must define at least one material");
        return -1;
    }
    if (n > TLSPH_MAX_MATERIALS) {
        tlsph_errors_add(err, "/materials", "at most %d materials are allowed, got %zu",
                         TLSPH_MAX_MATERIALS, n);
        return -1;
    }
    s->materials = calloc(n, sizeof *s->materials);
    if (!s->materials) {
        tlsph_errors_add(err, "/materials", "out of memory");
        return -1;
    }
    int bad = 0;
    const char *key;
    json_t *val;
    json_object_foreach((json_t *)mats, key, val) {
        bad |= parse_material(key, val, &s->materials[s->nmaterials], err) != 0;
        s->nmaterials++; /* names are kept even when invalid, for body lookups */
    }
    return bad ? -1 : 0;
}

int tlsph_scene_parse(const char *text, size_t len, struct tlsph_scene *scene,
                      struct tlsph_errors *err)
{
    tlsph_scene_defaults(scene);
    const size_t errors_before = err->count;
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &jerr);
    if (!root) {
        tlsph_errors_add(err, "", "invalid JSON at line %d, column %d: %s", jerr.line,
                         jerr.column, jerr.text);
        memset(scene, 0, sizeof *scene);
        return -1;
    }
    if (!json_is_object(root)) {
        tlsph_errors_add(err, "", "the scene must be a JSON object, got %s",
                         jc_type_name(root));
        json_decref(root);
        memset(scene, 0, sizeof *scene);
        return -1;
    }
    struct tlsph_scene *s = scene;
    /* name and dimension; an invalid dimension leaves the default: the other
     * problems are reported as in 3-D */
    int bad = tlsph_keys_read(root, &tlsph_scene_keys, "", &(struct tlsph_key_target){.base = s},
                              err) != 0;
    bad |= parse_parameters(root, s, err) != 0;
    int limits_bad = 0;
    bad |= parse_sections(root, s, &limits_bad, err) != 0;
    bad |= parse_materials(root, s, err) != 0;
    bad |= tlsph_parse_links(root, s, err) != 0;
    const int bodies_bad = tlsph_parse_bodies(root, s, err) != 0;
    bad |= bodies_bad;
    if (!bodies_bad)
        bad |= tlsph_parse_contact(root, s, err) != 0;
    bad |= tlsph_parse_rigid_bodies(root, s, err) != 0;
    const int cracks_bad = tlsph_parse_cracks(root, s, err) != 0;
    bad |= cracks_bad;
    if (!bodies_bad && !cracks_bad)
        bad |= tlsph_parse_crack_growth(root, s, err) != 0;
    const int bcs_bad = tlsph_parse_bcs(root, s, err) != 0;
    bad |= bcs_bad;
    if (!bcs_bad)
        bad |= tlsph_parse_measures(root, s, err) != 0;
    /* Particle counts only when every body is well-formed and the limit is known. */
    if (!bodies_bad && !limits_bad)
        bad |= tlsph_check_particle_counts(s, err) != 0;
    /* What the run meets first: finite initial velocities and a bounded step
     * count (check_values.c, check_steps.c); they read everything above. */
    if (!bad && err->count == errors_before && !err->out_of_memory)
        bad |= tlsph_check_run_start(s, err) != 0;
    if (!bad && err->count == errors_before && !err->out_of_memory) {
        s->json_text = json_dumps(root, JSON_COMPACT);
        if (!s->json_text) {
            tlsph_errors_add(err, "", "out of memory while storing the scene text");
            bad = 1;
        }
    } else {
        bad = 1;
        if (err->count == errors_before) /* an allocation failure lost the message */
            tlsph_errors_add(err, "", "out of memory while validating the scene");
    }
    json_decref(root);
    if (bad) {
        tlsph_scene_free(s);
        return -1;
    }
    return 0;
}

int tlsph_scene_load_file(const char *path, struct tlsph_scene *scene, struct tlsph_errors *err)
{
    memset(scene, 0, sizeof *scene);
    FILE *f = fopen(path, "rb");
    if (!f) {
        tlsph_errors_add(err, "", "cannot open scene file '%s': %s", path, strerror(errno));
        return -1;
    }
    size_t cap = 65536, len = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        tlsph_errors_add(err, "", "out of memory reading '%s'", path);
        return -1;
    }
    for (;;) {
        if (len == cap) {
            if (cap > (size_t)TLSPH_SCENE_FILE_MAX)
                break;
            char *nb = realloc(buf, 2 * cap);
            if (!nb) {
                free(buf);
                fclose(f);
                tlsph_errors_add(err, "", "out of memory reading '%s'", path);
                return -1;
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    const int read_error = ferror(f);
    fclose(f);
    if (read_error) {
        free(buf);
        tlsph_errors_add(err, "", "error reading scene file '%s'", path);
        return -1;
    }
    if (len > (size_t)TLSPH_SCENE_FILE_MAX) {
        free(buf);
        tlsph_errors_add(err, "", "scene file '%s' is larger than the limit of %ld bytes (16 MiB)",
                         path, TLSPH_SCENE_FILE_MAX);
        return -1;
    }
    const int rc = tlsph_scene_parse(buf, len, scene, err);
    free(buf);
    return rc;
}

void tlsph_scene_free(struct tlsph_scene *s)
{
    if (!s)
        return;
    for (size_t b = 0; b < s->nbodies; b++) {
        tlsph_geometry_free(&s->bodies[b].geometry);
        tlsph_refine_free(&s->bodies[b]);
        for (int k = 0; k < 3; k++)
            tlsph_expr_free(&s->bodies[b].initial_velocity[k]);
    }
    for (size_t i = 0; i < s->nbcs; i++) {
        tlsph_expr_free(&s->bcs[i].select.expression);
        for (int k = 0; k < 3; k++)
            tlsph_expr_free(&s->bcs[i].velocity[k]);
    }
    for (size_t i = 0; i < s->nprobes; i++)
        tlsph_expr_free(&s->probes[i].select.expression);
    for (size_t i = 0; i < s->nextents; i++)
        tlsph_expr_free(&s->extents[i].select.expression);
    free(s->bodies);
    free(s->bcs);
    tlsph_rigid_specs_free(s->rigid, s->nrigid);
    free(s->cracks);
    free(s->materials);
    free(s->params);
    free(s->json_text);
    memset(s, 0, sizeof *s);
}
