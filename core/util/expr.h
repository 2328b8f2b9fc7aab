/* Scene expressions (initial velocities, prescribed velocities, group selectors),
 * evaluated with libmatheval.
 *
 * An expression may use the variables it is compiled for (for example x, y, z
 * for reference coordinates in m, or t for time in s) and the named scalar
 * parameters of the scene.  Anything else is an error, reported at validation
 * time, never at run time. */
#ifndef TLSPH_EXPR_H
#define TLSPH_EXPR_H

#include <stddef.h>

#include "util/errors.h"

#define TLSPH_EXPR_MAX_VARS 48

struct tlsph_param {
    char name[64];
    double value;
};

struct tlsph_expr {
    void *evaluator;                      /* libmatheval handle (owned) */
    int nvars;                            /* variables passed to each evaluation */
    char *names[TLSPH_EXPR_MAX_VARS];     /* owned copies */
    double values[TLSPH_EXPR_MAX_VARS];   /* free variables first, then parameters */
    int nfree;                            /* number of free variables (x,y,z,t...) */
    int constant;                         /* uses no free variable */
    char *text;                           /* the text compiled (owned), for messages */
};

/* Compiles text; free_vars lists the allowed free variables (e.g. {"x","y","z"}).
 * On failure adds an error at pointer and returns -1. */
int tlsph_expr_compile(struct tlsph_expr *ex, const char *text, const char *const *free_vars,
                       int nfree, const struct tlsph_param *params, size_t nparams,
                       const char *pointer, struct tlsph_errors *err);
/* Evaluates with the free variables set to args[0..nfree-1]. Not thread-safe
 * (libmatheval evaluators share state); call from one thread. */
double tlsph_expr_eval(struct tlsph_expr *ex, const double *args);
void tlsph_expr_free(struct tlsph_expr *ex);
/* The text ex was compiled from (for messages); owned by ex, valid until
 * tlsph_expr_free.  "" when ex holds no expression. */
const char *tlsph_expr_text(const struct tlsph_expr *ex);

/* core/util/expr_syntax.c: checks text against libmatheval's grammar before
 * libmatheval sees it (0, or -1 with a message locating the problem);
 * tlsph_expr_compile calls it.  tlsph_expr_reserved: a built-in function or
 * constant name, which a scene parameter may not shadow. */
int tlsph_expr_syntax(const char *text, char *msg, size_t size);
int tlsph_expr_reserved(const char *name);

#endif
