#include "support/check_main.h"

#include <stdlib.h>

int tlsph_check_run(Suite *s)
{
    SRunner *sr = srunner_create(s);
    srunner_run_all(sr, CK_NORMAL);
    const int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}

int tlsph_check_run_tests(const char *name, double timeout, const TTest *const *tests, size_t n)
{
    Suite *s = suite_create(name);
    TCase *tc = tcase_create(name);
    if (timeout > 0)
        tcase_set_timeout(tc, timeout);
    for (size_t k = 0; k < n; k++)
        tcase_add_test(tc, tests[k]);
    suite_add_tcase(s, tc);
    return tlsph_check_run(s);
}
