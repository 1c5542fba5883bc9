/* test_reuse - reuse_unchanged (docs/tiles.md "Reusing the previous frame") changes how much a
 * frame computes, never its result. The reference of every frame is a context without reuse that
 * computes that frame alone; a reusing context runs a sequence of frames and must give, frame by
 * frame, the reference's output bit for bit:
 *   - the first frame (a full one: changed = every tile);
 *   - the same frame again: nothing changed, nothing recomputed, no generate or blur group run;
 *   - one object moved (a sphere of the embedded scene, a few tiles): only tiles within reach of
 *     it recomputed (fewer than all, except at HIGHEST, which recomputes everything when anything
 *     changed), and the same frame again after it;
 *   - with the caller's normals, a frame whose normals alone changed in a region: recomputed; and,
 *     where the frame reads the normals of some pixels only (downsampled: pixel (0,0) of each 2x2
 *     block; LOWEST native: (0,0) and (1,1)), a frame whose normals changed at the other pixels
 *     alone: the reference's output is the first frame's (nothing reads them), and so is reuse's;
 *   - the output kept by the caller (output_holds_previous) on an unchanged frame: nothing is
 *     written and the output is still the reference's;
 *   - the camera moved (another projection): a full frame, without the diff; the next frame with
 *     that camera a full one that refreshes the copies, the one after it nothing;
 *   - force_full_frame; a settings change; a resize; NaN in the depth that stays NaN (unchanged);
 *   - the horizon estimators (horizon_sequence), which recompute everything when anything changed.
 * Every quality, native and downsampled, both shader forms, normals from depth and given, with
 * blur none, 2 and 8 (a subset of the product). The output image is NaN before each run
 * (vkdev): a pixel the frame fails to write shows. Validation (synchronization included) is on. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

enum { W = 512, H = 288 };

typedef struct frames {
    scene_buffers base, moved;
    float *nan_depth;
} frames;

/* The embedded scene, and the same with one sphere (the one by the column, far from the camera)
 * moved 0.3 m along x. */
static void render_frames(frames *f) {
    const cacao_scene scene = cacao_default_scene(W, H);
    scene_buffers_render(&scene, &f->base);
    cacao_prim prims[64];
    cacao_scene moved = scene;
    moved.prim_count = scene.prim_count < 64 ? scene.prim_count : 64;
    memcpy(prims, scene.prims, moved.prim_count * sizeof *prims);
    uint32_t sphere = moved.prim_count;
    for (uint32_t i = 0; i < moved.prim_count; ++i)
        if (prims[i].kind == CACAO_PRIM_SPHERE && fabs(prims[i].a[0] - 1.55) < 1e-9) sphere = i;
    CHECK(sphere < moved.prim_count);
    if (sphere < moved.prim_count) prims[sphere].a[0] += 0.3;
    moved.prims = prims;
    scene_buffers_render(&moved, &f->moved);
    const size_t n = (size_t)W * H;
    f->nan_depth = malloc(n * sizeof(float));
    memcpy(f->nan_depth, f->base.depth, n * sizeof(float));
    for (size_t i = 0; i < n; i += 97) f->nan_depth[i] = NAN;
}

static void free_frames(frames *f) {
    scene_buffers_free(&f->base);
    scene_buffers_free(&f->moved);
    free(f->nan_depth);
}

/* The reference: a fresh context without reuse, this frame alone. */
static bool reference(vkdev *dev, cacao_settings s, const vkdev_frame *f, float *ao) {
    s.reuse_unchanged = false;
    return run(dev, &s, f, ao);
}

/* One frame (or `repeat` of it) on the reusing context; false on a failure (reported). */
static bool step(vkdev *dev, cacao_context *ctx, const vkdev_frame *f, uint32_t repeat, float *ao, cacao_tile_counts *c) {
    char err[512];
    cacao_timings t;
    const cacao_result r = vkdev_run_context(dev, ctx, f, repeat, ao, &t, err, sizeof err);
    if (r != CACAO_SUCCESS || !t.has_tiles) {
        fprintf(stderr, "reusing run failed: %s: %s\n", cacao_result_string(r), err);
        ++test_failures;
        return false;
    }
    *c = t.tiles;
    return true;
}

static char config[160];

/* The reusing context's frame equals the reference's, bit for bit. */
static void check_same(const float *a, const float *b, const char *what) {
    size_t differ = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) differ += memcmp(&a[i], &b[i], sizeof(float)) != 0;
    if (differ) fprintf(stderr, "%s, %s: %zu pixels differ from the frame computed alone\n", config, what, differ);
    CHECK(differ == 0);
}

static void check_nothing_ran(const cacao_tile_counts *c, const char *what) {
    if (c->changed || c->recomputed || c->generate_run || c->blur_run)
        fprintf(stderr, "%s, %s: changed %u, recomputed %u, generate %u, blur %u (expected 0)\n", config, what,
                c->changed, c->recomputed, c->generate_run, c->blur_run);
    CHECK(c->changed == 0 && c->recomputed == 0 && c->generate_run == 0 && c->blur_run == 0);
}

static void check_full(const cacao_tile_counts *c, const char *what) {
    if (c->changed != c->tiles || c->recomputed != c->tiles)
        fprintf(stderr, "%s, %s: changed %u, recomputed %u of %u tiles (expected all)\n", config, what, c->changed,
                c->recomputed, c->tiles);
    CHECK(c->changed == c->tiles && c->recomputed == c->tiles);
}

/* A context with the settings at W x H (NULL on a failure, reported). */
static cacao_context *reusing_context(vkdev *dev, const cacao_settings *s) {
    cacao_context *ctx = NULL;
    if (vkdev_context_create(dev, &ctx) != CACAO_SUCCESS || cacao_context_set_settings(ctx, s) != CACAO_SUCCESS ||
        cacao_context_resize(ctx, W, H, NULL) != CACAO_SUCCESS) {
        fprintf(stderr, "%s: cannot create the reusing context\n", config);
        ++test_failures;
        cacao_context_destroy(ctx);
        return NULL;
    }
    return ctx;
}

/* One frame of f on the context, a full one: the reference's output. */
static bool full_frame(vkdev *dev, cacao_context *ctx, const vkdev_frame *f, const float *ref, float *ao,
                       cacao_tile_counts *c, const char *what) {
    if (!step(dev, ctx, f, 1, ao, c)) return false;
    check_same(ao, ref, what);
    check_full(c, what);
    return true;
}

/* f with force_full_frame: a full frame, the reference's output. */
static bool forced_full_frame(vkdev *dev, cacao_context *ctx, vkdev_frame f, const float *ref, float *ao,
                              cacao_tile_counts *c) {
    f.force_full_frame = true;
    return full_frame(dev, ctx, &f, ref, ao, c, "forced full frame");
}

/* `repeat` frames of f on the context, the last with nothing to run: the reference's output. */
static bool nothing_to_do(vkdev *dev, cacao_context *ctx, const vkdev_frame *f, uint32_t repeat, const float *ref,
                          float *ao, cacao_tile_counts *c, const char *what) {
    if (!step(dev, ctx, f, repeat, ao, c)) return false;
    check_same(ao, ref, what);
    check_nothing_ran(c, what);
    return true;
}

/* n's normals with those of the pixels of the image's middle third that pick accepts tilted (a
 * new array; the caller frees it). */
static float *tilted_normals(const float *n, bool (*pick)(uint32_t x, uint32_t y)) {
    float *out = malloc((size_t)3 * W * H * sizeof(float));
    memcpy(out, n, (size_t)3 * W * H * sizeof(float));
    for (uint32_t y = H / 3; y < 2 * H / 3; ++y)
        for (uint32_t x = W / 3; x < 2 * W / 3; ++x) {
            if (!pick(x, y)) continue;
            float *v = &out[3 * ((size_t)y * W + x)];
            const float a = v[0] + 0.25f, b = v[1], c = v[2], len = sqrtf(a * a + b * b + c * c);
            if (len > 0.0f) v[0] = a / len, v[1] = b / len, v[2] = c / len;
        }
    return out;
}

static bool every_pixel(uint32_t x, uint32_t y) { return (void)x, (void)y, true; }
/* pixels whose normal no CACAO pass reads downsampled (the slices' texels take 4 t + 2 d: both
 * even), and at LOWEST native (slices 0 and 3, 2 t and 2 t + 1: x and y of the same parity) */
static bool unread_downsampled(uint32_t x, uint32_t y) { return ((x | y) & 1u) != 0; }
static bool unread_lowest_native(uint32_t x, uint32_t y) { return ((x ^ y) & 1u) != 0; }

/* With the caller's normals: the normals alone change (see the file's comment); the context ends
 * on the base frame. */
static void normals_only(vkdev *dev, cacao_context *ctx, const cacao_settings *s, const vkdev_frame *base,
                         const float *normals, const float *ref) {
    const size_t n = (size_t)W * H;
    float *ref_changed = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    float *tilted = tilted_normals(normals, every_pixel);
    cacao_tile_counts c;
    vkdev_frame f = *base;
    f.normals = tilted;
    if (reference(dev, *s, &f, ref_changed) && step(dev, ctx, &f, 1, ao, &c)) {
        check_same(ao, ref_changed, "normals changed");
        CHECK(c.changed > 0 && c.changed < c.tiles);
        if (step(dev, ctx, base, 1, ao, &c)) check_same(ao, ref, "normals back");
    }
    free(tilted);
    bool (*unread)(uint32_t, uint32_t) = s->downsample                          ? unread_downsampled
                                         : s->quality == CACAO_QUALITY_LOWEST ? unread_lowest_native
                                                                              : NULL;
    if (unread) {
        tilted = tilted_normals(normals, unread);
        f.normals = tilted;
        if (reference(dev, *s, &f, ref_changed)) {
            check_same(ref_changed, ref, "normals changed where no pass reads them (computed alone)");
            /* the diff compares every pixel's normal (comparing only those read measured no
             * faster on lavapipe: docs/tiles.md), so the region is recomputed, to the same output */
            if (step(dev, ctx, &f, 1, ao, &c)) {
                check_same(ao, ref, "normals changed where no pass reads them");
                CHECK(c.changed > 0);
            }
            if (step(dev, ctx, base, 1, ao, &c)) check_same(ao, ref, "normals back");
        }
        free(tilted);
    }
    free(ref_changed);
    free(ao);
}

/* The sequence of the file's comment for one configuration. */
static void sequence(vkdev *dev, const frames *fr, cacao_settings s, bool normals) {
    snprintf(config, sizeof config, "quality %d, %s, blur %d, normals %s, %s forms", (int)s.quality,
             s.downsample ? "downsampled" : "native", s.blur_pass_count, normals ? "given" : "from depth",
             s.shader_forms == CACAO_SHADER_FORMS_GPU ? "GPU" : "CPU");
    s.generate_normals = !normals;
    s.reuse_unchanged = true;
    const size_t n = (size_t)W * H;
    float *ref = malloc(n * sizeof(float)), *ref_moved = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    const vkdev_frame base = scene_frame(&fr->base, false, normals), moved = scene_frame(&fr->moved, false, normals);
    cacao_context *ctx = NULL;
    cacao_tile_counts c;
    if (!reference(dev, s, &base, ref) || !reference(dev, s, &moved, ref_moved)) goto done;
    if (!(ctx = reusing_context(dev, &s)) || !full_frame(dev, ctx, &base, ref, ao, &c, "first frame")) goto done;
    /* the same frame: nothing changed */
    if (!nothing_to_do(dev, ctx, &base, 1, ref, ao, &c, "unchanged frame")) goto done;
    /* one sphere moved */
    if (!step(dev, ctx, &moved, 1, ao, &c)) goto done;
    check_same(ao, ref_moved, "a sphere moved");
    CHECK(c.changed > 0 && c.changed < c.tiles / 8);
    /* the tiles whose output the move changed: reuse must recompute at least these */
    const uint32_t px = s.downsample ? 32 : 16, tx = (W + px - 1) / px;
    uint32_t moved_tiles = 0;
    for (uint32_t ty = 0; ty * px < H; ++ty)
        for (uint32_t x0 = 0; x0 < tx; ++x0) {
            bool differs = false;
            for (uint32_t y = ty * px; y < (ty + 1) * px && y < H; ++y)
                for (uint32_t x = x0 * px; x < (x0 + 1) * px && x < W; ++x)
                    differs |= memcmp(&ref[(size_t)y * W + x], &ref_moved[(size_t)y * W + x], sizeof(float)) != 0;
            moved_tiles += differs;
        }
    printf("%s: a sphere moved: %u of %u tiles changed, %u output tiles differ, %u recomputed, generate %u, blur %u of "
           "%u groups\n", config, c.changed, c.tiles, moved_tiles, c.recomputed, c.generate_run, c.blur_run, c.blur_total);
    CHECK(c.recomputed >= moved_tiles);
    if (s.quality == CACAO_QUALITY_HIGHEST) CHECK(c.recomputed == c.tiles);
    else {
        if (!(c.recomputed >= c.changed && c.recomputed < c.tiles))
            fprintf(stderr, "%s: a sphere moved: %u tiles changed, %u of %u recomputed\n", config, c.changed,
                    c.recomputed, c.tiles);
        CHECK(c.recomputed >= c.changed && c.recomputed < c.tiles);
        CHECK(c.generate_run < c.tiles);
    }
    if (normals) {
        if (!step(dev, ctx, &base, 1, ao, &c)) goto done;
        check_same(ao, ref, "back to the first frame");
        normals_only(dev, ctx, &s, &base, fr->base.normals, ref);
    }
    /* back to the first frame, then kept by the caller: the second run of two writes nothing */
    vkdev_frame keep = base;
    keep.output_holds_previous = true;
    if (!nothing_to_do(dev, ctx, &keep, 2, ref, ao, &c, "output kept by the caller")) goto done;
    /* the camera moved: another projection (a slightly wider field of view) */
    vkdev_frame camera = base;
    camera.projection[0] *= 0.99f;
    camera.projection[5] *= 0.99f;
    float *ref_camera = malloc(n * sizeof(float));
    if (reference(dev, s, &camera, ref_camera) && step(dev, ctx, &camera, 1, ao, &c)) {
        check_same(ao, ref_camera, "camera moved");
        check_full(&c, "camera moved");
        /* the camera stops: the frame after the move refreshes the copies the move skipped (a
         * full frame), the next reuses everything */
        if (step(dev, ctx, &camera, 1, ao, &c)) {
            check_same(ao, ref_camera, "camera stopped");
            check_full(&c, "camera stopped");
        }
        if (step(dev, ctx, &camera, 1, ao, &c)) {
            check_same(ao, ref_camera, "camera stopped, next frame");
            check_nothing_ran(&c, "camera stopped, next frame");
        }
    }
    free(ref_camera);
    forced_full_frame(dev, ctx, base, ref, ao, &c);
done:
    cacao_context_destroy(ctx);
    free(ref);
    free(ref_moved);
    free(ao);
}

/* The horizon estimators (GTAO, BITMASK): any change recomputes the whole frame, nothing changed
 * runs nothing but, where the output is not held, the last pass (the GPU forms; in the CPU forms
 * such a frame is a full one). Every frame bit for bit the reference's. */
static void horizon_sequence(vkdev *dev, const frames *fr, cacao_settings s, bool normals) {
    const bool gpu = s.shader_forms == CACAO_SHADER_FORMS_GPU;
    snprintf(config, sizeof config, "%s, quality %d, %s, blur %d, normals %s, %s forms",
             cacao_estimator_name(s.estimator), (int)s.quality, s.downsample ? "downsampled" : "native",
             s.blur_pass_count, normals ? "given" : "from depth", gpu ? "GPU" : "CPU");
    s.generate_normals = !normals;
    s.reuse_unchanged = true;
    const size_t n = (size_t)W * H;
    float *ref = malloc(n * sizeof(float)), *ref_moved = malloc(n * sizeof(float)), *ref_index = malloc(n * sizeof(float)),
          *ao = malloc(n * sizeof(float));
    const vkdev_frame base = scene_frame(&fr->base, false, normals);
    vkdev_frame kept = base, alternating = base, index = base, moved = base;
    moved.depth = fr->moved.depth; /* the alternating frames' (the normals stay the base frame's) */
    kept.output_holds_previous = true;
    alternating.output_holds_previous = true;
    alternating.alternate_depth = fr->moved.depth;
    index.frame_index = 5; /* another sample pattern: other constants */
    cacao_context *ctx = NULL;
    cacao_tile_counts c;
    if (!reference(dev, s, &base, ref) || !reference(dev, s, &moved, ref_moved) || !reference(dev, s, &index, ref_index))
        goto done;
    CHECK(memcmp(ref, ref_index, n * sizeof(float)) != 0); /* the frame index matters */
    if (!(ctx = reusing_context(dev, &s)) || !full_frame(dev, ctx, &base, ref, ao, &c, "first frame")) goto done;
    /* unchanged, the output held from the run's second frame (the CPU forms: a full frame with no
     * diff before it, then one refreshing the copies): nothing runs */
    if (!nothing_to_do(dev, ctx, &kept, 3, ref, ao, &c, "unchanged, output kept")) goto done;
    /* unchanged, the output not held: the GPU forms run the last pass alone, the CPU forms a full frame */
    if (!step(dev, ctx, &base, 1, ao, &c)) goto done;
    check_same(ao, ref, "unchanged, output not kept");
    if (gpu) CHECK(c.changed == 0 && c.recomputed == 0);
    else check_full(&c, "unchanged, output not kept (CPU forms)");
    /* frames alternating with one sphere moved, the output held: the last two reuse (after the
     * frame refreshing the copies the full one left stale in the CPU forms), each recomputing all */
    if (!step(dev, ctx, &alternating, 4, ao, &c)) goto done;
    check_same(ao, ref_moved, "a sphere moved");
    if (!(c.changed > 0 && c.changed < c.tiles / 8 && c.recomputed == c.tiles))
        fprintf(stderr, "%s, a sphere moved: changed %u, recomputed %u of %u tiles\n", config, c.changed, c.recomputed,
                c.tiles);
    CHECK(c.changed > 0 && c.changed < c.tiles / 8 && c.recomputed == c.tiles);
    /* back, then unchanged with the output held */
    if (!nothing_to_do(dev, ctx, &kept, 3, ref, ao, &c, "back, then unchanged")) goto done;
    /* another frame index: other constants, a full frame; then unchanged */
    if (!full_frame(dev, ctx, &index, ref_index, ao, &c, "another frame index")) goto done;
    index.output_holds_previous = true;
    if (!nothing_to_do(dev, ctx, &index, 3, ref_index, ao, &c, "another frame index, unchanged")) goto done;
    forced_full_frame(dev, ctx, kept, ref, ao, &c);
done:
    cacao_context_destroy(ctx);
    free(ref);
    free(ref_moved);
    free(ref_index);
    free(ao);
}

/* Settings changes, a resize, NaN in the depth and the alternating frames of one run. */
static void other_changes(vkdev *dev, const frames *fr) {
    const size_t n = (size_t)W * H;
    float *ref = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    cacao_settings s = {.quality = CACAO_QUALITY_HIGH, .generate_normals = true, .reuse_unchanged = true};
    snprintf(config, sizeof config, "quality high, native, normals from depth");
    vkdev_frame base = scene_frame(&fr->base, false, false);
    cacao_context *ctx = NULL;
    cacao_tile_counts c;
    if (vkdev_context_create(dev, &ctx) != CACAO_SUCCESS || cacao_context_set_settings(ctx, &s) != CACAO_SUCCESS ||
        cacao_context_resize(ctx, W, H, NULL) != CACAO_SUCCESS) {
        ++test_failures;
        goto done;
    }
    /* NaN that stays NaN is no change */
    vkdev_frame nan_frame = base;
    nan_frame.depth = fr->nan_depth;
    if (!reference(dev, s, &nan_frame, ref) || !step(dev, ctx, &nan_frame, 1, ao, &c)) goto done;
    check_same(ao, ref, "NaN depth, first frame");
    if (!nothing_to_do(dev, ctx, &nan_frame, 1, ref, ao, &c, "NaN depth, unchanged")) goto done;
    /* another radius: the constants differ, a full frame */
    s.radius = 0.8f;
    if (cacao_context_set_settings(ctx, &s) != CACAO_SUCCESS || cacao_context_resize(ctx, W, H, NULL) != CACAO_SUCCESS) {
        ++test_failures;
        goto done;
    }
    if (!reference(dev, s, &base, ref) || !step(dev, ctx, &base, 1, ao, &c)) goto done;
    check_same(ao, ref, "settings changed");
    check_full(&c, "settings changed");
    /* a resize to another size and back: full frames */
    scene_buffers small;
    const cacao_scene scene = cacao_default_scene(W / 2, H / 2);
    scene_buffers_render(&scene, &small);
    vkdev_frame small_frame = scene_frame(&small, false, false);
    float *small_ref = malloc(n / 4 * sizeof(float)), *small_ao = malloc(n / 4 * sizeof(float));
    if (cacao_context_resize(ctx, W / 2, H / 2, NULL) == CACAO_SUCCESS && reference(dev, s, &small_frame, small_ref) &&
        step(dev, ctx, &small_frame, 1, small_ao, &c)) {
        CHECK(memcmp(small_ref, small_ao, n / 4 * sizeof(float)) == 0);
        check_full(&c, "resized");
    }
    free(small_ref);
    free(small_ao);
    scene_buffers_free(&small);
    if (cacao_context_resize(ctx, W, H, NULL) != CACAO_SUCCESS || !step(dev, ctx, &base, 1, ao, &c)) {
        ++test_failures;
        goto done;
    }
    check_same(ao, ref, "resized back");
    check_full(&c, "resized back");
    /* one run alternating the two frames (the command's --move-box): its last frame (the fourth,
     * the moved one) is the moved frame's reference */
    vkdev_frame alternating = base;
    alternating.alternate_depth = fr->moved.depth;
    const vkdev_frame moved = scene_frame(&fr->moved, false, false);
    if (!reference(dev, s, &moved, ref)) goto done;
    if (!step(dev, ctx, &alternating, 4, ao, &c)) goto done;
    check_same(ao, ref, "alternating frames");
    CHECK(c.changed > 0 && c.recomputed < c.tiles);
    printf("alternating frames, quality high: %u tiles changed, %u recomputed, generate %u, blur %u of %u groups\n",
           c.changed, c.recomputed, c.generate_run, c.blur_run, c.blur_total);
done:
    cacao_context_destroy(ctx);
    free(ref);
    free(ao);
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    frames fr;
    render_frames(&fr);
    static const cacao_quality qualities[] = {CACAO_QUALITY_LOWEST, CACAO_QUALITY_LOW, CACAO_QUALITY_MEDIUM,
                                              CACAO_QUALITY_HIGH, CACAO_QUALITY_HIGHEST};
    for (int forms = 0; forms < 2; ++forms)
        for (int q = 0; q < 5; ++q)
            for (int ds = 0; ds < 2; ++ds) {
                const cacao_settings s = {.quality = qualities[q],
                                          .downsample = ds != 0,
                                          .shader_forms = forms ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU};
                sequence(&dev, &fr, s, false);
            }
    /* blur none and 8, and normals given, at two qualities */
    static const int blurs[] = {CACAO_BLUR_NONE, 8};
    for (int forms = 0; forms < 2; ++forms)
        for (int b = 0; b < 2; ++b) {
            cacao_settings s = {.quality = b ? CACAO_QUALITY_MEDIUM : CACAO_QUALITY_HIGH,
                                .blur_pass_count = blurs[b],
                                .shader_forms = forms ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU};
            sequence(&dev, &fr, s, false);
            sequence(&dev, &fr, s, true);
        }
    /* the caller's normals where the frame reads some of them only: LOWEST native, downsampled */
    for (int forms = 0; forms < 2; ++forms) {
        const cacao_shader_forms f = forms ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU;
        sequence(&dev, &fr, (cacao_settings){.quality = CACAO_QUALITY_LOWEST, .shader_forms = f}, true);
        sequence(&dev, &fr, (cacao_settings){.quality = CACAO_QUALITY_LOW, .downsample = true, .shader_forms = f}, true);
        sequence(&dev, &fr, (cacao_settings){.quality = CACAO_QUALITY_HIGH, .downsample = true, .shader_forms = f}, true);
    }
    other_changes(&dev, &fr);
    /* the horizon estimators: both, both forms, native with no denoise pass and with 2, downsampled
     * with 1, normals from depth and given */
    for (int forms = 0; forms < 2; ++forms)
        for (int e = 0; e < 2; ++e) {
            const cacao_estimator est = e ? CACAO_ESTIMATOR_BITMASK : CACAO_ESTIMATOR_GTAO;
            const cacao_shader_forms f = forms ? CACAO_SHADER_FORMS_GPU : CACAO_SHADER_FORMS_CPU;
            horizon_sequence(&dev, &fr,
                             (cacao_settings){.estimator = est, .quality = CACAO_QUALITY_LOW, .blur_pass_count = CACAO_BLUR_NONE,
                                              .shader_forms = f},
                             e == 0);
            horizon_sequence(&dev, &fr,
                             (cacao_settings){.estimator = est, .quality = CACAO_QUALITY_LOWEST, .blur_pass_count = 2, .shader_forms = f},
                             e != 0);
            horizon_sequence(&dev, &fr,
                             (cacao_settings){.estimator = est, .quality = CACAO_QUALITY_LOW, .downsample = true, .shader_forms = f},
                             false);
        }
    free_frames(&fr);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_reuse");
}
