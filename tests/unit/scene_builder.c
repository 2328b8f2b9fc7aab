#include "scene_builder.h"

#include <check.h>
#include <stdio.h>
#include <string.h>

struct tlsph_model *build_model(const char *json)
{
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    if (tlsph_scene_parse(json, strlen(json), &scene, &err) == 0)
        tlsph_model_create(&scene, &m, &err);
    for (size_t k = 0; k < err.count; k++)
        fprintf(stderr, "scene error: %s: %s\n", err.items[k].pointer, err.items[k].message);
    tlsph_errors_free(&err);
    ck_assert_msg(m != NULL, "test scene rejected");
    return m;
}

void run_until(struct tlsph_model *m, double t_end)
{
    struct tlsph_diagnostic d;
    while (m->t < t_end * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "unstable: %s", d.message);
    }
}
