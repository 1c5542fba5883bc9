/* test_shader_forms - the GPU forms of the blur, apply, prepare and generate (cacao_shader_forms)
 * compute what the CPU forms compute, on lavapipe with validation:
 *   - fp32: bit-identical output at every quality, native and downsampled, blur none, 1, 3 (the
 *     CPU form's last register blur), 4 (its first shared-memory one) and 8, on the embedded scene
 *     at 131x77 (normals from depth; given normals with blur none, 4 and 8: at LOWEST and LOW the
 *     CPU forms' generate transforms the caller's normals itself where the GPU forms'
 *     prepare_normals stores them), and at 7x5 and 1x1 with blur none, 2 and 8 (the blur's tiles
 *     and the apply's quads meet the image edge differently in the two forms);
 *   - fp16: within a few half ulps (the forms round in a different order where the CPU apply
 *     filters 8-bit texels by hand): mean |GPU - CPU| at most 0.1/255, max at most 2/255;
 *   - the choice: a context on lavapipe (a CPU device) plans the CPU forms by default; with
 *     cacao_context_desc.shader_forms = GPU it plans the GPU passes (blur_gpu, apply_gpu,
 *     prepare_gpu with normals from depth, generate_gpu; the upsample has one form) and no CPU
 *     form; the settings' own shader_forms wins over the desc's;
 *   - the horizon estimators: direct grids with no classify, compact, clear or fill (GPU forms)
 *     where the CPU forms run lists, the output bit-identical.
 * The prepare's and generate's intermediates (depths, mips: the GPU forms' a mip chain their
 * generate samples, the CPU forms' an atlas; normals, AO and edges, the importance map and load
 * counter) feed every later pass, so an output identical at every quality, from
 * depth and from given normals, checks them; the GPU prepare runs only with normals from depth. */
#include <string.h>

#include "gpu_scene.h"

static bool plan_has(const cacao_plan *p, const char *prefix) {
    for (uint32_t i = 0; i < p->step_count; ++i)
        if (strncmp(p->steps[i].key_name, prefix, strlen(prefix)) == 0) return true;
    return false;
}

/* AO of one frame with these settings on a context whose desc asks for `desc_forms`. */
static bool run_forms(vkdev *dev, cacao_shader_forms desc_forms, const cacao_settings *s, const vkdev_frame *f,
                      float *ao, cacao_plan *plan) {
    dev->shader_forms = desc_forms;
    vkdev_frame fr = *f;
    fr.plan_out = plan;
    char err[512] = "";
    const cacao_result r = vkdev_run(dev, s, &fr, 1, ao, NULL, err, sizeof err);
    dev->shader_forms = CACAO_SHADER_FORMS_DEFAULT;
    if (r != CACAO_SUCCESS) fprintf(stderr, "run failed: %s\n", err);
    CHECK(r == CACAO_SUCCESS);
    return r == CACAO_SUCCESS;
}

static void compare_forms(vkdev *dev, uint32_t w, uint32_t h, unsigned *runs, double *worst_fp16_mean,
                          double *worst_fp16_max) {
    scene_buffers sb;
    scene_buffers_default(w, h, &sb);
    const size_t n = (size_t)w * h;
    float *cpu = malloc(sizeof(float) * n), *gpu = malloc(sizeof(float) * n);
    const bool tiny = w < 16;
    static const int all_blurs[] = {CACAO_BLUR_NONE, 1, 3, 4, 8}, tiny_blurs[] = {CACAO_BLUR_NONE, 2, 8};
    const int *blurs = tiny ? tiny_blurs : all_blurs;
    const size_t blur_count = tiny ? 3 : 5;
    for (int normals = 0; normals < (tiny ? 1 : 2); ++normals) {
        const vkdev_frame f = scene_frame(&sb, false, normals != 0);
        for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
            for (int ds = 0; ds < 2; ++ds)
                for (int fp = CACAO_PRECISION_FP32; fp <= CACAO_PRECISION_FP16; ++fp)
                    for (size_t b = 0; b < blur_count; ++b) {
                        if (fp == CACAO_PRECISION_FP16 && (!dev->fp16 || tiny)) continue;
                        if (normals && (fp == CACAO_PRECISION_FP16 || blurs[b] == 1 || blurs[b] == 3)) continue;
                        const cacao_settings s = {.quality = (cacao_quality)q, .downsample = ds != 0,
                                                  .precision = (cacao_precision)fp, .generate_normals = !normals,
                                                  .blur_pass_count = blurs[b]};
                        cacao_plan pc, pg;
                        if (!run_forms(dev, CACAO_SHADER_FORMS_CPU, &s, &f, cpu, &pc) ||
                            !run_forms(dev, CACAO_SHADER_FORMS_GPU, &s, &f, gpu, &pg))
                            continue;
                        ++*runs;
                        CHECK(!plan_has(&pc, "blur_gpu") && !plan_has(&pc, "apply_gpu") &&
                              !plan_has(&pc, "prepare_gpu") && !plan_has(&pc, "generate_gpu"));
                        CHECK((ds ? plan_has(&pg, "upsample.") : plan_has(&pg, "apply_gpu")) &&
                              !plan_has(&pg, "apply.") && !plan_has(&pg, "blur.") && !plan_has(&pg, "prepare.") &&
                              !plan_has(&pg, "generate.") && plan_has(&pg, "generate_gpu."));
                        if (!normals) CHECK(plan_has(&pg, "prepare_gpu.") && plan_has(&pc, "prepare."));
                        /* the caller's normals from HIGH up: the GPU forms' depth prepare writes the
                         * mip chain their generate samples, the CPU forms' the atlas */
                        if (normals && q >= CACAO_QUALITY_HIGH)
                            CHECK(plan_has(&pg, "prepare_depths.mips_chain.") && plan_has(&pc, "prepare_depths.mips.") &&
                                  !plan_has(&pc, "prepare_depths.mips_chain."));
                        /* at LOWEST and LOW the CPU forms' generate transforms the caller's normal of
                         * its texel itself, the GPU forms' reads what prepare_normals stored: the two
                         * ways agree to the bit (the image's snorm8 rounding included; docs/tiles.md) */
                        if (normals && q <= CACAO_QUALITY_LOW)
                            CHECK(plan_has(&pc, "generate.q0_input") && !plan_has(&pc, "prepare_normals") &&
                                  plan_has(&pg, "prepare_normals.") && plan_has(&pg, "generate_gpu.q0"));
                        if (blurs[b] > 0) CHECK(plan_has(&pg, "blur_gpu"));
                        double sum = 0.0, max = 0.0;
                        for (size_t i = 0; i < n; ++i) {
                            const double d = fabs((double)gpu[i] - cpu[i]);
                            sum += d;
                            max = fmax(max, d);
                        }
                        if (fp == CACAO_PRECISION_FP32) {
                            if (max != 0.0)
                                fprintf(stderr, "%ux%u q%d ds%d blur %d normals %d: GPU form differs, max %g\n", w, h, q,
                                        ds, blurs[b], normals, max);
                            CHECK(memcmp(cpu, gpu, sizeof(float) * n) == 0);
                        } else {
                            *worst_fp16_mean = fmax(*worst_fp16_mean, sum / (double)n);
                            *worst_fp16_max = fmax(*worst_fp16_max, max);
                            CHECK(sum / (double)n <= 0.1 / 255.0 && max <= 2.0 / 255.0);
                        }
                    }
    }
    free(cpu);
    free(gpu);
    scene_buffers_free(&sb);
}

/* The horizon estimators: the CPU forms classify, compact lists, clear their intermediates and
 * fill the output; the GPU forms run their passes on direct grids with none of those (the prepare
 * classifies, the others store 1 in the groups that are not needed); the output is the same to
 * the bit, with tiles of every class (a fade-out that fades part of the scene), every estimator,
 * native and downsampled, and the blur counts that use AO_RAW and AO_PONG. */
static void compare_horizon_forms(vkdev *dev, uint32_t w, uint32_t h, unsigned *runs) {
    scene_buffers sb;
    scene_buffers_default(w, h, &sb);
    const size_t n = (size_t)w * h;
    float *cpu = malloc(sizeof(float) * n), *gpu = malloc(sizeof(float) * n);
    const vkdev_frame f = scene_frame(&sb, false, false);
    for (int e = CACAO_ESTIMATOR_GTAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
        for (int ds = 0; ds < 2; ++ds)
            for (int blur = 0; blur <= 3; ++blur)
                for (int fade = 0; fade < 2; ++fade) {
                    const cacao_settings s = {.estimator = (cacao_estimator)e, .quality = CACAO_QUALITY_LOW,
                                              .downsample = ds != 0, .generate_normals = true,
                                              .blur_pass_count = blur == 0 ? CACAO_BLUR_NONE : blur,
                                              .fade_out_from = fade ? 2.0f : 0.0f, .fade_out_to = fade ? 4.0f : 0.0f};
                    cacao_plan pc, pg;
                    if (!run_forms(dev, CACAO_SHADER_FORMS_CPU, &s, &f, cpu, &pc) ||
                        !run_forms(dev, CACAO_SHADER_FORMS_GPU, &s, &f, gpu, &pg))
                        continue;
                    ++*runs;
                    CHECK(plan_has(&pc, "clear.view_depth") && plan_has(&pc, "classify.horizon") &&
                          !plan_has(&pc, "horizon_prepare_gpu."));
                    CHECK(plan_has(&pg, "horizon_prepare_gpu.") && !plan_has(&pg, "clear.") && !plan_has(&pg, "fill") &&
                          !plan_has(&pg, "classify") && !plan_has(&pg, "compact") && !plan_has(&pg, "horizon_prepare."));
                    if (memcmp(cpu, gpu, sizeof(float) * n) != 0)
                        fprintf(stderr, "%ux%u estimator %d ds%d blur %d fade %d: the GPU forms differ\n", w, h, e, ds,
                                blur, fade);
                    CHECK(memcmp(cpu, gpu, sizeof(float) * n) == 0);
                }
    free(cpu);
    free(gpu);
    scene_buffers_free(&sb);
}

static void test_choice(vkdev *dev) {
    scene_buffers sb;
    scene_buffers_default(64, 48, &sb);
    const vkdev_frame f = scene_frame(&sb, false, false);
    float *ao = malloc(sizeof(float) * 64 * 48);
    const cacao_settings plain = {.quality = CACAO_QUALITY_HIGH, .generate_normals = true};
    cacao_plan p;
    /* a CPU device: the CPU forms by default */
    if (run_forms(dev, CACAO_SHADER_FORMS_DEFAULT, &plain, &f, ao, &p))
        CHECK(plan_has(&p, "blur.") && plan_has(&p, "apply.") && !plan_has(&p, "blur_gpu"));
    /* the desc's override, and the settings' over the desc's */
    if (run_forms(dev, CACAO_SHADER_FORMS_GPU, &plain, &f, ao, &p))
        CHECK(plan_has(&p, "blur_gpu") && plan_has(&p, "apply_gpu") && plan_has(&p, "prepare_gpu") &&
              plan_has(&p, "generate_gpu"));
    cacao_settings cpu = plain;
    cpu.shader_forms = CACAO_SHADER_FORMS_CPU;
    if (run_forms(dev, CACAO_SHADER_FORMS_GPU, &cpu, &f, ao, &p))
        CHECK(plan_has(&p, "blur.") && !plan_has(&p, "blur_gpu") && !plan_has(&p, "generate_gpu"));
    /* what a context reports it runs: the device's (a CPU here), or the desc's */
    cacao_context *ctx = NULL;
    CHECK(vkdev_context_create(dev, &ctx) == CACAO_SUCCESS && cacao_context_shader_forms(ctx) == CACAO_SHADER_FORMS_CPU);
    cacao_context_destroy(ctx);
    ctx = NULL;
    dev->shader_forms = CACAO_SHADER_FORMS_GPU;
    CHECK(vkdev_context_create(dev, &ctx) == CACAO_SUCCESS && cacao_context_shader_forms(ctx) == CACAO_SHADER_FORMS_GPU);
    dev->shader_forms = CACAO_SHADER_FORMS_DEFAULT;
    cacao_context_destroy(ctx);
    ctx = NULL;
    CHECK(cacao_context_shader_forms(NULL) == CACAO_SHADER_FORMS_DEFAULT);
    /* a value outside the enum: refused, naming the field */
    const cacao_context_desc bad = {.physical_device = dev->physical_device, .device = dev->device,
                                    .shader_forms = (cacao_shader_forms)7};
    CHECK(cacao_context_create(&bad, &ctx) == CACAO_ERROR_INVALID_ARGUMENT && ctx == NULL);
    cacao_settings wrong = plain;
    wrong.shader_forms = (cacao_shader_forms)3;
    char err[256] = "";
    cacao_settings out;
    CHECK(cacao_settings_resolve(&wrong, &out, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT &&
          strstr(err, "shader_forms") != NULL);
    free(ao);
    scene_buffers_free(&sb);
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    test_choice(&dev);
    unsigned runs = 0;
    double fp16_mean = 0.0, fp16_max = 0.0;
    const uint32_t sizes[][2] = {{131, 77}, {7, 5}, {1, 1}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; ++i)
        compare_forms(&dev, sizes[i][0], sizes[i][1], &runs, &fp16_mean, &fp16_max);
    unsigned horizon_runs = 0;
    compare_horizon_forms(&dev, 131, 77, &horizon_runs);
    compare_horizon_forms(&dev, 7, 5, &horizon_runs);
    CHECK(horizon_runs == 64);
    printf("%u horizon estimator configurations: GPU forms bit-identical to the CPU forms\n", horizon_runs);
    printf("%u configurations: GPU forms bit-identical to the CPU forms in fp32; fp16 worst mean |diff| %.6f "
           "(%.3f/255), worst max %.6f (%.2f/255)\n",
           runs, fp16_mean, fp16_mean * 255.0, fp16_max, fp16_max * 255.0);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("shader_forms");
}
