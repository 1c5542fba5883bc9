/* cacao_policy.h - what each setting selects: the quality levels (variants, slices, radius and
 * near-limit scales, the horizon estimators' budgets, in one table), the sequence of steps one
 * configuration dispatches, the keys it needs, and build-time subsets of the configuration space.
 * Compiled into the generator, the runtime and the tools, so all of them choose alike.
 *
 * Depends on cacao_keys.h and cacao_passes.h; neither depends on it (layering: cacao_passes.h).
 */
#ifndef CACAO_POLICY_H
#define CACAO_POLICY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao_keys.h"
#include "cacao_passes.h"

/* Key-space quality levels, 0-based. The public cacao_quality is 1-based (0 there means "default"):
 * key quality = cacao_quality - 1 (cacaoi_key_quality). */
#define CACAO_KEY_QUALITY_LOWEST 0
#define CACAO_KEY_QUALITY_LOW 1
#define CACAO_KEY_QUALITY_MEDIUM 2
#define CACAO_KEY_QUALITY_HIGH 3
#define CACAO_KEY_QUALITY_HIGHEST 4
#define CACAO_KEY_QUALITY_COUNT 5

_Static_assert(CACAO_KEY_QUALITY_COUNT == CACAO_QUALITY_HIGHEST, "key qualities are cacao_quality - 1");
/* Names: cacaoi_quality_names (cacao_names.h), indexed by key quality. Key quality of a public (1-based) cacao_quality value. */
#define cacaoi_key_quality(api_quality) ((unsigned)(api_quality) - 1u)

/* What one quality level selects (spec: README "Quality levels"; estimators.md section 6). The
 * taps of each generate variant are constants of the algorithm (CACAO_TAPS_Q* in cacao_shared.h). */
typedef struct cacaoi_quality_row {
    uint8_t depths_variant;     /* CACAO_DEPTHS_*: MEDIUM builds no mips, its generate (Q1) never
                                   reads them ([quirk] MIPS-AT-MEDIUM) */
    uint8_t generate_variant;   /* CACAO_GENERATE_*: q = max(0, quality - 1); HIGHEST's Q3 runs after
                                   the Q3 base pass */
    uint8_t output_native;      /* CACAO_OUTPUT_* of apply */
    uint8_t output_downsampled; /* CACAO_OUTPUT_* of upsample */
    uint8_t slice_count;        /* deinterleaved layers: 2 at LOWEST (slices 0 and 3), else 4 */
    float radius_scale;         /* of the effect radius (spec: constants.md: LOWEST 0.8) */
    float near_limit_scale;     /* of the sampling radius near limit (LOW and LOWEST 1.5) */
    /* The horizon estimators' budget, [0] GTAO, [1] bitmask: slices per pixel and steps per side
     * (2 depth reads per step). Chosen from the measured error/time front (docs/estimators.md):
     * steps buy more than slices (a missed occluder between two steps is a bias no denoise
     * removes; the slice rotation varies per pixel, so the denoise averages slices), so each
     * estimator adds steps first and keeps 2 slices once it has them. */
    uint8_t horizon_budget[2][2];
} cacaoi_quality_row;

/* A quality level's horizon budget for an estimator (CACAO_KEY_ESTIMATOR_GTAO or _BITMASK). */
#define CACAOI_HORIZON_SLICES(quality, estimator) \
    (cacaoi_qualities[quality].horizon_budget[(estimator) == CACAO_KEY_ESTIMATOR_BITMASK][0])
#define CACAOI_HORIZON_STEPS(quality, estimator) \
    (cacaoi_qualities[quality].horizon_budget[(estimator) == CACAO_KEY_ESTIMATOR_BITMASK][1])

extern const cacaoi_quality_row cacaoi_qualities[CACAO_KEY_QUALITY_COUNT];

/* Estimators (the public cacao_estimator less one: 0-based, no "default"). */
#define CACAO_KEY_ESTIMATOR_CACAO 0
#define CACAO_KEY_ESTIMATOR_GTAO 1
#define CACAO_KEY_ESTIMATOR_BITMASK 2
#define CACAO_KEY_ESTIMATOR_COUNT 3

/* One configuration's axes, as far as they select shader keys. */
typedef struct cacao_key_config {
    unsigned quality;      /* CACAO_KEY_QUALITY_* */
    bool downsampled;      /* CACAO estimator only: the horizon estimators have no downsampled keys */
    bool fp16;
    bool normals_from_input;
    unsigned blur_passes;  /* 0..8 (horizon estimators: denoise passes) */
    unsigned estimator;    /* CACAO_KEY_ESTIMATOR_* */
    bool gpu_forms;        /* the GPU forms of the blur, apply, prepare and generate (cacao_shader_forms) */
    bool reuse;            /* reuse_unchanged (the REUSE passes first) */
    bool temporal;         /* temporal_frames (the HORIZON_TEMPORAL passes last; horizon estimators only) */
} cacao_key_config;

/* The pass of the configuration's forms: BLUR, APPLY, PREPARE, GENERATE or their GPU rows (any
 * other pass, the upsample included, is itself). */
unsigned cacaoi_form_pass(unsigned pass, bool gpu_forms);

/* True when some configuration with these forms dispatches the key (cacaoi_sequence): false for
 * the other forms' rows (the CPU blur, apply, prepare and generate under GPU forms, their GPU rows
 * under CPU forms) and for CACAO's compact and fill under GPU forms, which skip in the shader. */
bool cacaoi_key_in_forms(const cacao_key *key, bool gpu_forms);

/* ---- The sequence ---- */

/* One dispatch: its key and, where it binds another resource than its row's default at a slot
 * (ping-pong buffers), that resource. */
typedef struct cacaoi_step {
    cacao_key key;
    uint8_t override_count;
    uint8_t override_slot[2];
    uint8_t override_resource[2];
} cacaoi_step;

/* Steps one configuration dispatches at most: a plan holds them all. */
#define CACAOI_SEQUENCE_MAX CACAO_PLAN_MAX_STEPS

/* The steps one configuration dispatches, in order (at most CACAOI_SEQUENCE_MAX). */
size_t cacaoi_sequence(const cacao_key_config *config, cacaoi_step out[CACAOI_SEQUENCE_MAX]);

/* The frame's prepare classifies the tiles, and no classify pass runs: CACAO's GPU forms with
 * normals from depth (prepare_gpu: native, the texels it stores; downsampled, groups of its own
 * from the caller's depth; docs/tiles.md). */
bool cacaoi_prepare_classifies(const cacao_key_config *config);

/* The bindings a step makes: its row's bindings for its variant, with the step's overrides.
 * Returns their number (more than CACAO_PLAN_MAX_BINDINGS only if the table is wrong, see
 * cacaoi_variant_bindings). */
size_t cacaoi_step_bindings(const cacaoi_step *step, cacaoi_pass_binding out[CACAO_PLAN_MAX_BINDINGS]);

/* Keys one configuration dispatches, each once, in first-dispatch order (at most
 * CACAO_KEY_CONFIG_MAX: every step could have its own key). */
#define CACAO_KEY_CONFIG_MAX CACAOI_SEQUENCE_MAX
size_t cacaoi_keys_for_config(const cacao_key_config *config, cacao_key out[CACAO_KEY_CONFIG_MAX]);

/* A plan step's key (cacao_plan_step.key holds pass, variant, downsampled, blur passes, fp16). */
static inline cacao_key cacaoi_plan_step_key(const cacao_plan_step *step) {
    return (cacao_key){step->key[0], step->key[1], step->key[2], step->key[3], step->key[4]};
}

/* ---- Build-time subsets ---- */

/* A subset of the configuration space (bit masks; bit i = quality i, bit 0/1 = native/downsampled,
 * bit 0/1 = fp32/fp16). */
typedef struct cacao_key_subset {
    unsigned quality_mask;
    unsigned resolution_mask;
    unsigned precision_mask;
} cacao_key_subset;

#define CACAO_KEY_SUBSET_ALL ((cacao_key_subset){0x1f, 0x3, 0x3})

/* True when some configuration inside the subset dispatches this key. */
bool cacaoi_key_in_subset(const cacao_key *key, const cacao_key_subset *subset);

/* Parses the CMake-style lists used by the build: qualities "medium;high" (or "all"), downsample
 * "ON" (native and downsampled), "OFF" (native only) or "ONLY" (downsampled only), precision
 * "fp32;fp16". Return false and leave *subset unchanged on an unknown word. */
bool cacaoi_key_subset_parse(const char *qualities, const char *downsample, const char *precision,
                            cacao_key_subset *subset);

#endif /* CACAO_POLICY_H */
