/* test_sweep - every configuration the settings can select (CACAO: 5 qualities x native/downsampled
 * x blur none..8 x fp32/fp16 x normals given/reconstructed = 360; GTAO and bitmask: 5 qualities x
 * denoise none..8 x normals given/reconstructed, native only = 180 more, plus fp16 asked at one
 * denoise pass = 20, which runs as fp32 and gives exactly the fp32 image) records and runs cleanly
 * under the
 * Khronos validation layer with synchronization validation, at a small size: any validation
 * message fails. Why: the barriers, layouts and bindings differ per configuration (mips, importance
 * maps, ping-pong blur chains, the fp16 permutations), so each one is its own synchronization
 * case; docs/integration.md promises all of them are clean.
 * Each output must also be finite and in [0,1], and an fp16 configuration may differ from its
 * fp32 twin only by rounding (mean |diff| below 0.25/255).
 * One context serves every configuration, as in an engine whose user changes settings: each is
 * set_settings + resize on the same context, so the rebuild of intermediates and pipelines is
 * swept too.
 * usage: test_sweep [WIDTH HEIGHT] */
#include "gpu_scene.h"

int main(int argc, char **argv) {
    const uint32_t w = argc > 2 ? (uint32_t)atoi(argv[1]) : 64, h = argc > 2 ? (uint32_t)atoi(argv[2]) : 48;
    vkdev dev;
    open_device(&dev);
    scene_buffers b;
    const float radius = scene_buffers_default(w, h, &b);
    const size_t n = (size_t)w * h;
    float *ao = malloc(n * sizeof *ao), *ao32 = malloc(n * sizeof *ao32);
    cacao_context *ctx = NULL;
    if (vkdev_context_create(&dev, &ctx) != CACAO_SUCCESS) {
        fprintf(stderr, "cannot create a cacao context\n");
        return 1;
    }
    unsigned configs = 0, failed = 0;
    for (int e = CACAO_ESTIMATOR_CACAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
        for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
            for (int ds = 0; ds < 2; ++ds)
                for (int blur = 0; blur <= 8; ++blur)
                    for (int given = 0; given < 2; ++given)
                        for (int fp16 = 0; fp16 < 2; ++fp16) {
                            const bool slice = e != CACAO_ESTIMATOR_CACAO;
                            const cacao_settings s = {.estimator = (cacao_estimator)e,
                                                      /* both visibilities: binary where normals are given */
                                                      .visibility =
                                                          given ? CACAO_VISIBILITY_BINARY : CACAO_VISIBILITY_FALLOFF,
                                                      .quality = (cacao_quality)q,
                                                      .downsample = ds,
                                                      .blur_pass_count = blur ? blur : CACAO_BLUR_NONE,
                                                      .generate_normals = !given,
                                                      .precision = fp16 ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32,
                                                      .radius = radius};
                            if (slice && fp16 && blur != 1) continue; /* fp16 asked runs fp32: checked once */
                            if (slice && ds && blur > CACAO_HORIZON_HALF_MAX_PASSES) { /* refused naming it */
                                CHECK(cacao_context_set_settings(ctx, &s) == CACAO_ERROR_INVALID_ARGUMENT &&
                                      strstr(cacao_context_last_error(ctx), "settings.blur_pass_count") != NULL);
                                continue;
                            }
                            const uint32_t messages = dev.validation_messages, before = (uint32_t)test_failures;
                            vkdev_frame f = scene_frame(&b, false, given);
                            ++configs;
                            char err[512] = "";
                            cacao_result r = cacao_context_set_settings(ctx, &s);
                            if (r == CACAO_SUCCESS) r = cacao_context_resize(ctx, w, h, NULL);
                            if (r == CACAO_SUCCESS)
                                r = vkdev_run_context(&dev, ctx, &f, 1, fp16 ? ao : ao32, NULL, err, sizeof err);
                            if (r != CACAO_SUCCESS) {
                                fprintf(stderr, "%s %s %s blur %d normals %s %s: %s: %s%s\n", cacao_estimator_name(e),
                                        cacao_quality_name(q), ds ? "downsampled" : "native", blur,
                                        given ? "given" : "reconstructed", fp16 ? "fp16" : "fp32",
                                        cacao_result_string(r), err, cacao_context_last_error(ctx));
                                ++test_failures;
                                ++failed;
                                continue;
                            }
                            CHECK(all_finite_unit(fp16 ? ao : ao32, n));
                            if (fp16 && slice) {
                                CHECK(cacao_context_precision(ctx) == CACAO_PRECISION_FP32);
                                CHECK(memcmp(ao, ao32, n * sizeof *ao) == 0);
                            } else if (fp16) {
                                double mean = 0;
                                for (size_t i = 0; i < n; ++i) mean += fabs((double)ao[i] - ao32[i]);
                                CHECK(mean / (double)n < 0.25 / 255.0);
                            }
                            CHECK(dev.validation_messages == messages);
                            if ((uint32_t)test_failures != before) {
                                fprintf(stderr, "  ^ %s %s %s blur %d normals %s %s\n", cacao_estimator_name(e),
                                        cacao_quality_name(q), ds ? "downsampled" : "native", blur,
                                        given ? "given" : "reconstructed", fp16 ? "fp16" : "fp32");
                                ++failed;
                            }
                        }
    printf("sweep %ux%u: %u configurations, %u failed, %u validation messages%s\n", w, h, configs, failed,
           dev.validation_messages, dev.fp16 ? "" : " (no shaderFloat16: fp16 ran as fp32)");
    free(ao);
    free(ao32);
    scene_buffers_free(&b);
    cacao_context_destroy(ctx);
    vkdev_destroy(&dev);
    CHECK(configs == 720 && dev.validation_messages == 0); /* 360 CACAO, 2 x (100 native + 80 downsampled) */
    return test_report("test_sweep");
}
