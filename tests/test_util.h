/* test_util.h - the few helpers every C test here uses. */
#ifndef CACAO_TEST_UTIL_H
#define CACAO_TEST_UTIL_H

#include <stdio.h>
#include <stdlib.h>

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

/* dir/name, in one of 8 rotating buffers (so that one call can take several paths). */
static inline const char *test_path(const char *dir, const char *name) {
    static char paths[8][8192];
    static int next;
    char *p = paths[next++ % 8];
    snprintf(p, sizeof paths[0], "%s/%s", dir, name);
    return p;
}

/* For a test whose one argument is its scratch folder: copies it into dir (size bytes) and empties
 * it; exits 2 on a wrong argument count, or when the folder cannot be made. */
static inline void test_scratch_dir(int argc, char **argv, char *dir, size_t size) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s SCRATCH_DIR\n", argv[0]);
        exit(2);
    }
    snprintf(dir, size, "%s", argv[1]);
    char command[8300];
    snprintf(command, sizeof command, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
    if (system(command) != 0) exit(2);
}

/* ctest treats this exit code as "skipped" (SKIP_RETURN_CODE). */
#define TEST_SKIP_CODE 77

#endif
