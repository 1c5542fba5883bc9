/* test_subgroup_sizes - the output does not depend on the subgroup size (issue 14, item 5): no pass
 * uses subgroup operations, and every barrier, shared-memory exchange and atomic is per workgroup,
 * so a device that runs cacao's pipelines with 8, 16, 32 or 64 lanes must give bit-identical AO.
 * Where the device offers VK_EXT_subgroup_size_control for compute with more than one size, the
 * embedded scene runs at every quality, native and downsampled, once per power-of-two size in its
 * range (cacao_context_desc.required_subgroup_size), and every output must equal the first size's
 * byte for byte. Lavapipe offers one size (8..8): the test reports itself skipped there (77) and
 * stays for GPUs (a size outside the range is still checked to be refused). Validation (with synchronization
 * validation) must stay silent. */
#include "gpu_scene.h"

int main(void) {
    vkdev dev;
    char err[512];
    if (!vkdev_create(&(vkdev_options){.validation = true, .subgroup_size_control = true}, &dev, err, sizeof err)) {
        fprintf(stderr, "cannot open the Vulkan device: %s\n", err);
        return 1;
    }
    const uint32_t lo = dev.subgroup_size_min, hi = dev.subgroup_size_max;
    /* The field itself: a size outside the range (or not a power of two) is refused naming it. */
    cacao_context *bad = NULL;
    dev.required_subgroup_size = hi ? 3 * hi : 3;
    CHECK(vkdev_context_create(&dev, &bad) == CACAO_ERROR_UNSUPPORTED_DEVICE && bad == NULL);
    CHECK(strstr(dev.context_error, "required_subgroup_size") != NULL); /* desc.error names the field */
    dev.required_subgroup_size = 0;
    if (lo == hi) {
        printf("skipped: %s offers compute subgroup sizes %u..%u only (VK_EXT_subgroup_size_control%s)\n",
               dev.device_name, lo, hi, lo ? "" : " not offered");
        vkdev_destroy(&dev);
        return test_failures ? test_report("test_subgroup_sizes") : TEST_SKIP_CODE;
    }
    const uint32_t w = 160, h = 90;
    scene_buffers b;
    const float radius = scene_buffers_default(w, h, &b);
    const vkdev_frame f = scene_frame(&b, false, true);
    float *first = malloc(sizeof(float) * w * h), *ao = malloc(sizeof(float) * w * h);
    int runs = 0;
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (int ds = 0; ds < 2; ++ds) {
            const cacao_settings s = {.quality = q, .downsample = ds, .radius = radius};
            for (uint32_t size = lo; size <= hi; size *= 2) {
                dev.required_subgroup_size = size;
                float *out = size == lo ? first : ao;
                if (!run(&dev, &s, &f, out)) continue;
                ++runs;
                if (size != lo && memcmp(first, ao, sizeof(float) * w * h) != 0) {
                    size_t differing = 0;
                    for (size_t i = 0; i < (size_t)w * h; ++i) differing += first[i] != ao[i];
                    fprintf(stderr, "quality %d %s: subgroup size %u differs from %u at %zu pixels\n", q,
                            ds ? "downsampled" : "native", size, lo, differing);
                    ++test_failures;
                }
            }
        }
    printf("%s: subgroup sizes %u..%u, %d runs, outputs identical: %s\n", dev.device_name, lo, hi, runs,
           test_failures ? "NO" : "yes");
    free(first);
    free(ao);
    scene_buffers_free(&b);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_subgroup_sizes");
}
