/* fuzz_pfm - libFuzzer harness: any bytes given to the PFM reader give an image or one error. */
#include "fuzz_input.h"
#include "image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    cacao_img img;
    char err[512];
    if (cacao_pfm_read(fuzz_input_file(data, size, ".pfm"), &img, err, sizeof err))
        cacao_img_free(&img);
    else if (!err[0])
        abort(); /* a failure must say why */
    return 0;
}
