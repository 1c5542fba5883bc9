/* cacao.h - screen-space ambient occlusion for Vulkan, after AMD FidelityFX CACAO.
 *
 * Read top to bottom, this header is the manual.
 *
 * The engine owns its instance, device, queue, images and their memory. cacao owns only its
 * intermediates, pipelines and layouts, all created by cacao_context_create/_resize and freed by
 * cacao_context_destroy. cacao_record() records barriers and dispatches into the caller's command
 * buffer; it never submits, waits or allocates.
 *
 * Vulkan entry points: cacao calls no vk* symbol of the loader. By default it opens the system
 * loader (libvulkan.so.1) itself and takes its entry points from there, so a caller that links
 * the loader needs nothing more. Engines built on volk, with VK_NO_PROTOTYPES or with their own
 * dispatch give cacao_context_desc.get_instance_proc_addr (with .instance), and optionally
 * .get_device_proc_addr; cacao then loads every function through them (docs/integration.md).
 * Include volk.h (or define VK_NO_PROTOTYPES) before this header in such a build.
 *
 * Host memory: every allocation cacao makes (the context itself included) and every Vulkan
 * object it creates go through cacao_context_desc.allocation_callbacks when given. Device memory:
 * all intermediates of a context share one VkDeviceMemory per memory type (cacao_memory_info).
 *
 * Typical use:
 *     cacao_context *ctx;
 *     cacao_context_create(&(cacao_context_desc){.physical_device = pd, .device = dev}, &ctx);
 *     cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH});
 *     cacao_context_resize(ctx, width, height, NULL);
 *     per frame: cacao_record(ctx, cmd, &(cacao_inputs){...});
 *     cacao_context_destroy(ctx);
 *
 * Device requirements: Vulkan 1.1, VK_KHR_push_descriptor enabled on the device,
 * shaderStorageImageWriteWithoutFormat (the output is written by its view's format),
 * shaderStorageImageExtendedFormats (R16F, RG8, R8 intermediates). The fp16 permutations also need
 * shaderFloat16; without it cacao falls back to fp32 (cacao_context_precision tells which ran).
 *
 * Threading: a context is used by one thread at a time; distinct contexts are independent.
 * Structs follow one rule: zero means default. Fields whose zero is a meaningful value say how to
 * ask for it (CACAO_ZERO, CACAO_BLUR_NONE).
 */
#ifndef CACAO_H
#define CACAO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CACAO_VERSION_MAJOR 0
#define CACAO_VERSION_MINOR 1
#define CACAO_VERSION_PATCH 0

/* Marks the functions the library exports. It is built with hidden visibility, so these (every
 * function this header declares) are the only global symbols of libcacao.a and the only dynamic
 * symbols of libcacao.so. Define CACAO_API before including this header to mark them otherwise
 * (for instance __declspec(dllimport)). */
#ifndef CACAO_API
#if defined(__GNUC__) || defined(__clang__)
#define CACAO_API __attribute__((visibility("default")))
#else
#define CACAO_API
#endif
#endif

/* ---- Results ------------------------------------------------------------------------------- */

typedef enum cacao_result {
    CACAO_SUCCESS = 0,
    CACAO_ERROR_INVALID_ARGUMENT,    /* NULL where a value is required, NaN/Inf or out-of-range field */
    CACAO_ERROR_INVALID_SIZE,        /* width/height 0 or above CACAO_MAX_SIZE (1..16384 all work) */
    CACAO_ERROR_UNSUPPORTED_FORMAT,  /* an image of a format cacao cannot read or write */
    CACAO_ERROR_PERMUTATION_MISSING, /* the settings need a shader this build did not embed */
    CACAO_ERROR_UNSUPPORTED_DEVICE,  /* a required extension or feature is missing */
    CACAO_ERROR_NOT_READY,           /* cacao_record before cacao_context_resize */
    CACAO_ERROR_OUT_OF_MEMORY,       /* host or device allocation failed */
    CACAO_ERROR_VULKAN,              /* another Vulkan call failed */
} cacao_result;

/* Short English description of a result code ("invalid argument", ...). Never NULL. */
CACAO_API const char *cacao_result_string(cacao_result result);

/* Largest accepted width or height. */
#define CACAO_MAX_SIZE 16384

/* ---- Settings (spec: constants.md section 6) ----------------------------------------------- */

typedef enum cacao_quality {
    CACAO_QUALITY_DEFAULT = 0, /* = HIGHEST */
    CACAO_QUALITY_LOWEST,      /* 3 taps, 2 of 4 slices */
    CACAO_QUALITY_LOW,         /* 3 taps */
    CACAO_QUALITY_MEDIUM,      /* 5 taps, depth edges, detail AO */
    CACAO_QUALITY_HIGH,        /* 12 taps, depth mips, normal edges */
    CACAO_QUALITY_HIGHEST,     /* adaptive: 5 base taps + up to 27 more where the image needs them */
} cacao_quality;

typedef enum cacao_precision {
    CACAO_PRECISION_DEFAULT = 0, /* = FP32 */
    CACAO_PRECISION_FP32,
    CACAO_PRECISION_FP16,        /* blur, apply and upsample in half precision (needs shaderFloat16) */
} cacao_precision;

/* What the AO estimates and how (spec: estimators.md). CACAO is AMD CACAO's look; GTAO and BITMASK
 * are horizon-slice estimators of cosine-weighted visibility, evaluated at full resolution in fp32
 * and measured against ray-traced truth (docs/estimators.md): GTAO is the cheaper, BITMASK (32
 * equal-cosine sectors, constant thickness) the more accurate per depth read at high budgets. */
typedef enum cacao_estimator {
    CACAO_ESTIMATOR_DEFAULT = 0, /* = CACAO */
    CACAO_ESTIMATOR_CACAO,
    CACAO_ESTIMATOR_GTAO,
    CACAO_ESTIMATOR_BITMASK,
} cacao_estimator;

/* The quantity GTAO / BITMASK estimate. */
typedef enum cacao_visibility {
    CACAO_VISIBILITY_DEFAULT = 0, /* = FALLOFF */
    CACAO_VISIBILITY_FALLOFF,     /* occluders count max(0, 1 - t^2 / R^2) at hit distance t */
    CACAO_VISIBILITY_BINARY,      /* occluders within R count fully, beyond R not at all */
} cacao_visibility;

/* The shapes of the blur, apply, prepare (normals from depth) and generate shaders, and how the
 * tiles are skipped (the arithmetic, and so the output, is the same: bit for bit on lavapipe in
 * fp32). A CPU rasterizer runs large blocks of texels per invocation in registers fastest, and
 * only fewer dispatched groups save it time (tile lists, clears); a GPU spills such blocks to
 * memory and wants shared memory, one or a few texels per invocation, its hardware sampler, fewer
 * instructions and fewer dispatches (the GPU forms skip tiles inside the shader, and their
 * prepare passes classify the tiles: docs/tiles.md). */
typedef enum cacao_shader_forms {
    CACAO_SHADER_FORMS_DEFAULT = 0, /* a context picks by its device: CPU on a CPU device (lavapipe),
                                       GPU on every other (cacao_context_desc.shader_forms overrides);
                                       cacao_plan_build without a context: CPU */
    CACAO_SHADER_FORMS_CPU,
    CACAO_SHADER_FORMS_GPU,
} cacao_shader_forms;

/* Names of the values above, as the cacao command, its settings JSON and the tools spell them:
 * quality "lowest", "low", "medium", "high", "highest"; precision "fp32", "fp16"; estimator
 * "cacao", "gtao", "bitmask"; visibility "falloff", "binary"; shader forms "cpu", "gpu". A DEFAULT
 * (0) gives the name of the
 * value it stands for (cacao_quality_name(CACAO_QUALITY_DEFAULT) is "highest"); a value outside
 * the enum gives NULL, so the choices are listed by
 *     for (cacao_quality q = CACAO_QUALITY_LOWEST; cacao_quality_name(q); ++q) ...
 * The strings are static. */
CACAO_API const char *cacao_quality_name(cacao_quality quality);
CACAO_API const char *cacao_precision_name(cacao_precision precision);
CACAO_API const char *cacao_estimator_name(cacao_estimator estimator);
CACAO_API const char *cacao_visibility_name(cacao_visibility visibility);
CACAO_API const char *cacao_shader_forms_name(cacao_shader_forms forms);

/* The reverse: the value a name above spells, exactly (case matters); never a DEFAULT. A name
 * that is none of them, or NULL, gives CACAO_ERROR_INVALID_ARGUMENT and leaves *out unchanged. */
CACAO_API cacao_result cacao_quality_from_name(const char *name, cacao_quality *out);
CACAO_API cacao_result cacao_precision_from_name(const char *name, cacao_precision *out);
CACAO_API cacao_result cacao_estimator_from_name(const char *name, cacao_estimator *out);
CACAO_API cacao_result cacao_visibility_from_name(const char *name, cacao_visibility *out);
CACAO_API cacao_result cacao_shader_forms_from_name(const char *name, cacao_shader_forms *out);

/* Asks for an explicit 0 in a float field whose 0 would otherwise mean "default". */
#define CACAO_ZERO (-1.0f)
/* Downsampled GTAO/BITMASK run at most this many filter passes (blur_pass_count): the upsample
 * reads blocks up to 3 pixels away and each denoise pass 1 pixel more, and a tile the frame skips
 * is 8 pixels from any tile it computes: with 3 + 5 pixels of reach the skipped tiles stay exactly
 * what the full computation gives. */
#define CACAO_HORIZON_HALF_MAX_PASSES 6
/* settings.temporal_frames: 0 (off) or 2..CACAO_TEMPORAL_MAX_FRAMES */
#define CACAO_TEMPORAL_MAX_FRAMES 64

/* Asks for no blur (blur_pass_count 0 means the default, 2). */
#define CACAO_BLUR_NONE (-1)

typedef struct cacao_settings {
    float radius;                   /* world-space AO radius; 0 = 1.2 */
    float shadow_multiplier;        /* AO strength; 0 = 1.0 (range 0..5) */
    float shadow_power;             /* AO contrast exponent; 0 = 1.5 (range 0..10) */
    float shadow_clamp;             /* max occlusion before shaping; 0 = 0.98 (range 0..1) */
    float horizon_angle_threshold;  /* ignores samples this close to the surface plane; 0 = 0.06, CACAO_ZERO */
    float fade_out_from;            /* view distance where AO starts fading; 0 = 50, CACAO_ZERO */
    float fade_out_to;              /* view distance where AO is gone; 0 = 300 (must exceed fade_out_from) */
    float sharpness;                /* blur edge sharpness; 0 = 0.98, CACAO_ZERO (range 0..1) */
    float detail_shadow_strength;   /* small-scale detail AO; 0 = 0.5, CACAO_ZERO (range 0..5) */
    float adaptive_quality_limit;   /* HIGHEST: mean importance budget; 0 = 0.45, CACAO_ZERO (range 0..1) */
    float bilateral_sigma_squared;  /* downsampled upsample: spatial variance; 0 = 5.0 */
    float bilateral_similarity_distance_sigma; /* downsampled upsample: depth variance; 0 = 0.01 */
    int blur_pass_count;            /* edge-aware blur iterations 1..8; 0 = 2; CACAO_BLUR_NONE = none */
    cacao_quality quality;          /* 0 = HIGHEST */
    cacao_precision precision;      /* 0 = FP32 */
    bool generate_normals;          /* true: reconstruct normals from depth; false: inputs.normals */
    bool downsample;                /* true: AO at quarter resolution, upsampled (every estimator) */
    /* Horizon-slice estimators. With GTAO or BITMASK: radius is R (the world radius of the
     * visibility estimated); quality picks the budget (slices x steps per side, 2 depth reads per
     * step; per estimator, docs/estimators.md: GTAO LOWEST 1x4 ... HIGHEST 6x8, BITMASK LOWEST
     * 1x4 ... HIGHEST 2x16); blur_pass_count is the number of denoise passes (0 = 1,
     * CACAO_BLUR_NONE = none); downsample computes one pixel of each 2x2 block and upsamples it
     * with depth- and normal-aware weights, the first of the blur_pass_count filter passes (so
     * NONE and 1 both upsample only; at most CACAO_HORIZON_HALF_MAX_PASSES = 6); fade_out_* and
     * generate_normals apply; the shadow, sharpness, detail, adaptive and bilateral fields do
     * not; precision FP16 runs FP32 (view z, angles and sector masks need single precision;
     * cacao_context_precision tells). */
    cacao_estimator estimator;      /* 0 = CACAO */
    cacao_visibility visibility;    /* 0 = FALLOFF */
    float thickness;                /* BITMASK: assumed occluder thickness, world units; 0 = 1.0 R
                                       (FALLOFF) or 0.5 R (BINARY) */
    int horizon_slices;             /* GTAO/BITMASK: slices per pixel 1..16; 0 = by quality */
    int horizon_steps;              /* GTAO/BITMASK: steps per side 1..32; 0 = by quality */
    bool compute_all_tiles;         /* CACAO: true skips nothing: every tile is generated and
                                       blurred, and generate computes the taps of background and
                                       faded pixels too (docs/tiles.md); the output is the same,
                                       only slower. For measurement and tests. */
    cacao_shader_forms shader_forms; /* 0 = the context's choice (see cacao_shader_forms); resolving
                                        keeps 0 */
    /* Reuse what did not change (docs/tiles.md "Reusing the previous frame"). The context
     * keeps a copy of the depth (and of the input normals) and its intermediates from frame to
     * frame; a frame recomputes only the tiles whose output a changed depth or normal can reach
     * (the AO radius projected to pixels, the depth mips, the blur and apply footprints; a tile
     * nearer than that bound allows recomputes whenever anything changed), and nothing at all
     * when nothing changed. The output is bit for bit that of a full computation of the frame.
     * A change of camera, settings or size recomputes everything (so does
     * cacao_inputs.force_full_frame). HIGHEST recomputes every tile when anything changed (its
     * adaptive pass depends on the whole frame's importance). Frames must reach the GPU in the
     * order they were recorded: after a recorded frame that was not submitted, force a full frame.
     * Costs 4 bytes per pixel (plus 16 with input normals). GTAO/BITMASK: all or nothing (any
     * change recomputes the whole frame; so does another frame_index); in the CPU shader forms a
     * frame keeps nothing unless cacao_inputs.output_holds_previous (their last pass runs over a
     * list that only the classification makes), in the GPU forms such a frame runs the last
     * denoise pass alone. */
    bool reuse_unchanged;
    /* GTAO/BITMASK: temporal accumulation for engines without a temporal filter of their own
     * (docs/estimators.md "Temporal accumulation"). 0: off, each frame stands alone. 2..64: the
     * context keeps the AO of the last frames and blends each frame into it, a running mean of up
     * to temporal_frames frames (then an exponential one of weight 1 / temporal_frames), so that
     * the frames' sample patterns (cacao_inputs.frame_index, which the caller advances every
     * frame) average out. The history follows the camera (cacao_inputs.view_to_previous_view) and
     * is dropped per pixel where its view z does not match the surface (disocclusion, a moved
     * object), and wholly after a resize, a change of settings or cacao_inputs.temporal_reset.
     * Frames must reach the GPU in the order they were recorded. Costs 16 bytes per pixel. Not
     * with reuse_unchanged (refused). */
    int temporal_frames;
} cacao_settings;

/* Fills every defaulted field of *in into *out and checks every field. An explicit zero keeps its
 * encoding (CACAO_ZERO, CACAO_BLUR_NONE) in *out, so resolving *out again gives *out and
 * cacao_plan_build(&plan->settings, ...) rebuilds the same plan. On error returns
 * CACAO_ERROR_INVALID_ARGUMENT and, when error is not NULL, writes a message naming the field. */
CACAO_API cacao_result cacao_settings_resolve(const cacao_settings *in, cacao_settings *out, char *error,
                                              size_t error_size);

/* ---- The pass plan: what one frame dispatches, as pure data (no Vulkan) ------------------- */

/* Resources a pass can touch. The first three belong to the caller. */
typedef enum cacao_resource {
    CACAO_RES_DEPTH_INPUT = 0,  /* caller's depth image */
    CACAO_RES_NORMALS_INPUT,    /* caller's normals image */
    CACAO_RES_OUTPUT,           /* caller's AO output image */
    CACAO_RES_CONSTANTS,        /* uniform buffer, updated in the command buffer each frame */
    CACAO_RES_LOAD_COUNTER,     /* storage buffer (HIGHEST) */
    CACAO_RES_DEPTHS,           /* deinterleaved view-space depth, R16F, a mip atlas at HIGH+ */
    CACAO_RES_NORMALS,          /* deinterleaved normals, RGBA8 SNORM */
    CACAO_RES_SSAO_PING,        /* AO + edges, RG8 */
    CACAO_RES_SSAO_PONG,        /* Q3 base result / blur output, RG8 */
    CACAO_RES_IMPORTANCE,       /* importance map, R8 (HIGHEST) */
    CACAO_RES_IMPORTANCE_PONG,  /* importance ping-pong, R8 (HIGHEST) */
    CACAO_RES_VIEW_DEPTH,       /* GTAO/BITMASK: full-resolution view z, R32F (background < 0) */
    CACAO_RES_VIEW_NORMALS,     /* GTAO/BITMASK: full-resolution view normals, RGBA8 SNORM */
    CACAO_RES_AO_RAW,           /* GTAO/BITMASK: visibility before the last denoise pass, R16F */
    CACAO_RES_AO_PONG,          /* GTAO/BITMASK: denoise ping-pong, R16F */
    CACAO_RES_AO_HALF,          /* GTAO/BITMASK downsampled: the 2x2 blocks' visibility, R16F, half size */
    CACAO_RES_TILES,            /* storage + indirect buffer: tile classes, lists, dispatch commands */
    CACAO_RES_DEPTH_HISTORY,    /* reuse_unchanged: the caller's depth as the last frame read it, RGBA32F
                                   (2x2 pixels a texel) */
    CACAO_RES_NORMALS_HISTORY,  /* reuse_unchanged with input normals: the caller's normals, RGBA32F */
    CACAO_RES_AO_HISTORY,       /* temporal_frames: the accumulated AO, its frame count and view z, RG32F,
                                   kept from frame to frame */
    CACAO_RES_AO_HISTORY_NEXT,  /* temporal_frames: this frame's; the two trade roles every frame */
    CACAO_RES_COUNT
} cacao_resource;

/* Name of a resource ("depths", "ssao_ping", ...). */
CACAO_API const char *cacao_resource_name(cacao_resource resource);

/* One intermediate the plan needs (only those are allocated). */
typedef struct cacao_plan_image {
    cacao_resource resource;
    VkFormat format;
    uint32_t width, height, layers; /* of the Vulkan image (its level 0) */
    uint32_t mips;              /* depth mip levels it holds: more than 1 only for the depths at HIGH+:
                                   in the CPU forms an atlas, level 0 (the slice) with the others
                                   stacked to its right; in the GPU forms the image's mip levels */
    uint64_t bytes;             /* tightly packed size, all layers and levels */
    uint32_t image_levels;      /* mip levels of the Vulkan image: 1, or mips for a mip chain */
} cacao_plan_image;

#define CACAO_PLAN_MAX_STEPS 18     /* steps of any configuration (the longest has 18) */
#define CACAO_PLAN_MAX_BINDINGS 10  /* bindings of any step (the most one makes: 9) */
#define CACAO_PLAN_KEY_NAME_MAX 48  /* a step's key name, with its terminating zero */

/* One buffer the plan needs (only those are allocated). */
typedef struct cacao_plan_buffer {
    cacao_resource resource;
    uint64_t bytes;
} cacao_plan_buffer;

#define CACAO_PLAN_MAX_BUFFERS 3    /* constants, load counter, tiles */

/* One binding of a step: descriptor binding number -> resource. */
typedef struct cacao_plan_binding {
    uint8_t binding;            /* descriptor binding number in the pass's shader */
    uint8_t resource;           /* cacao_resource */
    uint8_t write;              /* 1 if the pass writes it */
} cacao_plan_binding;

typedef struct cacao_plan_step {
    char key_name[CACAO_PLAN_KEY_NAME_MAX]; /* permutation key, e.g. "generate.q2" */
    uint8_t key[5];             /* permutation key: pass, variant, downsampled, blur passes, fp16 */
    uint32_t dispatch[3];       /* workgroups (an indirect step: the most it can dispatch) */
    uint8_t list;               /* 0: dispatched directly; else the tile list it dispatches
                                   indirectly (CACAO_LIST_*: 1 generate, 2 fill, 3 the horizon
                                   prepare, 4 blur, 5 blocks of 2x2 tiles: docs/tiles.md) */
    bool clear;                 /* not a dispatch: vkCmdClearColorImage of every image the step
                                   writes (whole image) to the AO 1 / background value the tiles no
                                   pass computes keep (docs/tiles.md); no pipeline, dispatch 0 0 0 */
    uint32_t binding_count;
    cacao_plan_binding bindings[CACAO_PLAN_MAX_BINDINGS];
    uint8_t gate;               /* 0 none; else a direct step dispatched indirectly from gate
                                   command gate - 1: with reuse_unchanged, the full grid, which a
                                   frame with nothing changed zeroes; in the CPU forms without
                                   reuse (the steps after classify.quiet), 0, which a frame that is
                                   not quiet opens to the full grid (docs/tiles.md "A quiet frame") */
    bool barrier_before;        /* a barrier precedes this step (compute, and transfer for clears) */
    uint32_t barrier_resources; /* bit mask of cacao_resource the barrier orders */
} cacao_plan_step;

typedef struct cacao_plan {
    cacao_settings settings;    /* resolved (cacao_settings_resolve: explicit zeros stay encoded) */
    uint32_t width, height;     /* full resolution */
    uint32_t slice_width, slice_height;           /* deinterleaved (SSAO) size */
    uint32_t importance_width, importance_height; /* CACAO: half the slice each way (HIGHEST reads
                                   the map); 0 for the horizon estimators */
    uint32_t slice_count;       /* CACAO: 2 at LOWEST, else 4; horizon estimators: 1 (the full-res
                                   image is their one "slice") */
    uint32_t step_count;
    cacao_plan_step steps[CACAO_PLAN_MAX_STEPS];
    uint32_t image_count;
    cacao_plan_image images[CACAO_RES_COUNT];
    uint32_t buffer_count;
    cacao_plan_buffer buffers[CACAO_PLAN_MAX_BUFFERS];
    bool uses_load_counter;
    bool uses_tiles;            /* tile classification (docs/tiles.md): every estimator */
    uint32_t tiles_x, tiles_y;  /* tiles of CACAO_TILE x CACAO_TILE slice texels */
    uint32_t blur_groups_x, blur_groups_y;   /* the blur's full grid (0 without a blur) */
    uint64_t tile_buffer_bytes; /* header, classes and lists */
    uint64_t total_bytes;       /* all intermediates, buffers included */
} cacao_plan;

/* Builds the plan for these settings and size. Pure: no Vulkan calls, no allocation. */
CACAO_API cacao_result cacao_plan_build(const cacao_settings *settings, uint32_t width, uint32_t height,
                                        cacao_plan *plan, char *error, size_t error_size);

/* Writes a human-readable plan (one line per step, then the intermediates). */
CACAO_API void cacao_plan_print(const cacao_plan *plan, FILE *out);

/* ---- Context -------------------------------------------------------------------------------- */

typedef struct cacao_context cacao_context;

typedef struct cacao_context_desc {
    VkPhysicalDevice physical_device;               /* required */
    VkDevice device;                                /* required; VK_KHR_push_descriptor enabled */
    const VkAllocationCallbacks *allocation_callbacks; /* optional: cacao's own host allocations
                                                       (the context, scratch lists) and every Vulkan
                                                       object it creates go through it */
    /* Optional: where cacao gets its Vulkan entry points. With get_instance_proc_addr (and the
     * instance, required with it), instance-level functions come from
     * get_instance_proc_addr(instance, ...) and device-level ones from get_device_proc_addr(device,
     * ...) (default: the one get_instance_proc_addr gives), so layers and the caller's own dispatch
     * (volk, VK_NO_PROTOTYPES) are honoured. Without it, cacao opens the system loader
     * libvulkan.so.1 (dlopen) and uses the instance when given, else the loader's exported
     * functions; a loader that cannot be opened is CACAO_ERROR_UNSUPPORTED_DEVICE. A function that
     * cannot be loaded is CACAO_ERROR_UNSUPPORTED_DEVICE naming it. */
    VkInstance instance;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr;
    PFN_vkGetDeviceProcAddr get_device_proc_addr;
    char *error;                                    /* optional: where cacao_context_create writes
                                                       the message of a failure (naming the field or
                                                       the call), as cacao_context_last_error would */
    size_t error_size;
    VkPipelineCache pipeline_cache;                 /* optional */
    bool shader_float16_enabled;                    /* the device was created with shaderFloat16 on */
    bool separate_depth_stencil_layouts_enabled;    /* ... with separateDepthStencilLayouts on (Vulkan
                                                       1.2 or VK_KHR_separate_depth_stencil_layouts) */
    uint32_t required_subgroup_size;                /* 0: the driver's choice; else every pipeline runs
                                                       with it: a power of two in the device's
                                                       VK_EXT_subgroup_size_control range, with
                                                       subgroupSizeControl enabled on the device */
    VkPipelineCreateFlags pipeline_create_flags;    /* optional: added to every compute pipeline's
                                                       flags, e.g. CAPTURE_STATISTICS_BIT_KHR (with
                                                       pipelineExecutableInfo enabled) for tools that
                                                       read a compiler's statistics */
    cacao_shader_forms shader_forms;                /* DEFAULT: CPU forms on a CPU device, GPU forms
                                                       on others; CPU or GPU: those on any device (the
                                                       settings' own shader_forms, if set, wins) */
} cacao_context_desc;

/* Creates a context. Creates no pipelines and allocates no images yet. On failure *out_context is
 * NULL, nothing is left allocated, and desc->error (if given) says why. */
CACAO_API cacao_result cacao_context_create(const cacao_context_desc *desc, cacao_context **out_context);

/* Destroys everything the context created. The caller makes sure the GPU is done with it. NULL is
 * ignored; destroying the same context twice is undefined behaviour, as with free(). */
CACAO_API void cacao_context_destroy(cacao_context *context);

/* Replaces the settings (validated; see cacao_settings_resolve). Takes effect at the next
 * cacao_context_resize, which must follow before the next cacao_record. */
CACAO_API cacao_result cacao_context_set_settings(cacao_context *context, const cacao_settings *settings);

/* Memory the context holds for its intermediates. */
typedef struct cacao_memory_info {
    uint64_t total_bytes;       /* device memory allocated for intermediates and buffers */
    uint32_t allocation_count;  /* VkDeviceMemory objects holding them: 1 where one device-local
                                   memory type suits them all, else 2 (images, buffers), else one
                                   per memory type used */
    uint32_t image_count;       /* intermediate images */
    uint32_t pipeline_count;    /* compute pipelines (one per distinct permutation of the plan) */
} cacao_memory_info;

/* (Re)builds the plan for width x height (each 1..CACAO_MAX_SIZE) and the current settings, then
 * creates exactly the intermediates and pipelines it uses (nothing else); a resize that only
 * changes the size keeps the pipelines. The GPU must be done with earlier frames. out_info may be
 * NULL. The CPU shader forms read their tile lists through a texel view of the tile buffer: a size
 * whose tile buffer holds more entries than the device's maxTexelBufferElements is
 * CACAO_ERROR_UNSUPPORTED_DEVICE (none at CACAO_MAX_SIZE on lavapipe, whose limit is 2^27). */
CACAO_API cacao_result cacao_context_resize(cacao_context *context, uint32_t width, uint32_t height,
                                            cacao_memory_info *out_info);

/* Creates the pipelines the current settings need, before any size is known and without any
 * image or memory: load-time warm-up. A later cacao_context_resize with the same settings creates
 * no pipeline (a resize with other settings, or a set_settings that changes the steps, replaces
 * them). Calling it again with the same settings does nothing. Works on a device that can create
 * pipelines and nothing else (a GPU compiler's null device, for pipeline statistics). out_info
 * (may be NULL) gives pipeline_count; cacao_context_plan stays NULL until a resize. */
CACAO_API cacao_result cacao_context_create_pipelines(cacao_context *context, cacao_memory_info *out_info);

/* The pipeline step `step` of the settings' plan dispatches (after cacao_context_create_pipelines
 * or a resize; steps in cacao_plan_build's order, which the size does not change), for tools that
 * inspect, name or profile pipelines; steps with one permutation share one pipeline.
 * VK_NULL_HANDLE before either call (and after a set_settings until one), for a step past the plan's
 * and for a clear step (cacao_plan_step.clear: no pipeline). */
CACAO_API VkPipeline cacao_context_pipeline(const cacao_context *context, uint32_t step);

/* The plan the context records (valid after a successful resize; NULL before). */
CACAO_API const cacao_plan *cacao_context_plan(const cacao_context *context);

/* Message of the last error on this context, naming the offending field; "" if none. */
CACAO_API const char *cacao_context_last_error(const cacao_context *context);

/* ---- Recording ------------------------------------------------------------------------------ */

/* One of the caller's images as cacao sees it. */
typedef struct cacao_image {
    VkImage image;
    VkImageView view;           /* 2D view, one mip, one layer */
    VkFormat format;            /* the view's format */
    VkImageLayout layout;       /* its layout when the commands run; cacao leaves it there */
} cacao_image;

/* The formats inputs.normals may have: the one list, used by cacao_record's check (any other
 * format is CACAO_ERROR_UNSUPPORTED_FORMAT). Usable as an array initialiser. */
#define CACAO_NORMALS_FORMATS                                                                        \
    VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_SNORM,                    \
        VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_FORMAT_A2R10G10B10_UNORM_PACK32,                      \
        VK_FORMAT_R16G16B16A16_UNORM, VK_FORMAT_R16G16B16A16_SNORM, VK_FORMAT_R16G16B16A16_SFLOAT,   \
        VK_FORMAT_R32G32B32A32_SFLOAT

typedef struct cacao_inputs {
    /* Depth: D32_SFLOAT, D16_UNORM, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT, D32_SFLOAT_S8_UINT, R32_SFLOAT
     * or R16_SFLOAT; width x height of the resize. Layout: SHADER_READ_ONLY_OPTIMAL,
     * DEPTH_STENCIL_READ_ONLY_OPTIMAL or GENERAL; DEPTH_READ_ONLY_OPTIMAL only where the device was
     * created with separateDepthStencilLayouts and cacao_context_desc says so (refused otherwise). */
    cacao_image depth;
    /* Normals (required unless settings.generate_normals): one of CACAO_NORMALS_FORMATS; rgb
     * unpacked as rgb * normals_unpack_mul + normals_unpack_add. */
    cacao_image normals;
    /* Output: R32_SFLOAT, R16_SFLOAT, R8_UNORM or R16_UNORM with STORAGE usage. AO visibility in
     * [0,1], 1 = unoccluded. Layout: GENERAL, or any layout cacao transitions from and back to. */
    cacao_image output;
    /* Projection in math convention (clip = P * v), depth to [0,1] standard or reversed, clip y up
     * (P(1,1) > 0), left- or right-handed. Stored row-major when matrices_row_major, else
     * column-major (GLM). Perspective (P(3,2) != 0; far plane finite or infinite) or orthographic
     * (P(3,2) == 0, P(3,3) > 0); off-centre and jittered frusta through P(0,2), P(1,2)
     * (orthographic: P(0,3), P(1,3)). Skewed and oblique projections are refused. */
    float projection[16];
    /* Maps the caller's normals to cacao's view space (x right, y up, z forward; camera-facing
     * normals have negative z): n' = N * n (upper 3x3). All zero = identity. Same storage rule. */
    float normals_to_view[16];
    bool matrices_row_major;
    /* Orthographic projections only: true when depth 1 is the near plane (reverse-Z). An
     * orthographic matrix does not show that (an LH standard and an RH reversed one look alike);
     * a perspective projection shows its convention and ignores this. */
    bool depth_reversed;
    float normals_unpack_mul;   /* both 0: 2 and -1 (UNORM-packed normals) */
    float normals_unpack_add;
    /* Optional GPU timing: when set, cacao writes plan.step_count + 1 timestamps (compute stage)
     * starting at timestamp_first_query: one before the first step and one after each step. The
     * caller resets those queries before and reads them after. timestamp_query_count is the pool's
     * queryCount (required with a pool): a pool too small for the plan is refused, not written past. */
    VkQueryPool timestamp_query_pool;
    uint32_t timestamp_first_query;
    uint32_t timestamp_query_count;
    /* GTAO/BITMASK: frame number for temporal accumulation; it decorrelates the sample pattern of
     * successive frames (64 distinct patterns). 0 for a deterministic frame. */
    uint32_t frame_index;
    /* settings.reuse_unchanged only. force_full_frame: compute every tile this frame (as the first
     * frame after a resize does). output_holds_previous: the output image holds what this context
     * wrote into it last frame, untouched since (an engine's persistent AO target); a frame with
     * nothing changed then writes nothing (without it, apply runs over the whole output, or a
     * horizon estimator's last pass; in their CPU forms the frame is a full one). */
    bool force_full_frame;
    bool output_holds_previous;
    /* settings.temporal_frames only. view_to_previous_view maps this frame's view space (cacao's:
     * x right, y up, z forward) to the previous frame's, for static geometry: previous_view *
     * inverse(view) in the caller's conventions, expressed in cacao's view axes (the same change
     * of axes as normals_to_view); all zero = identity (a still camera). Same storage rule as
     * projection. The previous frame's projection is taken to be this one's (a change of
     * projection: set temporal_reset). temporal_reset drops the whole history this frame (a cut,
     * a teleport). */
    float view_to_previous_view[16];
    bool temporal_reset;
} cacao_inputs;

/* Records one frame: constant update, barriers and dispatches. cacao orders itself against the
 * caller's commands on both sides, so the caller records no barrier for cacao's sake:
 *   - before: a barrier from ALL_COMMANDS (memory writes) makes earlier writes to depth/normals
 *     visible and ends earlier accesses to the output;
 *   - after: a barrier from COMPUTE_SHADER (shader writes) to ALL_COMMANDS (memory reads and
 *     writes) returns the output to its layout, so later commands on the same queue may read or
 *     overwrite the AO directly (another queue needs the caller's semaphore, as always). A caller
 *     that moves the output to another layout afterwards records that transition as usual,
 *     naming COMPUTE_SHADER / SHADER_WRITE as its source. */
CACAO_API cacao_result cacao_record(cacao_context *context, VkCommandBuffer command_buffer, const cacao_inputs *inputs);

/* ---- Tiles skipped (docs/tiles.md) ---------------------------------------------------------
 * Every estimator classifies tiles as active, faded (beyond fade_out_to) or background (far
 * plane, invalid depth). CACAO: tiles of 8x8 slice texels (16x16 pixels native, 32x32
 * downsampled); generate and blur run only where an active tile is near (downsampled, the
 * upsample too, in the CPU forms without reuse), and HIGHEST's Q3 base pass only in the blocks of
 * 2x2 tiles holding an active tile (blocks_*). GTAO and BITMASK:
 * tiles of 8x8 pixels; the estimator and the denoise passes run only where an active tile is
 * near (generate_* counts them; blur_* is 0 of 0); downsampled, the estimator runs in the blocks
 * of 2x2 tiles holding an active tile (blocks_*) and the upsample and denoise passes where an
 * active tile is near. The rest of the AO is 1, as the full
 * computation gives it. The counts live on the device: record a copy after cacao_record, read it once the frame is
 * done. */
typedef struct cacao_tile_counts {
    uint32_t tiles, active, faded, background;   /* the frame's tiles by class */
    uint32_t generate_run, generate_total;       /* generate groups (tiles) run, of the full grid */
    uint32_t blur_run, blur_total;               /* blur groups (0 of 0 without a blur) */
    uint32_t fill_run;                           /* skipped tiles given AO 1 by the fills (CACAO's
                                                    CPU forms): without reuse, where apply or the
                                                    upsample runs over lists (downsampled; native
                                                    from MEDIUM up, and at LOWEST and LOW on frames
                                                    with at most 2/3 of the tiles active), only
                                                    those a pass reads; else every skipped tile (a
                                                    change can reach, with reuse). 0 where no fill
                                                    runs */
    uint32_t changed;                            /* reuse_unchanged: tiles whose inputs changed
                                                    (every tile on a full frame) */
    uint32_t recomputed;                         /* reuse_unchanged: tiles whose output a change
                                                    can reach (generate and the blur run over these
                                                    and one tile around them); 0 when nothing
                                                    changed. Without reuse both are 0. */
    uint32_t blocks_run, blocks_total;           /* the steps over blocks of 2x2 tiles holding an
                                                    active tile, of all blocks (the CPU forms:
                                                    HIGHEST's Q3 base pass, the horizon estimators'
                                                    downsampled estimator); the GPU form of the Q3
                                                    base pass: its active tiles, of all tiles; 0 of
                                                    0 where neither runs (docs/tiles.md) */
    bool quiet;                                  /* the frame was quiet: no pixel of the depth can
                                                    make AO other than 1 (background, or beyond the
                                                    fade-out), so only the quiet test ran (it wrote
                                                    the output) and no tile was classified (the
                                                    counts above are 0).
                                                    The CPU forms without reuse (docs/tiles.md
                                                    "A quiet frame"); false elsewhere */
} cacao_tile_counts;

#define CACAO_TILE_COUNTS_BYTES 128

/* Records, after cacao_record in the same command buffer, a copy of this frame's counts
 * (CACAO_TILE_COUNTS_BYTES bytes) into dst at offset (dst: TRANSFER_DST usage), with the barriers
 * around it (our writes before the copy; the copy before the caller's later host or transfer
 * reads, which the caller orders as usual). */
CACAO_API cacao_result cacao_record_tile_counts(cacao_context *context, VkCommandBuffer command_buffer, VkBuffer dst,
                                                VkDeviceSize offset);

/* Decodes the bytes such a copy wrote. */
CACAO_API cacao_result cacao_tile_counts_decode(const cacao_context *context, const void *bytes,
                                                cacao_tile_counts *out);

/* For tools and tests: the handle of one of the context's intermediates (image or buffer, the
 * other is set to VK_NULL_HANDLE), to copy it out after cacao_record. Images are in GENERAL
 * layout and were last written by the compute stage; treat them as read-only. Returns
 * CACAO_ERROR_INVALID_ARGUMENT when the current plan has no such resource. */
CACAO_API cacao_result cacao_context_intermediate(const cacao_context *context, cacao_resource resource, VkImage *image,
                                                  VkBuffer *buffer);

/* The precision that actually runs (FP32 when FP16 was asked but the device lacks it). */
CACAO_API cacao_precision cacao_context_precision(const cacao_context *context);

/* The shader forms the context runs for settings that leave shader_forms DEFAULT: the desc's, or
 * the device's (CPU on a CPU device, GPU on others). DEFAULT for a NULL context. */
CACAO_API cacao_shader_forms cacao_context_shader_forms(const cacao_context *context);

/* Number of permutations embedded in this build. */
CACAO_API uint32_t cacao_embedded_permutation_count(void);

#ifdef __cplusplus
}
#endif

#endif /* CACAO_H */
