/* test_tiles - tile classification (docs/tiles.md) and generate's per-pixel skip change how much
 * runs, never the result. The reference is compute_all_tiles, which skips nothing of any kind:
 * classify calls every tile active, so every tile is generated and every blur group runs, and
 * generate computes every pixel's detail AO and taps, background and faded pixels included. The
 * reference therefore shares none of the skipping rules (class thresholds, the one-tile margin,
 * generate's per-pixel background and fade test): it only evaluates the AO formulas everywhere.
 * A skip taken where the formulas would not give exactly 1 shows as a pixel that differs.
 *   - with skipping on, the AO is bit-identical to the reference on the embedded scene (sky and
 *     ground, a fade-out inside it: tiles of all three classes) at every quality, native and
 *     downsampled, with no blur, 2 and 8 blur passes, in standard and reverse Z, also with NaN
 *     in the depth;
 *   - skipping happens: with a fade-out that takes three quarters of the pixels, more than half of
 *     the generate tiles and some blur groups are skipped, native and downsampled, with and
 *     without a blur, and the output is still the reference's;
 *   - a frame that is all background (depth at the far plane) is exactly 1 everywhere and runs no
 *     generate and no blur group; the reference gives the same 1s with every tile active;
 *   - a frame with no background (the sky replaced by a far wall, fade-out beyond it) classifies
 *     no tile as background and skips nothing, with the same output;
 *   - a tile is quiet only where every slice is: one slice all beyond the fade-out, the others
 *     not, leaves every tile active (test_faded_layer).
 *   - the horizon estimators (GTAO, bitmask) likewise: identical to their reference, exactly 1
 *     with nothing estimated on an all-background frame, more than half the tiles skipped when
 *     three quarters of the pixels lie beyond the fade-out (test_horizon), and where samples past
 *     the image's edge read the normals of faded border tiles far from every active one
 *     (test_horizon_border).
 * The CACAO and horizon cases run with both shader forms: the CPU forms skip through tile lists
 * and clears, the GPU forms in the shader (a group that is not needed stores the 1 and returns;
 * the prepare classifies where it can), counting the same tiles. The counts come from the runtime (cacao_record_tile_counts) through vkdev's
 * timings. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

static const cacao_quality qualities[] = {CACAO_QUALITY_LOWEST, CACAO_QUALITY_LOW, CACAO_QUALITY_MEDIUM,
                                          CACAO_QUALITY_HIGH, CACAO_QUALITY_HIGHEST};

/* The shader forms the CACAO runs use: the CPU forms skip through tile lists, the GPU forms run
 * every group of generate and the blur and skip by the classes in the shader (docs/tiles.md);
 * main runs the CACAO cases with both. */
static cacao_shader_forms forms = CACAO_SHADER_FORMS_CPU;

/* One run; false (a test failure) when cacao fails or reports no tile counts. */
static bool run_counts(vkdev *dev, const cacao_settings *s, const vkdev_frame *f, float *ao, cacao_tile_counts *counts) {
    char err[512];
    cacao_timings t;
    cacao_settings settings = *s;
    settings.shader_forms = forms;
    const cacao_result r = vkdev_run(dev, &settings, f, 1, ao, &t, err, sizeof err);
    if (r != CACAO_SUCCESS || !t.has_tiles) {
        fprintf(stderr, "cacao run failed: %s: %s\n", cacao_result_string(r), err);
        ++test_failures;
        return false;
    }
    *counts = t.tiles;
    return true;
}

/* Frames at LOWEST or LOW native (CPU forms) with skipped tiles whose apply ran over every group
 * [0] and over compact's list [1]: main checks that the cases saw both. */
static int apply_modes_seen[2];

/* Runs s with skipping and with compute_all_tiles; checks the outputs are identical and the
 * counts add up. Returns the skipping run's counts in *on. */
static bool same_as_all_tiles(vkdev *dev, cacao_settings s, const vkdev_frame *f, const char *what,
                              cacao_tile_counts *on) {
    const size_t n = (size_t)f->width * f->height;
    float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));
    cacao_tile_counts off;
    bool ok = run_counts(dev, &s, f, a, on);
    s.compute_all_tiles = true;
    ok = ok && run_counts(dev, &s, f, b, &off);
    if (ok) {
        size_t differ = 0;
        for (size_t i = 0; i < n; ++i) differ += memcmp(&a[i], &b[i], sizeof(float)) != 0;
        if (differ)
            fprintf(stderr, "%s, quality %d, %s, blur %d, %s forms: %zu pixels differ from compute_all_tiles\n", what,
                    (int)s.quality, s.downsample ? "downsampled" : "native", s.blur_pass_count,
                    forms == CACAO_SHADER_FORMS_GPU ? "GPU" : "CPU", differ);
        CHECK(differ == 0);
        /* a quiet frame classifies nothing (docs/tiles.md "A quiet frame"): the CPU forms of CACAO
         * without reuse only; never with compute_all_tiles */
        const bool can_be_quiet = s.estimator <= CACAO_ESTIMATOR_CACAO && forms == CACAO_SHADER_FORMS_CPU && !s.reuse_unchanged;
        CHECK(!off.quiet && (can_be_quiet || !on->quiet));
        CHECK(on->active + on->faded + on->background == (on->quiet ? 0 : on->tiles));
        CHECK(on->generate_run >= on->active && on->generate_run <= on->tiles); /* active tiles and a margin */
        CHECK(off.active == off.tiles && off.generate_run == off.tiles && off.blur_run == off.blur_total);
        CHECK(on->generate_total == on->tiles && on->blur_run <= on->blur_total);
        /* The CPU forms of CACAO without reuse fill every tile generate skipped where apply runs
         * over every group, at most those where it is listed: downsampled (the upsample), smart
         * apply (MEDIUM up), and the half and non-smart applies on frames with at most 2/3 of the
         * tiles active (compact's choice, docs/tiles.md "Apply over a list where the frame skips
         * much") */
        if (s.estimator <= CACAO_ESTIMATOR_CACAO && forms == CACAO_SHADER_FORMS_CPU && !s.reuse_unchanged && !on->quiet) {
            const uint32_t skipped = on->generate_total - on->generate_run;
            const bool listed = s.downsample || s.quality >= CACAO_QUALITY_MEDIUM || 3 * on->active <= 2 * on->tiles;
            if (listed ? on->fill_run > skipped : on->fill_run != skipped)
                fprintf(stderr, "%s, quality %d, %s: %u active of %u tiles, %u skipped, %u filled (%s apply)\n", what,
                        (int)s.quality, s.downsample ? "downsampled" : "native", on->active, on->tiles, skipped,
                        on->fill_run, listed ? "listed" : "direct");
            CHECK(listed ? on->fill_run <= skipped : on->fill_run == skipped);
            if (!s.downsample && s.quality <= CACAO_QUALITY_LOW && skipped > 0) ++apply_modes_seen[listed];
        }
        /* The steps over blocks of 2x2 tiles (HIGHEST's Q3 base pass, the horizon estimators'
         * downsampled estimator in the CPU forms): every block without skipping; skipping, the
         * blocks holding an active tile, at least a quarter as many as the active tiles. The GPU
         * form of the Q3 base pass counts its active tiles. */
        const bool horizon = s.estimator == CACAO_ESTIMATOR_GTAO || s.estimator == CACAO_ESTIMATOR_BITMASK;
        const bool blocks = horizon ? s.downsample && forms == CACAO_SHADER_FORMS_CPU : s.quality == CACAO_QUALITY_HIGHEST;
        CHECK(blocks == (on->blocks_total > 0) && off.blocks_run == off.blocks_total);
        if (blocks && !horizon && forms == CACAO_SHADER_FORMS_GPU)
            CHECK(on->blocks_run == on->active && on->blocks_total == on->tiles);
        else if (blocks)
            CHECK(on->blocks_run <= on->blocks_total && 4 * on->blocks_run >= on->active && on->blocks_run <= on->active);
    }
    free(a);
    free(b);
    return ok;
}

/* The tiles generate ran per case of test_equal_everywhere with the CPU forms (compact's list),
 * which the GPU forms (classify's count of the tiles it marked needed) must match. */
static uint32_t cpu_generate_run[2][5][2][3];

static void test_equal_everywhere(vkdev *dev, const scene_buffers *sb) {
    static const int blurs[] = {CACAO_BLUR_NONE, 2, 8};
    for (int rev = 0; rev < 2; ++rev) {
        const vkdev_frame f = scene_frame(sb, rev != 0, false);
        for (int q = 0; q < 5; ++q)
            for (int ds = 0; ds < 2; ++ds)
                for (int bl = 0; bl < 3; ++bl) {
                    /* a fade-out inside the scene, so that all three classes occur */
                    const cacao_settings s = {.quality = qualities[q], .downsample = ds, .generate_normals = true,
                                              .blur_pass_count = blurs[bl], .fade_out_from = 6.0f,
                                              .fade_out_to = 12.0f};
                    cacao_tile_counts c;
                    if (!same_as_all_tiles(dev, s, &f, rev ? "embedded scene, reverse Z" : "embedded scene", &c))
                        continue;
                    CHECK(c.background > 0 && c.faded > 0 && c.active > 0);
                    uint32_t *cpu_run = &cpu_generate_run[rev][q][ds][bl];
                    if (forms == CACAO_SHADER_FORMS_CPU) *cpu_run = c.generate_run;
                    else CHECK(c.generate_run == *cpu_run); /* the same needed tiles, counted two ways */
                    /* native: 16x16-pixel tiles, some far enough from every active one to skip;
                     * downsampled at this size has 8x5 tiles of 32x32, all within one of an
                     * active tile */
                    if (!ds) CHECK(c.generate_run < c.tiles);
                }
    }
}

static void test_all_background(vkdev *dev, const scene_buffers *sb) {
    const size_t n = (size_t)sb->width * sb->height;
    float *sky = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    for (int rev = 0; rev < 2; ++rev) {
        for (size_t i = 0; i < n; ++i) sky[i] = rev ? 0.0f : 1.0f; /* the far plane */
        vkdev_frame f = scene_frame(sb, rev != 0, false);
        f.depth = sky;
        for (int q = 0; q < 5; ++q)
            for (int ds = 0; ds < 2; ++ds) {
                /* fade-out beyond the far plane: only the background rule makes the sky quiet */
                const cacao_settings s = {.quality = qualities[q], .downsample = ds, .generate_normals = true,
                                          .fade_out_from = 1e6f, .fade_out_to = 2e6f};
                cacao_tile_counts c;
                if (!run_counts(dev, &s, &f, ao, &c)) continue;
                size_t not_one = 0;
                for (size_t i = 0; i < n; ++i) not_one += ao[i] != 1.0f;
                CHECK(not_one == 0);
                /* the CPU forms find the frame quiet before classifying it (below) */
                CHECK(c.quiet == (forms == CACAO_SHADER_FORMS_CPU));
                CHECK(c.background == (c.quiet ? 0 : c.tiles) && c.generate_run == 0 && c.blur_run == 0 && c.blocks_run == 0);
                cacao_tile_counts unused;
                same_as_all_tiles(dev, s, &f, "all background", &unused);
            }
    }
    free(sky);
    free(ao);
}

static void test_no_background(vkdev *dev, const scene_buffers *sb) {
    const size_t n = (size_t)sb->width * sb->height;
    float *walled = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; ++i) walled[i] = sb->depth[i] >= 1.0f ? 0.999f : sb->depth[i]; /* a far wall */
    vkdev_frame f = scene_frame(sb, false, false);
    f.depth = walled;
    for (int q = 0; q < 5; q += 2) {
        const cacao_settings s = {.quality = qualities[q], .generate_normals = true, .fade_out_from = 1e6f,
                                  .fade_out_to = 2e6f};
        cacao_tile_counts c;
        if (!same_as_all_tiles(dev, s, &f, "no background", &c)) continue;
        CHECK(c.background == 0 && c.faded == 0 && c.active == c.tiles && c.generate_run == c.tiles);
    }
    free(walled);
}

/* A tile is quiet only when every layer's texels are: here the columns slice 0 reads lie beyond
 * the fade-out and the others' within it (native, slice 0 reads the even columns; downsampled,
 * those with x % 4 == 0, slice 1 those with x % 4 == 2), so slice 0 is all faded while slices 1
 * and 3 are not. Every tile is active, and the output is the reference's (a classification that
 * stopped at the first layer with a texel not background called every tile faded and skipped
 * generate: commit 16e6be8 and before). LOW and HIGH, native and downsampled. */
static void test_faded_layer(vkdev *dev, const scene_buffers *sb, const cacao_camera *camera) {
    const size_t n = (size_t)sb->width * sb->height;
    float *striped = malloc(n * sizeof(float));
    const double nz = camera->near_z, fz = camera->far_z;
    for (int ds = 0; ds < 2; ++ds) {
        for (size_t i = 0; i < n; ++i) {
            const size_t x = i % sb->width, y = i / sb->width;
            /* near columns: a rough surface at z 4..5 (it occludes itself); the others a wall at z 40 */
            const bool near = (x & (ds ? 2u : 1u)) != 0;
            const double z = near ? 4.0 + 0.25 * (double)((x * 7 + y * 13) % 5) : 40.0;
            striped[i] = (float)(fz * (z - nz) / (z * (fz - nz)));
        }
        vkdev_frame f = scene_frame(sb, false, false);
        f.depth = striped;
        for (int q = 1; q < 5; q += 2) {
            const cacao_settings s = {.quality = qualities[q], .downsample = ds != 0, .generate_normals = true,
                                      .fade_out_from = 10.0f, .fade_out_to = 20.0f};
            cacao_tile_counts c;
            if (!same_as_all_tiles(dev, s, &f, "one layer faded", &c)) continue;
            if (c.active != c.tiles) {
                fprintf(stderr, "one layer faded, quality %d, %s: %u of %u tiles active\n", (int)s.quality,
                        ds ? "downsampled" : "native", c.active, c.tiles);
                ++test_failures;
            }
        }
    }
    free(striped);
}

static int compare_float(const void *a, const void *b) {
    const float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* View z of the 25th percentile of the pixels of sb (standard depth; sky at infinity). */
static float first_quartile_z(const scene_buffers *sb, const cacao_camera *camera) {
    const size_t n = (size_t)sb->width * sb->height;
    float *z = malloc(n * sizeof(float));
    const double nz = camera->near_z, fz = camera->far_z;
    for (size_t i = 0; i < n; ++i) {
        const double d = sb->depth[i];
        z[i] = d >= 1.0 ? INFINITY : (float)(nz * fz / (fz - d * (fz - nz)));
    }
    qsort(z, n, sizeof(float), compare_float);
    const float quartile = z[n / 4];
    free(z);
    return quartile;
}

/* Skipping happens where it should: fade_out_to at the view z of the 25th percentile, so three
 * quarters of the pixels lie beyond it (or are sky). Native at 256x144 and downsampled at
 * 512x288 (the same 16x9 tiles of slice texels; at 256x144 downsampled all 8x5 tiles lie within
 * one of an active tile). Generate must skip more than half its tiles, and with a blur some
 * groups must be skipped, while the output stays the reference's; with normals from depth, and
 * with the scene's (which the CPU forms transform over the tiles within two of an active one). */
static void test_mostly_faded(vkdev *dev, uint32_t width, uint32_t height, bool downsample, bool half_skipped) {
    static const int blurs[] = {CACAO_BLUR_NONE, 2, 8};
    const cacao_scene scene = cacao_default_scene(width, height);
    scene_buffers sb;
    scene_buffers_render(&scene, &sb);
    const float to = first_quartile_z(&sb, &scene.camera);
    CHECK(isfinite(to));
    /* with the scene's normals too (blur 2): the CPU forms transform them over the tiles within
     * two of an active tile only (generate reads the needed tiles' and one texel around) */
    for (int q = 0; q < 5; ++q)
        for (int bl = 0; bl < 4; ++bl) {
            const bool given = bl == 3;
            const vkdev_frame f = scene_frame(&sb, false, given);
            const cacao_settings s = {.quality = qualities[q],
                                      .downsample = downsample,
                                      .generate_normals = !given,
                                      .blur_pass_count = given ? 2 : blurs[bl],
                                      .fade_out_from = 0.5f * to,
                                      .fade_out_to = to};
            cacao_tile_counts c;
            if (!same_as_all_tiles(dev, s, &f, "three quarters faded", &c)) continue;
            const bool blurred = s.blur_pass_count != CACAO_BLUR_NONE;
            if ((half_skipped ? c.generate_run * 2 >= c.tiles : c.generate_run >= c.tiles) || (blurred && c.blur_run >= c.blur_total))
                fprintf(stderr,
                        "three quarters faded, quality %d, %s, blur %d: generate ran %u of %u tiles, blur %u of %u "
                        "groups\n",
                        (int)s.quality, downsample ? "downsampled" : "native", s.blur_pass_count, c.generate_run,
                        c.tiles, c.blur_run, c.blur_total);
            CHECK(half_skipped ? c.generate_run * 2 < c.tiles : c.generate_run < c.tiles);
            if (blurred) CHECK(c.blur_run < c.blur_total);
        }
    scene_buffers_free(&sb);
}

/* A quiet frame (docs/tiles.md "A quiet frame"): in the CPU forms classify.quiet first tests the
 * caller's depth, and where no pixel can make a texel that is not quiet, only that test runs (it
 * stores the output's 1s). Each case against compute_all_tiles (the same output, every tile computed), and whether it
 * is quiet, at an even size and at an odd one (where the prepare reads depth 0 past the image's
 * right and bottom edges: with standard Z the near plane, a texel that is not quiet unless the
 * fade-out takes it), standard and reverse Z:
 *   - sky (the far plane) everywhere: quiet, except odd and standard Z;
 *   - the scene with a fade-out nearer than its nearest pixel (and than the near plane): quiet;
 *   - sky with NaN holes: quiet as sky;
 *   - sky with one pixel of the scene: not quiet (the classification finds its tile active). */
static void test_quiet_frames(vkdev *dev) {
    static const struct {
        cacao_quality quality;
        bool downsample;
    } configs[] = {{CACAO_QUALITY_LOWEST, false}, {CACAO_QUALITY_HIGH, false}, {CACAO_QUALITY_HIGHEST, false},
                   {CACAO_QUALITY_HIGH, true}};
    for (int odd = 0; odd < 2; ++odd) {
        const cacao_scene scene = cacao_default_scene(256 - odd, 144 - odd);
        scene_buffers sb;
        scene_buffers_render(&scene, &sb);
        const size_t n = (size_t)sb.width * sb.height;
        float *depth = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
        for (int rev = 0; rev < 2; ++rev)
            for (int kind = 0; kind < 4; ++kind) {
                const float *scene_depth = rev ? sb.depth_reversed : sb.depth;
                const float far = rev ? 0.0f : 1.0f;
                size_t one = n;  /* the pixel of the scene that kind 3 keeps: the middle's, not sky */
                for (size_t i = n / 2; i < n && one == n; ++i)
                    if (sb.depth[i] < 1.0f) one = i;
                CHECK(one < n);
                for (size_t i = 0; i < n; ++i)
                    depth[i] = kind == 1 ? scene_depth[i] : kind == 2 && i % 7 == 0 ? NAN : kind == 3 && i == one ? scene_depth[i] : far;
                vkdev_frame f = scene_frame(&sb, rev != 0, false);
                f.depth = depth;
                const bool expect = kind == 3 ? false : kind == 1 ? true : !(odd && !rev);
                for (size_t k = 0; k < sizeof configs / sizeof configs[0]; ++k) {
                    cacao_settings s = {.quality = configs[k].quality, .downsample = configs[k].downsample,
                                        .generate_normals = true, .fade_out_from = 1e6f, .fade_out_to = 2e6f};
                    if (kind == 1) s.fade_out_from = 0.5e-3f, s.fade_out_to = 1e-3f; /* before the near plane */
                    cacao_tile_counts c;
                    if (!same_as_all_tiles(dev, s, &f, "quiet frame", &c) || !run_counts(dev, &s, &f, ao, &c)) continue;
                    size_t not_one = 0;
                    for (size_t i = 0; i < n; ++i) not_one += ao[i] != 1.0f;
                    if (c.quiet != expect)
                        fprintf(stderr, "quiet frame: case %d, %s, %s Z, quality %d, %s: quiet %d, expected %d\n", kind,
                                odd ? "odd" : "even", rev ? "reverse" : "standard", (int)s.quality,
                                s.downsample ? "downsampled" : "native", c.quiet, expect);
                    CHECK(c.quiet == expect);
                    CHECK(c.quiet ? not_one == 0 && c.generate_run == 0 : c.active + c.faded + c.background == c.tiles);
                    /* the classification finds the pixel's tile active where every pixel makes a
                     * texel (native, above LOWEST, whose two slices read half the pixels; the
                     * downsampled ones a quarter): the quiet test looks at every pixel */
                    if (kind == 3 && !s.downsample && s.quality != CACAO_QUALITY_LOWEST) CHECK(c.active > 0);
                }
            }
        free(depth);
        free(ao);
        scene_buffers_free(&sb);
    }
}

/* The caller's normals are transformed only over the tiles within two of an active one (the CPU
 * forms without reuse): no pass may read a normal outside them. One context first runs a frame
 * with every tile active (a wall nearer than the fade-out) and the normals turned around, so that
 * every tile holds a wrong normal; then the three-quarters-faded frame with the right ones, whose output must be the
 * reference's (compute_all_tiles, a context of its own). Normals the second frame read but did not
 * transform would be the first frame's: a list that left out every fourth column of needed tiles
 * made 4255-6377 pixels differ at LOW (then listed), HIGH and HIGHEST. (One cut to the needed tiles, without the ring of one tile that
 * the edges of their border texels read, made none differ here, blur 2 or 8: the ring is kept
 * because those edges enter the blur of their neighbours.) */
static void test_stale_normals(vkdev *dev) {
    const cacao_scene scene = cacao_default_scene(256, 144);
    scene_buffers sb;
    scene_buffers_render(&scene, &sb);
    const float to = first_quartile_z(&sb, &scene.camera);
    const size_t n = (size_t)sb.width * sb.height;
    float *walled = malloc(n * sizeof(float)), *flipped = malloc(3 * n * sizeof(float));
    float *ao = malloc(n * sizeof(float)), *ref = malloc(n * sizeof(float));
    const double nz = scene.camera.near_z, fz = scene.camera.far_z, z = 0.4 * to;
    for (size_t i = 0; i < n; ++i) walled[i] = (float)(fz * (z - nz) / (z * (fz - nz)));
    for (size_t i = 0; i < 3 * n; ++i) flipped[i] = -sb.normals[i];
    vkdev_frame first = scene_frame(&sb, false, false), real = scene_frame(&sb, false, true);
    first.depth = walled;
    vkdev_frame_set_view_normals(&first, flipped);
    static const cacao_quality qs[] = {CACAO_QUALITY_MEDIUM, CACAO_QUALITY_HIGH, CACAO_QUALITY_HIGHEST}; /* the listed normals */
    for (int ds = 0; ds < 2; ++ds)
        for (size_t q = 0; q < sizeof qs / sizeof qs[0]; ++q) {
            cacao_settings s = {.quality = qs[q], .downsample = ds, .fade_out_from = 0.5f * to, .fade_out_to = to, .blur_pass_count = 8,
                                .shader_forms = CACAO_SHADER_FORMS_CPU};
            char err[512];
            cacao_settings all = s;
            all.compute_all_tiles = true;
            cacao_context *ctx = NULL;
            cacao_timings t;
            bool ok = vkdev_run(dev, &all, &real, 1, ref, NULL, err, sizeof err) == CACAO_SUCCESS &&
                      vkdev_context_create(dev, &ctx) == CACAO_SUCCESS && cacao_context_set_settings(ctx, &s) == CACAO_SUCCESS &&
                      cacao_context_resize(ctx, sb.width, sb.height, NULL) == CACAO_SUCCESS &&
                      vkdev_run_context(dev, ctx, &first, 1, ao, NULL, err, sizeof err) == CACAO_SUCCESS &&
                      vkdev_run_context(dev, ctx, &real, 1, ao, &t, err, sizeof err) == CACAO_SUCCESS;
            CHECK(ok);
            if (ok) {
                size_t differ = 0;
                for (size_t i = 0; i < n; ++i) differ += memcmp(&ao[i], &ref[i], sizeof(float)) != 0;
                if (differ)
                    fprintf(stderr, "stale normals, quality %d, %s: %zu pixels differ from compute_all_tiles\n",
                            (int)s.quality, ds ? "downsampled" : "native", differ);
                CHECK(differ == 0);
                /* native, most tiles skipped (downsampled at this size all lie near an active one) */
                CHECK(t.has_tiles && (ds || t.tiles.generate_run * 2 < t.tiles.tiles));
            }
            cacao_context_destroy(ctx);
        }
    free(walled);
    free(flipped);
    free(ao);
    free(ref);
    scene_buffers_free(&sb);
}

/* The slices' AO of a tile generate skips gets its 1 only where a later pass reads it, where the
 * CPU forms' apply or upsample runs over lists without reuse (docs/tiles.md, compact's fill_read):
 * no pass may read a tile the fills leave out. One context first runs the scene brought to a
 * third of its view z and made rough (most tiles active, the AO below 0.9 in most places, in both
 * AO images), then the three-quarters-faded frame, whose output must be the reference's
 * (compute_all_tiles, a context of its own): a tile read but not filled would hold the first
 * frame's AO (a fill cut to the tiles within one of a needed tile made 205-1097 pixels differ
 * native from MEDIUM up; none filled, 2233-10046 at every listed configuration). Native at
 * 256x144, downsampled at 512x288 (16x9 tiles each), every quality, blur none, 2 and 8; where
 * apply or the upsample runs over lists, the fills must leave some skipped tiles out. */
static void test_stale_ao(vkdev *dev) {
    static const int blurs[] = {CACAO_BLUR_NONE, 2, 8};
    for (int ds = 0; ds < 2; ++ds) {
        const cacao_scene scene = cacao_default_scene(256u << ds, 144u << ds);
        scene_buffers sb;
        scene_buffers_render(&scene, &sb);
        const float to = first_quartile_z(&sb, &scene.camera);
        const size_t n = (size_t)sb.width * sb.height;
        float *near = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float)), *ref = malloc(n * sizeof(float));
        const double nz = scene.camera.near_z, fz = scene.camera.far_z;
        for (size_t i = 0; i < n; ++i) { /* view z / 3, rough (at least 1.01 near), the sky kept */
            const double d = sb.depth[i], rough = 1.0 + 0.1 * (double)((uint32_t)(i * 2654435761u) >> 28) / 16.0;
            const double z = d >= 1.0 ? 0.0 : fmax(nz * fz / (fz - d * (fz - nz)) / 3.0 * rough, 1.01 * nz);
            near[i] = d >= 1.0 ? sb.depth[i] : (float)(fz * (z - nz) / (z * (fz - nz)));
        }
        vkdev_frame first = scene_frame(&sb, false, false), real = scene_frame(&sb, false, false);
        first.depth = near;
        for (int q = 0; q < 5; ++q)
            for (int b = 0; b < 3; ++b) {
                const cacao_settings s = {.quality = qualities[q], .downsample = ds, .generate_normals = true,
                                          .blur_pass_count = blurs[b], .fade_out_from = 0.5f * to, .fade_out_to = to,
                                          .shader_forms = CACAO_SHADER_FORMS_CPU};
                cacao_settings all = s;
                all.compute_all_tiles = true;
                char err[512];
                cacao_context *ctx = NULL;
                cacao_timings t, t_first;
                bool ok = vkdev_run(dev, &all, &real, 1, ref, NULL, err, sizeof err) == CACAO_SUCCESS &&
                          vkdev_context_create(dev, &ctx) == CACAO_SUCCESS && cacao_context_set_settings(ctx, &s) == CACAO_SUCCESS &&
                          cacao_context_resize(ctx, sb.width, sb.height, NULL) == CACAO_SUCCESS &&
                          vkdev_run_context(dev, ctx, &first, 1, ao, &t_first, err, sizeof err) == CACAO_SUCCESS;
                size_t below_one = 0; /* the first frame's AO: below 0.9 in most places */
                for (size_t i = 0; ok && i < n; ++i) below_one += ao[i] < 0.9f;
                ok = ok && vkdev_run_context(dev, ctx, &real, 1, ao, &t, err, sizeof err) == CACAO_SUCCESS;
                if (!ok) fprintf(stderr, "stale AO: %s\n", err);
                CHECK(ok && t_first.has_tiles && t.has_tiles);
                if (!ok || !t.has_tiles || !t_first.has_tiles) {
                    cacao_context_destroy(ctx);
                    continue;
                }
                size_t differ = 0;
                for (size_t i = 0; i < n; ++i) differ += memcmp(&ao[i], &ref[i], sizeof(float)) != 0;
                if (differ)
                    fprintf(stderr, "stale AO, quality %d, %s, blur %d: %zu pixels differ from compute_all_tiles\n",
                            (int)s.quality, ds ? "downsampled" : "native", s.blur_pass_count, differ);
                CHECK(differ == 0);
                CHECK(t_first.tiles.active > 2 * t.tiles.active && below_one * 2 > n);
                const cacao_tile_counts *c = &t.tiles;
                const uint32_t skipped = c->generate_total - c->generate_run;
                CHECK(skipped * 2 > c->tiles && c->fill_run <= skipped);
                /* apply or the upsample over lists: downsampled, smart apply (MEDIUM up) native, and
                 * the non-smart and half applies (LOWEST, LOW) where at most 2/3 of the tiles are
                 * active (these frames: fewer than half; else every skipped tile is filled) */
                const bool listed = ds || s.quality >= CACAO_QUALITY_MEDIUM || 3 * c->active <= 2 * c->tiles;
                if (listed && c->fill_run >= skipped)
                    fprintf(stderr, "stale AO, quality %d, %s, blur %d: the fills ran over all %u skipped tiles\n",
                            (int)s.quality, ds ? "downsampled" : "native", s.blur_pass_count, skipped);
                CHECK(listed ? c->fill_run < skipped : c->fill_run == skipped);
                cacao_context_destroy(ctx);
            }
        free(near);
        free(ao);
        free(ref);
        scene_buffers_free(&sb);
    }
}

static void test_nan_depth(vkdev *dev, const scene_buffers *sb) {
    const size_t n = (size_t)sb->width * sb->height;
    float *holes = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; ++i) holes[i] = (i % 97 == 0 || sb->depth[i] >= 1.0f) ? NAN : sb->depth[i];
    vkdev_frame f = scene_frame(sb, false, false);
    f.depth = holes;
    for (int q = 0; q < 5; q += 2) {
        const cacao_settings s = {.quality = qualities[q], .generate_normals = true};
        cacao_tile_counts c;
        if (same_as_all_tiles(dev, s, &f, "NaN depth", &c)) CHECK(c.background > 0); /* NaN sky is background */
    }
    free(holes);
}

/* The horizon estimators classify too: a tile is 8x8 pixels; the estimator and the denoise
 * passes run over the needed tiles, and the clears and compact give the rest the 1 they compute there. The
 * reference (compute_all_tiles) runs them over every tile, as before classification existed.
 * Every case above, for GTAO and the bitmask, their smallest and a middle budget, no denoise, one,
 * two (both intermediates filled) and eight passes, normals from depth and given; and downsampled
 * (the estimator over the blocks of 2x2 tiles holding an active tile, the upsample over the
 * needed tiles) with up to the 6 filter passes whose reach a skipped tile's margin covers. */
static void test_horizon(vkdev *dev, const scene_buffers *sb, const scene_buffers *faded_sb, float faded_to) {
    static const cacao_estimator estimators[] = {CACAO_ESTIMATOR_GTAO, CACAO_ESTIMATOR_BITMASK};
    static const int denoise[2][4] = {{CACAO_BLUR_NONE, 1, 2, 8}, {CACAO_BLUR_NONE, 1, 3, CACAO_HORIZON_HALF_MAX_PASSES}};
    const size_t n = (size_t)sb->width * sb->height;
    float *sky = malloc(n * sizeof(float)), *holes = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; ++i) {
        sky[i] = 1.0f;
        holes[i] = (i % 97 == 0 || sb->depth[i] >= 1.0f) ? NAN : sb->depth[i];
    }
    for (int ds = 0; ds < 2; ++ds)
    for (int e = 0; e < 2; ++e)
        for (int q = 0; q < 5; q += 3)
            for (int d = 0; d < 4; ++d)
                for (int given = 0; given < 2; ++given) {
                    cacao_settings s = {.estimator = estimators[e], .quality = qualities[q], .downsample = ds != 0,
                                        .generate_normals = !given, .blur_pass_count = denoise[ds][d],
                                        .fade_out_from = 6.0f, .fade_out_to = 12.0f};
                    cacao_tile_counts c;
                    vkdev_frame f = scene_frame(sb, d == 2, given != 0); /* reverse Z with two denoise passes */
                    if (same_as_all_tiles(dev, s, &f, "horizon, embedded scene", &c)) {
                        CHECK(c.background > 0 && c.faded > 0 && c.active > 0 && c.generate_run < c.tiles);
                        CHECK(c.blur_total == 0); /* the denoise passes use the estimator's list */
                    }
                    /* all background: exactly 1, nothing estimated */
                    f = scene_frame(sb, false, given != 0);
                    f.depth = sky;
                    s.fade_out_from = 1e6f;
                    s.fade_out_to = 2e6f;
                    if (run_counts(dev, &s, &f, ao, &c)) {
                        size_t not_one = 0;
                        for (size_t i = 0; i < n; ++i) not_one += ao[i] != 1.0f;
                        CHECK(not_one == 0 && c.background == c.tiles && c.generate_run == 0 && c.blocks_run == 0);
                    }
                    same_as_all_tiles(dev, s, &f, "horizon, all background", &c);
                    /* NaN holes and a NaN sky */
                    f.depth = holes;
                    s.fade_out_from = 0.0f;
                    s.fade_out_to = 0.0f;
                    if (same_as_all_tiles(dev, s, &f, "horizon, NaN depth", &c)) CHECK(c.background > 0);
                    /* three quarters beyond the fade-out: more than half the tiles skipped */
                    f = scene_frame(faded_sb, false, given != 0);
                    s.fade_out_from = 0.5f * faded_to;
                    s.fade_out_to = faded_to;
                    if (same_as_all_tiles(dev, s, &f, "horizon, three quarters faded", &c)) {
                        if (c.generate_run * 2 >= c.tiles)
                            fprintf(stderr, "horizon, three quarters faded: %u of %u tiles estimated\n",
                                    c.generate_run, c.tiles);
                        CHECK(c.generate_run * 2 < c.tiles);
                    }
                }
    free(sky);
    free(holes);
    free(ao);
}

/* The samples past the image's edge read the last pixel of the image on their line, its view z
 * and normal (horizon.glsl, side_plane), however far it lies from the tile being estimated: the CPU
 * forms' prepare must store the normals of every border tile, not only of those within two of an
 * active one. A box near the camera, right of the centre, is all that lies within the fade-out;
 * the turned wall around it (and the floor below, mostly hidden) is faded, its border tiles three
 * or more tiles from the box's; the radius makes the box's samples leave the image. (Without the
 * border tiles in compact's normals list, 6-50 pixels differed in seven of the eight cases of the
 * CPU forms.) */
static void test_horizon_border(vkdev *dev) {
    static const cacao_prim prims[] = {
        {.kind = CACAO_PRIM_PLANE, .a = {0, 0, -6.5}, .b = {0.15, 0.1, 1}}, /* the far wall, turned */
        {.kind = CACAO_PRIM_PLANE, .a = {0, -6, 0}, .b = {0, 1, 0}},  /* the floor, from 10.4 away */
        {.kind = CACAO_PRIM_BOX, .a = {0.6, -0.4, -3.4}, .b = {1.4, 0.4, -2.6}},
    };
    const cacao_scene scene = {.prims = prims,
                               .prim_count = 3,
                               .camera = {.width = 128,
                                          .height = 72,
                                          .fov_y_deg = 60.0,
                                          .near_z = 0.1,
                                          .far_z = 100.0,
                                          .eye = {0, 0, 0},
                                          .target = {0, 0, -1},
                                          .up = {0, 1, 0}},
                               .ao_radius_world = 5.0};
    scene_buffers sb;
    scene_buffers_render(&scene, &sb);
    static const cacao_estimator estimators[] = {CACAO_ESTIMATOR_GTAO, CACAO_ESTIMATOR_BITMASK};
    for (int ds = 0; ds < 2; ++ds)
        for (int e = 0; e < 2; ++e)
            for (int given = 0; given < 2; ++given) {
                const vkdev_frame f = scene_frame(&sb, false, given != 0);
                const cacao_settings s = {.estimator = estimators[e], .quality = CACAO_QUALITY_MEDIUM,
                                          .downsample = ds != 0, .generate_normals = !given,
                                          .radius = (float)scene.ao_radius_world, .blur_pass_count = 1,
                                          .fade_out_from = 4.0f, .fade_out_to = 5.0f};
                cacao_tile_counts c;
                if (same_as_all_tiles(dev, s, &f, "horizon, samples past the edge", &c)) {
                    if (!(c.active > 0 && c.active * 4 < c.tiles && c.faded > 0))
                        fprintf(stderr, "samples past the edge: %u active, %u faded of %u tiles\n", c.active, c.faded, c.tiles);
                    CHECK(c.active > 0 && c.active * 4 < c.tiles && c.faded > 0);
                }
            }
    scene_buffers_free(&sb);
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    const cacao_scene scene = cacao_default_scene(256, 144);
    scene_buffers sb;
    scene_buffers_render(&scene, &sb);
    test_equal_everywhere(&dev, &sb);
    test_all_background(&dev, &sb);
    test_no_background(&dev, &sb);
    test_mostly_faded(&dev, 256, 144, false, true);
    /* an odd size (the slices' last texels lie half outside the image; at LOWEST less than half
     * the tiles are skipped) */
    test_mostly_faded(&dev, 255, 143, false, false);
    test_mostly_faded(&dev, 512, 288, true, true);
    test_nan_depth(&dev, &sb);
    test_faded_layer(&dev, &sb, &scene.camera);
    test_quiet_frames(&dev);
    test_stale_normals(&dev);
    test_stale_ao(&dev);
    printf("LOWEST and LOW native with skipped tiles: %d frames applied over every group, %d over compact's list\n",
           apply_modes_seen[0], apply_modes_seen[1]);
    CHECK(apply_modes_seen[0] > 0 && apply_modes_seen[1] > 0);
    /* the GPU forms: the same cases (lavapipe runs both sides of their skip, slowly: the
     * downsampled frame once, with the CPU forms); mostly faded at 512x288, where the GPU blur's
     * larger groups (up to 64x48 texels) leave some away from every active tile */
    forms = CACAO_SHADER_FORMS_GPU;
    test_equal_everywhere(&dev, &sb);
    test_all_background(&dev, &sb);
    test_no_background(&dev, &sb);
    test_mostly_faded(&dev, 512, 288, false, true);
    test_nan_depth(&dev, &sb);
    test_faded_layer(&dev, &sb, &scene.camera);
    forms = CACAO_SHADER_FORMS_CPU;
    test_horizon(&dev, &sb, &sb, first_quartile_z(&sb, &scene.camera));
    test_horizon_border(&dev);
    /* the horizon estimators' GPU forms: the prepare classifies, the other passes skip in the shader */
    forms = CACAO_SHADER_FORMS_GPU;
    test_horizon(&dev, &sb, &sb, first_quartile_z(&sb, &scene.camera));
    test_horizon_border(&dev);
    scene_buffers_free(&sb);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_tiles");
}
