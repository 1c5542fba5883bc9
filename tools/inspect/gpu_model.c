/* gpu_model.c - the estimate of `cacao-inspect gpu` without a device (see gpu_model.h). */
#include "gpu_model.h"

#include <stdio.h>
#include <string.h>

const char *const gpu_stat_names[GPU_STAT_COUNT] = {
#define GPU_STAT_NAME(id, name, column) name,
    GPU_STATS(GPU_STAT_NAME)
#undef GPU_STAT_NAME
};

const char *const gpu_stat_columns[GPU_STAT_COUNT] = {
#define GPU_STAT_COLUMN(id, name, column) column,
    GPU_STATS(GPU_STAT_COLUMN)
#undef GPU_STAT_COLUMN
};

gpu_stats gpu_stats_none(void) {
    gpu_stats s = {0};
    for (int i = 0; i < GPU_STAT_COUNT; ++i) s.value[i] = -1.0;
    return s;
}

gpu_stat gpu_stat_from_name(const char *name) {
    for (int i = 0; i < GPU_STAT_COUNT; ++i)
        if (strcmp(gpu_stat_names[i], name) == 0) return (gpu_stat)i;
    return GPU_STAT_COUNT;
}

bool gpu_stats_spill(const gpu_stats *s) {
    return s->value[GPU_STAT_SCRATCH_BYTES] > 0 || s->value[GPU_STAT_SPILLED_VGPRS] > 0 ||
           s->value[GPU_STAT_SPILLED_SGPRS] > 0 || s->value[GPU_STAT_STACK_BYTES] > 0;
}

const char *const gpu_stage_names[GPU_STAGE_COUNT] = {
    "prepare",        "classify/compact", "base",         "importance",      "generate", "blur",
    "apply/upsample", "horizon_prepare",  "horizon_main", "horizon_denoise",
};

/* Which stage a key belongs to, by the start of its name; the first row that matches decides. */
static const struct {
    const char *prefix;
    gpu_stage stage;
} key_stages[] = {
    {"generate.q3base", GPU_STAGE_BASE}, /* before the other generate keys */
    {"generate_gpu.q3base", GPU_STAGE_BASE},
    {"generate.", GPU_STAGE_GENERATE},
    {"generate_gpu.", GPU_STAGE_GENERATE}, /* the GPU forms (cacao_shader_forms) */
    {"prepare", GPU_STAGE_PREPARE}, /* prepare (depths and normals in one), its GPU form prepare_gpu,
                                       prepare_depths, prepare_normals */
    {"classify", GPU_STAGE_CLASSIFY},
    {"compact", GPU_STAGE_CLASSIFY},
    {"reuse.", GPU_STAGE_CLASSIFY}, /* reuse_unchanged's diff, prefix and reach: tile bookkeeping */
    {"fill", GPU_STAGE_LEFT_OUT},
    {"clear.", GPU_STAGE_LEFT_OUT}, /* the clears of cacao's own images (transfers, not shaders) */
    {"importance_", GPU_STAGE_IMPORTANCE},
    {"blur.", GPU_STAGE_BLUR},
    {"blur_gpu.", GPU_STAGE_BLUR}, /* the GPU forms (cacao_shader_forms) */
    {"apply.", GPU_STAGE_APPLY},
    {"apply_gpu.", GPU_STAGE_APPLY},
    {"upsample.", GPU_STAGE_APPLY},
    {"horizon_prepare", GPU_STAGE_HORIZON_PREPARE}, /* and the GPU forms: horizon_prepare_gpu.* */
    {"horizon_main", GPU_STAGE_HORIZON_MAIN},
    {"horizon_denoise", GPU_STAGE_HORIZON_DENOISE},
    {"horizon_temporal", GPU_STAGE_HORIZON_DENOISE}, /* temporal accumulation: counted with the filters */
};

bool gpu_stage_of_key(const char *key_name, gpu_stage *out) {
    for (size_t i = 0; i < sizeof key_stages / sizeof key_stages[0]; ++i)
        if (strncmp(key_name, key_stages[i].prefix, strlen(key_stages[i].prefix)) == 0) {
            *out = key_stages[i].stage;
            return true;
        }
    return false;
}

double gpu_step_cost(const uint32_t groups[3], uint32_t dispatches, uint32_t threads, double inverse_throughput) {
    if (inverse_throughput < 0) return -1.0;
    return (double)groups[0] * groups[1] * groups[2] * dispatches * (threads / 64.0) * inverse_throughput;
}

/* ---- AMD FidelityFX CACAO v1.2 ----------------------------------------------------------------
 * Sources (AMD's code, read for these facts only):
 *   - which pipelines FFX_CACAO_VkDraw dispatches per quality and resolution, how often and on
 *     which grid: ffx_cacao_impl.cpp, FFX_CACAO_VkDraw (clear load counter; prepare depths: half
 *     at LOWEST, full at LOW, with mips above; prepare normals from depth or from the input;
 *     HIGHEST: Q3 base x4, importance map + postprocess A + B; generate Q0 at LOWEST and LOW, Q1
 *     at MEDIUM on the sparse grid, Q2 at HIGH, Q3 at HIGHEST on the 8x8 grid, x4 (x2 at LOWEST,
 *     passes 1 and 2 skipped); blur N x4 (x2) on a grid of (4 * 16 - 2N) x (3 * 16 - 2N) texels;
 *     native: NonSmartHalfApply / NonSmartApply / Apply; downsampled: UpscaleBilateral5x5 Half
 *     / NonSmart / Smart on a grid of 2 * 8 pixels);
 *   - the buffer sizes: ffx_cacao.cpp, FFX_CACAO_UpdateBufferSizeInfo (half = (w + 1) / 2,
 *     quarter and eighth likewise; native: SSAO and deinterleaved depths at half, importance at
 *     quarter; downsampled: quarter and eighth);
 *   - the tile sizes: ffx_cacao_defines.h (8x8 everywhere but the sparse generate, 4x16, and the
 *     blur, 16x16);
 *   - the numthreads of each entry point: ffx_cacao.hlsl (the tile sizes above; ClearLoadCounter
 *     1x1x1). */

/* The buffer a dispatch covers (FFX_CACAO_UpdateBufferSizeInfo). */
typedef enum amd_extent {
    AMD_EXTENT_ONE,        /* a single workgroup */
    AMD_EXTENT_OUTPUT,     /* the output */
    AMD_EXTENT_SSAO,       /* the SSAO buffer: half (native) or quarter (downsampled) resolution */
    AMD_EXTENT_DEPTHS,     /* the deinterleaved depths: as the SSAO buffer */
    AMD_EXTENT_IMPORTANCE, /* the importance map: half the SSAO buffer */
    AMD_EXTENT_COUNT,
} amd_extent;

typedef enum amd_grid {
    AMD_GRID_ONE,
    AMD_GRID_DEPTHS,
    AMD_GRID_SSAO,
    AMD_GRID_IMPORTANCE,
    AMD_GRID_SPARSE,
    AMD_GRID_BLUR,
    AMD_GRID_OUTPUT,
    AMD_GRID_UPSCALE,
} amd_grid;

/* How each grid covers its buffer: texels per workgroup (0: the blur's, 4 * 16 - 2N by 3 * 16 - 2N
 * for N passes), and AMD's sparse generate grid (groups in x then divided by 5, z 5). */
static const struct {
    amd_extent extent;
    uint32_t tile[2];
    bool sparse;
} amd_grids[] = {
    [AMD_GRID_ONE] = {AMD_EXTENT_ONE, {1, 1}, false},
    [AMD_GRID_DEPTHS] = {AMD_EXTENT_DEPTHS, {8, 8}, false},
    [AMD_GRID_SSAO] = {AMD_EXTENT_SSAO, {8, 8}, false},
    [AMD_GRID_IMPORTANCE] = {AMD_EXTENT_IMPORTANCE, {8, 8}, false},
    [AMD_GRID_SPARSE] = {AMD_EXTENT_SSAO, {4, 16}, true},
    [AMD_GRID_BLUR] = {AMD_EXTENT_SSAO, {0, 0}, false},
    [AMD_GRID_OUTPUT] = {AMD_EXTENT_OUTPUT, {8, 8}, false},
    [AMD_GRID_UPSCALE] = {AMD_EXTENT_OUTPUT, {16, 16}, false}, /* 8x8 invocations of 2x2 pixels */
};

typedef enum amd_when {
    AMD_ALWAYS,
    AMD_NORMALS_FROM_DEPTH,
    AMD_NORMALS_FROM_INPUT,
    AMD_WITH_BLUR,
    AMD_NATIVE,
    AMD_DOWNSAMPLED,
} amd_when;

typedef enum amd_count {
    AMD_ONCE,
    AMD_FOUR,      /* the four deinterleaved passes */
    AMD_PER_SLICE, /* four, two at LOWEST */
} amd_count;

#define Q(level) (1u << ((level)-CACAO_QUALITY_LOWEST))
#define Q_ALL 0x1fu

typedef struct amd_row {
    gpu_stage stage;
    unsigned qualities; /* Q() mask */
    amd_when when;
    const char *entry; /* %s: "Native"/"Downsampled", or the blur pass count */
    amd_grid grid;
    uint32_t threads;
    amd_count count;
} amd_row;

/* FFX_CACAO_VkDraw's dispatches in recording order. */
static const amd_row amd_rows[] = {
    {GPU_STAGE_PREPARE, Q_ALL, AMD_ALWAYS, "FFX_CACAO_ClearLoadCounter", AMD_GRID_ONE, 1, AMD_ONCE},
    {GPU_STAGE_PREPARE, Q(CACAO_QUALITY_LOWEST), AMD_ALWAYS, "FFX_CACAO_Prepare%sDepthsHalf", AMD_GRID_DEPTHS, 64,
     AMD_ONCE},
    {GPU_STAGE_PREPARE, Q(CACAO_QUALITY_LOW), AMD_ALWAYS, "FFX_CACAO_Prepare%sDepths", AMD_GRID_DEPTHS, 64, AMD_ONCE},
    {GPU_STAGE_PREPARE, Q(CACAO_QUALITY_MEDIUM) | Q(CACAO_QUALITY_HIGH) | Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS,
     "FFX_CACAO_Prepare%sDepthsAndMips", AMD_GRID_DEPTHS, 64, AMD_ONCE},
    {GPU_STAGE_PREPARE, Q_ALL, AMD_NORMALS_FROM_DEPTH, "FFX_CACAO_Prepare%sNormals", AMD_GRID_SSAO, 64, AMD_ONCE},
    {GPU_STAGE_PREPARE, Q_ALL, AMD_NORMALS_FROM_INPUT, "FFX_CACAO_Prepare%sNormalsFromInputNormals", AMD_GRID_SSAO, 64,
     AMD_ONCE},
    {GPU_STAGE_BASE, Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS, "FFX_CACAO_GenerateQ3Base", AMD_GRID_SSAO, 64, AMD_FOUR},
    {GPU_STAGE_IMPORTANCE, Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS, "FFX_CACAO_GenerateImportanceMap", AMD_GRID_IMPORTANCE,
     64, AMD_ONCE},
    {GPU_STAGE_IMPORTANCE, Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS, "FFX_CACAO_PostprocessImportanceMapA",
     AMD_GRID_IMPORTANCE, 64, AMD_ONCE},
    {GPU_STAGE_IMPORTANCE, Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS, "FFX_CACAO_PostprocessImportanceMapB",
     AMD_GRID_IMPORTANCE, 64, AMD_ONCE},
    {GPU_STAGE_GENERATE, Q(CACAO_QUALITY_LOWEST) | Q(CACAO_QUALITY_LOW), AMD_ALWAYS, "FFX_CACAO_GenerateQ0",
     AMD_GRID_SPARSE, 64, AMD_PER_SLICE},
    {GPU_STAGE_GENERATE, Q(CACAO_QUALITY_MEDIUM), AMD_ALWAYS, "FFX_CACAO_GenerateQ1", AMD_GRID_SPARSE, 64,
     AMD_PER_SLICE},
    {GPU_STAGE_GENERATE, Q(CACAO_QUALITY_HIGH), AMD_ALWAYS, "FFX_CACAO_GenerateQ2", AMD_GRID_SSAO, 64, AMD_PER_SLICE},
    {GPU_STAGE_GENERATE, Q(CACAO_QUALITY_HIGHEST), AMD_ALWAYS, "FFX_CACAO_GenerateQ3", AMD_GRID_SSAO, 64,
     AMD_PER_SLICE},
    {GPU_STAGE_BLUR, Q_ALL, AMD_WITH_BLUR, "FFX_CACAO_EdgeSensitiveBlur%s", AMD_GRID_BLUR, 256, AMD_PER_SLICE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_LOWEST), AMD_NATIVE, "FFX_CACAO_NonSmartHalfApply", AMD_GRID_OUTPUT, 64,
     AMD_ONCE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_LOW), AMD_NATIVE, "FFX_CACAO_NonSmartApply", AMD_GRID_OUTPUT, 64, AMD_ONCE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_MEDIUM) | Q(CACAO_QUALITY_HIGH) | Q(CACAO_QUALITY_HIGHEST), AMD_NATIVE,
     "FFX_CACAO_Apply", AMD_GRID_OUTPUT, 64, AMD_ONCE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_LOWEST), AMD_DOWNSAMPLED, "FFX_CACAO_UpscaleBilateral5x5Half", AMD_GRID_UPSCALE,
     64, AMD_ONCE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_LOW) | Q(CACAO_QUALITY_MEDIUM), AMD_DOWNSAMPLED,
     "FFX_CACAO_UpscaleBilateral5x5NonSmart", AMD_GRID_UPSCALE, 64, AMD_ONCE},
    {GPU_STAGE_APPLY, Q(CACAO_QUALITY_HIGH) | Q(CACAO_QUALITY_HIGHEST), AMD_DOWNSAMPLED,
     "FFX_CACAO_UpscaleBilateral5x5Smart", AMD_GRID_UPSCALE, 64, AMD_ONCE},
};

static uint32_t halved(uint32_t n) { return (n + 1) / 2; }
static uint32_t groups_of(uint32_t size, uint32_t tile) { return (size + tile - 1) / tile; }

/* AMD's buffers of a frame, x and y each (FFX_CACAO_UpdateBufferSizeInfo). */
static void amd_extents(uint32_t width, uint32_t height, bool downsample, uint32_t out[AMD_EXTENT_COUNT][2]) {
    const uint32_t size[2] = {width, height};
    for (int i = 0; i < 2; ++i) {
        const uint32_t half = halved(size[i]), quarter = halved(half), eighth = halved(quarter);
        out[AMD_EXTENT_ONE][i] = 1;
        out[AMD_EXTENT_OUTPUT][i] = size[i];
        out[AMD_EXTENT_SSAO][i] = out[AMD_EXTENT_DEPTHS][i] = downsample ? quarter : half;
        out[AMD_EXTENT_IMPORTANCE][i] = downsample ? eighth : quarter;
    }
}

static void amd_groups(amd_grid grid, const uint32_t extents[AMD_EXTENT_COUNT][2], int blur, uint32_t out[3]) {
    const uint32_t *size = extents[amd_grids[grid].extent], *tile = amd_grids[grid].tile;
    const bool blur_grid = grid == AMD_GRID_BLUR;
    out[0] = groups_of(size[0], blur_grid ? (uint32_t)(4 * 16 - 2 * blur) : tile[0]);
    out[1] = groups_of(size[1], blur_grid ? (uint32_t)(3 * 16 - 2 * blur) : tile[1]);
    out[2] = amd_grids[grid].sparse ? 5 : 1;
    if (amd_grids[grid].sparse) out[0] = (out[0] + 4) / 5;
}

static bool amd_row_runs(const amd_row *row, cacao_quality quality, bool downsample, int blur,
                         bool normals_from_depth) {
    if (!(row->qualities & Q(quality))) return false;
    switch (row->when) {
    case AMD_ALWAYS:
        return true;
    case AMD_NORMALS_FROM_DEPTH:
        return normals_from_depth;
    case AMD_NORMALS_FROM_INPUT:
        return !normals_from_depth;
    case AMD_WITH_BLUR:
        return blur > 0;
    case AMD_NATIVE:
        return !downsample;
    case AMD_DOWNSAMPLED:
        return downsample;
    }
    return false;
}

uint32_t gpu_amd_steps(cacao_quality quality, bool downsample, int blur, bool normals_from_depth, uint32_t width,
                       uint32_t height, gpu_amd_step out[GPU_AMD_MAX_STEPS]) {
    blur = blur < 0 ? 0 : blur > 8 ? 8 : blur; /* FFX_CACAO_VkDraw clamps to 0..MAX_BLUR_PASSES */
    uint32_t extents[AMD_EXTENT_COUNT][2];
    amd_extents(width, height, downsample, extents);
    uint32_t n = 0;
    for (size_t i = 0; i < sizeof amd_rows / sizeof amd_rows[0] && n < GPU_AMD_MAX_STEPS; ++i) {
        const amd_row *row = &amd_rows[i];
        if (!amd_row_runs(row, quality, downsample, blur, normals_from_depth)) continue;
        gpu_amd_step *st = &out[n++];
        char blur_count[12];
        snprintf(blur_count, sizeof blur_count, "%d", blur);
        snprintf(st->entry, sizeof st->entry, row->entry,
                 row->stage == GPU_STAGE_BLUR ? blur_count
                 : downsample                 ? "Downsampled"
                                              : "Native");
        st->stage = row->stage;
        st->dispatches = row->count == AMD_ONCE                                           ? 1
                         : row->count == AMD_PER_SLICE && quality == CACAO_QUALITY_LOWEST ? 2
                                                                                          : 4;
        st->threads = row->threads;
        amd_groups(row->grid, extents, blur, st->groups);
    }
    return n;
}
