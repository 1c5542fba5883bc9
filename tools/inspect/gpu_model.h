/* gpu_model.h - what `cacao-inspect gpu` estimates, apart from any device: the statistics it reads
 * from a GPU compiler, the stages a frame's steps fall into, AMD FidelityFX CACAO v1.2's steps per
 * configuration, and the estimated cost of a step.
 *
 * The estimate (docs/gpu.md): a step costs workgroups x wave64s per workgroup x the compiler's
 * "Inverse Throughput" (ACO: estimated cycles a wave64 keeps a SIMD busy at the pipeline's
 * occupancy). It is a compiler's static estimate, not a timing: memory bandwidth, caches, scratch
 * traffic and the real trip count of loops bounded by runtime values are not in it (ACO assumes
 * every loop runs 8 times, x4 for each further level of nesting). */
#ifndef CACAO_GPU_MODEL_H
#define CACAO_GPU_MODEL_H

#include <stdbool.h>
#include <stdint.h>

#include "cacao.h"

/* ---- Statistics ------------------------------------------------------------------------------ */

/* The pipeline statistics read, by the name the driver gives them (VK_KHR_pipeline_executable_properties)
 * and the short column header the tool prints: RADV's (VGPRs .. Inverse Throughput), then NVIDIA's
 * (registers per thread, the per-thread stack its compiler spills to, shared memory). A statistic
 * the driver does not report stays negative. */
#define GPU_STATS(X)                                                                                                   \
    X(VGPRS, "VGPRs", "vgpr")                                                                                          \
    X(SGPRS, "SGPRs", "sgpr")                                                                                          \
    X(SPILLED_VGPRS, "Spilled VGPRs", "spill_v")                                                                       \
    X(SPILLED_SGPRS, "Spilled SGPRs", "spill_s")                                                                       \
    X(SCRATCH_BYTES, "Scratch size", "scratch")                                                                        \
    X(LDS_BYTES, "LDS size", "lds")                                                                                    \
    X(OCCUPANCY, "Subgroups per SIMD", "waves/simd")                                                                   \
    X(INSTRUCTIONS, "Instructions", "instr")                                                                           \
    X(LATENCY, "Latency", "latency")                                                                                   \
    X(INVERSE_THROUGHPUT, "Inverse Throughput", "inv_thr")                                                         \
    X(REGISTERS, "Register Count", "regs")                                                                             \
    X(STACK_BYTES, "Stack Size", "stack")                                                                              \
    X(SHARED_BYTES, "Shared Memory Size", "shared")

typedef enum gpu_stat {
#define GPU_STAT_ENUM(id, name, column) GPU_STAT_##id,
    GPU_STATS(GPU_STAT_ENUM)
#undef GPU_STAT_ENUM
        GPU_STAT_COUNT
} gpu_stat;

extern const char *const gpu_stat_names[GPU_STAT_COUNT];   /* "VGPRs", ... */
extern const char *const gpu_stat_columns[GPU_STAT_COUNT]; /* "vgpr", ... */

/* One pipeline's statistics; a value the driver does not report is negative. */
typedef struct gpu_stats {
    uint32_t subgroup_size; /* of the executable (VkPipelineExecutablePropertiesKHR) */
    double value[GPU_STAT_COUNT];
} gpu_stats;

/* Statistics with nothing reported. */
gpu_stats gpu_stats_none(void);

/* The statistic called name (as gpu_stat_names spells it), or GPU_STAT_COUNT for another. */
gpu_stat gpu_stat_from_name(const char *name);

/* True when the pipeline uses scratch memory or spills registers (RADV), or a stack (NVIDIA). */
bool gpu_stats_spill(const gpu_stats *stats);

/* ---- Stages ---------------------------------------------------------------------------------- */

/* The stages the estimate sums steps into: CACAO's, then the horizon-slice estimators'. */
typedef enum gpu_stage {
    GPU_STAGE_PREPARE,
    GPU_STAGE_CLASSIFY, /* tile classification and compaction */
    GPU_STAGE_BASE,     /* HIGHEST's Q3 base pass */
    GPU_STAGE_IMPORTANCE,
    GPU_STAGE_GENERATE,
    GPU_STAGE_BLUR,
    GPU_STAGE_APPLY, /* apply (native) or upsample (downsampled) */
    GPU_STAGE_HORIZON_PREPARE,
    GPU_STAGE_HORIZON_MAIN,
    GPU_STAGE_HORIZON_DENOISE,
    GPU_STAGE_COUNT,
    GPU_STAGE_LEFT_OUT = GPU_STAGE_COUNT, /* the tile fill: left out of the estimate */
} gpu_stage;

extern const char *const gpu_stage_names[GPU_STAGE_COUNT]; /* "prepare", "classify/compact", ... */

/* The stage of a cacao step by its key name ("generate.q3base" -> base, "fill" -> left out).
 * False for a key no stage claims (a pass this model does not know yet). */
bool gpu_stage_of_key(const char *key_name, gpu_stage *out);

/* ---- Cost ------------------------------------------------------------------------------------ */

/* Estimated cycles of `dispatches` dispatches of `groups` workgroups of `threads` invocations each:
 * workgroups x threads / 64 x inverse_throughput. ACO's "Inverse Throughput" is the cycles a SIMD
 * spends per wave64 of active invocations (it scales wave32 code to wave64 and divides by the share
 * of lanes a workgroup leaves idle), so a workgroup costs threads / 64 of it: for wave64 code and
 * workgroups of a multiple of 64 invocations (every cacao pipeline), ceil(threads / subgroup size)
 * waves. Negative when the inverse throughput is unknown (negative). */
double gpu_step_cost(const uint32_t groups[3], uint32_t dispatches, uint32_t threads, double inverse_throughput);

/* ---- AMD FidelityFX CACAO v1.2 ----------------------------------------------------------------- */

/* One kind of dispatch AMD's FFX_CACAO_VkDraw records: its compute entry point (the key of
 * amd_cacao_pipelines' statistics), how often, with how many workgroups of how many threads. */
typedef struct gpu_amd_step {
    char entry[64];
    gpu_stage stage;
    uint32_t dispatches;
    uint32_t groups[3]; /* per dispatch */
    uint32_t threads;   /* numthreads x * y */
} gpu_amd_step;

#define GPU_AMD_MAX_STEPS 16

/* AMD's dispatches for a frame of width x height at this quality (LOWEST..HIGHEST), resolution,
 * blur pass count (0 = none, at most 8) and normals source. Returns their number. */
uint32_t gpu_amd_steps(cacao_quality quality, bool downsample, int blur, bool normals_from_depth, uint32_t width,
                       uint32_t height, gpu_amd_step out[GPU_AMD_MAX_STEPS]);

#endif /* CACAO_GPU_MODEL_H */
