/* test_gpu_model - the estimate of `cacao-inspect gpu` without a device (tools/inspect/gpu_model.h):
 *   - every key of the key space falls into a stage, and only the tile fill is left out, so a pass
 *     added to the pass table cannot silently drop out of the frame cost;
 *   - AMD FidelityFX CACAO v1.2's dispatches for a configuration are the ones worked out by hand
 *     here from AMD's FFX_CACAO_VkDraw, buffer sizes and numthreads (the numbers in the comments),
 *     not from the model's table;
 *   - a step's cost is workgroups x threads / 64 x the inverse throughput (ACO's figure is per
 *     wave64 of active invocations), so 64-invocation groups cost one inverse throughput each. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cacao_keys.h"
#include "gpu_model.h"
#include "test_util.h"

static void test_every_key_has_a_stage(void) {
    cacao_key keys[256];
    const size_t n = cacaoi_key_list(keys, 256);
    CHECK(n > 0 && n <= 256);
    for (size_t i = 0; i < n && i < 256; ++i) {
        char name[CACAO_KEY_NAME_MAX];
        cacaoi_key_name(&keys[i], name, sizeof name);
        gpu_stage stage;
        const bool known = gpu_stage_of_key(name, &stage);
        if (!known) fprintf(stderr, "no stage for %s\n", name);
        CHECK(known);
        /* the fills dispatch nothing when every tile is active */
        CHECK(!known || (stage == GPU_STAGE_LEFT_OUT) == (strncmp(name, "fill", 4) == 0));
    }
    gpu_stage stage;
    CHECK(gpu_stage_of_key("generate.q3base", &stage) && stage == GPU_STAGE_BASE);
    CHECK(gpu_stage_of_key("generate.q3", &stage) && stage == GPU_STAGE_GENERATE);
    CHECK(gpu_stage_of_key("upsample.smart.fp16", &stage) && stage == GPU_STAGE_APPLY);
    CHECK(gpu_stage_of_key("compact", &stage) && stage == GPU_STAGE_CLASSIFY);
    CHECK(gpu_stage_of_key("clear.ssao_ping", &stage) && stage == GPU_STAGE_LEFT_OUT); /* a transfer, no shader */
    CHECK(!gpu_stage_of_key("frobnicate.q1", &stage));
}

/* The step of `entry` in out[0..n), or NULL. */
static const gpu_amd_step *find(const gpu_amd_step *out, uint32_t n, const char *entry) {
    for (uint32_t i = 0; i < n; ++i)
        if (strcmp(out[i].entry, entry) == 0) return &out[i];
    return NULL;
}

static bool is(const gpu_amd_step *s, uint32_t dispatches, uint32_t x, uint32_t y, uint32_t z, uint32_t threads) {
    return s && s->dispatches == dispatches && s->groups[0] == x && s->groups[1] == y && s->groups[2] == z &&
           s->threads == threads;
}

static void test_amd_highest_native(void) {
    /* 1920x1080 native: SSAO buffer and deinterleaved depths 960x540, importance map 480x270. */
    gpu_amd_step s[GPU_AMD_MAX_STEPS];
    const uint32_t n = gpu_amd_steps(CACAO_QUALITY_HIGHEST, false, 2, true, 1920, 1080, s);
    CHECK(n == 10);
    CHECK(is(find(s, n, "FFX_CACAO_ClearLoadCounter"), 1, 1, 1, 1, 1));
    CHECK(is(find(s, n, "FFX_CACAO_PrepareNativeDepthsAndMips"), 1, 120, 68, 1, 64)); /* 960/8, ceil(540/8) */
    CHECK(is(find(s, n, "FFX_CACAO_PrepareNativeNormals"), 1, 120, 68, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ3Base"), 4, 120, 68, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_GenerateImportanceMap"), 1, 60, 34, 1, 64)); /* 480/8, ceil(270/8) */
    CHECK(is(find(s, n, "FFX_CACAO_PostprocessImportanceMapA"), 1, 60, 34, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_PostprocessImportanceMapB"), 1, 60, 34, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ3"), 4, 120, 68, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_EdgeSensitiveBlur2"), 4, 16, 13, 1, 256)); /* 960/60, ceil(540/44) */
    CHECK(is(find(s, n, "FFX_CACAO_Apply"), 1, 240, 135, 1, 64));             /* 1920/8, 1080/8 */
    CHECK(find(s, n, "FFX_CACAO_PrepareNativeNormalsFromInputNormals") == NULL);
    const gpu_amd_step *base = find(s, n, "FFX_CACAO_GenerateQ3Base");
    CHECK(base && base->stage == GPU_STAGE_BASE);
}

static void test_amd_lowest_downsampled(void) {
    /* 1920x1080 downsampled: SSAO buffer and depths 480x270; two of four slices at LOWEST. */
    gpu_amd_step s[GPU_AMD_MAX_STEPS];
    const uint32_t n = gpu_amd_steps(CACAO_QUALITY_LOWEST, true, 2, false, 1920, 1080, s);
    CHECK(n == 6);
    CHECK(is(find(s, n, "FFX_CACAO_PrepareDownsampledDepthsHalf"), 1, 60, 34, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_PrepareDownsampledNormalsFromInputNormals"), 1, 60, 34, 1, 64));
    /* sparse: ceil(480/4) = 120 columns of groups, by fives 24; ceil(270/16) = 17 rows; z 5 */
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ0"), 2, 24, 17, 5, 64));
    CHECK(is(find(s, n, "FFX_CACAO_EdgeSensitiveBlur2"), 2, 8, 7, 1, 256));        /* 480/60, ceil(270/44) */
    CHECK(is(find(s, n, "FFX_CACAO_UpscaleBilateral5x5Half"), 1, 120, 68, 1, 64)); /* 1920/16, ceil(1080/16) */
    CHECK(find(s, n, "FFX_CACAO_GenerateQ3Base") == NULL);
}

static void test_amd_levels_and_blur(void) {
    gpu_amd_step s[GPU_AMD_MAX_STEPS];
    /* LOW runs Q0 (3 taps, as LOWEST), MEDIUM Q1 on the sparse grid, HIGH Q2 on the 8x8 grid. */
    uint32_t n = gpu_amd_steps(CACAO_QUALITY_LOW, false, 0, true, 1920, 1080, s);
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ0"), 4, 48, 34, 5, 64)); /* ceil(960/4)=240 -> 48; ceil(540/16) */
    CHECK(find(s, n, "FFX_CACAO_PrepareNativeDepths") != NULL);
    CHECK(find(s, n, "FFX_CACAO_NonSmartApply") != NULL);
    for (uint32_t i = 0; i < n; ++i) CHECK(s[i].stage != GPU_STAGE_BLUR); /* blur 0: none */
    n = gpu_amd_steps(CACAO_QUALITY_MEDIUM, true, 8, true, 1920, 1080, s);
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ1"), 4, 24, 17, 5, 64));
    CHECK(is(find(s, n, "FFX_CACAO_EdgeSensitiveBlur8"), 4, 10, 9, 1, 256)); /* 480/48, ceil(270/32) */
    CHECK(find(s, n, "FFX_CACAO_UpscaleBilateral5x5NonSmart") != NULL);
    n = gpu_amd_steps(CACAO_QUALITY_HIGH, false, 2, true, 1921, 1081, s);
    /* odd sizes round up: half 961x541 */
    CHECK(is(find(s, n, "FFX_CACAO_GenerateQ2"), 4, 121, 68, 1, 64));
    CHECK(is(find(s, n, "FFX_CACAO_Apply"), 1, 241, 136, 1, 64));
}

static void test_cost(void) {
    const uint32_t groups[3] = {10, 10, 1};
    CHECK(fabs(gpu_step_cost(groups, 2, 256, 100.0) - 10 * 10 * 2 * 4 * 100.0) < 1e-9);
    CHECK(fabs(gpu_step_cost(groups, 1, 64, 50.0) - 100 * 50.0) < 1e-9);
    CHECK(fabs(gpu_step_cost((const uint32_t[]){1, 1, 1}, 1, 1, 1280.0) - 20.0) < 1e-9); /* 1/64 of a wave64 */
    CHECK(gpu_step_cost(groups, 1, 64, -1.0) < 0);
}

/* The statistics are read by the names drivers give them: RADV's and NVIDIA's ("Register Count",
 * "Stack Size": NVIDIA's per-thread stack, where it spills), and either driver's spill shows. */
static void test_statistic_names(void) {
    CHECK(gpu_stat_from_name("VGPRs") == GPU_STAT_VGPRS);
    CHECK(gpu_stat_from_name("Inverse Throughput") == GPU_STAT_INVERSE_THROUGHPUT);
    CHECK(gpu_stat_from_name("Register Count") == GPU_STAT_REGISTERS);
    CHECK(gpu_stat_from_name("Stack Size") == GPU_STAT_STACK_BYTES);
    CHECK(gpu_stat_from_name("Shared Memory Size") == GPU_STAT_SHARED_BYTES);
    CHECK(gpu_stat_from_name("Local Memory Size") == GPU_STAT_COUNT); /* NVIDIA reports 2^36 there: not read */
    CHECK(gpu_stat_from_name("vgprs") == GPU_STAT_COUNT);              /* exact names only */
    gpu_stats s = gpu_stats_none();
    CHECK(!gpu_stats_spill(&s));
    s.value[GPU_STAT_REGISTERS] = 255;
    s.value[GPU_STAT_STACK_BYTES] = 0;
    CHECK(!gpu_stats_spill(&s));
    s.value[GPU_STAT_STACK_BYTES] = 16;
    CHECK(gpu_stats_spill(&s));
    s = gpu_stats_none();
    s.value[GPU_STAT_SCRATCH_BYTES] = 1024;
    CHECK(gpu_stats_spill(&s));
}

int main(void) {
    test_statistic_names();
    test_every_key_has_a_stage();
    test_amd_highest_native();
    test_amd_lowest_downsampled();
    test_amd_levels_and_blur();
    test_cost();
    return test_report("gpu_model");
}
