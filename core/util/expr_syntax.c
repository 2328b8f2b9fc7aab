/* Syntax check of an expression in libmatheval's language, before libmatheval
 * sees it: its parser leaks memory on syntax errors and its lexer echoes
 * unknown characters to stdout, and a checker of our own can say where the
 * problem is.  The language (libmatheval 1.1):
 *
 *   expr    := operand (binop operand)*          binop := + - * / ^
 *   operand := '-'* atom
 *   atom    := number | constant | variable | function '(' expr ')' | '(' expr ')'
 *   number  := digits ['.' digits*] | '.' digits, then optional [eE][+-]?digits
 *
 * Precedence is libmatheval's (^ left-associative, unary minus below ^); here
 * only validity matters. */
#include <stdio.h>
#include <string.h>

#include "util/expr.h"

static const char *const functions[] = {
    "exp", "log", "sqrt", "sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan",
    "acot", "asec", "acsc", "sinh", "cosh", "tanh", "coth", "sech", "csch", "asinh", "acosh",
    "atanh", "acoth", "asech", "acsch", "abs", "step", "delta", "nandelta", "erf", NULL};

static const char *const constants[] = {"e", "log2e", "log10e", "ln2", "ln10", "pi", "pi_2",
                                        "pi_4", "1_pi", "2_pi", "2_sqrtpi", "sqrt2", "sqrt1_2",
                                        NULL};

static int in_list(const char *const *list, const char *s, size_t n)
{
    for (; *list; list++)
        if (strlen(*list) == n && strncmp(*list, s, n) == 0)
            return 1;
    return 0;
}

int tlsph_expr_reserved(const char *name)
{
    const size_t n = strlen(name);
    return in_list(functions, name, n) || in_list(constants, name, n);
}

struct cursor {
    const char *text, *p;
    char *msg;
    size_t size;
    int depth;
};

static int is_alpha(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static void skip(struct cursor *c)
{
    while (*c->p == ' ' || *c->p == '\t')
        c->p++;
}

static int fail(struct cursor *c, const char *what)
{
    const long col = (long)(c->p - c->text) + 1;
    if (*c->p)
        snprintf(c->msg, c->size, "%s at column %ld (near '%.12s')", what, col, c->p);
    else
        snprintf(c->msg, c->size, "%s at the end of the expression", what);
    return -1;
}

static int expr(struct cursor *c);

static int number(struct cursor *c)
{
    int digits = 0;
    while (is_digit(*c->p)) {
        c->p++;
        digits++;
    }
    if (*c->p == '.') {
        c->p++;
        while (is_digit(*c->p)) {
            c->p++;
            digits++;
        }
    }
    if (!digits)
        return fail(c, "malformed number");
    if (*c->p == 'e' || *c->p == 'E') {
        const char *save = c->p;
        c->p++;
        if (*c->p == '+' || *c->p == '-')
            c->p++;
        if (!is_digit(*c->p)) {
            c->p = save;
            return fail(c, "malformed exponent");
        }
        while (is_digit(*c->p))
            c->p++;
    }
    if (is_alpha(*c->p) || *c->p == '.')
        return fail(c, "unexpected character after a number (missing operator?)");
    return 0;
}

static int atom(struct cursor *c)
{
    skip(c);
    if (*c->p == '(') {
        c->p++;
        if (++c->depth > 100)
            return fail(c, "parentheses nested too deeply");
        if (expr(c))
            return -1;
        skip(c);
        if (*c->p != ')')
            return fail(c, "missing ')'");
        c->p++;
        c->depth--;
        return 0;
    }
    if (is_digit(*c->p) || *c->p == '.')
        return number(c);
    if (is_alpha(*c->p)) {
        const char *start = c->p;
        while (is_alpha(*c->p) || is_digit(*c->p))
            c->p++;
        const size_t n = (size_t)(c->p - start);
        const int function = in_list(functions, start, n);
        skip(c);
        if (function) {
            if (*c->p != '(') {
                c->p = start;
                return fail(c, "a function needs its argument in parentheses");
            }
            return atom(c);
        }
        if (*c->p == '(') {
            c->p = start;
            return fail(c, "unknown function");
        }
        return 0;
    }
    return fail(c, *c->p ? "unexpected character" : "missing operand");
}

static int expr(struct cursor *c)
{
    for (;;) {
        skip(c);
        while (*c->p == '-') {
            c->p++;
            skip(c);
        }
        if (atom(c))
            return -1;
        skip(c);
        if (*c->p && strchr("+-*/^", *c->p)) {
            c->p++;
            continue;
        }
        return 0;
    }
}

int tlsph_expr_syntax(const char *text, char *msg, size_t size)
{
    struct cursor c = {text, text, msg, size, 0};
    if (expr(&c))
        return -1;
    skip(&c);
    if (*c.p)
        return fail(&c, *c.p == ')' ? "unbalanced ')'" : "missing operator");
    return 0;
}
