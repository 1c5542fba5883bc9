/* cacao_policy.c - quality levels, the sequence, keys per configuration, subsets (see cacao_policy.h). */
#include "cacao_policy.h"

#include <assert.h>
#include <string.h>

/* spec: README "Quality levels", constants.md (radius and near limit), estimators.md section 6
 * (budgets: 2 depth reads per step). */
const cacaoi_quality_row cacaoi_qualities[CACAO_KEY_QUALITY_COUNT] = {
    /*                          depths             generate            apply              upsample      slices radius near_limit  horizon {gtao, bitmask} */
    [CACAO_KEY_QUALITY_LOWEST] = {CACAO_DEPTHS_HALF, CACAO_GENERATE_Q0, CACAO_OUTPUT_HALF, CACAO_OUTPUT_HALF, 2,
                                  (float)CACAO_LOWEST_RADIUS_FACTOR, (float)CACAO_LOW_NEAR_LIMIT_FACTOR, {{1, 4}, {1, 4}}},
    [CACAO_KEY_QUALITY_LOW] = {CACAO_DEPTHS_FULL, CACAO_GENERATE_Q0, CACAO_OUTPUT_NON_SMART, CACAO_OUTPUT_NON_SMART, 4,
                               1.0f, (float)CACAO_LOW_NEAR_LIMIT_FACTOR, {{2, 4}, {1, 6}}},
    [CACAO_KEY_QUALITY_MEDIUM] = {CACAO_DEPTHS_FULL, CACAO_GENERATE_Q1, CACAO_OUTPUT_SMART, CACAO_OUTPUT_NON_SMART, 4,
                                  1.0f, 1.0f, {{2, 6}, {2, 8}}},
    [CACAO_KEY_QUALITY_HIGH] = {CACAO_DEPTHS_MIPS, CACAO_GENERATE_Q2, CACAO_OUTPUT_SMART, CACAO_OUTPUT_SMART, 4, 1.0f,
                                1.0f, {{3, 8}, {2, 12}}},
    [CACAO_KEY_QUALITY_HIGHEST] = {CACAO_DEPTHS_MIPS, CACAO_GENERATE_Q3, CACAO_OUTPUT_SMART, CACAO_OUTPUT_SMART, 4,
                                   1.0f, 1.0f, {{6, 8}, {2, 16}}},
};

unsigned cacaoi_form_pass(unsigned pass, bool gpu_forms) {
    if (!gpu_forms) return pass;
    switch (pass) {
    case CACAO_PASS_BLUR: return CACAO_PASS_BLUR_GPU;
    case CACAO_PASS_APPLY: return CACAO_PASS_APPLY_GPU;
    case CACAO_PASS_PREPARE: return CACAO_PASS_PREPARE_GPU;
    case CACAO_PASS_GENERATE: return CACAO_PASS_GENERATE_GPU;
    default: return pass;
    }
}


size_t cacaoi_step_bindings(const cacaoi_step *step, cacaoi_pass_binding out[CACAO_PLAN_MAX_BINDINGS]) {
    const size_t n = cacaoi_variant_bindings(step->key.pass, step->key.variant, step->key.downsampled, out);
    for (size_t i = 0; i < n && i < CACAO_PLAN_MAX_BINDINGS; ++i)
        for (unsigned o = 0; o < step->override_count; ++o)
            if (step->override_slot[o] == out[i].slot) out[i].resource = step->override_resource[o];
    return n;
}

/* ---- The sequence (spec: README "Pass graph"; estimators.md for the slice estimators) ---- */

static cacaoi_step *push(cacaoi_step *out, size_t *n, unsigned pass, unsigned variant, unsigned ds, unsigned blur,
                         unsigned fp16) {
    assert(*n < CACAOI_SEQUENCE_MAX); /* the assertions below bound every configuration the settings allow */
    cacaoi_step *s = &out[(*n)++];
    memset(s, 0, sizeof *s);
    s->key = (cacao_key){(uint8_t)pass, (uint8_t)variant, (uint8_t)ds, (uint8_t)blur, (uint8_t)fp16};
    return s;
}

static void rebind(cacaoi_step *s, unsigned slot, cacao_resource resource) {
    s->override_slot[s->override_count] = (uint8_t)slot;
    s->override_resource[s->override_count++] = (uint8_t)resource;
}

/* The longest sequences: CACAO with the caller's normals at HIGHEST with a blur (prepare twice,
 * classify, compact, the importance map's clear, Q3 base, importance twice, generate, fill,
 * blur, apply: 12, and 3 reuse steps before), and the horizon estimators with the most denoise
 * passes: native, classify, compact, the view's clear, the prepare twice (normals, view z), two AO
 * clears, the estimator and a pass per blur iteration; downsampled, the half-size AO's clear and the
 * upsample besides, and at most CACAO_HORIZON_HALF_MAX_PASSES (the settings refuse more;
 * key_dispatched leaves such configurations out); with reuse, 2 steps before (diff, reach). */
_Static_assert(16 <= CACAOI_SEQUENCE_MAX && 2 + 8 + CACAO_KEY_MAX_BLUR_PASSES <= CACAOI_SEQUENCE_MAX &&
                   2 + 9 + CACAO_HORIZON_HALF_MAX_PASSES <= CACAOI_SEQUENCE_MAX,
               "a plan holds every step of the longest sequence");
_Static_assert(CACAO_WG_HORIZON_X == CACAO_TILE && CACAO_WG_HORIZON_Y == CACAO_TILE,
               "a horizon estimator's group is one tile of the list it runs over");

/* The reuse diff of the configuration: of the depth, or of the depth and the input normals. */
static unsigned reuse_diff_variant(const cacao_key_config *c) {
    return c->normals_from_input ? (c->gpu_forms ? CACAO_REUSE_DIFF_NORMALS_GPU : CACAO_REUSE_DIFF_NORMALS)
                                 : (c->gpu_forms ? CACAO_REUSE_DIFF_GPU : CACAO_REUSE_DIFF);
}

/* Denoise passes first..last over the needed tiles (pass: the form's), the first reading `ao`,
 * ping-ponging between AO_RAW and AO_PONG, the last into the output (with temporal accumulation,
 * into the next intermediate too). Returns the intermediate the last pass wrote (`ao` when none
 * ran). */
static cacao_resource push_denoise_passes(cacaoi_step *out, size_t *n, unsigned pass_id, unsigned first,
                                          unsigned last, cacao_resource ao, bool temporal) {
    for (unsigned pass = first; pass <= last; ++pass) {
        const bool final = pass == last && !temporal;
        cacaoi_step *s = push(out, n, pass_id, final ? CACAO_DENOISE_FINAL : CACAO_DENOISE_INTERMEDIATE, 0, 0, 0);
        const cacao_resource next = ao == CACAO_RES_AO_RAW ? CACAO_RES_AO_PONG : CACAO_RES_AO_RAW;
        rebind(s, CACAO_BINDING_HORIZON_AO, ao);
        if (!final) rebind(s, CACAO_BINDING_HORIZON_AO_OUT, next);
        ao = next;
    }
    return ao;
}

/* Temporal accumulation last: the resolve reads the frame's AO from `ao` (the two history images
 * trade roles every frame at record time: record.c). */
static void push_temporal(cacaoi_step *out, size_t *n, cacao_resource ao) {
    rebind(push(out, n, CACAO_PASS_HORIZON_TEMPORAL, CACAO_TEMPORAL_RESOLVE, 0, 0, 0), CACAO_BINDING_HORIZON_AO, ao);
}

/* Horizon estimators, the CPU forms: classification from the caller's depth (docs/tiles.md),
 * prepare over the tiles that are not all background (a clear before it gives the others the view
 * z and normal the prepare would store there). Native: the intermediates the denoise passes read
 * cleared to AO 1, the estimator over the needed tiles (into the output when no denoise pass
 * runs), then the denoise passes over the needed tiles; compact stores the AO 1 of the output's
 * other tiles. Downsampled: the estimator at one pixel of each 2x2 block (a direct grid of half the
 * size, into AO_HALF), then the upsample over the needed tiles as the first filter pass (into the
 * output, or AO_PONG when denoise passes follow); the clears give the later passes' inputs their
 * 1 on the tiles they skip. The GPU forms: the same passes on direct grids, with no classify,
 * compact, clear or fill: the prepare stores every pixel and classifies, the estimator and the
 * denoise passes store AO 1 in the groups that are not needed (a GPU ran the clears in 40-90
 * microseconds, the four small dispatches in 30: docs/gpu.md). */
static size_t horizon_sequence(const cacao_key_config *c, cacaoi_step out[CACAOI_SEQUENCE_MAX]) {
    size_t n = 0;
    const bool half = c->downsampled, gpu = c->gpu_forms;
    /* reuse: the diff, and the reach pass that zeroes the gates when nothing changed; any change
     * recomputes the whole frame (reuse_all_or_nothing), so no prefix sums (docs/tiles.md) */
    if (c->reuse) {
        push(out, &n, CACAO_PASS_REUSE, reuse_diff_variant(c), 0, 0, 0);
        push(out, &n, CACAO_PASS_REUSE, CACAO_REUSE_REACH, 0, 0, 0);
    }
    const unsigned blur = half && c->blur_passes < 1 ? 1 : c->blur_passes; /* downsampled: the upsample always runs */
    const bool gtao = c->estimator == CACAO_KEY_ESTIMATOR_GTAO;
    const unsigned normals = c->normals_from_input ? CACAO_HORIZON_NORMALS_INPUT : CACAO_HORIZON_NORMALS_DEPTH;
    const unsigned denoise = gpu ? CACAO_PASS_HORIZON_DENOISE_GPU : CACAO_PASS_HORIZON_DENOISE;
    if (gpu) {
        push(out, &n, CACAO_PASS_HORIZON_PREPARE_GPU, normals, 0, 0, 0);
    } else {
        push(out, &n, CACAO_PASS_CLASSIFY, CACAO_CLASSIFY_HORIZON, 0, 0, 0);
        push(out, &n, CACAO_PASS_COMPACT, CACAO_COMPACT_HORIZON, 0, 0, 0);
        push(out, &n, CACAO_PASS_FILL, CACAO_FILL_VIEW, 0, 0, 0);
        /* the view z where no normal is read and the normals with theirs; normals from depth: the
         * view z first, the normals from it (docs/tiles.md) */
        const bool from_depth = normals == CACAO_HORIZON_NORMALS_DEPTH;
        if (from_depth) push(out, &n, CACAO_PASS_HORIZON_PREPARE, CACAO_HORIZON_VIEW_Z_ONLY, 0, 0, 0);
        push(out, &n, CACAO_PASS_HORIZON_PREPARE, normals, 0, 0, 0);
        if (!from_depth) push(out, &n, CACAO_PASS_HORIZON_PREPARE, CACAO_HORIZON_VIEW_Z_ONLY, 0, 0, 0);
        /* the AO intermediates the denoise passes read, cleared to AO 1 (AO_RAW, AO_PONG); with
         * temporal accumulation also the one the last pass writes (the resolve reads every pixel) */
        const bool t = c->temporal;
        const bool raw = half ? blur >= 3 || (t && blur >= 2) : blur >= 1 || t,
                   pong = blur >= 2 || (t && (half || blur >= 1));
        if (raw) push(out, &n, CACAO_PASS_FILL, CACAO_FILL_HORIZON, 0, 0, 0);
        if (pong) rebind(push(out, &n, CACAO_PASS_FILL, CACAO_FILL_HORIZON, 0, 0, 0), CACAO_BINDING_HORIZON_AO_OUT,
                         CACAO_RES_AO_PONG);
    }
    if (half) {
        /* the CPU form over compact's blocks holding an active tile; the clear gives the others
         * the AO 1 it would store there (docs/tiles.md) */
        if (!gpu)
            rebind(push(out, &n, CACAO_PASS_FILL, CACAO_FILL_HORIZON, 0, 0, 0), CACAO_BINDING_HORIZON_AO_OUT, CACAO_RES_AO_HALF);
        push(out, &n, gpu ? CACAO_PASS_HORIZON_MAIN_GPU : CACAO_PASS_HORIZON_MAIN,
             gtao ? CACAO_HORIZON_GTAO_HALF : CACAO_HORIZON_BITMASK_HALF, 0, 0, 0);
        push(out, &n, denoise, blur == 1 && !c->temporal ? CACAO_DENOISE_UPSAMPLE_FINAL : CACAO_DENOISE_UPSAMPLE, 0,
             0, 0);
        const cacao_resource ao = push_denoise_passes(out, &n, denoise, 2, blur, CACAO_RES_AO_PONG, c->temporal);
        if (c->temporal) push_temporal(out, &n, ao);
        return n;
    }
    push(out, &n, gpu ? CACAO_PASS_HORIZON_MAIN_GPU : CACAO_PASS_HORIZON_MAIN,
         (gtao ? CACAO_HORIZON_GTAO : CACAO_HORIZON_BITMASK) + (blur == 0 && !c->temporal ? CACAO_HORIZON_GTAO_DIRECT : 0),
         0, 0, 0);
    const cacao_resource ao = push_denoise_passes(out, &n, denoise, 1, blur, CACAO_RES_AO_RAW, c->temporal);
    if (c->temporal) push_temporal(out, &n, ao);
    return n;
}

bool cacaoi_prepare_classifies(const cacao_key_config *c) {
    return c->estimator == CACAO_KEY_ESTIMATOR_CACAO && c->gpu_forms && !c->normals_from_input;
}

/* The CPU forms (lists): the tiles generate skips are read as AO 1 in its output and, where a
 * blur runs, in the blur's (the blur and apply groups next to a needed tile read them). Compact
 * stores the 1s of generate's output, the tiles of its fill list; the blur's input gets them from
 * a fill over that list, pushed here after the last step before it that writes that image:
 * generate (it writes another: no barrier separates them), or at HIGHEST the Q3 base pass, whose
 * blocks hold only needed tiles (so the texels differ; the barrier after the base pass orders
 * both) and which the importance passes follow, with no barrier for the fill either. The fills
 * were two steps behind a barrier of their own, which on lavapipe costs 0.05-0.1 ms whether or not
 * work ran (docs/tiles.md "A quiet frame"). */
static void push_blur_fill(const cacao_key_config *c, cacaoi_step out[CACAOI_SEQUENCE_MAX], size_t *n) {
    if (!c->gpu_forms && c->blur_passes > 0)
        rebind(push(out, n, CACAO_PASS_FILL, CACAO_FILL_SLICES, 0, 0, 0), CACAO_BINDING_SSAO_IMAGE, CACAO_RES_SSAO_PONG);
}

size_t cacaoi_sequence(const cacao_key_config *c, cacaoi_step out[CACAOI_SEQUENCE_MAX]) {
    if (c->estimator != CACAO_KEY_ESTIMATOR_CACAO) return horizon_sequence(c, out);
    size_t n = 0;
    const unsigned ds = c->downsampled ? 1 : 0, fp = c->fp16 ? 1 : 0;
    const unsigned depths = cacaoi_qualities[c->quality].depths_variant;
    /* HIGHEST, the CPU forms: the importance map's clear to 0, which the Q3 base pass's skipped
     * blocks keep (below). First in the frame, it needs no barrier of its own: next to the base
     * pass, its barrier cost lavapipe 0.3 ms (interior_fzkhaus HIGHEST at 960x540 took 1.02-1.035x
     * the time of the build before, and 1.00x with the clear first). */
    if (c->quality == CACAO_KEY_QUALITY_HIGHEST && !c->gpu_forms) push(out, &n, CACAO_PASS_FILL, CACAO_FILL_IMPORTANCE, 0, 0, 0);
    /* The CPU forms without reuse: first whether the frame is quiet (no pixel of the depth can make
     * a texel that is not quiet; on such a frame that test stores the whole output's AO 1 and
     * nothing else runs); the direct steps after it run from gates that classify.quiet opens on
     * any other frame, the list steps from lists that no compact fills then (docs/tiles.md "A
     * quiet frame"). With reuse the gates are the reach pass's; the GPU forms classify in the
     * prepare (a pass and a barrier more would cost every frame a few microseconds there). */
    if (!c->gpu_forms && !c->reuse) push(out, &n, CACAO_PASS_CLASSIFY, CACAO_CLASSIFY_QUIET, 0, 0, 0);
    if (c->reuse) { /* docs/tiles.md "Reusing the previous frame" */
        push(out, &n, CACAO_PASS_REUSE, reuse_diff_variant(c), 0, 0, 0);
        push(out, &n, CACAO_PASS_REUSE, CACAO_REUSE_PREFIX, 0, 0, 0);
        push(out, &n, CACAO_PASS_REUSE, CACAO_REUSE_REACH, 0, 0, 0);
    }
    /* The caller's normals (docs/tiles.md "The normals where they are read"). Below HIGH generate
     * reads no normal but its texel's own: in the CPU forms its _input variants transform it
     * themselves, with no prepare_normals pass and no normals image, at LOWEST and LOW, and at
     * MEDIUM with reuse (where that pass would run over every texel). Otherwise prepare_normals
     * transforms them: in the CPU forms without reuse after compact, over the tiles whose normals
     * generate reads (at MEDIUM on lavapipe that list costs about what the transform in generate
     * costs); the GPU forms over every texel (ACO estimates the transform in generate at twice
     * the pass's cost a texel). */
    const unsigned q = cacaoi_qualities[c->quality].generate_variant;
    const bool generate_reads_input = c->normals_from_input && !c->gpu_forms &&
                                      (q == CACAO_GENERATE_Q0 || (q == CACAO_GENERATE_Q1 && c->reuse));
    const bool listed_normals = c->normals_from_input && !generate_reads_input && !c->gpu_forms && !c->reuse;
    /* The GPU forms where no prepare classifies (the caller's normals): the classes from the caller's
     * depth, first (no barrier between it and the prepare: they read the same depth and write
     * different resources) */
    if (c->gpu_forms && !cacaoi_prepare_classifies(c)) push(out, &n, CACAO_PASS_CLASSIFY_GPU, 0, ds, 0, 0);
    if (c->normals_from_input) {
        /* the GPU forms' generate samples a mip chain, the CPU forms' loads from the atlas */
        const unsigned chain = c->gpu_forms && depths == CACAO_DEPTHS_MIPS ? CACAO_DEPTHS_MIPS_CHAIN : depths;
        push(out, &n, CACAO_PASS_PREPARE_DEPTHS, chain, ds, 0, 0);
        if (!listed_normals && !generate_reads_input) push(out, &n, CACAO_PASS_PREPARE_NORMALS, 0, ds, 0, 0);
    } else {
        push(out, &n, cacaoi_form_pass(CACAO_PASS_PREPARE, c->gpu_forms), depths, ds, 0, 0); /* depths and normals in one pass */
    }
    if (!c->gpu_forms) push(out, &n, CACAO_PASS_CLASSIFY, CACAO_CLASSIFY_SLICES, 0, 0, 0);
    /* The CPU forms run generate and the blur over lists of the groups that need them (compact);
     * the GPU forms run every group and store the AO 1 of a group they skip themselves: no lists,
     * no fills (docs/tiles.md). */
    const bool lists = !c->gpu_forms;
    if (lists) push(out, &n, CACAO_PASS_COMPACT, 0, 0, 0, 0);
    if (listed_normals) push(out, &n, CACAO_PASS_PREPARE_NORMALS, CACAO_PREPARE_NORMALS_LISTED, ds, 0, 0);
    if (c->quality == CACAO_KEY_QUALITY_HIGHEST) {
        /* The base pass computes the tiles holding an active texel; the others' importance is 0:
         * the CPU form runs over compact's list of blocks (the map was cleared first), the GPU
         * form over every tile, storing the 0 itself (docs/tiles.md). */
        push(out, &n, cacaoi_form_pass(CACAO_PASS_GENERATE, c->gpu_forms), CACAO_GENERATE_Q3_BASE, 0, 0, 0);
        push_blur_fill(c, out, &n);
        push(out, &n, CACAO_PASS_IMPORTANCE_A, 0, 0, 0, 0);
        push(out, &n, CACAO_PASS_IMPORTANCE_B, 0, 0, 0, 0);
    }
    push(out, &n, cacaoi_form_pass(CACAO_PASS_GENERATE, c->gpu_forms),
         cacaoi_qualities[c->quality].generate_variant + (generate_reads_input ? CACAO_GENERATE_Q0_INPUT : 0), 0, 0, 0);
    if (c->quality != CACAO_KEY_QUALITY_HIGHEST) push_blur_fill(c, out, &n);
    if (c->blur_passes > 0) push(out, &n, cacaoi_form_pass(CACAO_PASS_BLUR, c->gpu_forms), 0, 0, c->blur_passes, fp);
    /* The CPU forms without reuse: the upsample (downsampled) or smart apply over the groups that
     * touch a needed tile, the output's other tiles given their 1 by compact (with reuse they run from a
     * gate, over every tile). The non-smart and half applies (LOWEST, LOW) are two steps: the direct
     * one over every group, then the listed one. Compact lists their groups, and closes the direct
     * one's gate, where at most CACAO_APPLY_LIST_ACTIVE_NUM/_DEN of the tiles are active: listed
     * everywhere, they cost a frame with nothing to skip more than they saved (docs/tiles.md). */
    const unsigned output = c->downsampled ? cacaoi_qualities[c->quality].output_downsampled
                                           : cacaoi_qualities[c->quality].output_native;
    const bool listed_output = lists && !c->reuse;
    const unsigned out_pass = cacaoi_form_pass(c->downsampled ? CACAO_PASS_UPSAMPLE : CACAO_PASS_APPLY, c->gpu_forms);
    if (listed_output && !c->downsampled && output != CACAO_OUTPUT_SMART) {
        cacaoi_step *direct = push(out, &n, out_pass, output, 0, 0, fp);
        if (c->blur_passes > 0) rebind(direct, CACAO_BINDING_SSAO, CACAO_RES_SSAO_PONG);
    }
    cacaoi_step *s = push(out, &n, out_pass,
                          !listed_output                    ? output
                          : c->downsampled                  ? output + CACAO_UPSAMPLE_LISTED
                          : output == CACAO_OUTPUT_SMART     ? CACAO_APPLY_SMART_LIST
                          : output == CACAO_OUTPUT_NON_SMART ? CACAO_APPLY_NONSMART_LIST
                                                             : CACAO_APPLY_HALF_LIST,
                          0, 0, fp);
    if (c->blur_passes > 0) rebind(s, CACAO_BINDING_SSAO, CACAO_RES_SSAO_PONG);
    return n;
}

/* The keys of the configuration's steps (cacaoi_sequence), each once, in first-dispatch order. */
size_t cacaoi_keys_for_config(const cacao_key_config *c, cacao_key out[CACAO_KEY_CONFIG_MAX]) {
    cacaoi_step steps[CACAOI_SEQUENCE_MAX];
    const size_t count = cacaoi_sequence(c, steps);
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        if (cacaoi_fill_is_clear(steps[i].key.pass, steps[i].key.variant)) continue; /* a clear: no module */
        size_t j = 0;
        while (j < n && cacaoi_key_compare(&out[j], &steps[i].key) != 0) ++j;
        if (j == n) out[n++] = steps[i].key;
    }
    return n;
}

/* Some configuration of the subset, with forms in forms_mask (bit 0 CPU, bit 1 GPU), dispatches key. */
static bool key_dispatched(const cacao_key *key, const cacao_key_subset *subset, unsigned forms_mask) {
    for (unsigned q = 0; q < CACAO_KEY_QUALITY_COUNT; ++q) {
        if (!(subset->quality_mask & (1u << q))) continue;
        for (unsigned ds = 0; ds < 2; ++ds) {
            if (!(subset->resolution_mask & (1u << ds))) continue;
            for (unsigned fp = 0; fp < 2; ++fp) {
                if (!(subset->precision_mask & (1u << fp))) continue;
                for (unsigned ni = 0; ni < 2; ++ni)
                    for (unsigned blur = 0; blur <= CACAO_KEY_MAX_BLUR_PASSES; ++blur)
                        for (unsigned est = 0; est < CACAO_KEY_ESTIMATOR_COUNT; ++est)
                            for (unsigned gpu = 0; gpu < 2; ++gpu)
                                for (unsigned reuse = 0; reuse < 4u; ++reuse) { /* bit 1: temporal */
                                    if (!(forms_mask & (1u << gpu))) continue;
                                    if (est != CACAO_KEY_ESTIMATOR_CACAO && ds && blur > CACAO_HORIZON_HALF_MAX_PASSES)
                                        continue; /* refused by the settings (cacao_settings_resolve) */
                                    if ((reuse & 2u) && ((reuse & 1u) || est == CACAO_KEY_ESTIMATOR_CACAO))
                                        continue; /* refused likewise */
                                    cacao_key_config c = {q,   ds != 0,      fp != 0,          ni != 0, blur,
                                                          est, gpu != 0, (reuse & 1u) != 0, (reuse & 2u) != 0};
                                    cacao_key keys[CACAO_KEY_CONFIG_MAX];
                                    size_t n = cacaoi_keys_for_config(&c, keys);
                                    for (size_t i = 0; i < n; ++i)
                                        if (cacaoi_key_compare(&keys[i], key) == 0) return true;
                                }
            }
        }
    }
    return false;
}

bool cacaoi_key_in_subset(const cacao_key *key, const cacao_key_subset *subset) {
    return key_dispatched(key, subset, 3u); /* both forms: the device decides */
}

bool cacaoi_key_in_forms(const cacao_key *key, bool gpu_forms) {
    const cacao_key_subset all = CACAO_KEY_SUBSET_ALL;
    return key_dispatched(key, &all, gpu_forms ? 2u : 1u);
}

/* Parses a ';' or ',' separated list of words into a bit mask using `words[0..count)`. */
static bool parse_mask(const char *list, const char *const *words, unsigned count, unsigned *mask) {
    unsigned m = 0;
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ";, ");
        if (len > 0) {
            unsigned i = 0;
            while (i < count && !(strlen(words[i]) == len && strncmp(words[i], p, len) == 0)) ++i;
            if (i == count) return false;
            m |= 1u << i;
        }
        p += len;
        if (*p) ++p;
    }
    if (m == 0) return false;
    *mask = m;
    return true;
}

bool cacaoi_key_subset_parse(const char *qualities, const char *downsample, const char *precision,
                            cacao_key_subset *subset) {
    cacao_key_subset s = CACAO_KEY_SUBSET_ALL;
    if (qualities && *qualities && strcmp(qualities, "all") != 0 &&
        !parse_mask(qualities, cacaoi_quality_names, CACAO_KEY_QUALITY_COUNT, &s.quality_mask))
        return false;
    if (downsample && *downsample) {
        if (strcmp(downsample, "OFF") == 0 || strcmp(downsample, "native") == 0) s.resolution_mask = 1;
        else if (strcmp(downsample, "ONLY") == 0) s.resolution_mask = 2;
        else if (strcmp(downsample, "downsampled") == 0) s.resolution_mask = 2;
        else if (strcmp(downsample, "ON") == 0 || strcmp(downsample, "all") == 0) s.resolution_mask = 3;
        else return false;
    }
    if (precision && *precision && strcmp(precision, "all") != 0 &&
        !parse_mask(precision, cacaoi_precision_names, 2, &s.precision_mask))
        return false;
    *subset = s;
    return true;
}
