/* fuzz_settings_json - libFuzzer harness: any bytes given to `cacao --settings FILE` are parsed
 * into options or refused with one error line, its control bytes escaped (issue 35: a string
 * value such as "quality"'s was echoed raw). */
#include "fuzz_input.h"
#include "image_io.h"
#include "options.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    char *argv[] = {"cacao", "--settings", (char *)fuzz_input_file(data, size, ".json"), NULL};
    cli_options options;
    char err[1024] = "";
    if (!cli_parse(3, argv, &options, err, sizeof err) && (!err[0] || !cacao_text_is_printable(err))) abort();
    return 0;
}
