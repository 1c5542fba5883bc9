/* fuzz_cli_args - libFuzzer harness for the command line: the input, split at zero bytes, is the
 * argument list (up to 64 arguments) given to `cacao`'s parser, which must accept it or refuse it
 * with one error. --settings is left out (fuzz_settings_json covers the file; here it would open
 * whatever path the fuzzer names). */
#include <stdlib.h>
#include <string.h>

#include "options.h"

#define MAX_ARGS 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[MAX_ARGS + 2] = {"cacao"};
    int argc = 1;
    bool names_a_file = false;
    for (size_t at = 0; at <= size && argc <= MAX_ARGS; at += strlen(text + at) + 1) {
        names_a_file = names_a_file || strcmp(text + at, "--settings") == 0;
        argv[argc++] = text + at;
    }
    cli_options options;
    char err[1024];
    if (!names_a_file && !cli_parse(argc, argv, &options, err, sizeof err) && !err[0]) abort();
    free(text);
    return 0;
}
