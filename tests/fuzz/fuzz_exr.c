/* fuzz_exr - libFuzzer harness: any bytes given to the EXR reader, read both for depth (one channel)
 * and for normals (three), give an image or one error. */
#include "exr_io.h"
#include "fuzz_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *path = fuzz_input_file(data, size, ".exr");
    cacao_img img;
    char err[512];
    if (cacao_exr_read_scalar(path, &img, err, sizeof err))
        cacao_img_free(&img);
    else if (!err[0])
        abort();
    if (cacao_exr_read_vector(path, &img, err, sizeof err))
        cacao_img_free(&img);
    else if (!err[0])
        abort();
    return 0;
}
