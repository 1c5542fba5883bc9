/* fuzz_inspect_args - libFuzzer harness for cacao-inspect's command line (issue 35): the input,
 * split at zero bytes, is the argument list (up to 64) after the program's name. The parser must
 * accept it or refuse it with one line without control bytes. What it accepts must be what the
 * command can use whole: a --size is digits, x, digits, each 1..16384, read back exactly (before the
 * fix, -1x5 became 4294967295x5 and 10x10junk was taken as 10x10); a --pass is a pass name; a
 * quality a level; a show key a well-formed key. --settings is left out (fuzz_settings_json covers
 * the file; here it would open whatever path the fuzzer names). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cacao_keys.h"
#include "cacao_policy.h"
#include "fuzz_input.h"
#include "image_io.h"
#include "inspect_args.h"

#define MAX_ARGS 64

/* The value after the last "--size" in argv, or NULL. */
static const char *size_given(int argc, char **argv) {
    const char *value = NULL;
    for (int i = 2; i + 1 < argc; ++i)
        if (strcmp(argv[i], "--size") == 0) value = argv[i + 1];
    return value;
}

static void check_accepted(const inspect_args *a, int argc, char **argv) {
    if (a->command == INSPECT_PLAN && a->width) {
        char shown[32];
        snprintf(shown, sizeof shown, "%ux%u", a->width, a->height);
        const char *given = size_given(argc, argv);
        if (!given || strcmp(given, shown) != 0 || a->width > CACAO_MAX_SIZE || a->height > CACAO_MAX_SIZE ||
            !a->height)
            abort();
    }
    if (a->command == INSPECT_LIST) {
        bool known = !a->pass;
        for (unsigned p = 0; !known && p < CACAO_PASS_COUNT; ++p) known = strcmp(a->pass, cacaoi_pass_name(p)) == 0;
        if (!known || a->quality < -1 || a->quality >= CACAO_KEY_QUALITY_COUNT) abort();
    }
    cacao_key key;
    if (a->command == INSPECT_SHOW && !cacaoi_key_parse(a->key, &key)) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *argv[MAX_ARGS + 2], *text;
    bool names_a_file;
    const int argc = fuzz_args(data, size, "cacao-inspect", argv, MAX_ARGS, &text, &names_a_file);
    static inspect_args args;
    char err[1024] = "";
    if (argc && !names_a_file) {
        if (inspect_parse_args(argc, argv, &args, err, sizeof err))
            check_accepted(&args, argc, argv);
        else if (!err[0] || strchr(err, '\n') || !cacao_text_is_printable(err))
            abort();
    }
    free(text);
    return 0;
}
