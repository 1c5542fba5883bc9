/* test_soak - a leak soak for the sanitizer build (issue 16): 100 runs on lavapipe, each a fresh
 * context at a different small size with different settings (quality, blur, downsampling,
 * precision, normals given or generated), each recording and submitting 10 frames: 1,000 frames,
 * 100 context creations and sizings, 100 teardowns. Under ASan the leak checker runs at exit and
 * fails the test on any leak in cacao's code (driver leaks are suppressed by tests/lsan.supp);
 * every run must also succeed with no validation message and give AO in [0,1]. In the release
 * build it is the same workload without the leak check. */
#include "gpu_scene.h"

int main(void) {
    vkdev dev;
    open_device(&dev);
    scene_buffers scenes[4];
    static const uint32_t sizes[4][2] = {{32, 32}, {48, 40}, {64, 36}, {33, 47}};
    float radius[4];
    for (int k = 0; k < 4; ++k) radius[k] = scene_buffers_default(sizes[k][0], sizes[k][1], &scenes[k]);
    float *ao = malloc(sizeof(float) * 64 * 64);
    unsigned frames = 0, runs = 0;
    for (int i = 0; i < 100; ++i) {
        const scene_buffers *b = &scenes[i % 4];
        const cacao_settings s = {
            .quality = (cacao_quality)(1 + (i / 4) % 5),
            .downsample = (i / 3) % 2 == 1,
            .blur_pass_count = (i / 5) % 4 == 0 ? CACAO_BLUR_NONE : (i / 5) % 4,
            .precision = (i / 7) % 2 ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32,
            .generate_normals = (i / 2) % 2 == 1,
            .radius = radius[i % 4] * (1.0f + 0.1f * (float)(i % 3)),
        };
        const vkdev_frame f = scene_frame(b, false, !s.generate_normals);
        char err[512];
        const cacao_result r = vkdev_run(&dev, &s, &f, 10, ao, NULL, err, sizeof err);
        if (r != CACAO_SUCCESS) {
            fprintf(stderr, "run %d: %s: %s\n", i, cacao_result_string(r), err);
            ++test_failures;
            continue;
        }
        CHECK(all_finite_unit(ao, (size_t)b->width * b->height));
        frames += 10;
        ++runs;
    }
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    printf("soak: %u runs, %u frames, %u validation messages\n", runs, frames, dev.validation_messages);
    free(ao);
    for (int k = 0; k < 4; ++k) scene_buffers_free(&scenes[k]);
    return test_report("test_soak");
}
