/* test_util.h - the few helpers every C test here uses. */
#ifndef CACAO_TEST_UTIL_H
#define CACAO_TEST_UTIL_H

#include <stdio.h>

static int test_failures;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);  \
            ++test_failures;                                                          \
        }                                                                             \
    } while (0)

static inline int test_report(const char *name) {
    if (test_failures) fprintf(stderr, "%s: %d check(s) failed\n", name, test_failures);
    else printf("%s: all checks passed\n", name);
    return test_failures ? 1 : 0;
}

/* ctest treats this exit code as "skipped" (SKIP_RETURN_CODE). */
#define TEST_SKIP_CODE 77

#endif
