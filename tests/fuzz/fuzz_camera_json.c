/* fuzz_camera_json - libFuzzer harness: any bytes given as camera.json give a camera or one error. */
#include "camera_json.h"
#include "fuzz_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    cacao_camera_file camera;
    char err[512];
    if (!cacao_camera_json_read(fuzz_input_file(data, size, ".json"), &camera, err, sizeof err) && !err[0]) abort();
    return 0;
}
