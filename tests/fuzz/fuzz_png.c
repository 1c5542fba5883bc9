/* fuzz_png - libFuzzer harness: any bytes given to the PNG reader give an image or one error. */
#include "fuzz_input.h"
#include "image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    cacao_img img;
    bool is16;
    char err[512];
    if (cacao_png_read(fuzz_input_file(data, size, ".png"), &img, &is16, err, sizeof err))
        cacao_img_free(&img);
    else if (!err[0])
        abort();
    return 0;
}
