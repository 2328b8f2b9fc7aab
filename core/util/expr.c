#include "util/expr.h"

#include <matheval.h>
#include <stdlib.h>
#include <string.h>

void tlsph_expr_free(struct tlsph_expr *ex)
{
    if (ex->evaluator)
        evaluator_destroy(ex->evaluator);
    for (int i = 0; i < ex->nvars; i++)
        free(ex->names[i]);
    free(ex->text);
    memset(ex, 0, sizeof *ex);
}

int tlsph_expr_compile(struct tlsph_expr *ex, const char *text, const char *const *free_vars,
                       int nfree, const struct tlsph_param *params, size_t nparams,
                       const char *pointer, struct tlsph_errors *err)
{
    memset(ex, 0, sizeof *ex);
    if (!text || !*text) {
        tlsph_errors_add(err, pointer, "expression is empty");
        return -1;
    }
    if (strlen(text) > 4096) {
        tlsph_errors_add(err, pointer, "expression longer than 4096 characters");
        return -1;
    }
    char msg[256];
    if (tlsph_expr_syntax(text, msg, sizeof msg) != 0) {
        tlsph_errors_add(err, pointer, "cannot parse expression '%s': %s", text, msg);
        return -1;
    }
    /* libmatheval takes a mutable string. */
    char *copy = strdup(text);
    if (!copy) {
        tlsph_errors_add(err, pointer, "out of memory");
        return -1;
    }
    ex->evaluator = evaluator_create(copy);
    ex->text = copy; /* libmatheval keeps no pointer to it */
    if (!ex->evaluator) {
        tlsph_expr_free(ex);
        tlsph_errors_add(err, pointer, "cannot parse expression '%s'", text);
        return -1;
    }
    char **used;
    int nused;
    evaluator_get_variables(ex->evaluator, &used, &nused);
    int bad = 0;
    for (int k = 0; k < nused; k++) {
        int known = 0;
        for (int i = 0; i < nfree && !known; i++)
            known = strcmp(used[k], free_vars[i]) == 0;
        for (size_t i = 0; i < nparams && !known; i++)
            known = strcmp(used[k], params[i].name) == 0;
        if (!known) {
            char allowed[512] = "";
            size_t len = 0;
            for (int i = 0; i < nfree && len + 1 < sizeof allowed; i++)
                len += (size_t)snprintf(allowed + len, sizeof allowed - len, "%s%s", i ? ", " : "",
                                        free_vars[i]);
            tlsph_errors_add(err, pointer,
                             "expression '%s' uses unknown variable '%s' (allowed: %s%s)", text,
                             used[k], allowed, nparams ? " and the scene parameters" : "");
            bad = 1;
        }
    }
    if (bad || nfree + (int)nparams > TLSPH_EXPR_MAX_VARS) {
        if (!bad)
            tlsph_errors_add(err, pointer, "too many scene parameters (at most %d)",
                             TLSPH_EXPR_MAX_VARS - nfree);
        tlsph_expr_free(ex);
        return -1;
    }
    ex->nfree = nfree;
    ex->constant = 1;
    for (int k = 0; k < nused; k++)
        for (int i = 0; i < nfree; i++)
            if (strcmp(used[k], free_vars[i]) == 0)
                ex->constant = 0;
    for (int i = 0; i < nfree; i++) {
        ex->names[ex->nvars] = strdup(free_vars[i]);
        ex->values[ex->nvars] = 0.0;
        if (!ex->names[ex->nvars++])
            goto oom;
    }
    for (size_t i = 0; i < nparams; i++) {
        ex->names[ex->nvars] = strdup(params[i].name);
        ex->values[ex->nvars] = params[i].value;
        if (!ex->names[ex->nvars++])
            goto oom;
    }
    return 0;
oom:
    tlsph_errors_add(err, pointer, "out of memory");
    tlsph_expr_free(ex);
    return -1;
}

double tlsph_expr_eval(struct tlsph_expr *ex, const double *args)
{
    for (int i = 0; i < ex->nfree; i++)
        ex->values[i] = args[i];
    return evaluator_evaluate(ex->evaluator, ex->nvars, ex->names, ex->values);
}

const char *tlsph_expr_text(const struct tlsph_expr *ex)
{
    return ex->evaluator && ex->text ? ex->text : "";
}
