/* cacao_passes.c - the pass, resource and slot tables and their binding rules (see cacao_passes.h). */
#include "cacao_passes.h"

#include <string.h>

const char *const cacaoi_descriptor_names[CACAOI_DESCRIPTOR_COUNT] = {
    [CACAOI_DESCRIPTOR_NONE] = "-",
    [CACAOI_DESCRIPTOR_UNIFORM_BUFFER] = "uniform buffer",
    [CACAOI_DESCRIPTOR_STORAGE_BUFFER] = "storage buffer",
    [CACAOI_DESCRIPTOR_SAMPLED_IMAGE] = "combined image sampler",
    [CACAOI_DESCRIPTOR_STORAGE_IMAGE] = "storage image",
    [CACAOI_DESCRIPTOR_STORAGE_TEXEL_BUFFER] = "storage texel buffer",
};

#define SLOT(id, descriptor, sampler) [CACAO_BINDING_##id] = {#id, CACAOI_DESCRIPTOR_##descriptor, CACAOI_SAMPLER_##sampler}
const cacaoi_slot_row cacaoi_slots[CACAO_BINDING_COUNT] = {
    SLOT(CONSTANTS, UNIFORM_BUFFER, NONE),      SLOT(LOAD_COUNTER, STORAGE_BUFFER, NONE),
    SLOT(TILES, STORAGE_BUFFER, NONE),          SLOT(SRC_DEPTH, SAMPLED_IMAGE, NEAREST),
    SLOT(SRC_NORMALS, SAMPLED_IMAGE, NEAREST),  SLOT(DEPTHS, SAMPLED_IMAGE, NEAREST),
    SLOT(DEPTHS_IMAGE, STORAGE_IMAGE, NONE),    SLOT(NORMALS_IMAGE, STORAGE_IMAGE, NONE),
    SLOT(SSAO, SAMPLED_IMAGE, LINEAR),          SLOT(SSAO_BASE, SAMPLED_IMAGE, NEAREST),
    SLOT(SSAO_IMAGE, STORAGE_IMAGE, NONE),      SLOT(IMPORTANCE_MAP, SAMPLED_IMAGE, LINEAR),
    SLOT(IMPORTANCE_MAP_IMAGE, STORAGE_IMAGE, NONE), SLOT(VIEW_DEPTH, STORAGE_IMAGE, NONE),
    SLOT(VIEW_NORMALS, STORAGE_IMAGE, NONE),    SLOT(HORIZON_AO, STORAGE_IMAGE, NONE),
    SLOT(HORIZON_AO_OUT, STORAGE_IMAGE, NONE),  SLOT(OUTPUT, STORAGE_IMAGE, NONE),
    SLOT(DEPTH_HISTORY, STORAGE_IMAGE, NONE),   SLOT(NORMALS_HISTORY, STORAGE_IMAGE, NONE),
    SLOT(DEPTHS_MIP1, STORAGE_IMAGE, NONE),     SLOT(DEPTHS_MIP2, STORAGE_IMAGE, NONE),
    SLOT(DEPTHS_MIP3, STORAGE_IMAGE, NONE),     SLOT(HISTORY, STORAGE_IMAGE, NONE),
    SLOT(HISTORY_OUT, STORAGE_IMAGE, NONE),     SLOT(TILE_ENTRIES, STORAGE_TEXEL_BUFFER, NONE),
};
#undef SLOT

#define CALLER(id, name) [CACAO_RES_##id] = {name, CACAOI_SIZE_CALLER, false, false, VK_FORMAT_UNDEFINED, "caller's", "", 0, 0, 0}
#define BUFFER(id, name, bytes, usage)                                                                                 \
    [CACAO_RES_##id] = {name, CACAOI_SIZE_BUFFER, false, false, VK_FORMAT_UNDEFINED, "buffer", "", 0, bytes, usage}
#define TILES_BUFFER(id, name, usage)                                                                                  \
    [CACAO_RES_##id] = {name, CACAOI_SIZE_TILES, false, false, VK_FORMAT_UNDEFINED, "buffer", "", 0, 0, usage}
#define IMAGE(id, name, size, layered, filtered, fmt, glsl, bytes) \
    [CACAO_RES_##id] = {name, CACAOI_SIZE_##size, layered, filtered, VK_FORMAT_##fmt, #fmt, glsl, bytes, 0, 0}
const cacaoi_resource_row cacaoi_resources[CACAO_RES_COUNT] = {
    CALLER(DEPTH_INPUT, "depth_input"),
    CALLER(NORMALS_INPUT, "normals_input"),
    CALLER(OUTPUT, "output"),
    /* the constants are updated and the counter and tiles reset in the command buffer (transfers) */
    BUFFER(CONSTANTS, "constants", sizeof(cacao_constants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
    BUFFER(LOAD_COUNTER, "load_counter", sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
    /* the lists' indirect commands are dispatched from it; the list steps read their entries
     * through a texel view of it (CACAO_BINDING_TILE_ENTRIES) */
    TILES_BUFFER(TILES, "tiles",
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                     VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT),
    /*    resource         name               size        layered filtered format          glsl         bytes */
    IMAGE(DEPTHS,          "depths",          SLICE,      true,  false, R16_SFLOAT,     "r16f",        2),
    IMAGE(NORMALS,         "normals",         SLICE,      true,  false, R8G8B8A8_SNORM, "rgba8_snorm", 4),
    IMAGE(SSAO_PING,       "ssao_ping",       SLICE,      true,  true,  R8G8_UNORM,     "rg8",         2),
    IMAGE(SSAO_PONG,       "ssao_pong",       SLICE,      true,  true,  R8G8_UNORM,     "rg8",         2),
    IMAGE(IMPORTANCE,      "importance",      IMPORTANCE, false, true,  R8_UNORM,       "r8",          1),
    IMAGE(IMPORTANCE_PONG, "importance_pong", IMPORTANCE, false, true,  R8_UNORM,       "r8",          1),
    IMAGE(VIEW_DEPTH,      "view_depth",      FULL,       false, false, R32_SFLOAT,     "r32f",        4),
    IMAGE(VIEW_NORMALS,    "view_normals",    FULL,       false, false, R8G8B8A8_SNORM, "rgba8_snorm", 4),
    IMAGE(AO_RAW,          "ao_raw",          FULL,       false, false, R16_SFLOAT,     "r16f",        2),
    IMAGE(AO_PONG,         "ao_pong",         FULL,       false, false, R16_SFLOAT,     "r16f",        2),
    IMAGE(AO_HALF,         "ao_half",         HALF,       false, false, R16_SFLOAT,     "r16f",        2),
    /* reuse: 2x2 pixels a texel (tiles.glsl) */
    IMAGE(DEPTH_HISTORY,   "depth_history",   HALF,       false, false, R32G32B32A32_SFLOAT, "rgba32f", 16),
    IMAGE(NORMALS_HISTORY, "normals_history", HALF_X3,    false, false, R32G32B32A32_SFLOAT, "rgba32f", 16),
    /* temporal accumulation: per pixel 2 n + AO (n the frames the AO holds) and the view z */
    IMAGE(AO_HISTORY,      "ao_history",      FULL,       false, false, R32G32_SFLOAT,  "rg32f",       8),
    IMAGE(AO_HISTORY_NEXT, "ao_history_next", FULL,       false, false, R32G32_SFLOAT,  "rg32f",       8),
};
#undef CALLER
#undef BUFFER
#undef TILES_BUFFER
#undef IMAGE

#define COMMA ,
/* Binding rows: R reads, W writes; ALL variants or only those listed (bit mask). */
#define R(slot, res, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, 0, false, variants}
#define W(slot, res, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, 0, true, variants}
#define W_LEVELS(slot, res, levels, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, levels, true, variants}
/* the GPU forms' mip chain: levels 1..3 of the depths, each through its own slot (a view of that
 * level); the image then holds CACAO_DEPTH_MIP_COUNT levels as mip levels, not an atlas */
#define W_CHAIN(variants)                                                                        \
    W_LEVELS(DEPTHS_MIP1, DEPTHS, CACAO_DEPTH_MIP_COUNT, variants),                              \
        W_LEVELS(DEPTHS_MIP2, DEPTHS, CACAO_DEPTH_MIP_COUNT, variants),                          \
        W_LEVELS(DEPTHS_MIP3, DEPTHS, CACAO_DEPTH_MIP_COUNT, variants)
#define W_NATIVE(slot, res, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, 0, true, variants, true}
/* A list step's read of the tile buffer: its list's entries, through the buffer's R32_UINT texel
 * view (the slot argument is ignored). On lavapipe a storage buffer load costs each invocation
 * several times what a texel load does (docs/tiles.md "What a list costs"). */
#define R_LIST(slot, res, variants) R(TILE_ENTRIES, res, variants)
#define ALL CACAOI_ALL_VARIANTS
#define V(v) CACAOI_VARIANT(v)
#define CONSTANTS R(CONSTANTS, CONSTANTS, ALL)
#define PASS(id) [CACAO_PASS_##id]
#define WG(name) {CACAO_WG_##name##_X, CACAO_WG_##name##_Y}
#define GEN CACAO_LIST_GENERATE
#define GEN_INPUT (V(CACAO_GENERATE_Q0_INPUT) | V(CACAO_GENERATE_Q1_INPUT))
#define DIFFS_NORMALS (V(CACAO_REUSE_DIFF_NORMALS) | V(CACAO_REUSE_DIFF_NORMALS_GPU))
#define DIFFS (V(CACAO_REUSE_DIFF) | V(CACAO_REUSE_DIFF_GPU) | DIFFS_NORMALS)
#define LISTED_UPSAMPLES                                                                                   \
    (V(CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_SMART) | V(CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_NON_SMART) | \
     V(CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_HALF))

/* The generate row and its GPU form's (the same grids), `taps` the binding (with its comma) through
 * which the taps' depths come with imageLoad: the CPU form's every variant (lavapipe runs it
 * faster than a fetch through the sampled view; the atlas, cacao_shared.h); the GPU form has none:
 * it samples the mip chain through the sampled view, the sampler choosing level and texel
 * (docs/gpu.md). `variants`: the CPU form's 7, the GPU form's the first 5 (its generate reads
 * the normals prepare_normals stored: ACO estimates the caller's normal transformed in generate at
 * twice the pass's cost a texel, docs/tiles.md). `count` the row's bindings. `list` is the
 * tile list: the CPU form runs over the needed tiles' list; the GPU form over every tile, a group
 * whose tile is not needed (classify's flag) storing AO 1 and returning (docs/tiles.md: a
 * workgroup-uniform branch). */
#define GENERATE_ROW(name, variants, taps, count, list, base_list, base_grid, tiles, base_tiles)        \
    {name, {"q0", "q1", "q2", "q3", "q3base", "q0_input", "q1_input"}, variants, false, false, false, WG(GENERATE), \
     CACAOI_GRID_SLICE_LAYERS, count,                                                                  \
     {CONSTANTS, R(LOAD_COUNTER, LOAD_COUNTER, V(CACAO_GENERATE_Q3)), R(DEPTHS, DEPTHS, ALL),               \
      /* the normals' single texels: imageLoad (cacao.comp); the _input variants the caller's */  \
      taps R(NORMALS_IMAGE, NORMALS, ALL & ~GEN_INPUT), R(SRC_NORMALS, NORMALS_INPUT, GEN_INPUT),        \
      R(SSAO_BASE, SSAO_PONG, V(CACAO_GENERATE_Q3)),                                                    \
      R(IMPORTANCE_MAP, IMPORTANCE, V(CACAO_GENERATE_Q3)), W(SSAO_IMAGE, SSAO_PING, ALL & ~V(CACAO_GENERATE_Q3_BASE)), \
      W(SSAO_IMAGE, SSAO_PONG, V(CACAO_GENERATE_Q3_BASE)), W(IMPORTANCE_MAP_IMAGE, IMPORTANCE, V(CACAO_GENERATE_Q3_BASE)), \
      tiles(TILES, TILES, ALL & ~V(CACAO_GENERATE_Q3_BASE)), base_tiles(TILES, TILES, V(CACAO_GENERATE_Q3_BASE))}, \
     /* the Q3 base pass computes the tiles holding an active texel (its values feed the         \
      * importance map and the load counter, which steer the adaptive pass everywhere); a tile   \
      * that is not active has importance 0 (docs/tiles.md): the CPU form runs over compact's    \
      * blocks of 2x2 tiles after a clear of the map, the GPU form over every tile, reading the  \
      * classes */                                                                                \
     .lists = {list, list, list, list, base_list, list, list}, .grids = {[CACAO_GENERATE_Q3_BASE] = base_grid}}
/* The fused prepare (normals from depth) and its GPU form's row; the GPU form also classifies the
 * tiles (tiles_variants: ALL; native the texels it stores, downsampled in groups of its own, the
 * grid rule CACAOI_GRID_SLICE_CLASSIFY; the CPU form runs the classify pass after it). */
#define PREPARE_ROW(name, tiles_variants, grid, mips_binding, count)                              \
    {name, {"half", "full", "mips"}, 3, true, false, false, WG(PREPARE), grid, count,      \
     {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL), W(DEPTHS_IMAGE, DEPTHS, V(CACAO_DEPTHS_HALF) | V(CACAO_DEPTHS_FULL)), \
      mips_binding, W(NORMALS_IMAGE, NORMALS, ALL), W(TILES, TILES, tiles_variants)},          \
     .quad = {[CACAO_DEPTHS_HALF] = 2, [CACAO_DEPTHS_FULL] = 2, [CACAO_DEPTHS_MIPS] = 2}}

/* The horizon estimators' rows, for the CPU forms (tiles: R, over lists) and the GPU forms
 * (tiles: W, direct grids: the prepare classifies, the others count the needed groups). */
/* view_z: the variants that compute the view z from the caller's depth and store it (the CPU form
 * of the normals from depth reads the z its view z variant stored). */
#define HORIZON_PREPARE_ROW(name, variants, view_z, tiles, ...)                                 \
    {name, {"depth", "input", "z"}, variants, false, false, false, WG(HORIZON), CACAOI_GRID_OUTPUT, 7,      \
     {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, view_z), R(SRC_NORMALS, NORMALS_INPUT, V(CACAO_HORIZON_NORMALS_INPUT)), \
      W(VIEW_DEPTH, VIEW_DEPTH, view_z), R(VIEW_DEPTH, VIEW_DEPTH, ALL & ~(view_z)),                       \
      W(VIEW_NORMALS, VIEW_NORMALS, V(CACAO_HORIZON_NORMALS_DEPTH) | V(CACAO_HORIZON_NORMALS_INPUT)),      \
      tiles(TILES, TILES, ALL)},                                                                           \
     .lists = {__VA_ARGS__}}
#define HORIZON_MAIN_ROW(name, tiles, half_tiles, ...)                                                     \
    {name, {"gtao", "bitmask", "gtao_direct", "bitmask_direct", "gtao_half", "bitmask_half"}, 6, false, false, \
     false, WG(HORIZON), CACAOI_GRID_OUTPUT, 8,                                                               \
     {CONSTANTS, R(VIEW_DEPTH, VIEW_DEPTH, ALL), R(VIEW_NORMALS, VIEW_NORMALS, ALL),                           \
      W(HORIZON_AO_OUT, AO_RAW, V(CACAO_HORIZON_GTAO) | V(CACAO_HORIZON_BITMASK)),                            \
      W(HORIZON_AO_OUT, AO_HALF, V(CACAO_HORIZON_GTAO_HALF) | V(CACAO_HORIZON_BITMASK_HALF)),                 \
      W(OUTPUT, OUTPUT, V(CACAO_HORIZON_GTAO_DIRECT) | V(CACAO_HORIZON_BITMASK_DIRECT)),                      \
      tiles(TILES, TILES, V(CACAO_HORIZON_GTAO) | V(CACAO_HORIZON_BITMASK) | V(CACAO_HORIZON_GTAO_DIRECT) |   \
                              V(CACAO_HORIZON_BITMASK_DIRECT)),                                               \
      /* downsampled: the CPU form over compact's blocks, the GPU form reading the 2x2 tiles' classes */  \
      half_tiles(TILES, TILES, V(CACAO_HORIZON_GTAO_HALF) | V(CACAO_HORIZON_BITMASK_HALF))},              \
     .lists = {__VA_ARGS__},                                                                                        \
     .grids = {[CACAO_HORIZON_GTAO_HALF] = CACAOI_GRID_HALF, [CACAO_HORIZON_BITMASK_HALF] = CACAOI_GRID_HALF}}
#define HORIZON_DENOISE_ROW(name, tiles, ...)                                                   \
    {name, {"intermediate", "final", "upsample", "upsample_final"}, 4, false, false, false, WG(HORIZON),     \
     CACAOI_GRID_OUTPUT, 8,                                                                                   \
     {CONSTANTS, R(HORIZON_AO, AO_RAW, V(CACAO_DENOISE_INTERMEDIATE) | V(CACAO_DENOISE_FINAL)),                \
      R(HORIZON_AO, AO_HALF, V(CACAO_DENOISE_UPSAMPLE) | V(CACAO_DENOISE_UPSAMPLE_FINAL)),                    \
      R(VIEW_DEPTH, VIEW_DEPTH, ALL), R(VIEW_NORMALS, VIEW_NORMALS, ALL),                                     \
      W(HORIZON_AO_OUT, AO_PONG, V(CACAO_DENOISE_INTERMEDIATE) | V(CACAO_DENOISE_UPSAMPLE)),                  \
      W(OUTPUT, OUTPUT, V(CACAO_DENOISE_FINAL) | V(CACAO_DENOISE_UPSAMPLE_FINAL)), tiles(TILES, TILES, ALL)}, \
     .lists = {__VA_ARGS__}}

const cacaoi_pass_row cacaoi_passes[CACAO_PASS_COUNT] = {
    /* spec: prepare.md. HALF = slices 0 and 3 (LOWEST), FULL = four slices, MIPS = + mips 1..3,
     * all levels in one atlas image (cacao_shared.h). Where the caller gives normals; with
     * normals from depth PREPARE writes the same depths and the normals in one pass. */
    PASS(PREPARE_DEPTHS) = {"prepare_depths", {"half", "full", "mips", "mips_chain"}, 4, true, false, false, WG(PREPARE),
                            CACAOI_GRID_SLICE, 7,
                            {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL),
                             W(DEPTHS_IMAGE, DEPTHS, V(CACAO_DEPTHS_HALF) | V(CACAO_DEPTHS_FULL) | V(CACAO_DEPTHS_MIPS_CHAIN)),
                             W_LEVELS(DEPTHS_IMAGE, DEPTHS, CACAO_DEPTH_MIP_COUNT, V(CACAO_DEPTHS_MIPS)),
                             W_CHAIN(V(CACAO_DEPTHS_MIPS_CHAIN))},
                            /* the mips variants reduce a 2x2 quad per invocation in registers */
                            .quad = {[CACAO_DEPTHS_MIPS] = 2, [CACAO_DEPTHS_MIPS_CHAIN] = 2}},
    /* spec: prepare.md "Normals from input normals" (from depth: PREPARE). */
    /* list: the CPU forms without reuse, after compact, over the tiles whose normals generate
     * reads (docs/tiles.md); a group is a tile */
    PASS(PREPARE_NORMALS) = {"prepare_normals", {NULL, "list"}, 2, true, false, false, WG(PREPARE), CACAOI_GRID_SLICE, 4,
                             {CONSTANTS, R(SRC_NORMALS, NORMALS_INPUT, ALL), W(NORMALS_IMAGE, NORMALS, ALL),
                              R_LIST(TILES, TILES, V(CACAO_PREPARE_NORMALS_LISTED))},
                             .lists = {[CACAO_PREPARE_NORMALS_LISTED] = CACAO_LIST_NORMALS}},
    /* spec: generate.md. Q3 (HIGHEST's adaptive pass) adds its base, the importance map and the
     * load counter; the Q3 base pass writes the second AO buffer and the importance map
     * (importance.md "GenerateImportanceMap"): an invocation per importance texel computes the
     * 2x2 slice texels of every layer that texel reads. */
    PASS(GENERATE) = GENERATE_ROW("generate", 7, R(DEPTHS_IMAGE, DEPTHS, ALL) COMMA, 13, GEN, CACAO_LIST_BLOCKS,
                                  CACAOI_GRID_IMPORTANCE, R_LIST, R_LIST),
    /* spec: importance.md: two smoothing passes (ping-pong) of the map the Q3 base pass wrote. */
    PASS(IMPORTANCE_A) = {"importance_a", {NULL}, 1, false, false, false, WG(IMPORTANCE), CACAOI_GRID_IMPORTANCE, 3,
                          {CONSTANTS, R(IMPORTANCE_MAP, IMPORTANCE, ALL), W(IMPORTANCE_MAP_IMAGE, IMPORTANCE_PONG, ALL)}},
    PASS(IMPORTANCE_B) = {"importance_b", {NULL}, 1, false, false, false, WG(IMPORTANCE), CACAOI_GRID_IMPORTANCE, 4,
                          {CONSTANTS, W(LOAD_COUNTER, LOAD_COUNTER, ALL), R(IMPORTANCE_MAP, IMPORTANCE_PONG, ALL),
                           W(IMPORTANCE_MAP_IMAGE, IMPORTANCE, ALL)}},
    /* spec: blur.md: all iterations in one dispatch. */
    PASS(BLUR) = {"blur", {NULL}, 1, false, true, true, WG(BLUR), CACAOI_GRID_BLUR, 4,
                  {CONSTANTS, R(SSAO, SSAO_PING, ALL), W(SSAO_IMAGE, SSAO_PONG, ALL), R_LIST(TILES, TILES, ALL)},
                  .lists = {CACAO_LIST_BLUR}},
    /* spec: apply.md, upsample.md. They read the blur's output where a blur ran (step override).
     * The listed variants (the CPU forms without reuse) run over compact's list in
     * CACAO_LIST_PREPARE, the output's other tiles given their 1 by compact: smart_list over the
     * blocks of 2x2 tiles holding a needed tile; nonsmart_list and half_list over the tiles whose
     * quads touch one, on frames that skip much (after the direct apply, which compact's list
     * closes then). The others over every group (docs/tiles.md). */
    PASS(APPLY) = {"apply", {"smart", "nonsmart", "half", "smart_list", "nonsmart_list", "half_list"}, 6, false, false,
                   true, WG(APPLY), CACAOI_GRID_OUTPUT, 4,
                   {CONSTANTS, R(SSAO, SSAO_PING, ALL), W(OUTPUT, OUTPUT, ALL),
                    R_LIST(TILES, TILES, V(CACAO_APPLY_SMART_LIST) | V(CACAO_APPLY_NONSMART_LIST) | V(CACAO_APPLY_HALF_LIST))},
                   /* smart: 4x4 output pixels per invocation; non-smart and half: 2x2 */
                   .quad = {[CACAO_OUTPUT_SMART] = 4, [CACAO_OUTPUT_NON_SMART] = 2, [CACAO_OUTPUT_HALF] = 2,
                            [CACAO_APPLY_SMART_LIST] = 4, [CACAO_APPLY_NONSMART_LIST] = 2, [CACAO_APPLY_HALF_LIST] = 2},
                   .lists = {[CACAO_APPLY_SMART_LIST] = CACAO_LIST_PREPARE, [CACAO_APPLY_NONSMART_LIST] = CACAO_LIST_PREPARE,
                             [CACAO_APPLY_HALF_LIST] = CACAO_LIST_PREPARE}},
    /* The upsample's listed variants: over compact's list of the needed tiles (a group is a tile,
     * 32x32 pixels), the others' output given its 1 by compact: the CPU forms without reuse
     * (the upsample's bilateral filter over every pixel was most of a downsampled frame with sky). */
    PASS(UPSAMPLE) = {"upsample", {"smart", "nonsmart", "half", "smart_list", "nonsmart_list", "half_list"}, 6, false,
                      false, true, WG(UPSAMPLE), CACAOI_GRID_UPSAMPLE, 6,
                      {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL), R(DEPTHS, DEPTHS, ALL), R(SSAO, SSAO_PING, ALL),
                       W(OUTPUT, OUTPUT, ALL), R_LIST(TILES, TILES, LISTED_UPSAMPLES)},
                      .lists = {[CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_SMART] = CACAO_LIST_PREPARE,
                                [CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_NON_SMART] = CACAO_LIST_PREPARE,
                                [CACAO_UPSAMPLE_LISTED + CACAO_OUTPUT_HALF] = CACAO_LIST_PREPARE}},
    /* spec: estimators.md. Full-resolution intermediates, read and written as storage images. */
    /* Over the tiles classification found not all background (the clear before stores in the
     * others what it would): the normals over the tiles within two of an active one, whose
     * normals the estimator and the denoise passes read, and the view z everywhere: the caller's
     * normals with their view z, the view z alone over the rest; normals from depth from the view
     * z stored first (docs/tiles.md). */
    PASS(HORIZON_PREPARE) =
        HORIZON_PREPARE_ROW("horizon_prepare", 3, V(CACAO_HORIZON_NORMALS_INPUT) | V(CACAO_HORIZON_VIEW_Z_ONLY), R_LIST,
                            CACAO_LIST_NORMALS, CACAO_LIST_NORMALS, CACAO_LIST_PREPARE),
    /* The estimator and the denoise passes run over the needed tiles (docs/tiles.md: a group is a
     * tile of 8x8 pixels); the clears and compact give the rest their AO 1. Downsampled, the estimator runs on
     * a half-size grid over compact's blocks of 2x2 tiles holding an active tile (a clear gives the
     * rest the 1 it would store there) and the upsample over the needed tiles. */
    PASS(HORIZON_MAIN) = HORIZON_MAIN_ROW("horizon_main", R_LIST, R_LIST, GEN, GEN, GEN, GEN, CACAO_LIST_BLOCKS,
                                          CACAO_LIST_BLOCKS),
    PASS(HORIZON_DENOISE) = HORIZON_DENOISE_ROW("horizon_denoise", R_LIST, GEN, GEN, GEN, GEN),
    /* The GPU forms (CACAO_PASS_HORIZON_*_GPU): direct grids; the prepare writes every tile and its
     * classes, the estimator's and denoise passes' groups that are not needed store AO 1 (and
     * count: group_work). The downsampled estimator: every group of the half grid, one whose 2x2
     * tiles hold no active one storing AO 1 (it reads their classes). */
    PASS(HORIZON_PREPARE_GPU) = HORIZON_PREPARE_ROW("horizon_prepare_gpu", 2, ALL, W, CACAO_LIST_NONE),
    PASS(HORIZON_MAIN_GPU) = HORIZON_MAIN_ROW("horizon_main_gpu", W, R, CACAO_LIST_NONE),
    PASS(HORIZON_DENOISE_GPU) = HORIZON_DENOISE_ROW("horizon_denoise_gpu", W, CACAO_LIST_NONE),
    /* docs/tiles.md: classes (one invocation per tile), then the lists. CACAO classifies its
     * deinterleaved depths (variant 0 keeps the pass's name), the horizon estimators the caller's
     * depth before their prepare. */
    /* quiet: CACAO's CPU forms without reuse, first: whether the frame is quiet (docs/tiles.md);
     * the tiles it scans whole (every one on a quiet frame) get their output's AO 1 */
    PASS(CLASSIFY) = {"classify", {NULL, "horizon", "quiet"}, 3, false, false, false, {CACAO_WG_CLASSIFY, CACAO_WG_CLASSIFY},
                      CACAOI_GRID_TILES, 5,
                      {CONSTANTS, R(DEPTHS, DEPTHS, V(CACAO_CLASSIFY_SLICES)),
                       R(SRC_DEPTH, DEPTH_INPUT, V(CACAO_CLASSIFY_HORIZON) | V(CACAO_CLASSIFY_QUIET)), W(TILES, TILES, ALL),
                       W(OUTPUT, OUTPUT, V(CACAO_CLASSIFY_QUIET))}},
    /* CACAO's GPU forms with the caller's normals (no prepare classifies): a workgroup per 2x2
     * tiles, an invocation per 2x2 slice texels (their layers), from the caller's depth; it shares
     * no resource the prepare writes, so no barrier separates them and a GPU may run both at once
     * (a classify pass after the prepare cost an H200 a dispatch and a barrier, 7-12 microseconds a
     * frame: docs/gpu.md) */
    PASS(CLASSIFY_GPU) = {"classify_gpu", {NULL}, 1, true, false, false, {CACAO_WG_CLASSIFY, CACAO_WG_CLASSIFY},
                          CACAOI_GRID_SLICE, 3, {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL), W(TILES, TILES, ALL)},
                          .quad = {2}},
    /* it also stores the AO 1 of the output's unneeded tiles where a list step writes the others
     * (docs/tiles.md "What runs"); CACAO's (the CPU forms) also generate's AO 1 in the unneeded
     * tiles a later pass reads (its fill list). It reads the classes and flags the passes before
     * it wrote through the texel view (tile_read), and builds the lists through the buffer. */
    PASS(COMPACT) = {"compact", {NULL, "horizon"}, 2, false, false, false, {CACAO_WG_COMPACT, 1}, CACAOI_GRID_COMPACT, 5,
                     {CONSTANTS, W(TILES, TILES, ALL), R(TILE_ENTRIES, TILES, ALL), W(OUTPUT, OUTPUT, ALL),
                      W(SSAO_IMAGE, SSAO_PING, V(CACAO_COMPACT_SLICES))}},
    /* spec: prepare.md, normals from depth: PREPARE_DEPTHS's variants and the normals in one pass,
     * a 2x2 quad of slice texels per invocation sharing one block of depths. */
    PASS(PREPARE) = PREPARE_ROW("prepare", 0u, CACAOI_GRID_SLICE, W_LEVELS(DEPTHS_IMAGE, DEPTHS, CACAO_DEPTH_MIP_COUNT, V(CACAO_DEPTHS_MIPS)), 6),
    /* The GPU forms (cacao_shader_forms): the rows above, other shapes. The blur: every n in
     * shared memory, 4x3 texels per thread (CACAO_BLUR_GPU_OUT_X, _Y); apply: 2x2 pixels per invocation,
     * each read through the sampler. Generate's GPU form runs its Q3 base pass one texel per
     * invocation (the CPU form: 16), over the slice's grid. The GPU forms of generate and the blur
     * write the tile buffer's header: they count the needed groups they run. */
    /* Both GPU forms run every group: one that touches no needed tile (classify's flag) stores AO
     * 1 and computes nothing else (a workgroup-uniform branch a GPU skips). */
    PASS(BLUR_GPU) = {"blur_gpu", {NULL}, 1, false, true, true, WG(BLUR_GPU), CACAOI_GRID_BLUR, 4,
                      {CONSTANTS, R(SSAO, SSAO_PING, ALL), W(SSAO_IMAGE, SSAO_PONG, ALL), W(TILES, TILES, ALL)}},
    PASS(APPLY_GPU) = {"apply_gpu", {"smart", "nonsmart", "half"}, 3, false, false, true, WG(APPLY), CACAOI_GRID_OUTPUT,
                       3, {CONSTANTS, R(SSAO, SSAO_PING, ALL), W(OUTPUT, OUTPUT, ALL)},
                       .quad = {[CACAO_OUTPUT_SMART] = 2, [CACAO_OUTPUT_NON_SMART] = 2, [CACAO_OUTPUT_HALF] = 2}},
    /* prepare: each direction between two neighbouring depths normalised once for the two
     * normals that use it, and the tile classes (native: of the texels it stores; downsampled: in
     * groups of its own, z 0, from the caller's depth) (no classify pass: its dispatch and
     * barrier cost a GPU more than its work, docs/gpu.md), its mips as the depths' mip chain
     * (levels 1..3 through their own slots); generate: the taps sampled from that chain. */
    PASS(PREPARE_GPU) = PREPARE_ROW("prepare_gpu", ALL, CACAOI_GRID_SLICE_CLASSIFY, W(DEPTHS_IMAGE, DEPTHS, V(CACAO_DEPTHS_MIPS)) COMMA
                                    W_CHAIN(V(CACAO_DEPTHS_MIPS)), 9),
    PASS(GENERATE_GPU) = GENERATE_ROW("generate_gpu", 5, , 12, CACAO_LIST_NONE,
                                      CACAO_LIST_NONE, CACAOI_GRID_SLICE, W, R),
    /* The value of the tiles no pass computes: AO 1 over the unneeded tiles into the slices' AO
     * and the blur's output (CACAO's CPU forms, a step rebinding SSAO_IMAGE) and into the caller's
     * output (dispatches); into the horizon estimators' AO intermediates, and their view z and
     * normals for background: clears of the whole image before the passes that write the needed
     * tiles (on lavapipe a clear of a 16-bit image costs a full frame of CACAO about 4%, a fill
     * over an empty list nothing: docs/tiles.md). */
    PASS(FILL) = {"fill", {NULL, "horizon", "view", "importance"}, 4, false, false, false,
                  {CACAO_TILE, CACAO_TILE}, CACAOI_GRID_SLICE, 7,
                  {CONSTANTS,
                   R_LIST(TILES, TILES, V(CACAO_FILL_SLICES)),
                   W(SSAO_IMAGE, SSAO_PING, V(CACAO_FILL_SLICES)),
                   W(HORIZON_AO_OUT, AO_RAW, V(CACAO_FILL_HORIZON)),
                   W(VIEW_DEPTH, VIEW_DEPTH, V(CACAO_FILL_VIEW)),
                   W(VIEW_NORMALS, VIEW_NORMALS, V(CACAO_FILL_VIEW)),
                   W(IMPORTANCE_MAP_IMAGE, IMPORTANCE, V(CACAO_FILL_IMPORTANCE))},
                  /* the horizon estimators' own images, and CACAO's importance map before the CPU
                   * form of the Q3 base pass, are cleared (cacao_plan_step.clear) */
                  .lists = {[CACAO_FILL_SLICES] = CACAO_LIST_FILL_SLICES}},
    /* docs/tiles.md "Reusing the previous frame": the diff, one invocation per tile, compares the
     * caller's depth (and normals) with the copies the previous frame kept and updates them; the
     * prefix sums each row of tiles' changed flags (one invocation per row); the reach marks the
     * tiles whose output a change can reach, one invocation per tile. */
    PASS(REUSE) = {"reuse", {"diff", "diff_normals", "prefix", "reach", "diff_gpu", "diff_normals_gpu"}, 6, false, false,
                   false, {CACAO_WG_CLASSIFY, CACAO_WG_CLASSIFY}, CACAOI_GRID_TILES, 6,
                   {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, DIFFS), R(SRC_NORMALS, NORMALS_INPUT, DIFFS_NORMALS),
                    W(DEPTH_HISTORY, DEPTH_HISTORY, DIFFS), W(NORMALS_HISTORY, NORMALS_HISTORY, DIFFS_NORMALS),
                    W(TILES, TILES, ALL)},
                   .quad = {[CACAO_REUSE_DIFF_GPU] = 2, [CACAO_REUSE_DIFF_NORMALS_GPU] = 2},
                   .grids = {[CACAO_REUSE_PREFIX] = CACAOI_GRID_TILE_ROWS, [CACAO_REUSE_DIFF_GPU] = CACAOI_GRID_OUTPUT,
                             [CACAO_REUSE_DIFF_NORMALS_GPU] = CACAOI_GRID_OUTPUT}},
    /* Temporal accumulation (cacao_settings.temporal_frames), both shader forms, over every pixel:
     * the resolve reads the frame's AO from the intermediate the last filter pass wrote (a step
     * rebinds HORIZON_AO), the view z and the history, and writes the output and the next history.
     * The history is read where other invocations write, so it is two images that trade roles
     * every frame (record.c binds them crossed on every other frame). */
    PASS(HORIZON_TEMPORAL) = {"horizon_temporal", {NULL}, 1, false, false, false, WG(HORIZON), CACAOI_GRID_OUTPUT, 6,
                              {CONSTANTS, R(HORIZON_AO, AO_RAW, ALL), R(VIEW_DEPTH, VIEW_DEPTH, ALL),
                               R(HISTORY, AO_HISTORY, ALL), W(HISTORY_OUT, AO_HISTORY_NEXT, ALL), W(OUTPUT, OUTPUT, ALL)}},
};
#undef R
#undef W
#undef W_LEVELS
#undef W_CHAIN
#undef COMMA
#undef W_NATIVE
#undef R_LIST
#undef ALL
#undef V
#undef CONSTANTS
#undef PASS
#undef WG
#undef GEN
#undef GEN_INPUT
#undef DIFFS
#undef DIFFS_NORMALS
#undef GENERATE_ROW
#undef PREPARE_ROW
#undef HORIZON_PREPARE_ROW
#undef HORIZON_MAIN_ROW
#undef HORIZON_DENOISE_ROW

static bool binding_active(const cacaoi_pass_binding *b, unsigned variant, unsigned downsampled) {
    return ((b->variants >> variant) & 1u) && !(b->native_only && downsampled);
}

static const cacaoi_pass_row *row_of(unsigned pass, unsigned variant) {
    return pass < CACAO_PASS_COUNT && variant < cacaoi_passes[pass].variants ? &cacaoi_passes[pass] : NULL;
}

bool cacaoi_pass_expect(unsigned pass, unsigned variant, unsigned downsampled, cacaoi_module_expect *out) {
    const cacaoi_pass_row *row = row_of(pass, variant);
    if (!row) return false;
    memset(out, 0, sizeof *out);
    for (unsigned i = 0; i < row->binding_count; ++i) {
        const cacaoi_pass_binding *b = &row->bindings[i];
        if (!binding_active(b, variant, downsampled)) continue;
        out->descriptor[b->slot] = cacaoi_slots[b->slot].descriptor;
        out->resource[b->slot] = b->resource;
        out->write[b->slot] = b->write;
    }
    out->workgroup[0] = row->workgroup[0];
    out->workgroup[1] = row->workgroup[1];
    out->workgroup[2] = 1;
    return true;
}

size_t cacaoi_variant_bindings(unsigned pass, unsigned variant, unsigned downsampled,
                               cacaoi_pass_binding out[CACAO_PLAN_MAX_BINDINGS]) {
    const cacaoi_pass_row *row = row_of(pass, variant);
    size_t n = 0;
    for (unsigned i = 0; row && i < row->binding_count; ++i) {
        if (!binding_active(&row->bindings[i], variant, downsampled)) continue;
        if (n < CACAO_PLAN_MAX_BINDINGS) out[n] = row->bindings[i];
        ++n;
    }
    return n;
}

bool cacaoi_skips_by_class(unsigned pass, unsigned variant) {
    return (pass == CACAO_PASS_GENERATE_GPU && variant != CACAO_GENERATE_Q3_BASE) || pass == CACAO_PASS_BLUR_GPU ||
           (pass == CACAO_PASS_HORIZON_MAIN_GPU && variant != CACAO_HORIZON_GTAO_HALF && variant != CACAO_HORIZON_BITMASK_HALF) ||
           pass == CACAO_PASS_HORIZON_DENOISE_GPU;
}

bool cacaoi_reads_classes(unsigned pass, unsigned variant) {
    return (pass == CACAO_PASS_GENERATE_GPU && variant == CACAO_GENERATE_Q3_BASE) ||
           (pass == CACAO_PASS_HORIZON_MAIN_GPU &&
            (variant == CACAO_HORIZON_GTAO_HALF || variant == CACAO_HORIZON_BITMASK_HALF));
}

bool cacaoi_fill_is_clear(unsigned pass, unsigned variant) {
    return pass == CACAO_PASS_FILL &&
           (variant == CACAO_FILL_HORIZON || variant == CACAO_FILL_VIEW || variant == CACAO_FILL_IMPORTANCE);
}

/* What the passes would store there (the horizon estimators' fill and prepare): R16F AO 1, R32F
 * view z -1, RGBA8_SNORM normal (0, 0, -1); the Q3 base pass in a tile that is not active:
 * importance 0. */
bool cacaoi_clear_value(unsigned resource, float out[4]) {
    static const float ao[4] = {1.0f, 0.0f, 0.0f, 0.0f}, view_z[4] = {-1.0f, 0.0f, 0.0f, 0.0f},
                       normal[4] = {0.0f, 0.0f, -1.0f, 0.0f}, zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float *v = NULL;
    switch (resource) {
    case CACAO_RES_AO_RAW:
    case CACAO_RES_AO_HALF:
    case CACAO_RES_AO_PONG: v = ao; break;
    case CACAO_RES_VIEW_DEPTH: v = view_z; break;
    case CACAO_RES_VIEW_NORMALS: v = normal; break;
    case CACAO_RES_IMPORTANCE: v = zero; break;
    default: return false;
    }
    memcpy(out, v, 4 * sizeof(float));
    return true;
}
