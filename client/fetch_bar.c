/* Download progress bar (fetch_bar.h). */
#include "fetch_bar.h"

#include <stdio.h>
#include <unistd.h>

#include "util/clock.h"

#define BAR_CELLS 20
#define REDRAW_S 0.1

void fetch_bar_init(fetch_bar *b, const char *name, const long *status, const long long *offset)
{
    b->on = isatty(STDERR_FILENO);
    b->name = name;
    b->status = status;
    b->offset = offset;
    b->last_draw = -1;
    b->last_bytes = -1;
}

/* "1.6 MiB", "512 KiB", "900 B" */
static void human_bytes(char *buf, size_t n, double v)
{
    if (v >= 1048576.0)
        snprintf(buf, n, "%.1f MiB", v / 1048576.0);
    else if (v >= 1024.0)
        snprintf(buf, n, "%.0f KiB", v / 1024.0);
    else
        snprintf(buf, n, "%.0f B", v);
}

static void draw(const fetch_bar *b, double now_bytes, double total)
{
    char have[32], all[32];
    human_bytes(have, sizeof have, now_bytes);
    if (total > 0) {
        double f = now_bytes / total;
        f = f < 0 ? 0 : f > 1 ? 1 : f;
        int fill = (int)(f * BAR_CELLS + 0.5);
        char cells[BAR_CELLS + 1];
        for (int i = 0; i < BAR_CELLS; i++)
            cells[i] = i < fill ? '#' : '.';
        cells[BAR_CELLS] = '\0';
        human_bytes(all, sizeof all, total);
        fprintf(stderr, "\r%s  [%s] %3.0f%%  %s of %s\033[K", b->name, cells, 100.0 * f, have, all);
    } else {
        fprintf(stderr, "\r%s  %s\033[K", b->name, have);
    }
    fflush(stderr);
}

static int on_progress(void *u, curl_off_t dltotal, curl_off_t dlnow, curl_off_t ultotal, curl_off_t ulnow)
{
    (void)ultotal;
    (void)ulnow;
    fetch_bar *b = u;
    if (*b->status != 200 && *b->status != 206)
        return 0;
    double t = tlsph_monotonic_seconds();
    int done = dltotal > 0 && dlnow >= dltotal;
    double base = (double)*b->offset, bytes = base + (double)dlnow;
    if (b->last_draw >= 0 && ((t - b->last_draw < REDRAW_S && !done) || bytes == b->last_bytes))
        return 0;
    draw(b, bytes, dltotal > 0 ? base + (double)dltotal : 0);
    b->last_draw = t;
    b->last_bytes = bytes;
    return 0; /* never aborts the transfer */
}

int fetch_bar_attach(fetch_bar *b, CURL *c)
{
    if (!b->on)
        return 0;
    if (curl_easy_setopt(c, CURLOPT_XFERINFOFUNCTION, on_progress) != CURLE_OK ||
        curl_easy_setopt(c, CURLOPT_XFERINFODATA, b) != CURLE_OK ||
        curl_easy_setopt(c, CURLOPT_NOPROGRESS, 0L) != CURLE_OK)
        return -1;
    return 0;
}

void fetch_bar_end(fetch_bar *b)
{
    if (b->on && b->last_draw >= 0) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
    }
}
