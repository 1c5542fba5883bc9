/* cacao_passes.h - the one declarative definition of the pipeline's parts.
 *
 * Three tables, compiled into the generator, the runtime and the tools:
 *   - cacaoi_slots:     one row per binding slot of the single descriptor set layout (descriptor
 *                       kind, sampler, name used in the GLSL defines);
 *   - cacaoi_resources: one row per resource (format, size rule, layers, filtering);
 *   - cacaoi_passes:    one row per pass (key axes, variant names, workgroup size, dispatch grid and
 *                       its bindings: slot, resource, levels, access, which variants use it).
 *
 * Layering (each file depends only on those above it): cacao_shared.h (numbers shared with GLSL)
 * -> cacao_passes (these rows and their binding rules) -> cacao_keys (the key space, names, the
 * shader defines of a key, table lookup) -> cacao_policy (quality levels, the sequence of steps
 * one configuration dispatches, subsets).
 *
 * Everything else is derived from the rows: the GLSL declarations of every module (cacaoi_key_defines
 * writes CACAO_BIND_<slot>, CACAO_ACCESS_<slot> and CACAO_FORMAT_<slot> per key; shaders/glsl/
 * bindings.glsl declares each slot once under its CACAO_BIND_ guard), the steps, dispatch sizes,
 * intermediates, buffers and barriers of cacao_plan_build, the runtime's set layout, samplers,
 * image views and buffers, and the generator's check of every compiled module's reflection
 * against its row (cacaoi_pass_expect).
 *
 * Adding a pass: one row here (and its CACAO_PASS_* id in cacao_shared.h), its place in
 * cacaoi_sequence (cacao_policy.c), its GLSL body in shaders/glsl/, its tests.
 */
#ifndef CACAO_PASSES_H
#define CACAO_PASSES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao.h"
#include "cacao_shared.h"

/* Descriptor kinds a binding slot has (0 = the module does not use that slot). Kinds of
 * descriptors, not resources (those are cacao_resource, CACAO_RES_*). */
#define CACAOI_DESCRIPTOR_NONE 0
#define CACAOI_DESCRIPTOR_UNIFORM_BUFFER 1
#define CACAOI_DESCRIPTOR_STORAGE_BUFFER 2
#define CACAOI_DESCRIPTOR_SAMPLED_IMAGE 3 /* combined image sampler (immutable sampler) */
#define CACAOI_DESCRIPTOR_STORAGE_IMAGE 4
#define CACAOI_DESCRIPTOR_STORAGE_TEXEL_BUFFER 5 /* read-only R32_UINT view of a buffer */
#define CACAOI_DESCRIPTOR_COUNT 6

/* Their names in messages and listings: "-", "uniform buffer", ... "storage texel buffer". */
extern const char *const cacaoi_descriptor_names[CACAOI_DESCRIPTOR_COUNT];

/* Immutable samplers of combined-image-sampler slots. Both clamp to edge, mipmap nearest. */
#define CACAOI_SAMPLER_NONE 0
#define CACAOI_SAMPLER_NEAREST 1
#define CACAOI_SAMPLER_LINEAR 2

typedef struct cacaoi_slot_row {
    const char *name;   /* binding name without prefix: "SSAO_IMAGE" (GLSL defines CACAO_BIND_SSAO_IMAGE, ...) */
    uint8_t descriptor; /* CACAOI_DESCRIPTOR_* */
    uint8_t sampler;    /* CACAOI_SAMPLER_* (combined image samplers only) */
} cacaoi_slot_row;

extern const cacaoi_slot_row cacaoi_slots[CACAO_BINDING_COUNT];

/* How a resource is sized. */
#define CACAOI_SIZE_CALLER 0     /* the caller's image */
#define CACAOI_SIZE_BUFFER 1     /* a buffer of buffer_bytes */
#define CACAOI_SIZE_SLICE 2      /* one deinterleaved slice (half or quarter resolution) */
#define CACAOI_SIZE_IMPORTANCE 3 /* half a slice */
#define CACAOI_SIZE_FULL 4       /* the output's size */
#define CACAOI_SIZE_TILES 5      /* the tile buffer: header, classes and lists (cacao_plan.tile_buffer_bytes) */
#define CACAOI_SIZE_HALF 6       /* half the output's size, rounded up */
#define CACAOI_SIZE_HALF_X3 7    /* as HALF, three times as wide (three texels per 2x2 pixels) */

typedef struct cacaoi_resource_row {
    const char *name;        /* cacao_resource_name() */
    uint8_t size;            /* CACAOI_SIZE_* */
    bool layered;            /* one layer per slice: a 2D-array image, read and written as arrays */
    bool filtered;           /* read through the linear sampler: its format must support filtering */
    VkFormat format;         /* intermediates only */
    const char *format_name; /* "R16_SFLOAT" */
    const char *glsl_format; /* storage-image qualifier: "r16f" ("" where the view's format decides) */
    uint32_t texel_bytes;
    uint32_t buffer_bytes;   /* CACAOI_SIZE_BUFFER only */
    VkBufferUsageFlags buffer_usage; /* buffers only: how the passes and the runtime use it */
} cacaoi_resource_row;

extern const cacaoi_resource_row cacaoi_resources[CACAO_RES_COUNT];

/* How a pass's dispatch grid follows from the sizes. */
#define CACAOI_GRID_ROW 0          /* in a row's grids[]: the variant has the row's grid */
#define CACAOI_GRID_SLICE 1        /* slice size / workgroup, 1 layer */
#define CACAOI_GRID_SLICE_LAYERS 2 /* slice size / workgroup, one z per slice */
#define CACAOI_GRID_IMPORTANCE 3   /* importance map size / workgroup */
#define CACAOI_GRID_BLUR 4         /* slice size / CACAO_BLUR_OUT(n), one z per slice */
#define CACAOI_GRID_OUTPUT 5       /* output size / workgroup */
#define CACAOI_GRID_UPSAMPLE 6     /* output size / (2 CACAO_UPSAMPLE_SPAN) */
#define CACAOI_GRID_COMPACT 7      /* one invocation per tile, blur group and apply group */
#define CACAOI_GRID_TILES 8        /* one invocation per tile */
#define CACAOI_GRID_HALF 9         /* half the output size (rounded up) / workgroup */
#define CACAOI_GRID_TILE_ROWS 10   /* one invocation per row of tiles (x only) */
#define CACAOI_GRID_SLICE_CLASSIFY 11 /* as SLICE; downsampled z 2: groups z 0 classify the tiles
                                         (prepare_gpu downsampled), z 1 prepare */

#define CACAOI_ALL_VARIANTS 0xffu
#define CACAOI_VARIANT(v) (1u << (v))

typedef struct cacaoi_pass_binding {
    uint8_t slot;     /* CACAO_BINDING_* */
    uint8_t resource; /* cacao_resource bound unless the step names another of the same format */
    uint8_t levels;   /* the depths: mip levels the image holds as an atlas (cacao_shared.h), 0 = 1 */
    bool write;
    uint8_t variants; /* bit mask of the variants that declare it */
    bool native_only; /* declared by those variants' native keys only (the prepare passes' axis) */
} cacaoi_pass_binding;

/* Bindings a row lists (a binding per variant may share a slot) and variants a pass has. The
 * bindings one variant makes are at most CACAO_PLAN_MAX_BINDINGS (cacao.h): test_pass_table. */
#define CACAOI_PASS_MAX_BINDINGS 13
#define CACAOI_MAX_VARIANTS 7

/* The level (1..3) of the depths' mip chain whose view a slot binds (the GPU forms' prepare writes
 * each level through its own slot), 0 for any other slot. */
static inline unsigned cacaoi_depth_mip_slot_level(unsigned slot) {
    return slot >= CACAO_BINDING_DEPTHS_MIP1 && slot <= CACAO_BINDING_DEPTHS_MIP3 ? slot - CACAO_BINDING_DEPTHS_MIP1 + 1 : 0;
}

typedef struct cacaoi_pass_row {
    const char *name;                                /* key names: "generate" */
    const char *variant_names[CACAOI_MAX_VARIANTS];  /* NULL for a pass with one unnamed variant */
    uint8_t variants;
    bool has_resolution, has_blur, has_precision;    /* key axes besides the variant */
    uint32_t workgroup[2];                           /* local size x, y (z 1) */
    uint8_t grid;                                    /* CACAOI_GRID_* */
    uint8_t binding_count;
    cacaoi_pass_binding bindings[CACAOI_PASS_MAX_BINDINGS];
    uint8_t lists[CACAOI_MAX_VARIANTS];              /* per variant: CACAO_LIST_* it dispatches from
                                                        (indirect), CACAO_LIST_NONE: a direct grid */
    uint8_t quad[CACAOI_MAX_VARIANTS];               /* per variant: an invocation computes quad x
                                                        quad texels (grid x and y divided by it);
                                                        0 for one texel */
    uint8_t grids[CACAOI_MAX_VARIANTS];              /* per variant: CACAOI_GRID_* where it differs
                                                        from the row's grid, CACAOI_GRID_ROW where not */
} cacaoi_pass_row;

extern const cacaoi_pass_row cacaoi_passes[CACAO_PASS_COUNT];

/* Output texels (x, y) of one group of the blur pass `pass` (BLUR or BLUR_GPU) of n iterations:
 * the dispatch grid, the blur list's groups and the shader's tile all follow it. */
static inline void cacaoi_blur_out(unsigned pass, unsigned n, uint32_t out[2]) {
    out[0] = pass == CACAO_PASS_BLUR_GPU ? CACAO_BLUR_GPU_OUT_X(n) : CACAO_BLUR_OUT_X(n);
    out[1] = pass == CACAO_PASS_BLUR_GPU ? CACAO_BLUR_GPU_OUT_Y(n) : CACAO_BLUR_OUT_Y(n);
}

/* What a compiled module of this pass variant must declare: per slot, its descriptor kind (or
 * NONE), and for image slots the resource whose format and layering it has. False for a pass or
 * variant the table does not have. */
typedef struct cacaoi_module_expect {
    uint8_t descriptor[CACAO_BINDING_COUNT];
    uint8_t resource[CACAO_BINDING_COUNT];
    bool write[CACAO_BINDING_COUNT];
    uint32_t workgroup[3];
} cacaoi_module_expect;
bool cacaoi_pass_expect(unsigned pass, unsigned variant, unsigned downsampled, cacaoi_module_expect *out);

/* The bindings one variant of a pass makes, native or downsampled (its row's, in row order), written into out up to
 * CACAO_PLAN_MAX_BINDINGS. Returns their number, which exceeds that only if the table is wrong
 * (test_pass_table checks every variant; cacao_plan_build refuses such a step); 0 for a pass or
 * variant the table lacks. */
size_t cacaoi_variant_bindings(unsigned pass, unsigned variant, unsigned downsampled,
                               cacaoi_pass_binding out[CACAO_PLAN_MAX_BINDINGS]);

/* The passes that run over every group and skip by the tile classes (the GPU forms of generate
 * and the blur: docs/tiles.md): a group that is not needed stores AO 1 and returns. */
bool cacaoi_skips_by_class(unsigned pass, unsigned variant);

/* The GPU forms that read the tile classes and skip a group whose tiles hold no active one, with no
 * count (a workgroup-uniform branch around the body): the Q3 base pass and the horizon
 * estimators' downsampled estimator (docs/tiles.md). */
bool cacaoi_reads_classes(unsigned pass, unsigned variant);

/* The fill variants that fill cacao's own images: recorded as a clear of the whole image
 * (cacao_plan_step.clear), never dispatched. */
bool cacaoi_fill_is_clear(unsigned pass, unsigned variant);

/* The colour a clear step stores into an intermediate (float32 channels: the value the passes
 * would give the tiles they skip); false for a resource no step clears. */
bool cacaoi_clear_value(unsigned resource, float out[4]);

#endif /* CACAO_PASSES_H */
