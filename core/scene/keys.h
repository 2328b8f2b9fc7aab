/* Scene keys described once.
 *
 * Every key of a scene object is one row of a key table: its name, its JSON
 * type, its range with open or closed ends, its SI unit, its default or that it
 * is required, a description, and where its value goes (an offset from a base
 * pointer: a struct member, or a model parameter TLSPH_PARAM(i)).  One reader
 * walks a table over a JSON object: it reports unknown keys, wrong types,
 * missing required keys and out-of-range values (JSON pointer + a message that
 * names the key, its range and its unit, see json_check.h), stores what is
 * valid and writes the defaults.  What a table cannot say -- one key compared
 * with another, a key that needs a block elsewhere -- stays in the code that
 * calls the reader, after it.
 *
 * The same tables are the reference for schemas/scene.schema.json and
 * docs/scene.md: tests/engine/test_scene_keys prints them as JSON and
 * tests/support/scene_keys_check.py compares both documents with them.
 *
 * Tables: the scene's own sections in core/scene/scene_keys.c (the root is
 * tlsph_scene_keys; the others hang from it through .table), the geometry
 * primitives next to their parsers in core/scene/parse_geometry.c, each model's
 * parameters next to its law in core/material/{eos,strength,damage}/, each
 * boundary-condition kind's keys in its file in core/bc/. */
#ifndef TLSPH_SCENE_KEYS_H
#define TLSPH_SCENE_KEYS_H

#include <stddef.h>
#include <jansson.h>

#include "util/errors.h"
#include "scene/json_check.h"

enum tlsph_key_kind {
    TLSPH_KEY_NUMBER,  /* double */
    TLSPH_KEY_INTEGER, /* long, or int when .size == sizeof(int); range closed at both ends */
    TLSPH_KEY_BOOLEAN, /* int, 0 or 1 */
    TLSPH_KEY_CHOICE,  /* a string among .choices, stored as the choice's int value */
    TLSPH_KEY_STRING,  /* char[.size], 1 to .size - 1 characters */
    TLSPH_KEY_OBJECT,  /* keys described by .table (with TLSPH_KEY_MAP: each member is) */
    TLSPH_KEY_ARRAY,   /* items described by .table when they are objects */
    /* a string expression of the scene's parameters and some variables (or a
     * condition), compiled by the caller: always TLSPH_KEY_CALLER */
    TLSPH_KEY_EXPRESSION
};

/* .flags */
enum {
    TLSPH_KEY_REQUIRED = 1u, /* must be present (when its .with key is present) */
    /* Absent means .def (.def_text for a string); for a required key, the value
     * validation goes on with when it is missing or invalid. */
    TLSPH_KEY_DEFAULT = 2u,
    /* Read by the caller, not by tlsph_keys_values: listed so that it is allowed here
     * and documented. */
    TLSPH_KEY_CALLER = 4u,
    /* Not accepted: listed so that the caller can refuse it with its reason instead of
     * "unknown field". */
    TLSPH_KEY_REFUSED = 8u,
    TLSPH_KEY_MAP = 16u, /* OBJECT whose members, under any name, are each a .table */
    /* NUMBER in Pa that must be below the material's Young's modulus (a flow stress at
     * or above E means unit slip). */
    TLSPH_KEY_BELOW_E = 32u,
    /* A name that becomes part of an HDF5 path or a series name: a STRING (or, with
     * TLSPH_KEY_MAP, each member's name) that must follow the naming rule
     * (util/names.h).  The reader checks the STRING keys it reads; callers that read
     * a name themselves check it with tlsph_scene_check_name. */
    TLSPH_KEY_NAME = 64u
};

/* Where a key's value goes when it is stored nowhere (only validated). */
#define TLSPH_KEY_NOWHERE ((size_t)-1)
/* Offset of model parameter i from a double array base (m->strength_params ...). */
#define TLSPH_PARAM(i) ((size_t)(i) * sizeof(double))

struct tlsph_key_choice {
    const char *name; /* as written in the scene */
    int value;        /* as stored */
};

struct tlsph_key_table;

struct tlsph_key {
    const char *name;
    enum tlsph_key_kind kind;
    unsigned flags;        /* TLSPH_KEY_* */
    struct jc_range range; /* NUMBER, INTEGER (JC_NONE: unbounded on that side) */
    /* SI unit, "1" when dimensionless; NULL for choices, booleans, strings, objects */
    const char *unit;
    /* How messages name the unit when not .unit; NULL: .unit, or "(dimensionless)"
     * when .unit is "1". */
    const char *said;
    /* TLSPH_KEY_DEFAULT: the value of a NUMBER, INTEGER, BOOLEAN (0/1) or CHOICE (the
     * default choice's value); def_text that of a STRING. */
    double def;
    const char *def_text;
    size_t offset; /* from the reader's base; TLSPH_KEY_NOWHERE */
    /* INTEGER: sizeof(int) or sizeof(long) (0 = long); STRING, CHOICE: buffer size
     * with the NUL. */
    size_t size;
    const struct tlsph_key_choice *choices; /* CHOICE: ends with {NULL, 0} */
    /* CHOICE: "unknown <noun> 'x' (accepted: ...)"; TLSPH_KEY_NAME: what the name
     * names, for messages ("boundary condition name") */
    const char *noun;
    /* Only with this earlier key of the same object: read when it is present, "has no
     * effect without" when it is not. */
    const char *with;
    /* Or'ed into the target's *terms when the value is valid: the optional term of a
     * law it switches on (TLSPH_FLOW_RATE ...). */
    unsigned term;
    /* NUMBER: why values above the maximum are refused, in place of "is out of range". */
    const char *above_max;
    /* OBJECT, ARRAY: the keys of the object, of each member (TLSPH_KEY_MAP) or of each
     * item; read by the reader itself unless TLSPH_KEY_CALLER. */
    const struct tlsph_key_table *table;
    const char *description; /* what the key means, for people */
};

struct tlsph_key_table {
    /* Where the object sits in a scene: a JSON pointer with "*" for any member name or
     * item index (a material's thermal block: "/materials/" "*" "/thermal"). */
    const char *path;
    const char *model; /* a model's parameters: the "type" that selects this table */
    const struct tlsph_key *keys;
    size_t nkeys;
    /* The object holds exactly one of the keys, and its name says what the object is
     * (a geometry: {"box": {...}}). */
    int one_of;
};

/* clang-format off */
#define TLSPH_KEY_TABLE(path_, model_, keys_)                                                  \
    {.path = (path_), .model = (model_), .keys = (keys_), .nkeys = sizeof(keys_) / sizeof *(keys_)}

/* The "type" key of a model's table: read by the caller to choose the model. */
#define TLSPH_KEY_MODEL_TYPE                                                                   \
    {.name = "type", .kind = TLSPH_KEY_STRING,                                                 \
     .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER, .size = 64,                               \
     .description = "the model's name"}

/* A point, and a direction of any non-zero length, both 3 numbers and read by the
 * caller (jc_vector, tlsph_parse_direction). */
#define TLSPH_KEY_POINT(key, what)                                                             \
    {.name = (key), .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,  \
     .unit = "m", .description = (what)}
#define TLSPH_KEY_DIRECTION(key, what)                                                         \
    {.name = (key), .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,  \
     .unit = "1", .description = (what)}
/* clang-format on */

/* What the reader writes to. */
struct tlsph_key_target {
    void *base;            /* offsets count from here */
    unsigned *terms;       /* gets the .term bits of the valid keys; NULL: none */
    double youngs_modulus; /* bound of TLSPH_KEY_BELOW_E keys, Pa; 0 = unknown (unchecked) */
};

/* The scene's root object; every other scene table hangs from it. */
extern const struct tlsph_key_table tlsph_scene_keys;

/* Reports each key of obj that t does not list.  Returns 0, or -1 when there was one. */
int tlsph_keys_unknown(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                       struct tlsph_errors *err);
/* Writes the defaults of t (and of the objects it reads itself) at to->base, then
 * reads every key of t that is not TLSPH_KEY_CALLER: type, range, presence,
 * "only with".  Stores only valid values.  Returns 0, or -1 after an error. */
int tlsph_keys_values(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                      const struct tlsph_key_target *to, struct tlsph_errors *err);
/* tlsph_keys_unknown, then tlsph_keys_values. */
int tlsph_keys_read(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                    const struct tlsph_key_target *to, struct tlsph_errors *err);
/* Reads obj[name], an object, with table t: 1 when it is absent and optional, 0 when
 * read, -1 after an error (a required one missing included). */
int tlsph_keys_object(const json_t *obj, const char *name, int required,
                      const struct tlsph_key_table *t, const char *pointer,
                      const struct tlsph_key_target *to, struct tlsph_errors *err);
/* Reads the member `name` of obj (an OBJECT key of `parent`, the table of obj) with its
 * own table: 1 when it is absent and optional, 0 when read, -1 after an error
 * (a required one missing included). */
int tlsph_keys_member(const json_t *obj, const struct tlsph_key_table *parent, const char *name,
                      const char *pointer, const struct tlsph_key_target *to,
                      struct tlsph_errors *err);
/* Writes the defaults of t, and of the objects tlsph_keys_values reads with it. */
void tlsph_keys_defaults(const struct tlsph_key_table *t, void *base);
/* The names of t's keys in order, separated by ", ", into buf (size bytes; cut
 * short when it is too small).  For messages that list them. */
void tlsph_keys_names(const struct tlsph_key_table *t, char *buf, size_t size);
/* The row of t named name, or NULL. */
const struct tlsph_key *tlsph_key_find(const struct tlsph_key_table *t, const char *name);
/* The naming rule (util/names.h) for name, the scene's `what` ("body name"...) at
 * pointer: 0 when it follows the rule, else -1 with an error (core/scene/names.c). */
int tlsph_scene_check_name(const char *name, const char *what, const char *pointer,
                           struct tlsph_errors *err);
/* printf-style error at pointer/key: for the checks that follow a table. */
void tlsph_key_error(struct tlsph_errors *err, const char *pointer, const char *key,
                     const char *fmt, ...) __attribute__((format(printf, 4, 5)));

#endif
