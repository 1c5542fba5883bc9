/* test_names - cacao.h's names of the enum settings, through the library as users link it. Each
 * named value and its name convert both ways, and the names are the words the cacao command's
 * --help and settings JSON document (written out here by hand, from cacao.h's comment). A DEFAULT
 * names the value cacao_settings_resolve gives it, so printing unresolved settings shows what
 * runs. A value outside its enum gives NULL, which ends a loop over the choices. A name that is
 * not exactly one of the words (another case, an empty string, NULL) is refused with
 * CACAO_ERROR_INVALID_ARGUMENT and leaves *out as it was, so a parser can keep its default. */
#include <string.h>

#include "cacao.h"
#include "test_util.h"

/* One enum seen through int, so that one function checks all four. */
typedef struct named_enum {
    const char *what;
    const char *(*name_of)(int value);
    cacao_result (*from_name)(const char *name, int *value); /* *value is kept when refused */
    const char *words[6];                                    /* by value from 1, NULL-terminated */
    int resolved_default;                                    /* what 0 resolves to */
} named_enum;

#define ADAPT(kind)                                                                                                    \
    static const char *kind##_name(int value) { return cacao_##kind##_name((cacao_##kind)value); }                     \
    static cacao_result kind##_from_name(const char *name, int *value) {                                               \
        cacao_##kind v = (cacao_##kind)*value;                                                                         \
        const cacao_result r = cacao_##kind##_from_name(name, &v);                                                     \
        *value = (int)v;                                                                                               \
        return r;                                                                                                      \
    }
ADAPT(quality)
ADAPT(precision)
ADAPT(estimator)
ADAPT(visibility)

static void check_enum(const named_enum *e) {
    int count = 0;
    while (e->words[count]) ++count;
    for (int value = 1; value <= count; ++value) {
        const char *name = e->name_of(value);
        CHECK(name && strcmp(name, e->words[value - 1]) == 0);
        int back = -5;
        CHECK(e->from_name(e->words[value - 1], &back) == CACAO_SUCCESS && back == value);
    }
    CHECK(e->name_of(count + 1) == NULL);
    CHECK(e->name_of(-1) == NULL);
    CHECK(e->name_of(1000) == NULL);
    const char *default_name = e->name_of(0);
    CHECK(default_name && strcmp(default_name, e->words[e->resolved_default - 1]) == 0);
    printf("%s: %d names, 0 = %s\n", e->what, count, default_name ? default_name : "(null)");

    char upper[16];
    snprintf(upper, sizeof upper, "%s", e->words[0]);
    upper[0] = (char)(upper[0] - 'a' + 'A');
    const char *refused[] = {upper, "", "default", "?", NULL};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; ++i) {
        int kept = -5;
        CHECK(e->from_name(refused[i], &kept) == CACAO_ERROR_INVALID_ARGUMENT && kept == -5);
    }
}

int main(void) {
    cacao_settings resolved;
    CHECK(cacao_settings_resolve(&(cacao_settings){0}, &resolved, NULL, 0) == CACAO_SUCCESS);
    const named_enum enums[] = {
        {"quality", quality_name, quality_from_name, {"lowest", "low", "medium", "high", "highest"},
         (int)resolved.quality},
        {"precision", precision_name, precision_from_name, {"fp32", "fp16"}, (int)resolved.precision},
        {"estimator", estimator_name, estimator_from_name, {"cacao", "gtao", "bitmask"}, (int)resolved.estimator},
        {"visibility", visibility_name, visibility_from_name, {"falloff", "binary"}, (int)resolved.visibility},
    };
    for (size_t i = 0; i < sizeof enums / sizeof enums[0]; ++i) check_enum(&enums[i]);

    /* NULL for out: refused, not written through. */
    CHECK(cacao_quality_from_name("high", NULL) == CACAO_ERROR_INVALID_ARGUMENT);
    CHECK(cacao_estimator_from_name("gtao", NULL) == CACAO_ERROR_INVALID_ARGUMENT);

    /* The loop cacao.h shows lists each choice once, in order. */
    char listed[64] = "";
    for (cacao_quality q = CACAO_QUALITY_LOWEST; cacao_quality_name(q); ++q)
        snprintf(listed + strlen(listed), sizeof listed - strlen(listed), "%s ", cacao_quality_name(q));
    CHECK(strcmp(listed, "lowest low medium high highest ") == 0);
    return test_report("test_names");
}
