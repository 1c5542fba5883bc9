/* test_missing_permutation - run inside a subset build (medium;high, native, fp32): settings that
 * need a permutation this build did not embed are refused at resize with
 * CACAO_ERROR_PERMUTATION_MISSING and a message naming the permutation (quoted, so
 * 'generate.q3base' cannot pass for 'generate.q3') and the subset, and the context refuses to
 * record (NOT_READY) rather than dispatch its previous, successfully resized plan; embedded
 * settings work again afterwards; the build embeds exactly as many permutations as the caller's
 * hand-derived list (argv[1]). Built and run by the subset_build test. */
#include <string.h>

#include "gpu_scene.h"

static void expect_missing(vkdev *dev, cacao_context *ctx, const cacao_settings *s, const char *name) {
    /* A good plan first, so a refused resize that kept it would be noticed. */
    CHECK(cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_MEDIUM}) == CACAO_SUCCESS);
    CHECK(cacao_context_resize(ctx, 64, 64, NULL) == CACAO_SUCCESS);
    CHECK(cacao_context_set_settings(ctx, s) == CACAO_SUCCESS);
    const cacao_result r = cacao_context_resize(ctx, 64, 64, NULL);
    const char *message = cacao_context_last_error(ctx);
    printf("%s -> %s: %s\n", name, cacao_result_string(r), message);
    CHECK(r == CACAO_ERROR_PERMUTATION_MISSING);
    char want[128];
    snprintf(want, sizeof want, "permutation '%s' is not embedded in this build (subset ", name);
    CHECK(strncmp(message, want, strlen(want)) == 0);
    CHECK(strstr(message, "(subset medium,high|OFF|fp32)") != NULL);
    const VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(dev->cmd, &begin);
    CHECK(cacao_record(ctx, dev->cmd, &(cacao_inputs){0}) == CACAO_ERROR_NOT_READY);
    vkEndCommandBuffer(dev->cmd);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: test_missing_permutation EXPECTED_PERMUTATION_COUNT\n");
        return 2;
    }
    vkdev dev;
    open_device(&dev);
    cacao_context *ctx = NULL;
    CHECK(vkdev_context_create(&dev, &ctx) == CACAO_SUCCESS);
    CHECK(cacao_embedded_permutation_count() == strtoul(argv[1], NULL, 10));
    expect_missing(&dev, ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGHEST}, "generate.q3base");
    expect_missing(&dev, ctx, &(cacao_settings){.quality = CACAO_QUALITY_LOW, .generate_normals = true}, "generate.q0");
    /* with the caller's normals LOW's generate reads them itself */
    expect_missing(&dev, ctx, &(cacao_settings){.quality = CACAO_QUALITY_LOW}, "generate.q0_input");
    expect_missing(&dev, ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true},
                   "prepare_depths.mips.downsampled");
    const cacao_settings fp16 = {.quality = CACAO_QUALITY_HIGH, .precision = CACAO_PRECISION_FP16};
    if (dev.fp16) {
        expect_missing(&dev, ctx, &fp16, "blur.2.fp16");
    } else {
        /* Without shaderFloat16 cacao runs fp32, which this build embeds. */
        printf("skipped: the fp16 case (device has no shaderFloat16); checked the fp32 fallback instead\n");
        CHECK(cacao_context_set_settings(ctx, &fp16) == CACAO_SUCCESS);
        CHECK(cacao_context_resize(ctx, 64, 64, NULL) == CACAO_SUCCESS);
        CHECK(cacao_context_precision(ctx) == CACAO_PRECISION_FP32);
    }
    /* Embedded settings work again on the same context. */
    CHECK(cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH}) == CACAO_SUCCESS);
    CHECK(cacao_context_resize(ctx, 64, 64, NULL) == CACAO_SUCCESS);
    CHECK(cacao_context_plan(ctx) != NULL);
    cacao_context_destroy(ctx);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_missing_permutation");
}
