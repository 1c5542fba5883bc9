/* fuzz_cli_args - libFuzzer harness for the command line: the input, split at zero bytes, is the
 * argument list (up to 64 arguments) given to `cacao`'s parser, which must accept it or refuse it
 * with one error line whose control bytes are escaped (issue 35: the value of a flag such as
 * --quality was echoed raw, terminal escapes included). --settings is left out (fuzz_settings_json
 * covers the file; here it would open whatever path the fuzzer names). */
#include "fuzz_input.h"
#include "image_io.h"
#include "options.h"

#define MAX_ARGS 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *argv[MAX_ARGS + 2], *text;
    bool names_a_file;
    const int argc = fuzz_args(data, size, "cacao", argv, MAX_ARGS, &text, &names_a_file);
    cli_options options;
    char err[1024];
    err[0] = '\0';
    if (argc && !names_a_file && !cli_parse(argc, argv, &options, err, sizeof err) &&
        (!err[0] || !cacao_text_is_printable(err)))
        abort();
    free(text);
    return 0;
}
