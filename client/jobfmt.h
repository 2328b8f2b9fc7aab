/* Human-readable views of a job's statusInfo. */
#ifndef TLSPH_CLIENT_JOBFMT_H
#define TLSPH_CLIENT_JOBFMT_H

#include <jansson.h>
#include <stdio.h>

/* "status" member, "" when missing. */
const char *job_status(const json_t *info);
/* 1 for successful / failed / dismissed. */
int job_is_final(const char *status);
/* Exit code for a final status: 0 successful, 3 failed, 4 dismissed. */
int job_exit_code(const char *status);
/* Multi-line summary (status command). */
void job_print_summary(FILE *f, const json_t *info);
/* One line: "ID STATUS (outcome ...): message" */
void job_print_final_line(FILE *f, const json_t *info);
/* Parses an RFC 3339 UTC/offset date-time into seconds since the epoch; -1 on error. */
double job_parse_time(const char *s);
/* Writes s without control characters. */
void print_safe(FILE *f, const char *s);

#endif
