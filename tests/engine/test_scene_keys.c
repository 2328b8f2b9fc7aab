/* The scene's key tables (core/scene/keys.h).
 *
 * Run by make check: every table is well formed (ranges ordered, defaults
 * inside their ranges, choices named, "only with" keys after their switch,
 * linked tables where their links say), and the defaults tlsph_scene_parse
 * leaves in a scene that sets nothing are the tables' defaults.
 *
 * With --json it prints every table instead (the root's, the tables hanging
 * from it, each model's and each boundary-condition kind's):
 * tests/engine/scene_keys.sh hands that to
 * tests/support/scene_keys_check.py, which compares it with
 * schemas/scene.schema.json and docs/scene.md. */
#include <check.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bc/kind.h"
#include "contact/contact.h"
#include "material/damage/damage.h"
#include "sph/link_criterion.h"
#include "material/eos/eos.h"
#include "material/strength/strength.h"
#include "rigid/rigid.h"
#include "scene/keys.h"
#include "scene/scene.h"
#include "support/check_main.h"

#define MAX_TABLES 128

struct tables {
    const struct tlsph_key_table *t[MAX_TABLES];
    size_t n;
};

static void add_tree(struct tables *all, const struct tlsph_key_table *t)
{
    for (size_t i = 0; i < all->n; i++)
        if (all->t[i] == t)
            return;
    if (all->n == MAX_TABLES)
        abort();
    all->t[all->n++] = t;
    for (size_t i = 0; i < t->nkeys; i++)
        if (t->keys[i].table)
            add_tree(all, t->keys[i].table);
}

/* Each name of a family's comma-separated list, found in its registry. */
#define ADD_FAMILY(all, names, find)                                                           \
    do {                                                                                       \
        char list[256];                                                                        \
        snprintf(list, sizeof list, "%s", names());                                            \
        for (char *save, *s = strtok_r(list, ", ", &save); s; s = strtok_r(NULL, ", ", &save)) \
            add_tree(all, find(s)->keys);                                                      \
    } while (0)

/* The boundary-condition kinds' names, as the families' names() give theirs. */
static const char *bc_names(void)
{
    static char names[256];
    tlsph_bc_names(names, sizeof names, 0, "", ", ");
    return names;
}

static struct tables all_tables(void)
{
    struct tables all = {.n = 0};
    add_tree(&all, &tlsph_scene_keys);
    ADD_FAMILY(&all, tlsph_eos_names, tlsph_eos_find);
    ADD_FAMILY(&all, tlsph_strength_names, tlsph_strength_find);
    ADD_FAMILY(&all, tlsph_damage_names, tlsph_damage_find);
    ADD_FAMILY(&all, bc_names, tlsph_bc_find);
    ADD_FAMILY(&all, tlsph_contact_names, tlsph_contact_find);
    ADD_FAMILY(&all, tlsph_link_criterion_names, tlsph_link_criterion_find);
    ADD_FAMILY(&all, tlsph_rigid_shape_names, tlsph_rigid_shape_find);
    ADD_FAMILY(&all, tlsph_rigid_motion_names, tlsph_rigid_motion_find);
    return all;
}

static const char *kind_name(enum tlsph_key_kind k)
{
    static const char *const names[] = {"number", "integer", "boolean", "choice",
                                        "string", "object",  "array",   "expression"};
    return names[k];
}

/* ------------------------------------------------------------------ JSON */

static json_t *bound(double x, enum jc_bound b)
{
    return b == JC_NONE ? json_null() : json_real(x);
}

static json_t *default_json(const struct tlsph_key *k)
{
    if (!(k->flags & TLSPH_KEY_DEFAULT))
        return json_null();
    switch (k->kind) {
    case TLSPH_KEY_NUMBER: return json_real(k->def);
    case TLSPH_KEY_INTEGER: return json_integer((json_int_t)k->def);
    case TLSPH_KEY_BOOLEAN: return json_boolean(k->def != 0.0);
    case TLSPH_KEY_STRING: return json_string(k->def_text);
    case TLSPH_KEY_CHOICE:
        for (const struct tlsph_key_choice *c = k->choices; c->name; c++)
            if (c->value == (int)k->def)
                return json_string(c->name);
        return json_null();
    default: return json_null();
    }
}

static json_t *key_json(const struct tlsph_key *k)
{
    json_t *o = json_object();
    json_object_set_new(o, "name", json_string(k->name));
    json_object_set_new(o, "kind", json_string(kind_name(k->kind)));
    json_object_set_new(o, "required", json_boolean(k->flags & TLSPH_KEY_REQUIRED));
    json_object_set_new(o, "caller", json_boolean(k->flags & TLSPH_KEY_CALLER));
    json_object_set_new(o, "refused", json_boolean(k->flags & TLSPH_KEY_REFUSED));
    json_object_set_new(o, "map", json_boolean(k->flags & TLSPH_KEY_MAP));
    json_object_set_new(o, "below_youngs_modulus", json_boolean(k->flags & TLSPH_KEY_BELOW_E));
    json_object_set_new(o, "name_rule", json_boolean(k->flags & TLSPH_KEY_NAME));
    json_object_set_new(o, "default", default_json(k));
    json_object_set_new(o, "unit", k->unit ? json_string(k->unit) : json_null());
    json_object_set_new(o, "with", k->with ? json_string(k->with) : json_null());
    if (k->kind == TLSPH_KEY_NUMBER || k->kind == TLSPH_KEY_INTEGER) {
        json_object_set_new(o, "minimum", bound(k->range.min, k->range.lo));
        json_object_set_new(o, "minimum_open", json_boolean(k->range.lo == JC_OPEN));
        json_object_set_new(o, "maximum", bound(k->range.max, k->range.hi));
        json_object_set_new(o, "maximum_open", json_boolean(k->range.hi == JC_OPEN));
    }
    if (k->kind == TLSPH_KEY_STRING)
        json_object_set_new(o, "max_length", json_integer((json_int_t)k->size - 1));
    if (k->choices) {
        json_t *c = json_array();
        for (const struct tlsph_key_choice *ch = k->choices; ch->name; ch++)
            json_array_append_new(c, json_string(ch->name));
        json_object_set_new(o, "choices", c);
    }
    if (k->table)
        json_object_set_new(o, "table", json_string(k->table->path));
    json_object_set_new(o, "description", json_string(k->description));
    return o;
}

static int print_json(void)
{
    const struct tables all = all_tables();
    json_t *arr = json_array();
    for (size_t i = 0; i < all.n; i++) {
        const struct tlsph_key_table *t = all.t[i];
        json_t *keys = json_array();
        for (size_t k = 0; k < t->nkeys; k++)
            json_array_append_new(keys, key_json(&t->keys[k]));
        json_array_append_new(arr, json_pack("{s:s, s:s?, s:b, s:o}", "path", t->path, "model",
                                             t->model, "one_of", t->one_of, "keys", keys));
    }
    json_t *doc = json_pack("{s:o, s:s}", "tables", arr, "name_pattern", TLSPH_NAME_PATTERN);
    const int rc = doc ? json_dumpf(doc, stdout, JSON_INDENT(1)) : -1;
    json_decref(doc);
    putchar('\n');
    return rc == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

/* ------------------------------------------------------------------ checks */

static int in_range(double x, struct jc_range r)
{
    return (r.lo == JC_NONE || (r.lo == JC_OPEN ? x > r.min : x >= r.min)) &&
           (r.hi == JC_NONE || (r.hi == JC_OPEN ? x < r.max : x <= r.max));
}

static void check_key(const struct tlsph_key_table *t, size_t i)
{
    const struct tlsph_key *k = &t->keys[i];
    const char *where = k->name;
    ck_assert_msg(k->description && strlen(k->description) > 3, "%s: no description", where);
    for (size_t j = 0; j < i; j++)
        ck_assert_msg(strcmp(t->keys[j].name, k->name) != 0, "%s twice in %s", where, t->path);
    if (k->with) {
        const struct tlsph_key *sw = tlsph_key_find(t, k->with);
        ck_assert_msg(sw && sw < k && !sw->with, "%s: 'with' must name an earlier switch", where);
    }
    if (k->flags & (TLSPH_KEY_CALLER | TLSPH_KEY_REFUSED))
        ck_assert_msg(!(k->flags & TLSPH_KEY_DEFAULT), "%s: the caller's key has a default", where);
    if (k->kind == TLSPH_KEY_NUMBER || k->kind == TLSPH_KEY_INTEGER) {
        ck_assert_msg(k->unit != NULL, "%s: no unit", where);
        const struct jc_range r = k->range;
        if (r.lo != JC_NONE && r.hi != JC_NONE)
            ck_assert_msg(r.min < r.max, "%s: empty range", where);
        if (k->flags & TLSPH_KEY_DEFAULT)
            ck_assert_msg(in_range(k->def, r), "%s: default outside its range", where);
    }
    if (k->kind == TLSPH_KEY_INTEGER) {
        ck_assert_msg(k->range.lo == JC_CLOSED && k->range.hi == JC_CLOSED,
                      "%s: an integer range is closed", where);
        ck_assert_msg(k->size == 0 || k->size == sizeof(int) || k->size == sizeof(long),
                      "%s: integer size", where);
    }
    if (k->kind == TLSPH_KEY_BOOLEAN && (k->flags & TLSPH_KEY_DEFAULT))
        ck_assert_msg(k->def == 0.0 || k->def == 1.0, "%s: boolean default", where);
    if (k->kind == TLSPH_KEY_CHOICE) {
        ck_assert_msg(k->choices && k->choices[0].name && k->noun, "%s: choices", where);
        int has_default = !(k->flags & TLSPH_KEY_DEFAULT);
        for (const struct tlsph_key_choice *c = k->choices; c->name; c++) {
            ck_assert_msg(strlen(c->name) < k->size, "%s: buffer too small", where);
            has_default |= c->value == (int)k->def;
        }
        ck_assert_msg(has_default, "%s: default is not a choice", where);
    }
    if (k->kind == TLSPH_KEY_STRING)
        ck_assert_msg(k->size > 1, "%s: string size", where);
    if (k->flags & TLSPH_KEY_NAME) /* a name string, or an object of named members */
        ck_assert_msg((k->kind == TLSPH_KEY_STRING && k->size == TLSPH_NAME_MAX) ||
                          (k->kind == TLSPH_KEY_OBJECT && (k->flags & TLSPH_KEY_MAP)),
                      "%s: TLSPH_KEY_NAME on a key that holds no name", where);
    if (k->kind == TLSPH_KEY_EXPRESSION)
        ck_assert_msg(k->flags & TLSPH_KEY_CALLER, "%s: an expression is the caller's", where);
    if (k->table) {
        char want[256];
        const int many = k->kind == TLSPH_KEY_ARRAY || (k->flags & TLSPH_KEY_MAP);
        snprintf(want, sizeof want, "%s/%s%s", t->path, k->name, many ? "/*" : "");
        ck_assert_msg(strcmp(k->table->path, want) == 0, "%s: table at %s, link says %s", where,
                      k->table->path, want);
    }
}

START_TEST(test_tables_well_formed)
{
    const struct tables all = all_tables();
    ck_assert_uint_ge(all.n, 20);
    for (size_t i = 0; i < all.n; i++) {
        const struct tlsph_key_table *t = all.t[i];
        ck_assert(t->path != NULL && t->nkeys > 0 && t->nkeys <= 32);
        for (size_t k = 0; k < t->nkeys; k++)
            check_key(t, k);
    }
}
END_TEST

/* Each model's table sits at its family's key and names the model. */
#define CHECK_FAMILY(names, find, family)                                                        \
    do {                                                                                         \
        char list[256];                                                                          \
        snprintf(list, sizeof list, "%s", names());                                              \
        for (char *save, *s = strtok_r(list, ", ", &save); s; s = strtok_r(NULL, ", ", &save)) { \
            const struct tlsph_key_table *t = find(s)->keys;                                     \
            ck_assert_msg(t != NULL, "%s has no key table", s);                                  \
            ck_assert_str_eq(t->path, "/materials/*/" family);                                   \
            ck_assert_str_eq(t->model, s);                                                       \
            ck_assert_str_eq(t->keys[0].name, "type");                                           \
        }                                                                                        \
    } while (0)

START_TEST(test_models)
{
    CHECK_FAMILY(tlsph_eos_names, tlsph_eos_find, "eos");
    CHECK_FAMILY(tlsph_strength_names, tlsph_strength_find, "strength");
    CHECK_FAMILY(tlsph_damage_names, tlsph_damage_find, "damage");
}
END_TEST

/* Each boundary-condition kind's table sits at /boundary_conditions/<i>, names the
 * kind and starts with the rows parse_bcs.c reads before it knows the kind. */
START_TEST(test_bc_kinds)
{
    char list[256];
    snprintf(list, sizeof list, "%s", bc_names());
    for (char *save, *s = strtok_r(list, ", ", &save); s; s = strtok_r(NULL, ", ", &save)) {
        const struct tlsph_key_table *t = tlsph_bc_find(s)->keys;
        ck_assert_msg(t != NULL, "%s has no key table", s);
        ck_assert_str_eq(t->path, "/boundary_conditions/*");
        ck_assert_str_eq(t->model, s);
        ck_assert_uint_ge(t->nkeys, 3);
        ck_assert_str_eq(t->keys[0].name, "type");
        ck_assert_str_eq(t->keys[1].name, "name");
        for (size_t k = 2; k < t->nkeys; k++)
            ck_assert_msg(t->keys[k].flags & TLSPH_KEY_CALLER, "%s %s: read by the kind", s,
                          t->keys[k].name);
    }
}
END_TEST

/* The reader on a small table of its own: what it stores, defaults and says. */
struct sample {
    double x, rate, stress;
    long n;
    int on, choice;
};
static const struct tlsph_key_choice sample_choices[] = {{"a", 0}, {"b", 7}, {0}};
static const struct tlsph_key sample_keys[] = {
    {.name = "x",
     .kind = TLSPH_KEY_NUMBER,
     .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 1.0, JC_OPEN, JC_CLOSED},
     .unit = "m",
     .above_max = "too far",
     .offset = offsetof(struct sample, x),
     .description = "a length"},
    {.name = "n",
     .kind = TLSPH_KEY_INTEGER,
     .flags = TLSPH_KEY_DEFAULT,
     .range = {1.0, 9.0, JC_CLOSED, JC_CLOSED},
     .unit = "1",
     .def = 4.0,
     .offset = offsetof(struct sample, n),
     .description = "a count"},
    {.name = "on",
     .kind = TLSPH_KEY_BOOLEAN,
     .flags = TLSPH_KEY_DEFAULT,
     .def = 1.0,
     .term = 2u,
     .offset = offsetof(struct sample, on),
     .description = "a switch"},
    {.name = "rate",
     .kind = TLSPH_KEY_NUMBER,
     .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "1/s",
     .with = "on",
     .offset = offsetof(struct sample, rate),
     .description = "only with on"},
    {.name = "stress",
     .kind = TLSPH_KEY_NUMBER,
     .flags = TLSPH_KEY_BELOW_E,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "Pa",
     .offset = offsetof(struct sample, stress),
     .description = "a stress"},
    {.name = "choice",
     .kind = TLSPH_KEY_CHOICE,
     .flags = TLSPH_KEY_DEFAULT,
     .def = 7.0,
     .size = 8,
     .choices = sample_choices,
     .noun = "letter",
     .offset = offsetof(struct sample, choice),
     .description = "a letter"},
};
static const struct tlsph_key_table sample_table = TLSPH_KEY_TABLE("/sample", NULL, sample_keys);

/* Reads text with sample_table; returns the status, err holds the messages. */
static int read_sample(const char *text, struct sample *out, unsigned *terms,
                       struct tlsph_errors *err)
{
    json_t *obj = json_loads(text, 0, NULL);
    ck_assert_ptr_nonnull(obj);
    memset(out, 0, sizeof *out);
    *terms = 0;
    const struct tlsph_key_target to = {.base = out, .terms = terms, .youngs_modulus = 1e9};
    tlsph_errors_init(err);
    const int rc = tlsph_keys_read(obj, &sample_table, "/sample", &to, err);
    json_decref(obj);
    return rc;
}

static void expect_message(const struct tlsph_errors *e, size_t i, const char *pointer,
                           const char *message)
{
    ck_assert_uint_gt(e->count, i);
    ck_assert_str_eq(e->items[i].pointer, pointer);
    ck_assert_str_eq(e->items[i].message, message);
}

START_TEST(test_reader)
{
    struct sample v;
    struct tlsph_errors e;
    unsigned terms;
    ck_assert_int_eq(
        read_sample("{\"x\": 0.5, \"on\": true, \"rate\": 3, \"choice\": \"a\"}", &v, &terms, &e),
        0);
    ck_assert(v.x == 0.5 && v.rate == 3.0 && v.n == 4 && v.on == 1 && v.choice == 0);
    ck_assert_uint_eq(terms, 2u);
    tlsph_errors_free(&e);

    ck_assert_int_eq(read_sample("{\"x\": 2, \"n\": 10, \"on\": false, \"rate\": 1, "
                                 "\"stress\": 2e9, \"choice\": \"c\", \"y\": 1}",
                                 &v, &terms, &e),
                     -1);
    expect_message(&e, 0, "/sample/y",
                   "unknown field 'y' (allowed here: x, n, on, rate, stress, choice)");
    expect_message(&e, 1, "/sample/x", "'x' = 2: too far; must be in (0, 1]");
    expect_message(&e, 2, "/sample/n", "'n' = 10 is out of range: must be in [1, 9]");
    expect_message(&e, 3, "/sample/stress",
                   "'stress' = 2e+09 Pa must be below the Young's modulus E = 1e+09 Pa");
    expect_message(&e, 4, "/sample/choice", "unknown letter 'c' (accepted: a, b)");
    ck_assert_uint_eq(e.count, 5); /* on = false is present: rate is read, and valid */
    ck_assert(v.x == 0.0 && v.n == 4 && v.on == 0 && v.choice == 7 && v.rate == 1.0);
    tlsph_errors_free(&e);

    ck_assert_int_eq(read_sample("{\"x\": 0, \"rate\": 1}", &v, &terms, &e), -1);
    expect_message(&e, 0, "/sample/x", "'x' = 0 m is out of range: must be in (0, 1]");
    expect_message(&e, 1, "/sample/rate", "'rate' has no effect without 'on'");
    tlsph_errors_free(&e);
}
END_TEST

/* Every stored value lies inside the object its table writes to. */
static size_t target_size(const char *path)
{
    static const struct tlsph_material m;
    static const struct tlsph_geometry g;
    static const struct {
        const char *path;
        size_t size;
    } sizes[] = {
        {"/materials/*/thermal", sizeof(struct tlsph_thermal)},
        {"/materials/*/eos", sizeof m.eos_params},
        {"/materials/*/strength", sizeof m.strength_params},
        {"/materials/*/damage/evolution", sizeof(struct tlsph_damage)},
        {"/materials/*/damage", sizeof m.damage.params}, /* and its nucleation */
        {"/materials/*", sizeof(struct tlsph_material)},
        {"/bodies/*/geometry", sizeof g.a}, /* its primitives' lengths */
        {"/bodies/*", sizeof(struct tlsph_body)},
        {"/boundary_conditions/*", sizeof(struct tlsph_bc)},
        {"/output/gauges/*", sizeof(struct tlsph_gauge)},
        {"/output/sections/*", sizeof(struct tlsph_section)},
        {"", sizeof(struct tlsph_scene)}, /* the root and its sections */
    };
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        if (strncmp(path, sizes[i].path, strlen(sizes[i].path)) == 0)
            return sizes[i].size;
    return 0;
}

START_TEST(test_offsets)
{
    const struct tables all = all_tables();
    for (size_t i = 0; i < all.n; i++) {
        const size_t size = target_size(all.t[i]->path);
        for (size_t j = 0; j < all.t[i]->nkeys; j++) {
            const struct tlsph_key *k = &all.t[i]->keys[j];
            size_t bytes = 0;
            if (k->flags & (TLSPH_KEY_CALLER | TLSPH_KEY_REFUSED) || k->offset == TLSPH_KEY_NOWHERE)
                continue;
            switch (k->kind) {
            case TLSPH_KEY_NUMBER: bytes = sizeof(double); break;
            case TLSPH_KEY_INTEGER: bytes = k->size ? k->size : sizeof(long); break;
            case TLSPH_KEY_BOOLEAN:
            case TLSPH_KEY_CHOICE: bytes = sizeof(int); break;
            case TLSPH_KEY_STRING: bytes = k->size; break;
            default: continue;
            }
            ck_assert_msg(k->offset + bytes <= size, "%s %s: offset %zu outside %zu bytes",
                          all.t[i]->path, k->name, k->offset, size);
        }
    }
}
END_TEST

/* A scene that sets nothing optional holds the tables' defaults, and they are
 * scene/limits.h's constants. */
START_TEST(test_parser_defaults)
{
    const char *text =
        "{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"m\": {\"density\": "
        "1000, \"youngs_modulus\": 1e9, \"poisson_ratio\": 0.25}}, \"bodies\": [{\"name\": "
        "\"b\", \"material\": \"m\", \"spacing\": 0.001, \"geometry\": {\"box\": {\"min\": "
        "[0,0,0], \"max\": [0.002,0.002,0.002]}}}]}";
    struct tlsph_scene s, parsed, expect;
    struct tlsph_errors e;
    tlsph_errors_init(&e);
    ck_assert_int_eq(tlsph_scene_parse(text, strlen(text), &s, &e), 0);
    memcpy(&parsed, &s, sizeof s); /* padding included: both start zeroed */
    parsed.end_time = 0.0;         /* the one value the text sets */
    parsed.estimated_dt = parsed.estimated_steps = 0.0; /* derived by validation */
    parsed.params = NULL;
    parsed.materials = NULL;
    parsed.bodies = NULL;
    parsed.bcs = NULL;
    parsed.json_text = NULL;
    parsed.nparams = parsed.nmaterials = parsed.nbodies = parsed.nbcs = 0;
    tlsph_scene_defaults(&expect);
    ck_assert(memcmp(&parsed, &expect, sizeof expect) == 0);
    ck_assert_str_eq(expect.name, TLSPH_DEFAULT_NAME);
    ck_assert(expect.cfl == TLSPH_DEFAULT_CFL && expect.frames == TLSPH_DEFAULT_FRAMES);
    ck_assert(expect.max_particles == TLSPH_DEFAULT_MAX_PARTICLES);
    ck_assert(expect.support_factor == TLSPH_DEFAULT_SUPPORT_FACTOR);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
}
END_TEST

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--json") == 0)
        return print_json();
    const TTest *const tests[] = {test_tables_well_formed, test_models, test_bc_kinds, test_offsets,
                                  test_parser_defaults,    test_reader};
    return tlsph_check_run_tests("scene_keys", 0, tests, sizeof tests / sizeof *tests);
}
