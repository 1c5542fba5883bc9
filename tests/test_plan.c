/* test_plan - the pass plan is pure data that runs only the work the settings need: the step list
 * per quality matches the spec's pass graph (README "Pass graph"), dispatch sizes follow from the
 * sizes by hand, intermediates exist only when a step touches them, and barriers sit exactly
 * where a step reads or overwrites what an earlier step since the last barrier touched; with
 * reuse_unchanged, its passes come first and every later direct step runs from a gate. */
#include <string.h>

#include "cacao.h"
#include "cacao_shared.h"
#include "test_util.h"

static const cacao_plan_image *find_image(const cacao_plan *p, cacao_resource r) {
    for (uint32_t i = 0; i < p->image_count; ++i)
        if (p->images[i].resource == r) return &p->images[i];
    return NULL;
}

/* The steps CACAO's CPU forms without reuse begin with: classify.quiet (docs/tiles.md "A quiet
 * frame"). */
#define Q 1u

static cacao_plan build(cacao_settings s, uint32_t w, uint32_t h) {
    cacao_plan p;
    char err[256];
    CHECK(cacao_plan_build(&s, w, h, &p, err, sizeof err) == CACAO_SUCCESS);
    return p;
}

static uint32_t barrier_count(const cacao_plan *p) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->step_count; ++i) n += p->steps[i].barrier_before;
    return n;
}

static void test_steps_per_quality(void) {
    /* By hand from the spec's pass graph, with blur 2, native, normals from depth, and the tile
     * passes of docs/tiles.md: classify and compact (which fills generate's output where it
     * skips) after the depths, the fill of the blur's output beside generate (the CPU forms:
     * lists); at HIGHEST a clear of the importance map first, and the Q3 base pass over compact's
     * blocks. */
#define TILES "classify", "compact"
#define FILLS "fill"
    /* first the quiet frame's test and its fill (docs/tiles.md "A quiet frame") */
#define QUIET "classify.quiet"
    /* smart apply over compact's list of its groups at needed tiles (compact stores the other
     * tiles' output) */
#define OUT
    const char *expected[5][16] = {
        {QUIET, "prepare.half.native", TILES, "generate.q0", FILLS, "blur.2.fp32", "apply.half.fp32", "apply.half_list.fp32"},
        {QUIET, "prepare.full.native", TILES, "generate.q0", FILLS, "blur.2.fp32", "apply.nonsmart.fp32",
         "apply.nonsmart_list.fp32"},
        {QUIET, "prepare.full.native", TILES, "generate.q1", FILLS, "blur.2.fp32", OUT "apply.smart_list.fp32"},
        {QUIET, "prepare.mips.native", TILES, "generate.q2", FILLS, "blur.2.fp32", OUT "apply.smart_list.fp32"},
        {"clear.importance", QUIET, "prepare.mips.native", TILES, "generate.q3base", FILLS, "importance_a", "importance_b",
         "generate.q3", "blur.2.fp32", OUT "apply.smart_list.fp32"},
    };
#undef TILES
#undef FILLS
#undef QUIET
#undef OUT
    for (int q = 0; q < 5; ++q) {
        cacao_plan p = build((cacao_settings){.quality = (cacao_quality)(q + 1), .generate_normals = true}, 1920, 1080);
        uint32_t n = 0;
        while (n < 16 && expected[q][n]) ++n;
        CHECK(p.step_count == n);
        for (uint32_t i = 0; i < n && i < p.step_count; ++i) {
            if (strcmp(p.steps[i].key_name, expected[q][i]) != 0)
                fprintf(stderr, "quality %d step %u: %s, expected %s\n", q, i, p.steps[i].key_name, expected[q][i]);
            CHECK(strcmp(p.steps[i].key_name, expected[q][i]) == 0);
        }
        /* No barrier before the first step, between generate and the fill of the blur's output
         * (they write different images; at HIGHEST the fill follows the Q3 base pass, which
         * writes that image, and the first importance pass runs beside the fill), nor after the
         * clear of the importance map (classify.quiet does not touch it); every other step
         * depends on the one before. The clear is a transfer: it writes the map and dispatches
         * nothing; the barriers before the base pass order it (they are global). */
        CHECK(!p.steps[0].barrier_before);
        CHECK(p.steps[0].clear == (q == 4));
        for (uint32_t i = 1; i < p.step_count; ++i) {
            const bool clear = strcmp(p.steps[i].key_name, "clear.importance") == 0;
            CHECK(p.steps[i].clear == clear && (!clear || i == 0));
            const bool independent = (strcmp(p.steps[i].key_name, "fill") == 0 &&
                                      !strncmp(p.steps[i - 1].key_name, "generate.", 9) &&
                                      strcmp(p.steps[i - 1].key_name, "generate.q3base") != 0) ||
                                     (strcmp(p.steps[i].key_name, "importance_a") == 0 &&
                                      strcmp(p.steps[i - 1].key_name, "fill") == 0) ||
                                     p.steps[i - 1].clear;
            CHECK(p.steps[i].barrier_before == !independent);
            if (clear)
                CHECK(p.steps[i].binding_count == 1 && p.steps[i].bindings[0].resource == CACAO_RES_IMPORTANCE &&
                      p.steps[i].bindings[0].write && p.steps[i].dispatch[0] == 0);
            if (strcmp(p.steps[i].key_name, "generate.q3base") == 0)
                CHECK(p.steps[i].list == CACAO_LIST_BLOCKS && (p.steps[i].barrier_resources & (1u << CACAO_RES_TILES)));
        }
    }
}

static bool writes_tiles(const cacao_plan_step *st) {
    for (uint32_t j = 0; j < st->binding_count; ++j)
        if (st->bindings[j].resource == CACAO_RES_TILES && st->bindings[j].write) return true;
    return false;
}

/* The GPU forms (docs/tiles.md): the tile classes, then generate and the blur on direct grids that
 * skip by the flags the classification marks, in the shader; no compact, no lists, no fills (a
 * group that is not needed stores the 1 itself), at every quality and blur count. Native with
 * normals from depth, the prepare classifies (it writes the tile buffer) and no classify pass
 * runs: native the texels it stores, downsampled in groups of its own (the dispatch's z 0, the
 * prepare's groups z 1); with the caller's normals classify_gpu does, from the caller's depth,
 * first: no barrier separates it from the prepare after it (neither reads what the other writes),
 * and the prepare's barrier also serves its classes. */
static void test_gpu_forms_skip_in_shader(void) {
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (uint32_t blur = 0; blur <= 8; blur += 4)
            for (int form = 0; form < 3; ++form) { /* native, downsampled, the caller's normals */
                cacao_plan p = build((cacao_settings){.quality = (cacao_quality)q, .blur_pass_count = blur,
                                                      .downsample = form == 1, .generate_normals = form != 2,
                                                      .shader_forms = CACAO_SHADER_FORMS_GPU},
                                     1920, 1080);
                bool classified = false, classify_pass = false, generate = false;
                for (uint32_t i = 0; i < p.step_count; ++i) {
                    const cacao_plan_step *st = &p.steps[i];
                    CHECK(st->list == CACAO_LIST_NONE && !st->clear && strcmp(st->key_name, "compact") != 0 &&
                          strcmp(st->key_name, "fill") != 0);
                    const bool is_classify = strncmp(st->key_name, "classify_gpu.", 13) == 0;
                    CHECK(strncmp(st->key_name, "classify", 8) != 0 || is_classify); /* not the CPU forms' */
                    if (is_classify) { /* the first step, the prepare next without a barrier */
                        CHECK(i == 0 && i + 1 < p.step_count && strncmp(p.steps[i + 1].key_name, "prepare", 7) == 0 &&
                              !p.steps[i + 1].barrier_before);
                        CHECK(form == 2 && strcmp(st->key_name, "classify_gpu.native") == 0);
                        /* a group per 2x2 tiles */
                        CHECK(st->dispatch[0] == (p.tiles_x + 1) / 2 && st->dispatch[1] == (p.tiles_y + 1) / 2 &&
                              st->dispatch[2] == 1);
                    }
                    const bool prepare_classifies = strncmp(st->key_name, "prepare_gpu.", 12) == 0 && writes_tiles(st);
                    CHECK(!prepare_classifies || form != 2);
                    if (strncmp(st->key_name, "prepare_gpu.", 12) == 0)
                        CHECK(prepare_classifies && st->dispatch[2] == (form == 1 ? 2u : 1u));
                    classify_pass |= is_classify;
                    classified |= is_classify || prepare_classifies;
                    const bool skips = strncmp(st->key_name, "blur_gpu.", 9) == 0 ||
                                       (strncmp(st->key_name, "generate_gpu.", 13) == 0 &&
                                        strcmp(st->key_name, "generate_gpu.q3base") != 0);
                    if (skips) { /* after the classes; every group of the grid, reading their flags and
                                  * counting the needed groups into the header (written) */
                        CHECK(classified && st->dispatch[2] == p.slice_count && st->barrier_before);
                        CHECK(writes_tiles(st));
                    }
                    generate |= skips && st->key_name[0] == 'g';
                }
                CHECK(classified && generate && p.uses_tiles);
                CHECK(classify_pass == (form == 2));
            }
}

/* The horizon estimators' own images get the values of the tiles no pass computes from clears
 * (docs/tiles.md): view z and normals before their prepare, the AO intermediates the denoise passes
 * read before the estimator; the caller's output from compact, over the unneeded tiles. A clear is a
 * step with no dispatch that writes only the images it clears, and the step after it that uses
 * one waits for it. */
static void test_horizon_clears(void) {
    const char *expected[] = {"classify.horizon", "compact.horizon", "clear.view_depth", "horizon_prepare.z",
                              "horizon_prepare.depth", "clear.ao_raw", "clear.ao_pong", "horizon_main.gtao", "horizon_denoise.intermediate",
                              "horizon_denoise.final"};
    cacao_plan p = build((cacao_settings){.estimator = CACAO_ESTIMATOR_GTAO, .quality = CACAO_QUALITY_HIGH,
                                          .blur_pass_count = 2, .generate_normals = true},
                         640, 360);
    CHECK(p.step_count == sizeof expected / sizeof expected[0]);
    for (uint32_t i = 0; i < p.step_count && i < sizeof expected / sizeof expected[0]; ++i) {
        const cacao_plan_step *st = &p.steps[i];
        CHECK(strcmp(st->key_name, expected[i]) == 0);
        CHECK(st->clear == (strncmp(expected[i], "clear.", 6) == 0));
        if (!st->clear) continue;
        CHECK(st->dispatch[0] == 0 && st->list == CACAO_LIST_NONE && st->binding_count >= 1);
        for (uint32_t j = 0; j < st->binding_count; ++j) CHECK(st->bindings[j].write);
    }
    /* view z and normals in one clear; the prepare, then the estimator, wait for the clears */
    CHECK(p.steps[2].binding_count == 2 && p.steps[2].bindings[0].resource == CACAO_RES_VIEW_DEPTH &&
          p.steps[2].bindings[1].resource == CACAO_RES_VIEW_NORMALS);
    CHECK(p.steps[3].barrier_before && (p.steps[3].barrier_resources & (1u << CACAO_RES_VIEW_DEPTH)));
    /* the prepare over compact's two lists (docs/tiles.md). Normals from depth: the view z of
     * every tile not all background first, writing only view z; then the normals of the tiles
     * within two of an active one from it (reading view z, writing only the normals) */
    CHECK(p.steps[3].list == CACAO_LIST_PREPARE && p.steps[4].list == CACAO_LIST_NORMALS);
    CHECK(p.steps[4].barrier_before && (p.steps[4].barrier_resources & (1u << CACAO_RES_VIEW_DEPTH)));
    for (uint32_t j = 0; j < p.steps[3].binding_count; ++j)
        CHECK(!p.steps[3].bindings[j].write || p.steps[3].bindings[j].resource == CACAO_RES_VIEW_DEPTH);
    for (uint32_t j = 0; j < p.steps[4].binding_count; ++j)
        CHECK(p.steps[4].bindings[j].write == (p.steps[4].bindings[j].resource == CACAO_RES_VIEW_NORMALS));
    /* the caller's normals: their prepare stores the view z with them, then the view z alone over
     * the other tiles not all background */
    cacao_plan g = build((cacao_settings){.estimator = CACAO_ESTIMATOR_GTAO, .quality = CACAO_QUALITY_HIGH,
                                          .blur_pass_count = 2},
                         640, 360);
    CHECK(strcmp(g.steps[3].key_name, "horizon_prepare.input") == 0 && g.steps[3].list == CACAO_LIST_NORMALS);
    CHECK(strcmp(g.steps[4].key_name, "horizon_prepare.z") == 0 && g.steps[4].list == CACAO_LIST_PREPARE);
    CHECK(p.steps[7].barrier_before && (p.steps[7].barrier_resources & (1u << CACAO_RES_AO_RAW)));
    CHECK(!p.steps[5].barrier_before && !p.steps[6].barrier_before); /* images nothing touched yet */
}

static void test_only_needed_resources(void) {
    cacao_plan low = build(
        (cacao_settings){.quality = CACAO_QUALITY_LOW, .blur_pass_count = CACAO_BLUR_NONE, .generate_normals = true},
        1920, 1080);
    CHECK(find_image(&low, CACAO_RES_SSAO_PONG) == NULL);  /* no blur, no Q3 base: no second AO buffer */
    CHECK(find_image(&low, CACAO_RES_IMPORTANCE) == NULL); /* importance only at HIGHEST */
    CHECK(!low.uses_load_counter);
    CHECK(find_image(&low, CACAO_RES_DEPTHS)->mips == 1); /* LOW reads no mips */
    CHECK(low.steps[Q].dispatch[0] == 60 && low.steps[Q].dispatch[1] == 34); /* prepare.full: 2x2 texels each */
    /* (the quiet steps) prepare, classify, compact, generate, apply twice: no blur, no fill step
     * (compact fills generate's output) */
    CHECK(low.step_count == Q + 6);
    /* apply.nonsmart: a 2x2 quad of output pixels per invocation, one per slice texel: ceil(960/8), ceil(540/8);
     * from a gate (compact closes it where it lists the groups), then over compact's list of the
     * tiles (docs/tiles.md "Apply over a list where the frame skips much") */
    CHECK(strcmp(low.steps[Q + 4].key_name, "apply.nonsmart.fp32") == 0 && low.steps[Q + 4].list == CACAO_LIST_NONE);
    CHECK(low.steps[Q + 4].dispatch[0] == 120 && low.steps[Q + 4].dispatch[1] == 68 && low.steps[Q + 4].gate != 0);
    CHECK(strcmp(low.steps[Q + 5].key_name, "apply.nonsmart_list.fp32") == 0 && low.steps[Q + 5].list == CACAO_LIST_PREPARE);
    CHECK(low.steps[Q + 5].barrier_before); /* both write the output */
    cacao_plan given_low = build((cacao_settings){.quality = CACAO_QUALITY_LOW, .blur_pass_count = CACAO_BLUR_NONE}, 1920, 1080);
    /* normals given, below HIGH: prepare_depths, and generate transforms the caller's normal of its
     * texel itself (the only normal Q0 and Q1 read): no prepare_normals, no normals image */
    CHECK(given_low.step_count == Q + 6);
    CHECK(strcmp(given_low.steps[Q].key_name, "prepare_depths.full.native") == 0);
    CHECK(given_low.steps[Q].dispatch[0] == 120 && given_low.steps[Q].dispatch[1] == 68); /* a texel each */
    CHECK(strcmp(given_low.steps[Q + 3].key_name, "generate.q0_input") == 0);
    CHECK(find_image(&given_low, CACAO_RES_NORMALS) == NULL);
    for (uint32_t i = 0; i < given_low.step_count; ++i) CHECK(strncmp(given_low.steps[i].key_name, "prepare_normals", 15) != 0);
    /* MEDIUM (Q1 reads its texel's normal alone too): the same with reuse (prepare_normals would run
     * over every texel); without reuse the CPU forms transform them after compact, over its list,
     * as from HIGH up (normal edges, the Q3 base pass); the GPU forms' prepare_normals runs over
     * every texel at every quality (docs/tiles.md) */
    for (int gpu = 0; gpu < 2; ++gpu)
        for (int reuse = 0; reuse < 2; ++reuse)
            for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_MEDIUM; ++q) {
                cacao_plan given = build((cacao_settings){.quality = (cacao_quality)q, .downsample = true,
                                                          .reuse_unchanged = reuse,
                                                          .shader_forms = gpu ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU},
                                         1920, 1080);
                const bool reads_input = !gpu && (q != CACAO_QUALITY_MEDIUM || reuse);
                CHECK((find_image(&given, CACAO_RES_NORMALS) == NULL) == reads_input);
                int input = 0, prepare_normals = 0;
                for (uint32_t i = 0; i < given.step_count; ++i) {
                    prepare_normals += strncmp(given.steps[i].key_name, "prepare_normals", 15) == 0;
                    input += strstr(given.steps[i].key_name, "_input") != NULL;
                }
                CHECK(input == reads_input && prepare_normals == !reads_input);
            }
    cacao_plan given_medium = build((cacao_settings){.quality = CACAO_QUALITY_MEDIUM}, 1920, 1080);
    CHECK(strcmp(given_medium.steps[Q + 3].key_name, "prepare_normals.list.native") == 0 &&
          given_medium.steps[Q + 3].list == CACAO_LIST_NORMALS && strcmp(given_medium.steps[Q + 2].key_name, "compact") == 0);
    /* generate after it; the fill of the blur's output beside generate (no barrier of its own),
     * with or without the listed normals: a barrier more for the normals' step */
    CHECK(strcmp(given_medium.steps[Q + 4].key_name, "generate.q1") == 0 && given_medium.steps[Q + 4].barrier_before);
    CHECK(strcmp(given_medium.steps[Q + 5].key_name, "fill") == 0 && !given_medium.steps[Q + 5].barrier_before);
    cacao_plan from_depth_medium = build((cacao_settings){.quality = CACAO_QUALITY_MEDIUM, .generate_normals = true}, 1920, 1080);
    CHECK(strcmp(from_depth_medium.steps[Q + 3].key_name, "generate.q1") == 0 &&
          strcmp(from_depth_medium.steps[Q + 4].key_name, "fill") == 0 && !from_depth_medium.steps[Q + 4].barrier_before);
    CHECK(barrier_count(&given_medium) == barrier_count(&from_depth_medium) + 1);
    cacao_plan given_high = build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .reuse_unchanged = true}, 1920, 1080);
    CHECK(find_image(&given_high, CACAO_RES_NORMALS) != NULL);
    cacao_plan odd = build((cacao_settings){.quality = CACAO_QUALITY_LOWEST, .generate_normals = true}, 1001, 37);
    CHECK(strcmp(odd.steps[odd.step_count - 2].key_name, "apply.half.fp32") == 0);
    CHECK(strcmp(odd.steps[odd.step_count - 1].key_name, "apply.half_list.fp32") == 0);
    /* odd sizes: still one quad per slice texel (501x19): ceil(501/8), ceil(19/8) */
    CHECK(odd.steps[odd.step_count - 2].dispatch[0] == 63 && odd.steps[odd.step_count - 2].dispatch[1] == 3);
    /* with reuse, or the GPU forms, one apply over every group */
    for (int gpu = 0; gpu < 2; ++gpu) {
        cacao_plan one = build((cacao_settings){.quality = CACAO_QUALITY_LOWEST, .generate_normals = true, .reuse_unchanged = !gpu,
                                                .shader_forms = gpu ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU},
                               1001, 37);
        int applies = 0;
        for (uint32_t i = 0; i < one.step_count; ++i) applies += strncmp(one.steps[i].key_name, "apply", 5) == 0;
        CHECK(applies == 1 && one.steps[one.step_count - 1].list == CACAO_LIST_NONE);
    }
    cacao_plan medium = build((cacao_settings){.quality = CACAO_QUALITY_MEDIUM, .generate_normals = true}, 1920, 1080);
    CHECK(find_image(&medium, CACAO_RES_DEPTHS)->mips == 1); /* MEDIUM never reads mips: none built */
    cacao_plan lowest = build((cacao_settings){.quality = CACAO_QUALITY_LOWEST, .generate_normals = true}, 1920, 1080);
    CHECK(lowest.slice_count == 2 && find_image(&lowest, CACAO_RES_DEPTHS)->layers == 2);
    CHECK(strcmp(lowest.steps[Q + 3].key_name, "generate.q0") == 0 && lowest.steps[Q + 3].dispatch[2] == 2); /* two slices */
    CHECK(lowest.steps[Q + 3].list == CACAO_LIST_GENERATE); /* indirect, over the needed tiles */
    /* 1920x1080: slices 960x540, tiles of 8x8 texels 120x68; a blur group of 2 passes outputs
     * 64x32 texels (8x8 threads of 8x4 each, from their footprints). */
    CHECK(lowest.tiles_x == 120 && lowest.tiles_y == 68 && lowest.blur_groups_x == 15 && lowest.blur_groups_y == 17);
    /* header, classes, six lists of a tile each (generate, fill, the horizon estimators' prepare
     * list, the blur list, the blocks, the normals), then a needed flag per tile and per blur group; reuse's
     * four words per tile (changed, least z, row sum, recompute) and a recompute flag per blur
     * group; 18 gate commands and each one's grid x */
    CHECK(lowest.tile_buffer_bytes == 4u * (32u + 12u * 120u * 68u + 2u * 15u * 17u + 3u * 18u + 18u));
    cacao_plan highest =
        build((cacao_settings){.quality = CACAO_QUALITY_HIGHEST, .generate_normals = true}, 1920, 1080);
    const cacao_plan_image *depths = find_image(&highest, CACAO_RES_DEPTHS);
    /* The atlas: 960x540 with 480x270, 240x135 and 120x67 stacked to its right (270 + 135 + 67 =
     * 472 rows, fewer than 540): 1440x540 texels, 4 layers, 2 bytes. */
    CHECK(depths->mips == 4 && depths->layers == 4 && depths->width == 1440 && depths->height == 540);
    CHECK(depths->bytes == (uint64_t)1440 * 540 * 4 * 2);
    CHECK(find_image(&highest, CACAO_RES_IMPORTANCE)->width == 480);
    CHECK(highest.uses_load_counter);
    uint64_t sum = 0;
    for (uint32_t i = 0; i < highest.image_count; ++i) sum += highest.images[i].bytes;
    /* + constants, counter, tile buffer */
    CHECK(highest.total_bytes == sum + sizeof(cacao_constants) + sizeof(uint32_t) + highest.tile_buffer_bytes);
    CHECK(highest.total_bytes > low.total_bytes);
}

static void test_dispatch_sizes(void) {
    /* 1920x1080 native: S = 960x540, I = 480x270. Downsampled: S = 480x270. Odd 1001x37. */
    cacao_plan p = build((cacao_settings){.quality = CACAO_QUALITY_HIGHEST, .generate_normals = true}, 1920, 1080);
    /* prepare.mips (depths and normals from depth): 2x2 texels per invocation, ceil(960/16),
     * ceil(540/16) */
    CHECK(strcmp(p.steps[0].key_name, "clear.importance") == 0 && p.steps[0].clear); /* first: no dispatch */
    CHECK(strcmp(p.steps[Q + 1].key_name, "prepare.mips.native") == 0);
    CHECK(p.steps[Q + 1].dispatch[0] == 60 && p.steps[Q + 1].dispatch[1] == 34);
    cacao_plan given = build((cacao_settings){.quality = CACAO_QUALITY_HIGHEST}, 1920, 1080);
    CHECK(strcmp(given.steps[Q + 1].key_name, "prepare_depths.mips.native") == 0);
    CHECK(given.steps[Q + 1].dispatch[0] == 60 && given.steps[Q + 1].dispatch[1] == 34); /* mips: 2x2 texels each */
    CHECK(strcmp(given.steps[Q + 4].key_name, "prepare_normals.list.native") == 0); /* after classify and compact */
    CHECK(given.steps[Q + 4].dispatch[0] == 120 && given.steps[Q + 4].dispatch[1] == 68); /* the caller's: one each, a group a tile */
    CHECK(given.step_count == p.step_count + 1);
    CHECK(p.steps[Q + 2].dispatch[0] == 15 && p.steps[Q + 2].dispatch[1] == 9);     /* classify: 120x68 tiles / 8x8 */
    CHECK(p.steps[Q + 3].dispatch[0] == (120 * 68 + 15 * 17 + 63) / 64);         /* compact: tiles + blur groups */
    /* the Q3 base pass (the map cleared first): an invocation per importance texel (its 2x2
     * slice texels in all 4 layers), at most ceil(480/8), ceil(270/8) groups (a group is a block of
     * 2x2 tiles), one z; the importance passes the same grid */
    CHECK(strcmp(p.steps[Q + 4].key_name, "generate.q3base") == 0);
    CHECK(p.steps[Q + 4].dispatch[0] == 60 && p.steps[Q + 4].dispatch[1] == 34 && p.steps[Q + 4].dispatch[2] == 1);
    CHECK(p.steps[Q + 6].dispatch[0] == 60 && p.steps[Q + 6].dispatch[1] == 34);    /* importance_a */
    CHECK(p.steps[Q + 8].dispatch[2] == 4);                                     /* generate.q3: 4 slices */
    CHECK(p.steps[Q + 9].dispatch[0] == 15 && p.steps[Q + 9].dispatch[1] == 17);  /* blur, N = 2: ceil(960/64), ceil(540/32) */
    /* past CACAO_BLUR_REGISTER_PASSES a group computes its 64x32 padded tile less N each side */
    cacao_plan b8 = build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .blur_pass_count = 8, .generate_normals = true},
                          1920, 1080);
    CHECK(strcmp(b8.steps[b8.step_count - 2].key_name, "blur.8.fp32") == 0); /* then apply */
    CHECK(b8.blur_groups_x == 20 && b8.blur_groups_y == 34); /* ceil(960/48), ceil(540/16) */
    CHECK(p.steps[Q + 10].dispatch[0] == 60 && p.steps[Q + 10].dispatch[1] == 34); /* smart apply: 4x4 per invocation */
    /* the list's indirect command takes its z from these: generate and the blur cover the four
     * layers with z, a fill group loops over them, a base pass group covers its block's layers */
    CHECK(p.steps[Q + 5].dispatch[2] == 1 && p.steps[Q + 9].dispatch[2] == 4);
    CHECK(p.steps[Q + 8].list == CACAO_LIST_GENERATE && p.steps[Q + 5].list == CACAO_LIST_FILL_SLICES &&
          p.steps[Q + 9].list == CACAO_LIST_BLUR && p.steps[Q + 10].list == CACAO_LIST_PREPARE &&
          p.step_count == Q + 11 &&
          p.steps[Q + 4].list == CACAO_LIST_BLOCKS && p.steps[Q + 6].list == CACAO_LIST_NONE);
    cacao_plan d =
        build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true, .generate_normals = true}, 1001, 37);
    CHECK(d.slice_width == 251 && d.slice_height == 10); /* ceil(ceil(1001/2)/2), ceil(ceil(37/2)/2) */
    /* the CPU forms without reuse: the upsample over compact's list of the needed tiles (compact
     * stores the output of the others), after the blur */
    CHECK(strcmp(d.steps[d.step_count - 1].key_name, "upsample.smart_list.fp32") == 0);
    CHECK(d.steps[d.step_count - 1].list == CACAO_LIST_PREPARE && d.steps[d.step_count - 1].dispatch[2] == 1);
    CHECK(d.steps[d.step_count - 2].key[0] == CACAO_PASS_BLUR && d.steps[d.step_count - 2].list == CACAO_LIST_BLUR);
    /* upsample: 2x2 full-res pixels per half-res position, 2x2 positions per thread, 8x8 threads:
     * a group is a tile (8x8 slice texels) */
    CHECK(d.steps[d.step_count - 1].dispatch[0] == 32 && d.steps[d.step_count - 1].dispatch[1] == 2); /* /32 */
    CHECK(d.tiles_x == 32 && d.tiles_y == 2);
    /* with reuse (the gates need a direct grid) and in the GPU forms (no lists): every tile */
    cacao_plan dr = build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true, .generate_normals = true,
                                           .reuse_unchanged = true},
                          1001, 37);
    CHECK(strcmp(dr.steps[dr.step_count - 1].key_name, "upsample.smart.fp32") == 0 && dr.steps[dr.step_count - 1].gate);
    cacao_plan dg = build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true, .generate_normals = true,
                                           .shader_forms = CACAO_SHADER_FORMS_GPU},
                          1001, 37);
    CHECK(strcmp(dg.steps[dg.step_count - 1].key_name, "upsample.smart.fp32") == 0 &&
          dg.steps[dg.step_count - 1].list == CACAO_LIST_NONE);
}

/* The host writes each list's indirect command z from the steps that dispatch over it (record.c):
 * the steps sharing a list agree on it, in every configuration. */
static void test_lists_agree_on_layers(void) {
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (int e = CACAO_ESTIMATOR_CACAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
            for (int ds = 0; ds < 2; ++ds)
                for (uint32_t blur = 0; blur <= 6; ++blur) {
                    cacao_plan p = build((cacao_settings){.quality = (cacao_quality)q, .estimator = (cacao_estimator)e,
                                                          .downsample = ds != 0, .blur_pass_count = blur,
                                                          .generate_normals = true},
                                         640, 360);
                    uint32_t z[CACAO_LIST_COUNT + 1] = {0};
                    for (uint32_t i = 0; i < p.step_count; ++i) {
                        const cacao_plan_step *st = &p.steps[i];
                        if (!st->list) continue;
                        CHECK(z[st->list] == 0 || z[st->list] == st->dispatch[2]);
                        z[st->list] = st->dispatch[2];
                    }
                }
}

/* Small sizes: the depth mip chain is the one a mip-mapped image of the slice's size would have
 * (floor(log2(max side)) + 1 levels, at most 4), laid out as an atlas: the slice, then levels 1..
 * stacked to its right, each max(1, side >> level), by hand below. */
static void test_small_mip_chain(void) {
    static const struct {
        uint32_t w, h, slice_w, slice_h, mips, atlas_w, atlas_h;
    } cases[] = {
        {1, 1, 1, 1, 1, 1, 1},          /* one level: the slice alone */
        {3, 1, 2, 1, 2, 3, 1},          /* 2x1 + 1x1 */
        {1, 9, 1, 5, 3, 2, 5},          /* 1x5 + 1x2, 1x1 (3 rows) */
        {14, 5, 7, 3, 3, 10, 3},        /* 7x3 + 3x1, 1x1 */
        {15, 2, 8, 1, 4, 12, 3},        /* 8x1 + 4x1, 2x1, 1x1: the chain is taller than the slice */
        {64, 64, 32, 32, 4, 48, 32}};   /* 32x32 + 16x16, 8x8, 4x4 (28 rows) */
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        cacao_plan p =
            build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .generate_normals = true}, cases[c].w, cases[c].h);
        CHECK(p.slice_width == cases[c].slice_w && p.slice_height == cases[c].slice_h);
        const cacao_plan_image *depths = find_image(&p, CACAO_RES_DEPTHS);
        CHECK(depths && depths->mips == cases[c].mips);
        CHECK(depths->width == cases[c].atlas_w && depths->height == cases[c].atlas_h);
        CHECK(depths->bytes == (uint64_t)cases[c].atlas_w * cases[c].atlas_h * 4 * 2);
        /* prepare.mips: constants, source depth, the atlas, the normals */
        const cacao_plan_binding *b = &p.steps[Q].bindings[2];
        CHECK(p.steps[Q].binding_count == 4 && b->binding == CACAO_BINDING_DEPTHS_IMAGE && b->write &&
              b->resource == CACAO_RES_DEPTHS);
        CHECK(p.steps[Q].bindings[3].binding == CACAO_BINDING_NORMALS_IMAGE && p.steps[Q].bindings[3].write);
        CHECK(depths->image_levels == 1); /* the CPU forms: one Vulkan level */
        /* The GPU forms: the same levels as the image's mip levels, level 0 the slice; bytes the
         * sum of the levels, each max(1, side >> level); prepare_gpu.mips binds levels 1..3 each
         * through its own slot, the depths (level 0) through the storage slot. */
        cacao_plan g = build((cacao_settings){.quality = CACAO_QUALITY_HIGH, .generate_normals = true,
                                              .shader_forms = CACAO_SHADER_FORMS_GPU},
                             cases[c].w, cases[c].h);
        const cacao_plan_image *chain = find_image(&g, CACAO_RES_DEPTHS);
        CHECK(chain && chain->mips == cases[c].mips && chain->image_levels == cases[c].mips);
        CHECK(chain->width == cases[c].slice_w && chain->height == cases[c].slice_h);
        uint64_t texels = 0;
        for (uint32_t l = 0; l < cases[c].mips; ++l) {
            const uint32_t lw = cases[c].slice_w >> l, lh = cases[c].slice_h >> l;
            texels += (uint64_t)(lw ? lw : 1) * (lh ? lh : 1);
        }
        CHECK(chain->bytes == texels * 4 * 2);
        const cacao_plan_step *prep = NULL;
        for (uint32_t i = 0; i < g.step_count; ++i)
            if (!strcmp(g.steps[i].key_name, "prepare_gpu.mips.native")) prep = &g.steps[i];
        CHECK(prep != NULL);
        if (prep) {
            unsigned levels = 0, level0 = 0;
            for (uint32_t i = 0; i < prep->binding_count; ++i) {
                const cacao_plan_binding *pb = &prep->bindings[i];
                if (pb->binding >= CACAO_BINDING_DEPTHS_MIP1 && pb->binding <= CACAO_BINDING_DEPTHS_MIP3)
                    levels += pb->resource == CACAO_RES_DEPTHS && pb->write;
                level0 += pb->binding == CACAO_BINDING_DEPTHS_IMAGE && pb->write;
            }
            CHECK(levels == 3 && level0 == 1);
        }
    }
    /* with the caller's normals the GPU forms' depth prepare writes the chain too */
    cacao_plan given = build((cacao_settings){.quality = CACAO_QUALITY_HIGHEST, .shader_forms = CACAO_SHADER_FORMS_GPU},
                             1920, 1080);
    bool chain_prepare = false;
    for (uint32_t i = 0; i < given.step_count; ++i)
        chain_prepare |= !strcmp(given.steps[i].key_name, "prepare_depths.mips_chain.native");
    CHECK(chain_prepare);
    const cacao_plan_image *d = find_image(&given, CACAO_RES_DEPTHS);
    CHECK(d->width == 960 && d->height == 540 && d->image_levels == 4 &&
          d->bytes == (uint64_t)(960 * 540 + 480 * 270 + 240 * 135 + 120 * 67) * 4 * 2);
}

static void test_invalid(void) {
    cacao_plan p;
    char err[256];
    CHECK(cacao_plan_build(&(cacao_settings){0}, 0, 64, &p, err, sizeof err) == CACAO_ERROR_INVALID_SIZE);
    CHECK(cacao_plan_build(&(cacao_settings){0}, 64, 65536, &p, err, sizeof err) == CACAO_ERROR_INVALID_SIZE);
    CHECK(cacao_plan_build(&(cacao_settings){.radius = -1}, 64, 64, &p, err, sizeof err) ==
          CACAO_ERROR_INVALID_ARGUMENT);
    CHECK(cacao_plan_build(&(cacao_settings){0}, 64, 64, NULL, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT);
}

/* reuse_unchanged (docs/tiles.md "Reusing the previous frame"): the diff (with input normals, the
 * variant that also compares them; the GPU forms' own diff), prefix and reach run first, ungated;
 * every later direct step runs from a gate, numbered in step order so that apply's, the last, is
 * the last gate; the list-dispatched steps have none; the copies of the inputs are intermediates
 * (depth: a texel per 2x2 pixels; normals: three texels per 2x2 pixels) and nothing else is added;
 * the first gated step has a barrier before it (it reads the commands the reach pass wrote); the
 * horizon estimators' plans (below). */
static void test_reuse(void) {
    for (int gpu = 0; gpu < 2; ++gpu)
        for (int normals = 0; normals < 2; ++normals) {
            const cacao_settings s = {.quality = CACAO_QUALITY_HIGH, .generate_normals = !normals, .reuse_unchanged = true,
                                      .shader_forms = gpu ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU};
            cacao_plan p = build(s, 1920, 1080);
            cacao_settings plain_settings = s;
            plain_settings.reuse_unchanged = false;
            cacao_plan plain = build(plain_settings, 1920, 1080);
            /* The steps after the reuse passes are those of the plan without reuse, but for what
             * the CPU forms without reuse do otherwise: the quiet frame's test first, the caller's
             * normals transformed over a list after compact, apply over a list (compact stores the
             * output's other tiles) (docs/tiles.md). That plan, undone: */
            const char *same[CACAO_PLAN_MAX_STEPS];
            uint32_t m = 0;
            const bool listed_normals = !gpu && normals;
            CHECK(!listed_normals || strcmp(plain.steps[Q + 3].key_name, "prepare_normals.list.native") == 0);
            for (uint32_t i = 0; i < plain.step_count; ++i) {
                const char *name = plain.steps[i].key_name;
                if (!strcmp(name, "classify.quiet") || !strcmp(name, "prepare_normals.list.native"))
                    continue;
                same[m++] = !strcmp(name, "apply.smart_list.fp32") ? "apply.smart.fp32" : name;
                if (listed_normals && !strcmp(name, "prepare_depths.mips.native")) same[m++] = "prepare_normals.native";
            }
            CHECK(p.step_count == m + 3);
            const char *diff = gpu ? (normals ? "reuse.diff_normals_gpu" : "reuse.diff_gpu")
                                   : (normals ? "reuse.diff_normals" : "reuse.diff");
            CHECK(strcmp(p.steps[0].key_name, diff) == 0);
            CHECK(strcmp(p.steps[1].key_name, "reuse.prefix") == 0 && p.steps[1].dispatch[0] == 2); /* 68 rows / 64 */
            CHECK(strcmp(p.steps[2].key_name, "reuse.reach") == 0);
            uint32_t gate = 0;
            for (uint32_t i = 0; i < p.step_count; ++i) {
                const cacao_plan_step *st = &p.steps[i];
                if (i < 3) {
                    CHECK(st->gate == 0);
                    continue;
                }
                CHECK(i - 3 < m && strcmp(st->key_name, same[i - 3]) == 0);
                if (st->list) {
                    CHECK(st->gate == 0); /* a list's command is compact's */
                } else {
                    CHECK(st->gate == gate + 1); /* numbered in step order */
                    gate = st->gate;
                }
            }
            CHECK(p.steps[p.step_count - 1].gate == gate); /* apply's is the last */
            const cacao_plan_image *depth = find_image(&p, CACAO_RES_DEPTH_HISTORY);
            const cacao_plan_image *norm = find_image(&p, CACAO_RES_NORMALS_HISTORY);
            CHECK(depth && depth->width == 960 && depth->height == 540 && depth->format == VK_FORMAT_R32G32B32A32_SFLOAT);
            CHECK(normals ? norm && norm->width == 3 * 960 && norm->height == 540 : norm == NULL);
            CHECK(p.image_count == plain.image_count + 1 + (uint32_t)normals);
            CHECK(p.steps[3].barrier_before); /* the first gated step reads the commands the reach pass wrote */
        }
    /* the horizon estimators: the diff and the reach pass first (no prefix: any change recomputes
     * the whole frame), every direct step after them gated, list steps not */
    for (int gpu = 0; gpu < 2; ++gpu)
        for (int normals = 0; normals < 2; ++normals) {
            const cacao_settings s = {.estimator = CACAO_ESTIMATOR_BITMASK, .reuse_unchanged = true, .blur_pass_count = 8,
                                      .generate_normals = !normals,
                                      .shader_forms = gpu ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU};
            const cacao_plan p = build(s, 960, 540);
            CHECK(p.step_count == (gpu ? 12u : 18u)); /* the longest sequence the settings allow (CPU forms) */
            CHECK(p.steps[0].key[0] == CACAO_PASS_REUSE && p.steps[1].key[0] == CACAO_PASS_REUSE &&
                  p.steps[1].key[1] == CACAO_REUSE_REACH);
            CHECK(p.steps[0].key[1] == (gpu ? (normals ? CACAO_REUSE_DIFF_NORMALS_GPU : CACAO_REUSE_DIFF_GPU)
                                            : (normals ? CACAO_REUSE_DIFF_NORMALS : CACAO_REUSE_DIFF)));
            for (uint32_t i = 2; i < p.step_count; ++i)
                CHECK((p.steps[i].gate != 0) == (!p.steps[i].clear && p.steps[i].list == 0));
            CHECK((p.steps[p.step_count - 1].gate != 0) == (gpu != 0)); /* the output's last pass: gated in the GPU forms */
            CHECK(find_image(&p, CACAO_RES_DEPTH_HISTORY) != NULL);
            CHECK((find_image(&p, CACAO_RES_NORMALS_HISTORY) != NULL) == (normals != 0));
        }
}

/* A quiet frame (docs/tiles.md): CACAO's CPU forms without reuse test for it first, over a grid of
 * an invocation a tile whose output pixels cover the output (a quiet frame's output is the test's
 * stores); every direct step after that test runs from a gate, numbered in step order from 1; the
 * list steps have none. With reuse (whose gates are the reach pass's) and in the GPU forms there
 * is no such test. */
static bool find_binding(const cacao_plan_step *st, uint32_t resource, bool write) {
    for (uint32_t i = 0; i < st->binding_count; ++i)
        if (st->bindings[i].resource == resource && st->bindings[i].write == write) return true;
    return false;
}

static void test_quiet_frame(void) {
    for (int ds = 0; ds < 2; ++ds)
        for (int q = 1; q <= 5; ++q) {
            const cacao_settings s = {.quality = (cacao_quality)q, .downsample = ds, .generate_normals = true};
            const cacao_plan p = build(s, 1001, 37);
            const uint32_t first = q == 5 ? 1 : 0; /* after HIGHEST's clear */
            CHECK(strcmp(p.steps[first].key_name, "classify.quiet") == 0 && p.steps[first].gate == 0);
            CHECK(p.steps[first].dispatch[0] == (p.tiles_x + 7) / 8 && p.steps[first].dispatch[1] == (p.tiles_y + 7) / 8);
            /* a tile's output pixels, each way (16 native, 32 downsampled), cover the output */
            CHECK(p.tiles_x * (ds ? 32u : 16u) >= 1001 && p.tiles_y * (ds ? 32u : 16u) >= 37);
            CHECK(find_binding(&p.steps[first], CACAO_RES_OUTPUT, true));
            uint32_t gate = 0;
            for (uint32_t i = first + 1; i < p.step_count; ++i) {
                const cacao_plan_step *st = &p.steps[i];
                if (st->list || st->clear) {
                    CHECK(st->gate == 0);
                } else {
                    CHECK(st->gate == gate + 1);
                    gate = st->gate;
                }
            }
            CHECK(p.steps[p.step_count - 1].gate == gate || p.steps[p.step_count - 1].list); /* apply, or the listed upsample */
            for (int other = 0; other < 2; ++other) {
                cacao_settings o = s;
                if (other) o.reuse_unchanged = true;
                else o.shader_forms = CACAO_SHADER_FORMS_GPU;
                const cacao_plan op = build(o, 1001, 37);
                for (uint32_t i = 0; i < op.step_count; ++i)
                    CHECK(strcmp(op.steps[i].key_name, "classify.quiet") != 0);
            }
        }
}

int main(void) {
    test_steps_per_quality();
    test_quiet_frame();
    test_reuse();
    test_gpu_forms_skip_in_shader();
    test_horizon_clears();
    test_only_needed_resources();
    test_dispatch_sizes();
    test_lists_agree_on_layers();
    test_small_mip_chain();
    test_invalid();
    cacao_plan p = build((cacao_settings){.quality = CACAO_QUALITY_HIGHEST, .generate_normals = true}, 1920, 1080);
    cacao_plan_print(&p, stdout);
    return test_report("test_plan");
}
