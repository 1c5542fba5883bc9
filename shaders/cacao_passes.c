/* cacao_passes.c - the pass, resource and slot tables and the sequence (see cacao_passes.h). */
#include "cacao_passes.h"

#include <string.h>

#define SLOT(id, descriptor, sampler) [CACAO_BINDING_##id] = {#id, CACAO_RESOURCE_##descriptor, CACAOI_SAMPLER_##sampler}
const cacaoi_slot_row cacaoi_slots[CACAO_BINDING_COUNT] = {
    SLOT(CONSTANTS, UNIFORM_BUFFER, NONE),    SLOT(LOAD_COUNTER, STORAGE_BUFFER, NONE),
    SLOT(SRC_DEPTH, SAMPLED_IMAGE, NEAREST),  SLOT(SRC_NORMALS, SAMPLED_IMAGE, NEAREST),
    SLOT(DEPTHS, SAMPLED_IMAGE, NEAREST),     SLOT(NORMALS, SAMPLED_IMAGE, NEAREST),
    SLOT(SSAO_IN, SAMPLED_IMAGE, LINEAR),     SLOT(SSAO_BASE, SAMPLED_IMAGE, NEAREST),
    SLOT(IMPORTANCE_IN, SAMPLED_IMAGE, LINEAR), SLOT(DEPTHS_OUT0, STORAGE_IMAGE, NONE),
    SLOT(DEPTHS_OUT1, STORAGE_IMAGE, NONE),   SLOT(DEPTHS_OUT2, STORAGE_IMAGE, NONE),
    SLOT(DEPTHS_OUT3, STORAGE_IMAGE, NONE),   SLOT(NORMALS_OUT, STORAGE_IMAGE, NONE),
    SLOT(SSAO_OUT, STORAGE_IMAGE, NONE),      SLOT(IMPORTANCE_OUT, STORAGE_IMAGE, NONE),
    SLOT(OUTPUT, STORAGE_IMAGE, NONE),        SLOT(TILES, STORAGE_BUFFER, NONE),
};
#undef SLOT

#define CALLER(id, name) [CACAO_RES_##id] = {name, CACAOI_SIZE_CALLER, false, false, VK_FORMAT_UNDEFINED, "caller's", "", 0, 0}
#define BUFFER(id, name, bytes) [CACAO_RES_##id] = {name, CACAOI_SIZE_BUFFER, false, false, VK_FORMAT_UNDEFINED, "buffer", "", 0, bytes}
#define TILES_BUFFER(id, name) [CACAO_RES_##id] = {name, CACAOI_SIZE_TILES, false, false, VK_FORMAT_UNDEFINED, "buffer", "", 0, 0}
#define IMAGE(id, name, size, layered, filtered, fmt, glsl, bytes) \
    [CACAO_RES_##id] = {name, CACAOI_SIZE_##size, layered, filtered, VK_FORMAT_##fmt, #fmt, glsl, bytes, 0}
const cacaoi_resource_row cacaoi_resources[CACAO_RES_COUNT] = {
    CALLER(DEPTH_INPUT, "depth_input"),
    CALLER(NORMALS_INPUT, "normals_input"),
    CALLER(OUTPUT, "output"),
    BUFFER(CONSTANTS, "constants", sizeof(cacao_constants)),
    BUFFER(LOAD_COUNTER, "load_counter", sizeof(uint32_t)),
    TILES_BUFFER(TILES, "tiles"),
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
};
#undef CALLER
#undef BUFFER
#undef TILES_BUFFER
#undef IMAGE

/* Binding rows: R reads, W writes; ALL variants or only those listed (bit mask). */
#define R(slot, res, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, 0, false, variants}
#define W(slot, res, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, 0, true, variants}
#define W_LEVELS(slot, res, levels, variants) {CACAO_BINDING_##slot, CACAO_RES_##res, levels, true, variants}
#define ALL CACAOI_ALL_VARIANTS
#define V(v) CACAOI_VARIANT(v)
#define CONSTANTS R(CONSTANTS, CONSTANTS, ALL)
#define PASS(id) [CACAO_PASS_##id]
#define WG(name) {CACAO_WG_##name##_X, CACAO_WG_##name##_Y}
#define GEN CACAO_LIST_GENERATE

const cacaoi_pass_row cacaoi_passes[CACAO_PASS_COUNT] = {
    /* spec: prepare.md. HALF = slices 0 and 3 (LOWEST), FULL = four slices, MIPS = + mips 1..3,
     * all levels in one atlas image (cacao_shared.h). Where the caller gives normals; with
     * normals from depth PREPARE writes the same depths and the normals in one pass. */
    PASS(PREPARE_DEPTHS) = {"prepare_depths", {"half", "full", "mips"}, 3, true, false, false, WG(PREPARE),
                            CACAOI_GRID_SLICE, 4,
                            {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL),
                             W(DEPTHS_OUT0, DEPTHS, V(CACAO_DEPTHS_HALF) | V(CACAO_DEPTHS_FULL)),
                             W_LEVELS(DEPTHS_OUT0, DEPTHS, CACAO_DEPTH_MIP_COUNT, V(CACAO_DEPTHS_MIPS))},
                            /* the mips variant reduces a 2x2 quad per invocation in registers */
                            .quad = {[CACAO_DEPTHS_MIPS] = 2}},
    /* spec: prepare.md "Normals from input normals" (from depth: PREPARE). */
    PASS(PREPARE_NORMALS) = {"prepare_normals", {NULL}, 1, true, false, false, WG(PREPARE), CACAOI_GRID_SLICE, 3,
                             {CONSTANTS, R(SRC_NORMALS, NORMALS_INPUT, ALL), W(NORMALS_OUT, NORMALS, ALL)}},
    /* spec: generate.md. Q3 (HIGHEST's adaptive pass) adds its base, the importance map and the
     * load counter; the Q3 base pass writes the second AO buffer and the importance map
     * (importance.md "GenerateImportanceMap"): an invocation per importance texel computes the
     * 2x2 slice texels of every layer that texel reads. */
    PASS(GENERATE) = {"generate", {"q0", "q1", "q2", "q3", "q3base"}, 5, false, false, false, WG(GENERATE),
                      CACAOI_GRID_SLICE_LAYERS, 11,
                      {CONSTANTS, R(LOAD_COUNTER, LOAD_COUNTER, V(CACAO_GENERATE_Q3)), R(DEPTHS, DEPTHS, ALL),
                       /* the taps' and normals' single texels: imageLoad (cacao.comp) */
                       R(DEPTHS_OUT0, DEPTHS, ALL), R(NORMALS_OUT, NORMALS, ALL),
                       R(SSAO_BASE, SSAO_PONG, V(CACAO_GENERATE_Q3)),
                       R(IMPORTANCE_IN, IMPORTANCE, V(CACAO_GENERATE_Q3)),
                       W(SSAO_OUT, SSAO_PING, ALL & ~V(CACAO_GENERATE_Q3_BASE)),
                       W(SSAO_OUT, SSAO_PONG, V(CACAO_GENERATE_Q3_BASE)),
                       W(IMPORTANCE_OUT, IMPORTANCE, V(CACAO_GENERATE_Q3_BASE)),
                       R(TILES, TILES, ALL & ~V(CACAO_GENERATE_Q3_BASE))},
                      /* the Q3 base pass covers every tile: its values feed the importance map and
                       * the load counter, which steer the adaptive pass everywhere */
                      .lists = {GEN, GEN, GEN, GEN, CACAO_LIST_NONE},
                      .grids = {[CACAO_GENERATE_Q3_BASE] = CACAOI_GRID_IMPORTANCE}},
    /* spec: importance.md: two smoothing passes (ping-pong) of the map the Q3 base pass wrote. */
    PASS(IMPORTANCE_A) = {"importance_a", {NULL}, 1, false, false, false, WG(IMPORTANCE), CACAOI_GRID_IMPORTANCE, 3,
                          {CONSTANTS, R(IMPORTANCE_IN, IMPORTANCE, ALL), W(IMPORTANCE_OUT, IMPORTANCE_PONG, ALL)}},
    PASS(IMPORTANCE_B) = {"importance_b", {NULL}, 1, false, false, false, WG(IMPORTANCE), CACAOI_GRID_IMPORTANCE, 4,
                          {CONSTANTS, W(LOAD_COUNTER, LOAD_COUNTER, ALL), R(IMPORTANCE_IN, IMPORTANCE_PONG, ALL),
                           W(IMPORTANCE_OUT, IMPORTANCE, ALL)}},
    /* spec: blur.md: all iterations in one dispatch. */
    PASS(BLUR) = {"blur", {NULL}, 1, false, true, true, WG(BLUR), CACAOI_GRID_BLUR, 4,
                  {CONSTANTS, R(SSAO_IN, SSAO_PING, ALL), W(SSAO_OUT, SSAO_PONG, ALL), R(TILES, TILES, ALL)},
                  .lists = {CACAO_LIST_BLUR}},
    /* spec: apply.md, upsample.md. They read the blur's output where a blur ran (step override).
     * Dispatched over every group: where no tile near is active they read the fill's 1 and write
     * 1. (Indirect over the groups near an active tile, with a fill for the rest, was slower on
     * lavapipe: docs/tiles.md.) */
    PASS(APPLY) = {"apply", {"smart", "nonsmart", "half"}, 3, false, false, true, WG(APPLY), CACAOI_GRID_OUTPUT, 3,
                   {CONSTANTS, R(SSAO_IN, SSAO_PING, ALL), W(OUTPUT, OUTPUT, ALL)},
                   /* smart: 4x4 output pixels per invocation; non-smart and half: 2x2 */
                   .quad = {[CACAO_OUTPUT_SMART] = 4, [CACAO_OUTPUT_NON_SMART] = 2, [CACAO_OUTPUT_HALF] = 2}},
    PASS(UPSAMPLE) = {"upsample", {"smart", "nonsmart", "half"}, 3, false, false, true, WG(UPSAMPLE),
                      CACAOI_GRID_UPSAMPLE, 5,
                      {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL), R(DEPTHS, DEPTHS, ALL), R(SSAO_IN, SSAO_PING, ALL),
                       W(OUTPUT, OUTPUT, ALL)}},
    /* spec: estimators.md. Full-resolution intermediates, read and written as storage images. */
    PASS(SLICE_PREPARE) = {"slice_prepare", {"depth", "input"}, 2, false, false, false, WG(SLICE), CACAOI_GRID_OUTPUT,
                           5,
                           {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL),
                            R(SRC_NORMALS, NORMALS_INPUT, V(CACAO_SLICE_NORMALS_INPUT)),
                            W(DEPTHS_OUT0, VIEW_DEPTH, ALL), W(NORMALS_OUT, VIEW_NORMALS, ALL)}},
    PASS(SLICE_MAIN) = {"slice_main", {"gtao", "bitmask", "gtao_direct", "bitmask_direct"}, 4, false, false, false,
                        WG(SLICE), CACAOI_GRID_OUTPUT, 5,
                        {CONSTANTS, R(DEPTHS_OUT0, VIEW_DEPTH, ALL), R(NORMALS_OUT, VIEW_NORMALS, ALL),
                         W(SSAO_OUT, AO_RAW, V(CACAO_SLICE_GTAO) | V(CACAO_SLICE_BITMASK)),
                         W(OUTPUT, OUTPUT, V(CACAO_SLICE_GTAO_DIRECT) | V(CACAO_SLICE_BITMASK_DIRECT))}},
    PASS(SLICE_DENOISE) = {"slice_denoise", {"intermediate", "final"}, 2, false, false, false, WG(SLICE),
                           CACAOI_GRID_OUTPUT, 6,
                           {CONSTANTS, R(DEPTHS_OUT1, AO_RAW, ALL), R(DEPTHS_OUT0, VIEW_DEPTH, ALL),
                            R(NORMALS_OUT, VIEW_NORMALS, ALL), W(SSAO_OUT, AO_PONG, V(CACAO_DENOISE_INTERMEDIATE)),
                            W(OUTPUT, OUTPUT, V(CACAO_DENOISE_FINAL))}},
    /* docs/tiles.md: classes from the deinterleaved depths (one invocation per tile), then the lists. */
    PASS(CLASSIFY) = {"classify", {NULL}, 1, false, false, false, {CACAO_WG_CLASSIFY, CACAO_WG_CLASSIFY},
                      CACAOI_GRID_TILES, 3,
                      {CONSTANTS, R(DEPTHS, DEPTHS, ALL), W(TILES, TILES, ALL)}},
    PASS(COMPACT) = {"compact", {NULL}, 1, false, false, false, {CACAO_WG_COMPACT, 1}, CACAOI_GRID_COMPACT, 2,
                     {CONSTANTS, W(TILES, TILES, ALL)}},
    /* AO 1 into the slices' AO of the tiles generate skips (and, a step rebinding SSAO_OUT, into
     * the blur's output there when a blur runs). */
    /* spec: prepare.md, normals from depth: PREPARE_DEPTHS's variants and the normals in one pass,
     * a 2x2 quad of slice texels per invocation sharing one block of depths. */
    PASS(PREPARE) = {"prepare", {"half", "full", "mips"}, 3, true, false, false, WG(PREPARE), CACAOI_GRID_SLICE, 5,
                     {CONSTANTS, R(SRC_DEPTH, DEPTH_INPUT, ALL),
                      W(DEPTHS_OUT0, DEPTHS, V(CACAO_DEPTHS_HALF) | V(CACAO_DEPTHS_FULL)),
                      W_LEVELS(DEPTHS_OUT0, DEPTHS, CACAO_DEPTH_MIP_COUNT, V(CACAO_DEPTHS_MIPS)),
                      W(NORMALS_OUT, NORMALS, ALL)},
                     .quad = {[CACAO_DEPTHS_HALF] = 2, [CACAO_DEPTHS_FULL] = 2, [CACAO_DEPTHS_MIPS] = 2}},
    PASS(FILL) = {"fill", {NULL}, 1, false, false, false, {CACAO_TILE, CACAO_TILE}, CACAOI_GRID_SLICE_LAYERS, 3,
                  {CONSTANTS, R(TILES, TILES, ALL), W(SSAO_OUT, SSAO_PING, ALL)},
                  .lists = {CACAO_LIST_FILL_SLICES}},
};
#undef R
#undef W
#undef W_LEVELS
#undef ALL
#undef V
#undef CONSTANTS
#undef PASS
#undef WG
#undef GEN

static bool binding_active(const cacaoi_pass_binding *b, unsigned variant) {
    return (b->variants >> variant) & 1u;
}

bool cacaoi_pass_expect(const cacao_key *key, cacaoi_module_expect *out) {
    if (!cacaoi_key_is_valid(key)) return false;
    memset(out, 0, sizeof *out);
    const cacaoi_pass_row *row = &cacaoi_passes[key->pass];
    for (unsigned i = 0; i < row->binding_count; ++i) {
        const cacaoi_pass_binding *b = &row->bindings[i];
        if (!binding_active(b, key->variant)) continue;
        out->descriptor[b->slot] = cacaoi_slots[b->slot].descriptor;
        out->resource[b->slot] = b->resource;
        out->write[b->slot] = b->write;
    }
    out->workgroup[0] = row->workgroup[0];
    out->workgroup[1] = row->workgroup[1];
    out->workgroup[2] = 1;
    return true;
}

size_t cacaoi_step_bindings(const cacaoi_step *step, cacaoi_pass_binding out[CACAOI_PASS_MAX_BINDINGS]) {
    const cacaoi_pass_row *row = &cacaoi_passes[step->key.pass];
    size_t n = 0;
    for (unsigned i = 0; i < row->binding_count; ++i) {
        const cacaoi_pass_binding *b = &row->bindings[i];
        if (!binding_active(b, step->key.variant)) continue;
        out[n] = *b;
        for (unsigned o = 0; o < step->override_count; ++o)
            if (step->override_slot[o] == b->slot) out[n].resource = step->override_resource[o];
        ++n;
    }
    return n;
}

/* ---- The sequence (spec: README "Pass graph"; estimators.md for the slice estimators) ---- */

static cacaoi_step *push(cacaoi_step *out, size_t *n, unsigned pass, unsigned variant, unsigned ds, unsigned blur,
                         unsigned fp16) {
    cacaoi_step *s = &out[(*n)++];
    memset(s, 0, sizeof *s);
    s->key = (cacao_key){(uint8_t)pass, (uint8_t)variant, (uint8_t)ds, (uint8_t)blur, (uint8_t)fp16};
    return s;
}

static void rebind(cacaoi_step *s, unsigned slot, cacao_resource resource) {
    s->override_slot[s->override_count] = (uint8_t)slot;
    s->override_resource[s->override_count++] = (uint8_t)resource;
}

/* Horizon-slice estimators: prepare, the estimator (into the output when no denoise pass runs),
 * then the denoise passes ping-ponging between AO_RAW and AO_PONG, the last into the output. */
static size_t slice_sequence(const cacao_key_config *c, cacaoi_step out[CACAOI_SEQUENCE_MAX]) {
    if (c->downsampled) return 0; /* full resolution only */
    size_t n = 0;
    const unsigned blur = c->blur_passes;
    push(out, &n, CACAO_PASS_SLICE_PREPARE, c->normals_from_input ? CACAO_SLICE_NORMALS_INPUT : CACAO_SLICE_NORMALS_DEPTH,
         0, 0, 0);
    const unsigned main_variant = (c->estimator == CACAO_KEY_ESTIMATOR_GTAO ? CACAO_SLICE_GTAO : CACAO_SLICE_BITMASK) +
                                  (blur == 0 ? CACAO_SLICE_GTAO_DIRECT : 0);
    push(out, &n, CACAO_PASS_SLICE_MAIN, main_variant, 0, 0, 0);
    cacao_resource ao = CACAO_RES_AO_RAW;
    for (unsigned pass = 1; pass <= blur; ++pass) {
        const bool last = pass == blur;
        cacaoi_step *s = push(out, &n, CACAO_PASS_SLICE_DENOISE, last ? CACAO_DENOISE_FINAL : CACAO_DENOISE_INTERMEDIATE,
                              0, 0, 0);
        const cacao_resource next = ao == CACAO_RES_AO_RAW ? CACAO_RES_AO_PONG : CACAO_RES_AO_RAW;
        rebind(s, CACAO_BINDING_DEPTHS_OUT1, ao);
        if (!last) rebind(s, CACAO_BINDING_SSAO_OUT, next);
        ao = next;
    }
    return n;
}

size_t cacaoi_sequence(const cacao_key_config *c, cacaoi_step out[CACAOI_SEQUENCE_MAX]) {
    if (c->estimator != CACAO_KEY_ESTIMATOR_CACAO) return slice_sequence(c, out);
    size_t n = 0;
    const unsigned ds = c->downsampled ? 1 : 0, fp = c->fp16 ? 1 : 0;
    const unsigned depths = cacaoi_depths_variant_for_quality(c->quality);
    if (c->normals_from_input) {
        push(out, &n, CACAO_PASS_PREPARE_DEPTHS, depths, ds, 0, 0);
        push(out, &n, CACAO_PASS_PREPARE_NORMALS, 0, ds, 0, 0);
    } else {
        push(out, &n, CACAO_PASS_PREPARE, depths, ds, 0, 0); /* depths and normals in one pass */
    }
    push(out, &n, CACAO_PASS_CLASSIFY, 0, 0, 0, 0);
    push(out, &n, CACAO_PASS_COMPACT, 0, 0, 0, 0);
    if (c->quality == CACAO_KEY_QUALITY_HIGHEST) {
        push(out, &n, CACAO_PASS_GENERATE, CACAO_GENERATE_Q3_BASE, 0, 0, 0);
        push(out, &n, CACAO_PASS_IMPORTANCE_A, 0, 0, 0, 0);
        push(out, &n, CACAO_PASS_IMPORTANCE_B, 0, 0, 0, 0);
    }
    push(out, &n, CACAO_PASS_GENERATE, cacaoi_generate_variant_for_quality(c->quality), 0, 0, 0);
    /* The tiles generate skips read as AO 1 in its output and, where a blur runs, in the blur's
     * (the blur and apply groups next to a needed tile read them). */
    push(out, &n, CACAO_PASS_FILL, 0, 0, 0, 0);
    if (c->blur_passes > 0) {
        cacaoi_step *f = push(out, &n, CACAO_PASS_FILL, 0, 0, 0, 0);
        rebind(f, CACAO_BINDING_SSAO_OUT, CACAO_RES_SSAO_PONG);
        push(out, &n, CACAO_PASS_BLUR, 0, 0, c->blur_passes, fp);
    }
    cacaoi_step *s = push(out, &n, c->downsampled ? CACAO_PASS_UPSAMPLE : CACAO_PASS_APPLY,
                          cacaoi_output_variant_for_quality(c->quality, c->downsampled), 0, 0, fp);
    if (c->blur_passes > 0) rebind(s, CACAO_BINDING_SSAO_IN, CACAO_RES_SSAO_PONG);
    return n;
}
