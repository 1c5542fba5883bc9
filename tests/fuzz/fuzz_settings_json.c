/* fuzz_settings_json - libFuzzer harness: any bytes given to `cacao --settings FILE` are parsed
 * into options or refused with one error. */
#include "fuzz_input.h"
#include "options.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *argv[] = {"cacao", "--settings", (char *)fuzz_input_file(data, size, ".json"), NULL};
    cli_options options;
    char err[1024];
    if (!cli_parse(3, argv, &options, err, sizeof err) && !err[0]) abort();
    return 0;
}
