/* test_missing_permutation - run inside a subset build (medium;high, native, fp32): settings that
 * need a permutation this build did not embed are refused at resize with
 * CACAO_ERROR_PERMUTATION_MISSING and a message naming the permutation, while embedded settings
 * work. Built and run by the subset_build test. */
#include <string.h>

#include "gpu_scene.h"

static void expect_missing(cacao_context *ctx, const cacao_settings *s, const char *name) {
    CHECK(cacao_context_set_settings(ctx, s) == CACAO_SUCCESS);
    const cacao_result r = cacao_context_resize(ctx, 64, 64, NULL);
    printf("%s -> %s: %s\n", name, cacao_result_string(r), cacao_context_last_error(ctx));
    CHECK(r == CACAO_ERROR_PERMUTATION_MISSING);
    CHECK(strstr(cacao_context_last_error(ctx), name) != NULL);
    CHECK(cacao_context_plan(ctx) == NULL); /* nothing half-built */
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    cacao_context *ctx = NULL;
    CHECK(cacao_context_create(&(cacao_context_desc){.physical_device = dev.physical_device, .device = dev.device,
                                                     .shader_float16_enabled = dev.fp16},
                               &ctx) == CACAO_SUCCESS);
    CHECK(cacao_embedded_permutation_count() == 15);
    expect_missing(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGHEST}, "generate.q3base");
    expect_missing(ctx, &(cacao_settings){.quality = CACAO_QUALITY_LOW}, "generate.q0");
    expect_missing(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true},
                   "prepare_depths.mips.downsampled");
    if (dev.fp16)
        expect_missing(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH, .precision = CACAO_PRECISION_FP16},
                       "blur.2.fp16");
    CHECK(cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_MEDIUM}) == CACAO_SUCCESS);
    CHECK(cacao_context_resize(ctx, 64, 64, NULL) == CACAO_SUCCESS);
    cacao_context_destroy(ctx);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_missing_permutation");
}
