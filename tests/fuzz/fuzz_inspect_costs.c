/* fuzz_inspect_costs - libFuzzer harness for the cacao-bench JSON of `cacao-inspect list --costs`
 * (issue 35): any bytes are read or refused with one line without control bytes. What is accepted
 * is checked here apart from the reader, against what `list` relies on when it prints: every
 * "results" entry an object whose "config" is a printable string (printed as it is), and every
 * pass of it an object with a string "name" and a finite "time_ms" of 0 or more. (Before the fix,
 * an array of numbers was taken as results, and a config with a terminal escape printed raw.) */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_input.h"
#include "image_io.h"
#include "inspect_args.h"

static void check_accepted(const cJSON *root) {
    const cJSON *results = cJSON_GetObjectItemCaseSensitive(root, "results"), *r, *p;
    if (!cJSON_IsArray(results)) abort();
    cJSON_ArrayForEach(r, results) {
        if (!cJSON_IsObject(r) ||
            !cacao_text_is_printable(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(r, "config"))))
            abort();
        const cJSON *passes = cJSON_GetObjectItemCaseSensitive(r, "passes");
        if (passes && !cJSON_IsArray(passes)) abort();
        cJSON_ArrayForEach(p, passes) {
            const cJSON *ms = cJSON_GetObjectItemCaseSensitive(p, "time_ms");
            if (!cJSON_IsObject(p) || !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(p, "name")) ||
                !cJSON_IsNumber(ms) || !isfinite(ms->valuedouble) || ms->valuedouble < 0)
                abort();
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char err[1024] = "";
    cJSON *root = inspect_read_costs(fuzz_input_file(data, size, ".json"), err, sizeof err);
    if (root)
        check_accepted(root);
    else if (!err[0] || strchr(err, '\n') || !cacao_text_is_printable(err))
        abort();
    cJSON_Delete(root);
    return 0;
}
