/* The main() every Check test program shares: run the suite, free it, and turn
 * the failure count into the exit status automake's test driver reads
 * (0 pass, 1 fail; 77 skip is the caller's to return before running). */
#ifndef TLSPH_TEST_CHECK_MAIN_H
#define TLSPH_TEST_CHECK_MAIN_H

#include <check.h>
#include <stddef.h>

/* Runs every test of s (CK_NORMAL output), frees the runner and the suite.
 * Returns EXIT_SUCCESS when no test failed, EXIT_FAILURE otherwise. */
int tlsph_check_run(Suite *s);

/* A suite named `name` with one test case of that name holding tests[0..n-1];
 * timeout in seconds (0: Check's default).  The timeout only detects a hung
 * test; nothing is judged by speed.  Same return as tlsph_check_run. */
int tlsph_check_run_tests(const char *name, double timeout, const TTest *const *tests, size_t n);

/* main() of a test program whose tests all belong to one case:
 *   TLSPH_CHECK_MAIN("kernel", 0, normalisation, support_and_gradient)   */
#define TLSPH_CHECK_MAIN(NAME, TIMEOUT, ...)                                                       \
    int main(void)                                                                                 \
    {                                                                                              \
        const TTest *const tests_[] = {__VA_ARGS__};                                               \
        return tlsph_check_run_tests(NAME, TIMEOUT, tests_, sizeof tests_ / sizeof *tests_);       \
    }

#endif
