/* tlsph: command-line client of the tlsphd job daemon.  Parses the global options,
 * loads the settings and dispatches to a subcommand. */
#ifdef HAVE_CONFIG_H
#include <config.h>
#endif
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "settings.h"

#ifndef PACKAGE_VERSION
#define PACKAGE_VERSION "dev"
#endif

static const char usage_text[] =
    "usage: tlsph [--url URL] [--token TOKEN] [--config FILE] COMMAND [ARGS...]\n"
    "\n"
    "commands:\n"
    "  submit SCENE.json             submit a run; prints the job id\n"
    "  status ID [--json]            job summary (or the statusInfo JSON)\n"
    "  watch ID                      live progress until the job is final\n"
    "  wait ID [--timeout S]         block until the job is final; print its status\n"
    "  fetch ID [-o DIR]             download result.h5 and result.xmf into DIR (default ./ID),\n"
    "                                resuming an interrupted download (DIR/result.h5.part)\n"
    "  series ID [NAME...] [--csv]   list the time series, or print them (JSON or CSV)\n"
    "  plot ID NAME[:C]... -o FILE.svg [--x NAME:C] [--title T] [--log]\n"
    "                                SVG line plot versus time (or versus another series);\n"
    "                                series of other units or magnitudes get their own panel\n"
    "  cancel ID [--remove]          dismiss a queued/running job (--remove: also delete a\n"
    "                                final job and its files)\n"
    "  list [--status S] [--study ID] [--limit N] [--json]   table of jobs, newest first\n"
    "  study submit STUDY.json       submit a parameter study; prints its id\n"
    "  study status ID               study summary with counts of its children\n"
    "  study table ID [--csv]        summary table (one row per child)\n"
    "  convergence submit FILE.json  submit a convergence study (base, ladder, outputs, target)\n"
    "  convergence table ID [--csv|--json]\n"
    "                                per output: values, observed order, Richardson limit,\n"
    "                                error and GCI per spacing; cost model and prediction\n"
    "  convergence plot ID -o FILE.svg [--reference NAME=VALUE]... [--title T]\n"
    "                                estimated (and true) error vs wall time, log-log\n"
    "\n"
    "settings (first found wins): --url/--token flags; TLSPH_URL/TLSPH_TOKEN; the config file\n"
    "(--config FILE, else $XDG_CONFIG_HOME/tlsph/client.conf or ~/.config/tlsph/client.conf,\n"
    "lines 'url = ...' and 'token = ...'); default URL " SETTINGS_DEFAULT_URL ".\n"
    "The token is sent as 'Authorization: Bearer TOKEN'.\n"
    "\n"
    "exit codes:\n"
    "  0 success (for watch/wait: job successful)   5 cannot reach the server / network error\n"
    "  1 usage error                                6 authentication failed (401/403)\n"
    "  2 server rejected the request (4xx/5xx)      7 local I/O error\n"
    "  3 job failed                                 8 timeout (wait --timeout)\n"
    "  4 job dismissed\n";

typedef int (*command_fn)(const settings *, int, char **);

static const struct {
    const char *name;
    command_fn fn;
} commands[] = {
    {"submit", cmd_submit}, {"status", cmd_status}, {"watch", cmd_watch},   {"wait", cmd_wait},
    {"fetch", cmd_fetch},   {"series", cmd_series}, {"plot", cmd_plot},     {"cancel", cmd_cancel},
    {"list", cmd_list},     {"study", cmd_study},   {"convergence", cmd_convergence},
};

/* Matches "--name VALUE" or "--name=VALUE"; advances *i. */
static int option_value(int argc, char **argv, int *i, const char *name, const char **val)
{
    size_t n = strlen(name);
    if (strncmp(argv[*i], name, n) != 0)
        return 0;
    if (argv[*i][n] == '=') {
        *val = argv[*i] + n + 1;
        return 1;
    }
    if (argv[*i][n] != '\0')
        return 0;
    if (*i + 1 >= argc) {
        *val = NULL;
        return -1;
    }
    *val = argv[++*i];
    return 1;
}

int main(int argc, char **argv)
{
    const char *url = NULL, *token = NULL, *config = NULL;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        const char *v;
        int m;
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            fputs(usage_text, stdout);
            return RC_OK;
        }
        if (strcmp(argv[i], "--version") == 0) {
            printf("tlsph %s\n", PACKAGE_VERSION);
            return RC_OK;
        }
        if ((m = option_value(argc, argv, &i, "--url", &v)) != 0)
            url = v;
        else if ((m = option_value(argc, argv, &i, "--token", &v)) != 0)
            token = v;
        else if ((m = option_value(argc, argv, &i, "--config", &v)) != 0)
            config = v;
        else {
            fprintf(stderr, "tlsph: unknown option %s\n%s", argv[i], usage_text);
            return RC_USAGE;
        }
        if (m < 0) {
            fprintf(stderr, "tlsph: %s needs a value\n", argv[i]);
            return RC_USAGE;
        }
    }
    if (i >= argc) {
        fputs(usage_text, stderr);
        return RC_USAGE;
    }
    command_fn fn = NULL;
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        if (strcmp(argv[i], commands[k].name) == 0)
            fn = commands[k].fn;
    if (!fn) {
        fprintf(stderr, "tlsph: unknown command '%s' (see tlsph --help)\n", argv[i]);
        return RC_USAGE;
    }
    for (int k = i + 1; k < argc; k++)
        if (strcmp(argv[k], "-h") == 0 || strcmp(argv[k], "--help") == 0) {
            fputs(usage_text, stdout);
            return RC_OK;
        }
    settings s;
    int rc = settings_load(&s, url, token, config);
    if (rc != RC_OK)
        return rc;
    if ((rc = http_global_init()) != RC_OK)
        return rc;
    rc = fn(&s, argc - i, argv + i);
    http_global_cleanup();
    if (fflush(stdout) != 0 && rc == RC_OK) {
        perror("tlsph: stdout");
        rc = RC_IO;
    }
    return rc;
}
