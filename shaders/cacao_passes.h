/* cacao_passes.h - the one declarative definition of the pipeline.
 *
 * Three tables and one sequence, compiled into the generator, the runtime and the tools:
 *   - cacaoi_slots:     one row per binding slot of the single descriptor set layout (descriptor
 *                       kind, sampler, name used in the GLSL defines);
 *   - cacaoi_resources: one row per resource (format, size rule, layers, filtering);
 *   - cacaoi_passes:    one row per pass (key axes, variant names, workgroup size, dispatch grid and
 *                       its bindings: slot, resource, levels, access, which variants use it);
 *   - cacaoi_sequence:  the steps one configuration dispatches, in order.
 *
 * Everything else is derived from them: the keys a configuration needs (cacaoi_keys_for_config,
 * subset builds, cacao-inspect verify), the steps, dispatch sizes, intermediates and barriers of
 * cacao_plan_build, the storage-image format qualifiers of the GLSL (cacaoi_key_defines writes
 * CACAO_FORMAT_<slot> per key), the runtime's set layout, samplers and image views, and the
 * generator's check of every compiled module's reflection against its row (cacaoi_pass_expect).
 *
 * Adding a pass: one row here (and its CACAO_PASS_* id in cacao_shared.h), its place in
 * cacaoi_sequence, its GLSL body in cacao.comp, its tests.
 */
#ifndef CACAO_PASSES_H
#define CACAO_PASSES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao.h"
#include "cacao_keys.h"

/* Descriptor kinds a binding slot has (0 = the module does not use that slot). */
#define CACAO_RESOURCE_NONE 0
#define CACAO_RESOURCE_UNIFORM_BUFFER 1
#define CACAO_RESOURCE_STORAGE_BUFFER 2
#define CACAO_RESOURCE_SAMPLED_IMAGE 3 /* combined image sampler (immutable sampler) */
#define CACAO_RESOURCE_STORAGE_IMAGE 4

/* Immutable samplers of combined-image-sampler slots. Both clamp to edge, mipmap nearest. */
#define CACAOI_SAMPLER_NONE 0
#define CACAOI_SAMPLER_NEAREST 1
#define CACAOI_SAMPLER_LINEAR 2

typedef struct cacaoi_slot_row {
    const char *name;   /* binding name without prefix: "SSAO_OUT" (GLSL define CACAO_FORMAT_SSAO_OUT) */
    uint8_t descriptor; /* CACAO_RESOURCE_* */
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

typedef struct cacaoi_resource_row {
    const char *name;        /* cacao_resource_name() */
    uint8_t size;            /* CACAOI_SIZE_* */
    bool layered;            /* one layer per slice: a 2D-array image, read and written as arrays */
    bool filtered;           /* read through the linear sampler: its format must support filtering */
    VkFormat format;         /* intermediates only */
    const char *format_name; /* "R16_SFLOAT" */
    const char *glsl_format; /* storage-image qualifier: "r16f" ("" where the view's format decides) */
    uint32_t texel_bytes;
    uint32_t buffer_bytes;   /* buffers only */
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

#define CACAOI_ALL_VARIANTS 0xffu
#define CACAOI_VARIANT(v) (1u << (v))

typedef struct cacaoi_pass_binding {
    uint8_t slot;     /* CACAO_BINDING_* */
    uint8_t resource; /* cacao_resource bound unless the step names another of the same format */
    uint8_t levels;   /* the depths: mip levels the image holds as an atlas (cacao_shared.h), 0 = 1 */
    bool write;
    uint8_t variants; /* bit mask of the variants that declare it */
} cacaoi_pass_binding;

#define CACAOI_PASS_MAX_BINDINGS 11
#define CACAOI_MAX_VARIANTS 5

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

/* What a compiled module of this key must declare: per slot, its descriptor kind (or NONE), and
 * for image slots the resource whose format and layering it has. False for an invalid key. */
typedef struct cacaoi_module_expect {
    uint8_t descriptor[CACAO_BINDING_COUNT];
    uint8_t resource[CACAO_BINDING_COUNT];
    bool write[CACAO_BINDING_COUNT];
    uint32_t workgroup[3];
} cacaoi_module_expect;
bool cacaoi_pass_expect(const cacao_key *key, cacaoi_module_expect *out);

/* ---- The sequence ---- */

/* One dispatch: its key and, where it binds another resource than its row's default at a slot
 * (ping-pong buffers), that resource. */
typedef struct cacaoi_step {
    cacao_key key;
    uint8_t override_count;
    uint8_t override_slot[2];
    uint8_t override_resource[2];
} cacaoi_step;

#define CACAOI_SEQUENCE_MAX 16

/* The steps one configuration dispatches, in order. */
size_t cacaoi_sequence(const cacao_key_config *config, cacaoi_step out[CACAOI_SEQUENCE_MAX]);

/* The bindings a step makes: its row's bindings for its variant, with the step's overrides. */
size_t cacaoi_step_bindings(const cacaoi_step *step, cacaoi_pass_binding out[CACAOI_PASS_MAX_BINDINGS]);

/* A plan step's key (cacao_plan_step.key holds pass, variant, downsampled, blur passes, fp16). */
static inline cacao_key cacaoi_plan_step_key(const cacao_plan_step *step) {
    return (cacao_key){step->key[0], step->key[1], step->key[2], step->key[3], step->key[4]};
}

#endif /* CACAO_PASSES_H */
