/* test_estimators - the horizon-slice estimators (GTAO, visibility bitmask) against facts known
 * independently of this implementation:
 *  - the synthetic crease of shared/spec/estimators.md section 9.3: per-row means of the spec's
 *    double-precision prototype (raw output, columns 400-559) and the closed-form visibility of a
 *    floor point at distance c R from a wall (V_fall, V_bin, section 9.1);
 *  - past the image's edge a plane goes on: a crop whose border lies on one gives the whole
 *    frame's visibility;
 *  - unoccluded planes give 1 (the normalisation by the unoccluded slice weight, section 9.2),
 *    through a perspective and an orthographic camera;
 *  - the bottom of a V-groove of opening alpha sees sin(alpha / 2) (edge formula, section 9.1);
 *  - invariances any correct implementation has: standard vs reverse-Z depth, world scale, NaN and
 *    Inf depth treated exactly as background, a 64-frame noise period, and frame accumulation
 *    converging towards a 4x larger budget.
 * With the shared scenes (argv[1]): RMSE against the ray-traced truths at every quality level
 * (test_shared_scenes says what is bounded and why). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

static const double pi = 3.14159265358979323846;

/* The crease of section 9.3 as a 320x540 crop (columns 320-639 of the 960x540 frame: the same
 * pixel centres, the same 64-pixel noise tiles, and every sample of columns 400-559 inside it). */
#define CREASE_W 320
#define CREASE_H 540
#define CREASE_X0 320 /* crop offset: columns 400-559 of the frame are 80..239 here */

static const cacao_prim crease_prims[] = {
    {.kind = CACAO_PRIM_PLANE, .a = {0, 0, 0}, .b = {0, 1, 0}},  /* floor, 1.6 below the eye */
    {.kind = CACAO_PRIM_PLANE, .a = {0, 0, -5}, .b = {0, 0, 1}}, /* wall, axial distance 5 */
};

static cacao_scene crease_scene(uint32_t prim_count, const cacao_prim *prims) {
    return (cacao_scene){.prims = prims,
                         .prim_count = prim_count,
                         .camera = {.width = CREASE_W,
                                    .height = CREASE_H,
                                    .fov_y_deg = 60.0,
                                    .near_z = 0.05,
                                    .far_z = 100.0,
                                    .eye = {0, 1.6, 0},
                                    .target = {0, 1.6, -1},
                                    .up = {0, 1, 0}},
                         .ao_radius_world = 0.5};
}

/* Spec section 9.3: rows, c = d / R, and the prototype's raw row means. */
static const int crease_rows[] = {209, 396, 404, 412, 418, 420, 424, 428, 432, 440};
#define CREASE_ROWS 10
typedef struct crease_config {
    const char *name;
    cacao_estimator estimator;
    cacao_visibility visibility;
    int slices, steps;
    double prototype[CREASE_ROWS];
} crease_config;
static const crease_config crease_configs[] = {
    {"gtao-f 3x3",
     CACAO_ESTIMATOR_GTAO,
     CACAO_VISIBILITY_FALLOFF,
     3,
     3,
     {0.9999, 0.9700, 0.9252, 0.8166, 0.6325, 0.6105, 0.8650, 0.9533, 0.9850, 0.9957}},
    {"gtao-f 4x8",
     CACAO_ESTIMATOR_GTAO,
     CACAO_VISIBILITY_FALLOFF,
     4,
     8,
     {0.9997, 0.9359, 0.8610, 0.7166, 0.5454, 0.5776, 0.8254, 0.9346, 0.9746, 0.9907}},
    {"gtao-f 8x16",
     CACAO_ESTIMATOR_GTAO,
     CACAO_VISIBILITY_FALLOFF,
     8,
     16,
     {0.9996, 0.9275, 0.8421, 0.6931, 0.5374, 0.5707, 0.8185, 0.9281, 0.9693, 0.9860}},
    {"bitmask-f 4x8",
     CACAO_ESTIMATOR_BITMASK,
     CACAO_VISIBILITY_FALLOFF,
     4,
     8,
     {1.0000, 0.9426, 0.8628, 0.7255, 0.5719, 0.5743, 0.8182, 0.9427, 0.9914, 0.9986}},
    {"bitmask-f 8x16",
     CACAO_ESTIMATOR_BITMASK,
     CACAO_VISIBILITY_FALLOFF,
     8,
     16,
     {1.0000, 0.9290, 0.8415, 0.7020, 0.5495, 0.5640, 0.8071, 0.9331, 0.9874, 0.9979}},
    {"bitmask-b 4x8",
     CACAO_ESTIMATOR_BITMASK,
     CACAO_VISIBILITY_BINARY,
     4,
     8,
     {1.0000, 0.8510, 0.7450, 0.6313, 0.5402, 0.5352, 0.7025, 0.8491, 0.9510, 0.9986}},
    {"bitmask-b 8x16",
     CACAO_ESTIMATOR_BITMASK,
     CACAO_VISIBILITY_BINARY,
     8,
     16,
     {1.0000, 0.8313, 0.7326, 0.6212, 0.5296, 0.5272, 0.6920, 0.8305, 0.9401, 0.9979}},
};

/* Closed forms of section 9.1: a floor point at distance c R from an infinite wall. */
static double v_bin(double c) { return c >= 1 ? 1 : 1 - (acos(c) - c * sqrt(1 - c * c)) / pi; }
static double v_fall(double c) { return c >= 1 ? 1 : 1 - ((1 + 2 * c * c) * acos(c) - 3 * c * sqrt(1 - c * c)) / pi; }

/* c = d / R of a crease row in the 960x540 frame (section 9.3). */
static double crease_c(int row) {
    const double ry = (1 - 2 * (row + 0.5) / 540.0) * tan(pi / 6);
    const double z = ry < 0 ? fmin(5.0, 1.6 / -ry) : 5.0;
    const bool floor_row = ry < 0 && 1.6 / -ry < 5.0;
    return (floor_row ? 5.0 - z : 1.6 + 5.0 * ry) / 0.5;
}

static double row_mean(const float *ao, uint32_t width, int row, uint32_t x0, uint32_t x1) {
    double sum = 0;
    for (uint32_t x = x0; x <= x1; ++x) sum += ao[(size_t)row * width + x];
    return sum / (x1 - x0 + 1);
}

static cacao_settings slice_settings(cacao_estimator e, cacao_visibility v, int slices, int steps, float radius) {
    return (cacao_settings){.estimator = e,
                            .visibility = v,
                            .horizon_slices = slices,
                            .horizon_steps = steps,
                            .radius = radius,
                            .blur_pass_count = CACAO_BLUR_NONE,
                            .fade_out_from = 1e6f,
                            .fade_out_to = 2e6f};
}

/* Against the spec's prototype and the closed forms, per configuration:
 *  - wall rows (396-418) within 0.01 of the prototype's row means (a few thousandths of
 *    fp32-vs-double and depth-buffer rounding);
 *  - over all rows, the mean |row mean - closed form| at most the prototype's, plus 0.001 for the
 *    rounding the wall rows show (measured up to 0.0010; the mean errors differ by -0.0014 to
 *    +0.0005). The floor rows
 *    differ from the prototype's by design: cacao keeps a snapped sample's height above the
 *    tangent plane where the prototype drops its offset from the slice plane (horizon.glsl,
 *    make_horizon_frame; the prototype's open floor, row 440, is 0.986 at GTAO 8x16 where the truth
 *    is 1), so they move, on the whole, towards the truth;
 *  - bitmask-f 8x16 floor rows within 0.01 of V_fall, what the spec reports for its prototype. */
static void test_crease(vkdev *dev) {
    const cacao_scene scene = crease_scene(2, crease_prims);
    scene_buffers b;
    scene_buffers_render(&scene, &b);
    float *ao = malloc(sizeof(float) * CREASE_W * CREASE_H);
    for (size_t k = 0; k < sizeof crease_configs / sizeof crease_configs[0]; ++k) {
        const crease_config *cc = &crease_configs[k];
        const cacao_settings s = slice_settings(cc->estimator, cc->visibility, cc->slices, cc->steps, 0.5f);
        vkdev_frame f = scene_frame(&b, false, true);
        if (!run(dev, &s, &f, ao)) continue;
        double worst = 0, worst_analytic = 0, error = 0, prototype_error = 0;
        for (int r = 0; r < CREASE_ROWS; ++r) {
            const int row = crease_rows[r];
            const double m = row_mean(ao, CREASE_W, row, 400 - CREASE_X0, 559 - CREASE_X0);
            const double c = crease_c(row);
            const double truth = cc->visibility == CACAO_VISIBILITY_BINARY ? v_bin(c) : v_fall(c);
            const bool floor_row = row >= 420;
            if (!floor_row && row != 209) worst = fmax(worst, fabs(m - cc->prototype[r]));
            if (floor_row) worst_analytic = fmax(worst_analytic, fabs(m - truth));
            error += fabs(m - truth) / CREASE_ROWS;
            prototype_error += fabs(cc->prototype[r] - truth) / CREASE_ROWS;
            printf("crease %-14s row %d c %.3f: %.4f (prototype %.4f, closed form %.4f)\n", cc->name, row, c, m,
                   cc->prototype[r], truth);
        }
        printf("crease %-14s: wall rows vs prototype worst %.4f; mean |row - closed form| %.4f (prototype %.4f); "
               "floor rows vs closed form worst %.4f\n",
               cc->name, worst, error, prototype_error, worst_analytic);
        CHECK(worst <= 0.01);
        CHECK(error <= prototype_error + 0.001);
        if (strcmp(cc->name, "bitmask-f 8x16") == 0) CHECK(worst_analytic <= 0.01);
    }
    free(ao);
    scene_buffers_free(&b);
}

/* Samples past the image's edge: the surface is taken to go on as the tangent plane of the last
 * pixel on the slice's line (horizon.glsl, side_plane). Exact where the surface there is one plane
 * that goes on: a far wall seen through a square hole in a nearer one (1 unit in front of it,
 * facing the camera), in a 960x540 frame and in a 64x156 crop of its middle (the same pixel
 * centres and, at offsets that are multiples of 64, the same noise) whose border lies on the
 * nearer wall. With the radius 2, samples reach 117 pixels from the far wall and 133 from the
 * nearer one: the crop's leave it and meet the nearer wall past its edge, the frame's stay in it.
 * The crop must give the frame's visibility. The spec's prototype's rule (a side stops at its
 * first sample past the edge) differed by up to 0.45 (GTAO) and 0.34 (bitmask) in a pixel here.
 * This rule: 0 (lavapipe); bound 0.01 per pixel, for a driver whose rounding of the plane's
 * intersection differs from its read of a stored view z. */
static void test_past_edge(vkdev *dev) {
    enum { CROP_W = 64, CROP_H = 156, CROP_X0 = (960 - CROP_W) / 2, CROP_Y0 = (540 - CROP_H) / 2 };
    static const cacao_prim prims[] = {
        {.kind = CACAO_PRIM_PLANE, .a = {0, 0, -8}, .b = {0, 0, 1}}, /* the far wall */
        /* the nearer wall, its front at z = -7, around the hole x in [-0.4, 0.4], y in [1.2, 2] */
        {.kind = CACAO_PRIM_BOX, .a = {-100, -100, -7.3}, .b = {-0.4, 100, -7}},
        {.kind = CACAO_PRIM_BOX, .a = {0.4, -100, -7.3}, .b = {100, 100, -7}},
        {.kind = CACAO_PRIM_BOX, .a = {-0.4, 2.0, -7.3}, .b = {0.4, 100, -7}},
        {.kind = CACAO_PRIM_BOX, .a = {-0.4, -100, -7.3}, .b = {0.4, 1.2, -7}},
    };
    cacao_scene frame = crease_scene(5, prims);
    frame.camera.width = 960;
    frame.camera.height = 540;
    frame.ao_radius_world = 2.0;
    cacao_scene crop = frame;
    crop.camera.width = CROP_W;
    crop.camera.height = CROP_H;
    crop.camera.fov_y_deg = 2.0 * atan(tan(pi / 6) * CROP_H / 540.0) * 180.0 / pi;
    scene_buffers bf, bc;
    scene_buffers_render(&frame, &bf);
    scene_buffers_render(&crop, &bc);
    float *af = malloc(sizeof(float) * 960 * 540), *ac = malloc(sizeof(float) * CROP_W * CROP_H);
    static const cacao_estimator estimators[] = {CACAO_ESTIMATOR_GTAO, CACAO_ESTIMATOR_BITMASK};
    for (int e = 0; e < 2; ++e) {
        const cacao_settings s = slice_settings(estimators[e], CACAO_VISIBILITY_FALLOFF, 4, 8, 2.0f);
        vkdev_frame ff = scene_frame(&bf, false, true), fc = scene_frame(&bc, false, true);
        if (!run(dev, &s, &ff, af) || !run(dev, &s, &fc, ac)) continue;
        double worst = 0, occlusion = 0;
        for (uint32_t y = 0; y < CROP_H; ++y)
            for (uint32_t x = 0; x < CROP_W; ++x) {
                const float c = ac[(size_t)y * CROP_W + x], f = af[(size_t)(y + CROP_Y0) * 960 + x + CROP_X0];
                worst = fmax(worst, fabs(c - f));
                occlusion = fmax(occlusion, 1.0 - f);
            }
        printf("past the edge, %s 4x8: the 64x156 crop against the frame, worst pixel difference %.5f "
               "(the frame's deepest occlusion there %.3f)\n",
               cacao_estimator_name(estimators[e]), worst, occlusion);
        CHECK(occlusion > 0.1); /* the nearer wall occludes the far one */
        CHECK(worst <= 0.01);
    }
    free(af);
    free(ac);
    scene_buffers_free(&bf);
    scene_buffers_free(&bc);
}

/* Unoccluded surfaces give 1 at every budget: a wall facing the camera, and a floor alone seen at
 * grazing angles (the spec's prototype darkens them by pixel snapping, GTAO most: its pitfall 6
 * reports row means 0.991 at 4x8 and 0.986 at 8x16 for GTAO, 0.999 / 0.998 for the bitmask). */
static void test_unoccluded(vkdev *dev) {
    const cacao_prim wall[] = {crease_prims[1]}, floor_only[] = {crease_prims[0]};
    const struct {
        const char *name;
        const cacao_prim *prims;
    } cases[] = {{"wall", wall}, {"floor", floor_only}};
    float *ao = malloc(sizeof(float) * CREASE_W * CREASE_H);
    /* through the crease's perspective camera, and an orthographic one (its own branch of the
     * view rays: the bitmask's thickness interval once ran towards the camera there, and the
     * wall came out at 0.2, the floor at 0.09) */
    for (int ortho = 0; ortho < 2; ++ortho)
    for (int c = 0; c < 2; ++c) {
        cacao_scene scene = crease_scene(1, cases[c].prims);
        const cacao_lens lens = {.ortho_half_height = ortho ? 3.0 : 0.0};
        if (ortho) { /* looking down 30 degrees: parallel rays see a level floor only from above */
            scene.camera.eye[1] = 3.0;
            scene.camera.target[1] = 3.0 - 0.57735;
        }
        scene_buffers b;
        scene_buffers_render_lens(&scene, &lens, &b);
        for (int e = CACAO_ESTIMATOR_GTAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
            for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; q += 2) {
                cacao_settings s = slice_settings(e, CACAO_VISIBILITY_FALLOFF, 0, 0, 0.5f);
                s.quality = q;
                vkdev_frame f = scene_frame(&b, false, true);
                if (!run(dev, &s, &f, ao)) continue;
                double lowest = 1, mean = 0;
                size_t counted = 0;
                for (size_t i = 0; i < (size_t)CREASE_W * CREASE_H; ++i) {
                    if (b.depth[i] >= 1.0f) continue;
                    lowest = fmin(lowest, ao[i]);
                    mean += ao[i];
                    ++counted;
                }
                CHECK(counted > 0);
                mean /= (double)(counted ? counted : 1);
                printf("unoccluded %-5s %-12s %-7s quality %d: mean %.5f, lowest %.5f\n", cases[c].name,
                       ortho ? "orthographic" : "perspective", cacao_estimator_name(e), q, mean, lowest);
                CHECK(all_finite_unit(ao, (size_t)CREASE_W * CREASE_H));
                /* Means over the image. A snapped sample keeps its height above the tangent plane
                 * (horizon.glsl, make_horizon_frame), so a plane occludes nothing of itself: the
                 * wall is 1 (measured 1.00000 at every level, both cameras; the spec's prototype,
                 * which drops the offset instead, has 0.9996-0.9999 for GTAO). What remains on the
                 * perspective floor is depth-buffer precision towards the horizon, where the view
                 * z of neighbouring rows steps (lowest printed; measured means GTAO 0.9885-0.9964,
                 * bitmask 0.9934-0.9978, LOWEST's one slice the darkest). */
                const bool bitmask = e == CACAO_ESTIMATOR_BITMASK;
                if (c == 0) {
                    CHECK(mean >= 0.99999);
                } else if (!ortho) {
                    CHECK(mean >= (bitmask ? 0.99 : 0.98));
                } else {
                    /* orthographic floor, seen from 30 degrees above: measured GTAO 0.99994,
                     * bitmask 1.00000 at every level, with the BOUND() margin of
                     * test_amd_reference on 1 - mean */
                    const double measured = bitmask ? 1.0 : 0.99994;
                    CHECK(1.0 - mean <= 1.25 * (1.0 - measured) + 0.02 / 255.0);
                }
            }
        scene_buffers_free(&b);
    }
    free(ao);
}

/* The bottom of a V-groove of opening alpha, normal along the bisector, sees sin(alpha / 2). The
 * camera looks straight down at the groove; the image's middle row lies on the bottom line. Unlike
 * the crease rows, no prototype value exists here: the bound is the closed form's. */
static void test_groove(vkdev *dev) {
    const uint32_t w = 161, h = 161;
    float *ao = malloc(sizeof(float) * w * h);
    const double openings[] = {90.0, 120.0};
    for (int k = 0; k < 2; ++k) {
        const double half = openings[k] * pi / 360.0;
        const cacao_prim groove[] = {
            {.kind = CACAO_PRIM_PLANE, .a = {0, 0, 0}, .b = {0, sin(half), -cos(half)}},
            {.kind = CACAO_PRIM_PLANE, .a = {0, 0, 0}, .b = {0, sin(half), cos(half)}},
        };
        const cacao_scene scene = {.prims = groove,
                                   .prim_count = 2,
                                   .camera = {.width = w,
                                              .height = h,
                                              .fov_y_deg = 40.0,
                                              .near_z = 0.05,
                                              .far_z = 100.0,
                                              .eye = {0, 3, 0},
                                              .target = {0, 0, 0},
                                              .up = {0, 0, -1}},
                                   .ao_radius_world = 0.5};
        scene_buffers b;
        scene_buffers_render(&scene, &b);
        /* the bottom row's normal is the bisector: the mean of the two faces' normals */
        const uint32_t mid = h / 2;
        for (uint32_t x = 0; x < w; ++x) {
            float *n = &b.normals[3 * ((size_t)mid * w + x)];
            const float *up = &b.normals[3 * ((size_t)(mid - 1) * w + x)],
                        *dn = &b.normals[3 * ((size_t)(mid + 1) * w + x)];
            double s[3], len = 0;
            for (int j = 0; j < 3; ++j) s[j] = (double)up[j] + dn[j], len += s[j] * s[j];
            for (int j = 0; j < 3; ++j) n[j] = (float)(s[j] / sqrt(len));
        }
        const double truth = sin(half);
        for (int e = CACAO_ESTIMATOR_GTAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
            for (int v = CACAO_VISIBILITY_FALLOFF; v <= CACAO_VISIBILITY_BINARY; ++v) {
                const cacao_settings s = slice_settings(e, v, 8, 16, 0.5f);
                vkdev_frame f = scene_frame(&b, false, true);
                if (!run(dev, &s, &f, ao)) continue;
                const double m = row_mean(ao, w, (int)mid, 40, w - 41);
                printf("V-groove %.0f deg, %s %s 8x16: bottom row %.4f, closed form sin(alpha/2) %.4f\n", openings[k],
                       cacao_estimator_name(e), cacao_visibility_name(v), m, truth);
                /* measured 0.023-0.052 below: the groove runs along a pixel row, so samples snapped
                 * to the next row sit on a wall at a steeper elevation than the slice's own (spec
                 * pitfall 6); both estimators share it. Bound: 1.25 x the worst. */
                CHECK(m < truth && truth - m <= 0.065);
            }
        scene_buffers_free(&b);
    }
    free(ao);
}

/* The same geometry in reverse-Z depth, and at world scales 1e-3..1e3 (radius, near, far scaled),
 * gives the same AO: the estimators see only view-space vectors and their ratios. */
static void test_invariance(vkdev *dev) {
    const uint32_t w = 320, h = 180;
    const size_t n = (size_t)w * h;
    float *ref = malloc(sizeof(float) * n), *ao = malloc(sizeof(float) * n);
    const cacao_scene base = cacao_default_scene(w, h);
    cacao_prim prims[64];
    for (int ds = 0; ds < 2; ++ds)
    for (int e = CACAO_ESTIMATOR_GTAO; e <= CACAO_ESTIMATOR_BITMASK; ++e) {
        scene_buffers b;
        scene_buffers_render(&base, &b);
        cacao_settings s = slice_settings(e, CACAO_VISIBILITY_FALLOFF, 0, 0, (float)base.ao_radius_world);
        s.blur_pass_count = 0; /* the default denoise pass (downsampled: the upsample) */
        s.downsample = ds != 0;
        vkdev_frame f = scene_frame(&b, false, true), fr = scene_frame(&b, true, true);
        if (run(dev, &s, &f, ref) && run(dev, &s, &fr, ao)) {
            const double m = mean_abs_diff(ref, ao, n);
            printf("%s%s reverse-Z vs standard: mean |diff| %.6f\n", cacao_estimator_name(e), ds ? " downsampled" : "",
                   m);
            CHECK(m < 0.5 / 255.0);
        }
        scene_buffers_free(&b);
        const double scales[] = {1e-3, 1e3};
        for (int k = 0; k < 2; ++k) {
            const double sc = scales[k];
            const cacao_scene scene = scene_scaled(&base, sc, prims, 64);
            scene_buffers bs;
            scene_buffers_render(&scene, &bs);
            cacao_settings ss = s;
            ss.radius = (float)(base.ao_radius_world * sc);
            ss.fade_out_from = (float)(1e6 * sc), ss.fade_out_to = (float)(2e6 * sc);
            vkdev_frame fs = scene_frame(&bs, false, true);
            if (run(dev, &ss, &fs, ao)) {
                const double m = mean_abs_diff(ref, ao, n);
                printf("%s%s world scale x%g vs x1: mean |diff| %.6f\n", cacao_estimator_name(e),
                       ds ? " downsampled" : "", sc, m);
                CHECK(m <= 1.0 / 255.0);
            }
            scene_buffers_free(&bs);
        }
    }
    free(ref);
    free(ao);
}

/* NaN, +Inf and -Inf depth are background, exactly: the output equals that of the same frame with
 * those pixels at the far plane (depth 1), and stays in [0,1]. Reconstructed normals, so the bad
 * block also reaches the normals of its neighbours. */
static void test_invalid_depth(vkdev *dev) {
    scene_buffers b;
    const float radius = scene_buffers_default(256, 144, &b);
    const size_t n = (size_t)b.width * b.height;
    float *dirty_depth = malloc(sizeof(float) * n), *far_depth = malloc(sizeof(float) * n);
    float *dirty = malloc(sizeof(float) * n), *far = malloc(sizeof(float) * n);
    memcpy(dirty_depth, b.depth, sizeof(float) * n);
    memcpy(far_depth, b.depth, sizeof(float) * n);
    for (uint32_t y = 60; y < 76; ++y)
        for (uint32_t x = 100; x < 130; ++x) {
            const size_t i = (size_t)y * b.width + x;
            dirty_depth[i] = x % 3 == 0 ? NAN : (x % 3 == 1 ? INFINITY : -INFINITY);
            far_depth[i] = 1.0f;
        }
    for (int ds = 0; ds < 2; ++ds)
    for (int e = CACAO_ESTIMATOR_GTAO; e <= CACAO_ESTIMATOR_BITMASK; ++e) {
        cacao_settings s = slice_settings(e, CACAO_VISIBILITY_FALLOFF, 0, 0, radius);
        s.generate_normals = true;
        s.blur_pass_count = 2;
        s.downsample = ds != 0;
        vkdev_frame f = scene_frame(&b, false, false);
        f.depth = dirty_depth;
        if (!run(dev, &s, &f, dirty)) continue;
        f.depth = far_depth;
        if (!run(dev, &s, &f, far)) continue;
        size_t differ = 0;
        for (size_t i = 0; i < n; ++i) differ += dirty[i] != far[i];
        printf("%s%s NaN/Inf block vs the same block at the far plane: %zu pixels differ\n", cacao_estimator_name(e),
               ds ? " downsampled" : "", differ);
        CHECK(all_finite_unit(dirty, n));
        CHECK(differ == 0);
    }
    free(dirty_depth);
    free(far_depth);
    free(dirty);
    free(far);
    scene_buffers_free(&b);
}

/* cacao_inputs.frame_index: frames differ, the pattern repeats after 64 frames, and the mean of 16
 * frames at 4x8 lies closer to the 8x16 result (4x the reads) than one frame does. */
static void test_frames(vkdev *dev) {
    scene_buffers b;
    const float radius = scene_buffers_default(320, 180, &b);
    const size_t n = (size_t)b.width * b.height;
    float *ref = malloc(sizeof(float) * n), *ao = malloc(sizeof(float) * n), *first = malloc(sizeof(float) * n);
    double *sum = calloc(n, sizeof(double));
    cacao_settings s = slice_settings(CACAO_ESTIMATOR_BITMASK, CACAO_VISIBILITY_FALLOFF, 8, 16, radius);
    vkdev_frame f = scene_frame(&b, false, true);
    run(dev, &s, &f, ref);
    s.horizon_slices = 4;
    s.horizon_steps = 8;
    double rmse[3] = {0}; /* mean of 1, 4 and 16 frames against the 8x16 result */
    for (uint32_t frame = 0; frame < 16; ++frame) {
        f.frame_index = frame;
        if (!run(dev, &s, &f, frame == 0 ? first : ao)) continue;
        const float *out = frame == 0 ? first : ao;
        if (frame == 1) CHECK(mean_abs_diff(first, ao, n) > 0.001); /* another sample pattern */
        for (size_t i = 0; i < n; ++i) sum[i] += out[i];
        if (frame == 0 || frame == 3 || frame == 15) {
            double se = 0;
            for (size_t i = 0; i < n; ++i) se += (sum[i] / (frame + 1) - ref[i]) * (sum[i] / (frame + 1) - ref[i]);
            rmse[frame == 0 ? 0 : frame == 3 ? 1 : 2] = sqrt(se / (double)n);
        }
    }
    f.frame_index = 64;
    if (run(dev, &s, &f, ao)) CHECK(memcmp(ao, first, sizeof(float) * n) == 0); /* period 64 */
    printf("frames: RMSE vs 8x16 of the mean of 1, 4, 16 frames at 4x8: %.5f, %.5f, %.5f\n", rmse[0], rmse[1], rmse[2]);
    /* measured 0.0147, -, 0.0098: the noise averages out, the 4x8-vs-8x16 bias stays */
    CHECK(rmse[2] < rmse[1] && rmse[1] < rmse[0] && rmse[2] < 0.75 * rmse[0]);
    free(ref);
    free(ao);
    free(first);
    free(sum);
    scene_buffers_free(&b);
}

/* RMSE of ao against truth over the scene's foreground (depth < 1, finite truth). */
static double scene_rmse(const float *ao, const float *truth, const float *depth, size_t n) {
    double se = 0;
    size_t counted = 0;
    for (size_t i = 0; i < n; ++i) {
        if (depth[i] >= 1.0f || !isfinite(truth[i])) continue;
        const double d = (double)ao[i] - truth[i];
        se += d * d;
        ++counted;
    }
    return counted ? sqrt(se / (double)counted) : INFINITY;
}

/* The shared scenes: native, fp32, the scenes' normals, one parameter set, default denoise, RMSE
 * over non-background pixels. Bounds: the figures measured at the budgets of docs/estimators.md
 * (issue 34), 3e-4 above them; and three properties of the quality levels that do not depend
 * on those figures (issue 34's targets):
 *  - no quality level of an estimator is less accurate than a lower one, on any scene, native
 *    and downsampled;
 *  - each estimator's LOWEST (native) is more accurate than AMD CACAO's LOWEST (its own output,
 *    reference-amd/<scene>/LOWEST_native.png) on every scene;
 *  - the bitmask's HIGHEST has a mean RMSE over the three scenes <= 0.048. */
static void test_shared_scenes(vkdev *dev, const char *shared) {
    static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};
    static const cacao_estimator estimators[] = {CACAO_ESTIMATOR_GTAO, CACAO_ESTIMATOR_BITMASK};
    /* measured (lavapipe), per level LOWEST..HIGHEST, interior/statues/street:
     * gtao .0884/.0522/.0673, .0837/.0326/.0630, .0772/.0285/.0529, .0760/.0265/.0462, .0752/.0258/.0458;
     * bitmask .0996/.0436/.0737, .0868/.0389/.0641, .0752/.0237/.0541, .0716/.0219/.0509, .0692/.0207/.0474 */
    static const double bound[2][2][5][3] = {
        {
            {{0.0887, 0.0525, 0.0676},
             {0.0840, 0.0329, 0.0633},
             {0.0775, 0.0288, 0.0532},
             {0.0763, 0.0268, 0.0465},
             {0.0755, 0.0261, 0.0461}},
            {{0.0999, 0.0439, 0.0740},
             {0.0871, 0.0392, 0.0644},
             {0.0755, 0.0240, 0.0544},
             {0.0719, 0.0222, 0.0512},
             {0.0695, 0.0210, 0.0477}},
        },
        /* downsampled, measured: gtao .0959/.0574/.0702, .0882/.0355/.0640, .0814/.0319/.0543,
         * .0789/.0294/.0472, .0780/.0281/.0466; bitmask .1050/.0481/.0752, .0930/.0443/.0662, .0791/.0275/.0548,
         * .0756/.0259/.0516, .0733/.0246/.0483 */
        {
            {{0.0962, 0.0577, 0.0705},
             {0.0885, 0.0358, 0.0643},
             {0.0817, 0.0322, 0.0546},
             {0.0792, 0.0297, 0.0475},
             {0.0783, 0.0284, 0.0469}},
            {{0.1053, 0.0484, 0.0755},
             {0.0933, 0.0446, 0.0665},
             {0.0794, 0.0278, 0.0551},
             {0.0759, 0.0262, 0.0519},
             {0.0736, 0.0249, 0.0486}},
        },
    };
    /* binary visibility against ao_gt, bitmask HIGHEST: measured .0868/.0279/.0607 */
    static const double binary_bound[3] = {0.0871, 0.0282, 0.0610};
    /* temporal accumulation, bitmask HIGHEST downsampled after 8 frames of a still camera
     * (frame_index 0..7): measured .0705/.0222/.0466 (one frame: .0733/.0246/.0483) */
    static const double temporal_bound[3] = {0.0708, 0.0225, 0.0469};
    double temporal_sum = 0;
    int temporal_scenes = 0;
    double highest_sum = 0;
    int highest_scenes = 0;
    for (int k = 0; k < 3; ++k) {
        char path[4096], err[512];
        cacao_img depth = {0}, normals = {0}, gt = {0}, gt_falloff = {0}, amd = {0};
        cacao_camera_file cam;
        bool amd16 = false;
        if (!load_shared_scene(shared, scenes[k], &depth, &gt_falloff, &cam)) continue;
        snprintf(path, sizeof path, "%s/scenes/%s/normals.pfm", shared, scenes[k]);
        bool ok = cacao_pfm_read(path, &normals, err, sizeof err);
        snprintf(path, sizeof path, "%s/scenes/%s/ao_gt.pfm", shared, scenes[k]);
        ok = ok && cacao_pfm_read(path, &gt, err, sizeof err);
        snprintf(path, sizeof path, "%s/reference-amd/%s/LOWEST_native.png", shared, scenes[k]);
        ok = ok && cacao_png_read(path, &amd, &amd16, err, sizeof err) && amd.channels == 1 &&
             amd.width == depth.width && amd.height == depth.height;
        if (!ok) fprintf(stderr, "%s: %s\n", scenes[k], err);
        CHECK(ok);
        const size_t n = (size_t)depth.width * depth.height;
        float *ao = malloc(sizeof(float) * n);
        const double amd_lowest = ok ? scene_rmse(amd.data, gt_falloff.data, depth.data, n) : 0;
        if (ok) printf("%-17s AMD CACAO LOWEST (reference output) vs ao_gt_falloff RMSE %.4f\n", scenes[k], amd_lowest);
        vkdev_frame f = {.width = depth.width, .height = depth.height, .depth = depth.data};
        memcpy(f.projection, cam.projection, sizeof f.projection);
        vkdev_frame_set_view_normals(&f, normals.data);
        for (int ds = 0; ok && ds < 2; ++ds)
        for (int e = 0; ok && e < 2; ++e) {
            double previous = INFINITY;
            for (int q = 0; q < 5; ++q) {
                cacao_settings s =
                    slice_settings(estimators[e], CACAO_VISIBILITY_FALLOFF, 0, 0, (float)cam.ao_radius_world);
                s.quality = (cacao_quality)(CACAO_QUALITY_LOWEST + q);
                s.downsample = ds != 0;
                s.blur_pass_count = 0; /* default: one denoise pass (downsampled: the upsample) */
                if (!run(dev, &s, &f, ao)) continue;
                const double rmse = scene_rmse(ao, gt_falloff.data, depth.data, n);
                printf("%-17s %-7s %-7s %-11s vs ao_gt_falloff RMSE %.4f (bound %.4f)\n", scenes[k],
                       cacao_estimator_name(estimators[e]), cacao_quality_name(s.quality), ds ? "downsampled" : "native",
                       rmse, bound[ds][e][q][k]);
                CHECK(rmse <= bound[ds][e][q][k]);
                if (!(rmse <= previous))
                    fprintf(stderr, "%s %s %s: RMSE %.4f above the level below's %.4f\n", scenes[k],
                            cacao_estimator_name(estimators[e]), cacao_quality_name(s.quality), rmse, previous);
                CHECK(rmse <= previous);
                if (q == 0 && !ds) CHECK(rmse < amd_lowest);
                if (q == 4 && !ds && estimators[e] == CACAO_ESTIMATOR_BITMASK) {
                    highest_sum += rmse;
                    ++highest_scenes;
                }
                previous = rmse;
            }
        }
        if (ok) {
            cacao_settings s =
                slice_settings(CACAO_ESTIMATOR_BITMASK, CACAO_VISIBILITY_BINARY, 0, 0, (float)cam.ao_radius_world);
            s.quality = CACAO_QUALITY_HIGHEST;
            s.blur_pass_count = 0;
            if (run(dev, &s, &f, ao)) {
                const double rmse = scene_rmse(ao, gt.data, depth.data, n);
                printf("%-17s bitmask highest, binary vs ao_gt RMSE %.4f (bound %.4f)\n", scenes[k], rmse,
                       binary_bound[k]);
                CHECK(rmse <= binary_bound[k]);
            }
        }
        if (ok) {
            cacao_settings s =
                slice_settings(CACAO_ESTIMATOR_BITMASK, CACAO_VISIBILITY_FALLOFF, 0, 0, (float)cam.ao_radius_world);
            s.quality = CACAO_QUALITY_HIGHEST;
            s.downsample = true;
            s.blur_pass_count = 0;
            s.temporal_frames = 8;
            vkdev_frame frames = f;
            frames.advance_frame_index = true;
            char err[512];
            const cacao_result r = vkdev_run(dev, &s, &frames, 8, ao, NULL, err, sizeof err);
            if (r != CACAO_SUCCESS) fprintf(stderr, "%s: temporal run failed: %s\n", scenes[k], err);
            CHECK(r == CACAO_SUCCESS);
            if (r == CACAO_SUCCESS) {
                const double rmse = scene_rmse(ao, gt_falloff.data, depth.data, n);
                printf("%-17s bitmask highest downsampled, after 8 frames (temporal) vs ao_gt_falloff RMSE %.4f "
                       "(bound %.4f)\n",
                       scenes[k], rmse, temporal_bound[k]);
                CHECK(rmse <= temporal_bound[k]);
                temporal_sum += rmse;
                ++temporal_scenes;
            }
        }
        free(ao);
        cacao_img_free(&amd);
        free(depth.data);
        free(normals.data);
        free(gt.data);
        free(gt_falloff.data);
    }
    if (highest_scenes == 3) {
        printf("bitmask highest: mean RMSE over the three scenes %.4f (target <= 0.048)\n", highest_sum / 3);
        CHECK(highest_sum / 3 <= 0.048);
    }
    if (temporal_scenes == 3) { /* after 8 frames: never in place of the single frame's figure above */
        printf("bitmask highest downsampled after 8 frames: mean RMSE %.4f\n", temporal_sum / 3);
        CHECK(temporal_sum / 3 <= 0.048);
    }
}

int main(int argc, char **argv) {
    vkdev dev;
    open_device(&dev);
    if (argc > 1 && strcmp(argv[1], "--shared") == 0) {
        const char *shared = require_shared_dir(argc - 1, argv + 1);
        test_shared_scenes(&dev, shared);
    } else {
        test_crease(&dev);
        test_past_edge(&dev);
        test_unoccluded(&dev);
        test_groove(&dev);
        test_invariance(&dev);
        test_invalid_depth(&dev);
        test_frames(&dev);
    }
    CHECK(dev.validation_messages == 0);
    vkdev_destroy(&dev);
    return test_report("test_estimators");
}
