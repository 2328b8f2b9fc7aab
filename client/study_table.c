/* The study summary as a table for people (study_table.h). */
#include "study_table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "schema_units.h"

#define CELL_MAX 40  /* longer texts keep their end: "...steel/strength/yield_stress" */
#define GAP 2        /* spaces between columns */
#define SHORT_ID 8   /* job id characters kept when the table is too wide */
#define PLAIN_MIN 1e-3
#define PLAIN_MAX 1e4

typedef struct {
    char name[CELL_MAX * 4 + 8];  /* the summary's column name, clipped */
    const char *unit;             /* shown in brackets; NULL: none */
    char head[CELL_MAX * 4 + 16]; /* header text with its unit */
    char brief[CELL_MAX * 4 + 16]; /* the same, pointer shortened to its last segments */
    int right;                    /* numbers: right-aligned */
    int pointer, job;             /* a swept pointer; the job_id column */
    char **cell;                  /* one text per row, owned */
    size_t width;
} column;

/* Display width: UTF-8 continuation bytes take no column. */
static size_t text_width(const char *s)
{
    size_t w = 0;
    for (; *s; s++)
        w += ((unsigned char)*s & 0xC0) != 0x80;
    return w;
}

/* Copies s, control characters as spaces; a text wider than CELL_MAX keeps its end. */
static void clip(char *out, size_t size, const char *s)
{
    size_t w = text_width(s);
    const char *t = s;
    int cut = w > CELL_MAX;
    if (cut)
        for (size_t skip = w - (CELL_MAX - 3); skip > 0 || ((unsigned char)*t & 0xC0) == 0x80; t++)
            if (((unsigned char)*t & 0xC0) != 0x80)
                skip--;
    snprintf(out, size, "%s%s", cut ? "..." : "", t);
    for (char *p = out; *p; p++)
        if ((unsigned char)*p < 0x20)
            *p = ' ';
}

/* STUDY_TABLE_DIGITS significant digits, in fixed notation ("0.2787", "12.90")
 * or scientific ("7.113e+05"). */
static void format_real(char *b, size_t n, double v, int fixed)
{
    if (!isfinite(v)) {
        snprintf(b, n, "%g", v);
        return;
    }
    if (!fixed) {
        snprintf(b, n, "%.*e", STUDY_TABLE_DIGITS - 1, v);
        return;
    }
    if (v == 0) {
        snprintf(b, n, "0");
        return;
    }
    char e[48];
    snprintf(e, sizeof e, "%.*e", STUDY_TABLE_DIGITS - 1, v); /* its exponent after rounding */
    int decimals = STUDY_TABLE_DIGITS - 1 - atoi(strchr(e, 'e') + 1);
    snprintf(b, n, "%.*f", decimals < 0 ? 0 : decimals, v);
}

/* The text of every cell of column i, numbers formatted alike (study_table.h). */
static int fill_cells(column *c, const json_t *rows, size_t i, size_t nrows)
{
    int any_real = 0, any_int = 0, fixed = 1;
    size_t r;
    json_t *row;
    json_array_foreach(rows, r, row)
    {
        json_t *v = json_array_get(row, i);
        any_real |= json_is_real(v);
        any_int |= json_is_integer(v);
        double a = fabs(json_number_value(v));
        if (json_is_number(v) && a != 0 && (a < PLAIN_MIN || a >= PLAIN_MAX))
            fixed = 0;
    }
    c->right = any_real || any_int;
    c->cell = calloc(nrows ? nrows : 1, sizeof *c->cell);
    if (!c->cell)
        return -1;
    size_t left_w = 0, frac_w = 0; /* fixed notation: widths either side of the '.' */
    json_array_foreach(rows, r, row)
    {
        json_t *v = json_array_get(row, i);
        char b[CELL_MAX * 4 + 8];
        if (json_is_integer(v) && !any_real)
            snprintf(b, sizeof b, "%lld", (long long)json_integer_value(v));
        else if (json_is_number(v))
            format_real(b, sizeof b, json_number_value(v), fixed);
        else if (json_is_string(v))
            clip(b, sizeof b, json_string_value(v));
        else if (json_is_boolean(v))
            snprintf(b, sizeof b, "%s", json_is_true(v) ? "true" : "false");
        else
            snprintf(b, sizeof b, "%s", json_is_null(v) || !v ? "-" : "?");
        if (!(c->cell[r] = strdup(b)))
            return -1;
        size_t dot = strcspn(b, ".");
        left_w = dot > left_w ? dot : left_w;
        frac_w = strlen(b) - dot > frac_w ? strlen(b) - dot : frac_w;
    }
    if (!any_real || !fixed)
        return 0;
    /* align on the decimal point: pad each number's integer part on the left and its fraction on the right */
    for (r = 0; r < nrows; r++) {
        const char *t = c->cell[r];
        size_t dot = strcspn(t, "."), len = strlen(t);
        char *p = malloc(left_w + frac_w + 1);
        if (!p)
            return -1;
        snprintf(p, left_w + frac_w + 1, "%*s%s%*s", (int)(left_w - dot), "", t, (int)(frac_w - (len - dot)), "");
        free(c->cell[r]);
        c->cell[r] = p;
    }
    return 0;
}

/* The fewest last segments of pointer column self's name that no other pointer
 * column's name ends with: "/materials/steel/density" -> "density". */
static const char *brief_pointer(const column *cols, size_t nc, size_t self)
{
    const char *name = cols[self].name;
    for (const char *p = name + strlen(name); p > name; p--) {
        if (p[-1] != '/')
            continue;
        size_t lp = strlen(p), k;
        for (k = 0; k < nc; k++) {
            const char *other = cols[k].name;
            size_t lo = strlen(other);
            if (k != self && cols[k].pointer && lo >= lp && strcmp(other + lo - lp, p) == 0 &&
                (lo == lp || other[lo - lp - 1] == '/'))
                break;
        }
        if (k == nc)
            return p;
    }
    return name;
}

static void name_column(column *c, const char *name, const json_t *schema)
{
    clip(c->name, sizeof c->name, name);
    c->pointer = name[0] == '/';
    c->job = strcmp(name, "job_id") == 0;
    const char *unit = c->pointer ? schema_unit(schema, name) : NULL;
    if (unit && strcmp(unit, "user") == 0)
        unit = NULL; /* a parameter's unit is its author's */
    else if (unit && strcmp(unit, "1") == 0)
        unit = "-";
    if (strcmp(name, "wall_seconds") == 0)
        snprintf(c->head, sizeof c->head, "wall [s]");
    else if (strcmp(name, "particle_steps_per_second") == 0)
        snprintf(c->head, sizeof c->head, "speed [1/s]");
    else if (unit)
        snprintf(c->head, sizeof c->head, "%s [%s]", c->name, unit);
    else
        snprintf(c->head, sizeof c->head, "%s", c->name);
    c->unit = unit;
    snprintf(c->brief, sizeof c->brief, "%s", c->head);
}

static size_t column_width(const column *c, size_t nrows, int brief)
{
    size_t w = text_width(brief ? c->brief : c->head);
    for (size_t r = 0; r < nrows; r++) {
        size_t cw = text_width(c->cell[r]);
        if (c->job && brief && cw > SHORT_ID)
            cw = SHORT_ID;
        w = cw > w ? cw : w;
    }
    return w;
}

static void put_cell(FILE *f, const char *t, size_t width, int right, int last)
{
    size_t w = text_width(t), pad = width > w ? width - w : 0;
    if (right)
        fprintf(f, "%*s%s", (int)pad, "", t);
    else
        fprintf(f, "%s%*s", t, last ? 0 : (int)pad, "");
}

/* The columns pick[0..np-1]: a header line and one line per row. */
static void print_block(FILE *f, const column *cols, const size_t *pick, size_t np, size_t nrows, int brief)
{
    for (size_t k = 0; k < np; k++) {
        const column *c = &cols[pick[k]];
        if (k)
            fputs("  ", f);
        put_cell(f, brief ? c->brief : c->head, c->width, c->right, k + 1 == np);
    }
    fputc('\n', f);
    for (size_t r = 0; r < nrows; r++) {
        for (size_t k = 0; k < np; k++) {
            const column *c = &cols[pick[k]];
            char id[SHORT_ID + 1];
            const char *t = c->cell[r];
            if (c->job && brief && strlen(t) > SHORT_ID) {
                memcpy(id, t, SHORT_ID);
                id[SHORT_ID] = '\0';
                t = id;
            }
            if (k)
                fputs("  ", f);
            put_cell(f, t, c->width, c->right, k + 1 == np);
        }
        fputc('\n', f);
    }
}

int study_table_print(FILE *f, FILE *note, const json_t *summary, const json_t *schema, size_t max_width)
{
    const json_t *names = json_object_get(summary, "columns"), *rows = json_object_get(summary, "rows");
    size_t nc = json_array_size(names), nrows = json_array_size(rows);
    column *cols = calloc(nc ? nc : 1, sizeof *cols);
    size_t *pick = malloc((nc ? nc : 1) * sizeof *pick);
    int rc = cols && pick ? 0 : -1;
    for (size_t i = 0; i < nc && rc == 0; i++) {
        const char *name = json_string_value(json_array_get(names, i));
        name_column(&cols[i], name ? name : "?", schema);
        rc = fill_cells(&cols[i], rows, i, nrows);
    }
    /* fit: full; then short job ids; then brief pointers too; then blocks */
    int level = 0;
    size_t total = 0;
    for (; rc == 0 && level < 3; level++) {
        total = 0;
        for (size_t i = 0; i < nc; i++) {
            if (level == 2 && cols[i].pointer) {
                const char *u = cols[i].unit;
                snprintf(cols[i].brief, sizeof cols[i].brief, "%s%s%s%s", brief_pointer(cols, nc, i), u ? " [" : "",
                         u ? u : "", u ? "]" : "");
            }
            cols[i].width = column_width(&cols[i], nrows, level > 0);
            total += cols[i].width + (i ? GAP : 0);
        }
        if (total <= max_width)
            break;
    }
    if (level == 3)
        level = 2;
    if (rc == 0 && level > 0 && note)
        fprintf(note, "tlsph: job ids shortened to %d characters%s to fit %zu columns "
                      "(--csv has everything in full)\n",
                SHORT_ID, level > 1 ? " and pointers to their last segments" : "", max_width);
    /* blocks: seq (column 0) starts each; columns added while they fit */
    for (size_t i = nc ? 1 : 0, first = 1; rc == 0 && (i < nc || first);) {
        size_t np = 0, w = 0;
        if (nc) {
            pick[np++] = 0;
            w = cols[0].width;
        }
        while (i < nc && (np == 1 || w + GAP + cols[i].width <= max_width)) {
            w += GAP + cols[i].width;
            pick[np++] = i++;
        }
        if (!first)
            fputc('\n', f);
        print_block(f, cols, pick, np, nrows, level > 0);
        first = 0;
    }
    for (size_t i = 0; cols && i < nc; i++) {
        for (size_t r = 0; cols[i].cell && r < nrows; r++)
            free(cols[i].cell[r]);
        free(cols[i].cell);
    }
    free(cols);
    free(pick);
    return rc;
}
