/* Axis labels from the series' names and units (docs/output.md names every
 * series after what it measures, so its last segment is the quantity). */
#include "plot_label.h"

#include <stdio.h>
#include <string.h>

/* What a unit measures, for lines that share nothing but their unit. */
static const struct {
    const char *units, *quantity;
} unit_quantities[] = {
    {"J", "energy"},     {"N", "force"},          {"Pa", "stress"},   {"m", "length"},
    {"K", "temperature"}, {"s", "time"},          {"kg m/s", "momentum"}, {"m/s", "velocity"},
    {"kg", "mass"},      {"W", "power"},
};

void plot_name_split(const char *series, char *owner, size_t owner_size, char *quantity,
                     size_t quantity_size)
{
    const char *slash = strrchr(series, '/');
    const char *last = slash ? slash + 1 : series;
    snprintf(owner, owner_size, "%.*s", slash ? (int)(slash - series) : 0, series);
    snprintf(quantity, quantity_size, "%s", last);
    for (char *p = quantity; *p; p++)
        if (*p == '_')
            *p = ' ';
}

static int same(const char *a, const char *b)
{
    return (!a && !b) || (a && b && strcmp(a, b) == 0);
}

/* Length of the words every quantity ends with ("energy"), 0 when none. */
static size_t common_last_words(const plot_quantity *q, size_t n)
{
    const char *q0 = q[0].quantity;
    size_t l0 = strlen(q0), best = 0;
    /* candidate suffixes of q0 start after a space (or at its start) */
    for (size_t start = 0; start < l0; start++) {
        if (start > 0 && q0[start - 1] != ' ')
            continue;
        size_t len = l0 - start;
        size_t i;
        for (i = 1; i < n; i++) {
            size_t li = strlen(q[i].quantity);
            if (li < len || strcmp(q[i].quantity + li - len, q0 + start) != 0 ||
                (li > len && q[i].quantity[li - len - 1] != ' '))
                break;
        }
        if (i == n) {
            best = len;
            break; /* the first match is the longest */
        }
    }
    return best;
}

/* Appends " [units]" and accepts the text when it fits. */
static int try_label(char *buf, size_t size, size_t max_chars, const char *text, const char *units)
{
    char t[512];
    if (*units)
        snprintf(t, sizeof t, "%s [%s]", text, units);
    else
        snprintf(t, sizeof t, "%s", text);
    if (strlen(t) > max_chars)
        return 0;
    snprintf(buf, size, "%s", t);
    return 1;
}

static void describe(char *t, size_t size, const char *quantity, const char *component, const char *owner)
{
    snprintf(t, size, "%s%s%s%s%s", quantity, component ? " " : "", component ? component : "",
             owner && *owner ? " of " : "", owner && *owner ? owner : "");
}

void plot_axis_label(char *buf, size_t size, size_t max_chars, const plot_quantity *q, size_t n)
{
    const char *units = q[0].units ? q[0].units : "";
    char t[512];
    int all_quantity = 1, all_component = 1, all_owner = 1;
    for (size_t i = 1; i < n; i++) {
        all_quantity &= same(q[i].quantity, q[0].quantity);
        all_component &= same(q[i].component, q[0].component);
        all_owner &= same(q[i].owner, q[0].owner);
    }
    if (all_quantity) {
        describe(t, sizeof t, q[0].quantity, all_component ? q[0].component : NULL,
                 all_owner ? q[0].owner : NULL);
        if (try_label(buf, size, max_chars, t, units))
            return;
        describe(t, sizeof t, q[0].quantity, all_component ? q[0].component : NULL, NULL);
        if (try_label(buf, size, max_chars, t, units))
            return;
    } else {
        size_t len = common_last_words(q, n);
        if (len > 0 && try_label(buf, size, max_chars, q[0].quantity + strlen(q[0].quantity) - len, units))
            return;
        /* the distinct quantities, in order */
        size_t k = 0;
        t[0] = '\0';
        for (size_t i = 0; i < n && k < sizeof t; i++) {
            size_t j = 0;
            while (j < i && !same(q[j].quantity, q[i].quantity))
                j++;
            if (j == i)
                k += (size_t)snprintf(t + k, sizeof t - k, "%s%s", k ? ", " : "", q[i].quantity);
        }
        if (k < sizeof t && try_label(buf, size, max_chars, t, units))
            return;
    }
    for (size_t i = 0; i < sizeof unit_quantities / sizeof *unit_quantities; i++)
        if (strcmp(units, unit_quantities[i].units) == 0 &&
            try_label(buf, size, max_chars, unit_quantities[i].quantity, units))
            return;
    if (try_label(buf, size, max_chars, "value", units))
        return;
    /* narrower than "value [unit]": the unit alone, cut to fit */
    snprintf(buf, size, "[%s]", units);
    if (strlen(buf) > max_chars && max_chars < size)
        buf[max_chars] = '\0';
}
