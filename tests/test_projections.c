/* test_projections - orthographic, off-centre and jittered projections on the GPU (lavapipe,
 * validation on), with scenes the project ray-casts itself through the same lens:
 *  - an orthographic floor meeting a wall: the open floor is unoccluded, the crease darkened, for
 *    every estimator (CACAO, GTAO, bitmask: the bitmask's thickness interval once ran towards the
 *    camera under an orthographic projection, and a flat floor came out at 0.09);
 *  - the same scene at world scales 2^-100 and 1e-30 (near plane, far plane, radius): every
 *    estimator gives the output of scale 1 (the horizon estimators once gave 0 everywhere there);
 *  - orthographic against perspective cameras backed away with the frame held: the look
 *    converges on the orthographic one as the focal length grows;
 *  - a frustum made off-centre by k pixels moves the output by k pixels (a quarter-width
 *    asymmetric frustum) and by a sub-pixel TAA jitter;
 *  - the conformance matrix: every depth convention x handedness x centred/jittered gives the
 *    reference convention's output, for every estimator on the embedded scene (column-major storage gives byte-identical constants, see
 *    test_constants). */
#include "gpu_scene.h"
#include "projections.h"

/* A scene rendered through a lens (gpu_scene.h) and room for cacao's output. */
typedef struct lens_buffers {
    uint32_t w, h;
    float *depth, *depth_reversed, *normals, *ao;
} lens_buffers;

static void lens_render(const cacao_scene *scene, const cacao_lens *lens, lens_buffers *b) {
    scene_buffers sb;
    scene_buffers_render_lens(scene, lens, &sb);
    *b = (lens_buffers){sb.width,          sb.height,  sb.depth,
                        sb.depth_reversed, sb.normals, malloc(sizeof(float) * sb.width * sb.height)};
}

static void lens_free(lens_buffers *b) {
    scene_buffers sb = {.depth = b->depth, .depth_reversed = b->depth_reversed, .normals = b->normals};
    scene_buffers_free(&sb);
    free(b->ao);
}

/* Runs cacao on the standard (or reversed) depth with the lens's right-handed projection. */
static bool lens_run(vkdev *dev, const cacao_scene *scene, const cacao_lens *lens, lens_buffers *b, bool reversed,
                     const cacao_settings *s) {
    vkdev_frame f = {
        .width = b->w, .height = b->h, .depth = reversed ? b->depth_reversed : b->depth, .depth_reversed = reversed};
    cacao_camera_projection_lens(&scene->camera, lens, reversed, f.projection);
    vkdev_frame_set_view_normals(&f, b->normals);
    return run(dev, s, &f, b->ao);
}

/* Mean and 99th percentile of |a(x + dx, y + dy) - b(x, y)| over pixels at least `margin` from
 * every border of both images. */
static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void diff_shifted(const float *a, const float *b, uint32_t w, uint32_t h, int dx, int dy, int margin,
                         double *mean, double *p99) {
    double *d = malloc(sizeof(double) * w * h);
    size_t count = 0;
    double sum = 0.0;
    for (int y = margin; y < (int)h - margin; ++y)
        for (int x = margin; x < (int)w - margin; ++x) {
            const int xa = x + dx, ya = y + dy;
            if (xa < margin || ya < margin || xa >= (int)w - margin || ya >= (int)h - margin) continue;
            d[count] = fabs((double)a[(size_t)ya * w + xa] - b[(size_t)y * w + x]);
            sum += d[count++];
        }
    qsort(d, count, sizeof *d, cmp_double);
    *mean = count ? sum / (double)count : 0.0;
    *p99 = count ? d[(size_t)(0.99 * (double)(count - 1))] : 0.0;
    free(d);
}

/* An orthographic view of a floor (y = 0) meeting a wall (z = -6), looking down 30 degrees. */
static void test_ortho_crease(vkdev *dev) {
    const cacao_prim prims[] = {{CACAO_PRIM_PLANE, {0, 0, 0}, {0, 1, 0}, 0},
                                {CACAO_PRIM_PLANE, {0, 0, -6}, {0, 0, 1}, 0}};
    const cacao_scene scene = {prims, 2, {128, 96, 60.0, 0.1, 60.0, {0, 3.0, 0}, {0, 0, -5.196}, {0, 1, 0}}, 0.6};
    const cacao_lens lens = {.ortho_half_height = 2.5};
    lens_buffers b;
    lens_render(&scene, &lens, &b);
    /* The crease row: where the floor's and the wall's depth meet, per column (all columns alike). */
    int crease = -1;
    for (uint32_t y = 1; y < b.h && crease < 0; ++y) {
        const float n0 = b.normals[3 * ((size_t)(y - 1) * b.w) + 1], n1 = b.normals[3 * ((size_t)y * b.w) + 1];
        if ((n0 > 0.5f) != (n1 > 0.5f)) crease = (int)y;
    }
    CHECK(crease > 20 && crease < (int)b.h - 20);
    for (int est = CACAO_ESTIMATOR_CACAO; est <= CACAO_ESTIMATOR_BITMASK; ++est)
    for (int reversed = 0; reversed < 2; ++reversed)
        for (int q = CACAO_QUALITY_LOW; q <= CACAO_QUALITY_HIGHEST; ++q) {
            const cacao_settings s = {.estimator = (cacao_estimator)est, .quality = q, .radius = 0.6f,
                                      .blur_pass_count = CACAO_BLUR_NONE};
            if (!lens_run(dev, &scene, &lens, &b, reversed, &s)) continue;
            CHECK(all_finite_unit(b.ao, (size_t)b.w * b.h));
            /* Open floor (>= 10 px below the crease, where the radius does not reach the wall) and
             * open wall: unoccluded. The crease rows: clearly darker. */
            double floor_mean = 0, crease_mean = 0, wall_mean = 0;
            int nf = 0, nc = 0, nw = 0;
            for (uint32_t y = 4; y < b.h - 4; ++y)
                for (uint32_t x = 8; x < b.w - 8; ++x) {
                    const double v = b.ao[(size_t)y * b.w + x];
                    if ((int)y >= crease + 16)
                        floor_mean += v, ++nf;
                    else if ((int)y <= crease - 16)
                        wall_mean += v, ++nw;
                    else if (abs((int)y - crease) <= 1)
                        crease_mean += v, ++nc;
                }
            floor_mean /= nf, crease_mean /= nc, wall_mean /= nw;
            printf("orthographic floor/wall (%s, %s, %s): open floor %.4f, open wall %.4f, crease %.4f\n",
                   cacao_estimator_name((cacao_estimator)est), reversed ? "reversed" : "standard",
                   cacao_quality_name((cacao_quality)q), floor_mean, wall_mean, crease_mean);
            CHECK(floor_mean > 0.97 && wall_mean > 0.97);
            CHECK(crease_mean < floor_mean - 0.15);
        }
    lens_free(&b);
}

/* The floor and wall of test_ortho_crease through a perspective camera, at world scale 1 and at
 * tiny scales (the near and far planes, the radius and the fade-out distances scaled; the depth
 * buffer of a scaled scene is the same):
 *  - 2^-100 (about 7.9e-31): every estimator gives the AO of scale 1 (a power of two changes no
 *    rounding, so only an underflow could make a difference: the horizon estimators once gave 0);
 *  - 1e-30: the horizon estimators the same AO within rounding; CACAO within the rounding of its
 *    R16F depths, which quantise a scene scaled by other than a power of two differently (the
 *    bound is the measured 0.00072 x 1.25 + 0.0002, as test_amd_reference bounds). */
static void test_tiny_world_scale(vkdev *dev) {
    const cacao_prim prims[] = {{CACAO_PRIM_PLANE, {0, 0, 0}, {0, 1, 0}, 0},
                                {CACAO_PRIM_PLANE, {0, 0, -6}, {0, 0, 1}, 0}};
    cacao_scene scene = {prims, 2, {128, 96, 60.0, 0.1, 60.0, {0, 3.0, 0}, {0, 0, -5.196}, {0, 1, 0}}, 0.6};
    const cacao_lens lens = {0};
    lens_buffers b;
    lens_render(&scene, &lens, &b);
    float *ref = malloc(sizeof(float) * b.w * b.h);
    const double scales[2] = {ldexp(1.0, -100), 1e-30};
    for (int est = CACAO_ESTIMATOR_CACAO; est <= CACAO_ESTIMATOR_BITMASK; ++est) {
        cacao_settings s = {.estimator = (cacao_estimator)est, .quality = CACAO_QUALITY_HIGH, .radius = 0.6f,
                            .blur_pass_count = CACAO_BLUR_NONE};
        scene.camera.near_z = 0.1, scene.camera.far_z = 60.0;
        if (!lens_run(dev, &scene, &lens, &b, false, &s)) continue;
        memcpy(ref, b.ao, sizeof(float) * b.w * b.h);
        double ref_mean = 0.0;
        for (size_t i = 0; i < (size_t)b.w * b.h; ++i) ref_mean += ref[i];
        ref_mean /= (double)b.w * b.h;
        CHECK(ref_mean > 0.5 && ref_mean < 0.999); /* a scene with occlusion to lose */
        for (int i = 0; i < 2; ++i) {
            const double scale = scales[i];
            s.radius = (float)(0.6 * scale); /* and the fade-out's distances (defaults 50, 300) */
            s.fade_out_from = (float)(50.0 * scale), s.fade_out_to = (float)(300.0 * scale);
            scene.camera.near_z = 0.1 * scale, scene.camera.far_z = 60.0 * scale;
            if (!lens_run(dev, &scene, &lens, &b, false, &s)) continue;
            CHECK(all_finite_unit(b.ao, (size_t)b.w * b.h));
            double mean, p99;
            diff_shifted(b.ao, ref, b.w, b.h, 0, 0, 0, &mean, &p99);
            printf("world scale %.3g (%s): mean AO at scale 1 %.4f; |scaled - scale 1|: mean %.6f, p99 %.6f\n", scale,
                   cacao_estimator_name((cacao_estimator)est), ref_mean, mean, p99);
            if (i == 0 || est != CACAO_ESTIMATOR_CACAO)
                CHECK(mean <= 0.1 / 255.0 && p99 <= 1.0 / 255.0);
            else
                CHECK(mean <= 0.00072 * 1.25 + 0.0002);
        }
    }
    free(ref);
    lens_free(&b);
}

/* The default scene through an orthographic camera, and through perspective cameras backed away
 * along the view axis by L with the fov narrowed so the frame at the target stays the same: the
 * difference must shrink as L grows and be small at the longest focal length. */
static void test_ortho_vs_long_focal(vkdev *dev) {
    cacao_scene scene = cacao_default_scene(128, 72);
    const double *e = scene.camera.eye, *t = scene.camera.target;
    const double axis[3] = {e[0] - t[0], e[1] - t[1], e[2] - t[2]};
    const double dist = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double half_h = dist * tan(scene.camera.fov_y_deg * 3.14159265358979323846 / 360.0);
    const double backs[] = {0.0, 20.0, 200.0};
    const cacao_settings s = {
        .quality = CACAO_QUALITY_HIGH, .radius = 0.5f, .fade_out_from = 1e5f, .fade_out_to = 2e5f};
    float *ortho_ao = NULL;
    double prev = 1e9;
    for (int k = -1; k < 3; ++k) {
        cacao_scene sc = scene;
        const double back = k < 0 ? 200.0 : backs[k];
        for (int i = 0; i < 3; ++i) sc.camera.eye[i] = e[i] + axis[i] / dist * back;
        sc.camera.far_z = 1000.0;
        sc.camera.near_z = k < 0 ? 0.1 : 0.05 * (dist + back);
        sc.camera.fov_y_deg = 360.0 / 3.14159265358979323846 * atan(half_h / (dist + back));
        const cacao_lens lens = {.ortho_half_height = k < 0 ? half_h : 0.0};
        lens_buffers b;
        lens_render(&sc, &lens, &b);
        if (lens_run(dev, &sc, &lens, &b, false, &s)) {
            if (k < 0) {
                ortho_ao = b.ao;
                b.ao = NULL;
            } else {
                double mean, p99;
                diff_shifted(b.ao, ortho_ao, b.w, b.h, 0, 0, 4, &mean, &p99);
                printf("orthographic vs perspective backed off %g (fov %.3g deg): mean |diff| %.4f, p99 %.4f\n", back,
                       sc.camera.fov_y_deg, mean, p99);
                if (k > 0) CHECK(mean < prev);
                if (k == 2) CHECK(mean <= 1.0 / 255.0);
                prev = mean;
            }
        }
        lens_free(&b);
    }
    free(ortho_ao);
}

/* Off-centre frusta: the lens offset by k pixels renders the depth shifted by k pixels; cacao's
 * output must be the centred output shifted by k. k is a multiple of 20 so the per-pixel pattern
 * (period 5 in 2y + x), the 2x2 deinterleaving and the quarter-resolution importance map line up. */
static void test_off_centre_shift(vkdev *dev) {
    const uint32_t w = 160, h = 80;
    const cacao_scene scene = cacao_default_scene(w, h);
    const struct {
        double jx, jy;
        int dx, dy;
        const char *name;
    } cases[] = {{0.5, 0.0, 40, 0, "quarter-width asymmetric frustum"},
                 {0.0, 0.5, 0, -20, "quarter-height asymmetric frustum"},
                 {40.0 / w, -40.0 / h, 20, 20, "20-pixel diagonal offset"}};
    for (int persp = 0; persp < 2; ++persp)
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c)
            for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; q += 2) {
                const cacao_settings s = {.quality = q, .radius = 0.5f};
                const cacao_lens centred = {.ortho_half_height = persp ? 0.0 : 5.0};
                const cacao_lens moved = {.ortho_half_height = centred.ortho_half_height,
                                          .jitter_ndc = {cases[c].jx, cases[c].jy}};
                lens_buffers a, b;
                lens_render(&scene, &centred, &a);
                lens_render(&scene, &moved, &b);
                if (lens_run(dev, &scene, &centred, &a, false, &s) && lens_run(dev, &scene, &moved, &b, false, &s)) {
                    double mean, p99;
                    diff_shifted(b.ao, a.ao, w, h, cases[c].dx, cases[c].dy, 8, &mean, &p99);
                    printf("%s, %s, quality %d: mean |diff| %.5f, p99 %.5f\n", cases[c].name,
                           persp ? "perspective" : "orthographic", q, mean, p99);
                    CHECK(mean <= 0.5 / 255.0 && p99 <= 2.0 / 255.0);
                }
                lens_free(&a);
                lens_free(&b);
            }
}

/* The conformance matrix on one scene: `distance` holds each pixel's view distance (<= 0 for
 * background), `normals` its RH view normals (NULL: generated). For every kind x {RH, LH} x
 * {centred, sub-pixel jittered} the depth is written as that convention writes it and the
 * projection built by projections.h; each output must equal the standard right-handed output of
 * the same family (perspective / orthographic) and jitter. */
static void conformance_matrix(vkdev *dev, const char *name, const double *distance, const float *normals, uint32_t w,
                               uint32_t h, double sx_persp, double sy_persp, double sx_ortho, double sy_ortho, double n,
                               double f, float radius, bool with_ortho, cacao_estimator estimator) {
    const size_t count = (size_t)w * h;
    float *depth = malloc(sizeof(float) * count), *ref = malloc(sizeof(float) * count);
    float *ao = malloc(sizeof(float) * count);
    const cacao_settings s = {.estimator = estimator, .quality = CACAO_QUALITY_HIGH, .radius = radius,
                              .generate_normals = normals == NULL};
    const double jitter[2] = {0.37 * 2.0 / w, -0.21 * 2.0 / h};
    double worst_mean = 0.0, worst_p99 = 0.0;
    int runs = 0;
    for (int ortho = 0; ortho < (with_ortho ? 2 : 1); ++ortho)
        for (int j = 0; j < 2; ++j)
            for (int k = ortho ? PROJ_ORTHO : PROJ_STANDARD; k < (ortho ? PROJ_KIND_COUNT : PROJ_ORTHO); ++k)
                for (int lh = 0; lh < 2; ++lh) {
                    const proj_kind kind = (proj_kind)k;
                    const bool reversed = proj_is_reversed(kind);
                    for (size_t i = 0; i < count; ++i)
                        depth[i] = distance[i + (ortho ? count : 0)] > 0.0
                                       ? (float)proj_depth(kind, n, f, distance[i + (ortho ? count : 0)])
                                       : (reversed ? 0.0f : 1.0f);
                    vkdev_frame fr = {.width = w, .height = h, .depth = depth, .depth_reversed = reversed};
                    proj_build(kind, lh, ortho ? sx_ortho : sx_persp, ortho ? sy_ortho : sy_persp, n, f,
                               j ? jitter[0] : 0.0, j ? jitter[1] : 0.0, fr.projection);
                    if (normals) vkdev_frame_set_view_normals(&fr, normals + (ortho ? 3 * count : 0));
                    /* (An LH caller's normals are these with z negated and N = identity: the same
                     * normals in cacao's space, so N = diag(1, 1, -1) on the RH data stands for both.) */
                    const bool is_ref = k == (ortho ? PROJ_ORTHO : PROJ_STANDARD) && !lh;
                    if (!run(dev, &s, &fr, is_ref ? ref : ao)) continue;
                    ++runs;
                    if (is_ref) continue;
                    double mean, p99;
                    diff_shifted(ao, ref, w, h, 0, 0, 0, &mean, &p99);
                    worst_mean = fmax(worst_mean, mean);
                    worst_p99 = fmax(worst_p99, p99);
                    if (!(mean <= 0.5 / 255.0 && p99 <= 2.0 / 255.0)) {
                        fprintf(stderr, "%s: %s %s %s: mean %.5f p99 %.5f against the reference\n", name,
                                proj_kind_names[k], lh ? "LH" : "RH", j ? "jittered" : "centred", mean, p99);
                        ++test_failures;
                    }
                }
    printf("conformance matrix, %s, %s: %d runs, worst mean |diff| %.5f, worst p99 %.5f\n", name,
           cacao_estimator_name(estimator), runs, worst_mean, worst_p99);
    free(depth);
    free(ref);
    free(ao);
}

static void test_conformance_embedded(vkdev *dev) {
    const uint32_t w = 128, h = 72;
    const cacao_scene scene = cacao_default_scene(w, h);
    const double n = scene.camera.near_z, f = scene.camera.far_z, aspect = (double)w / h;
    const double ty = tan(scene.camera.fov_y_deg * 3.14159265358979323846 / 360.0), oh = 5.0;
    double *distance = malloc(sizeof(double) * 2 * w * h);
    float *normals = malloc(sizeof(float) * 6 * w * h);
    for (int ortho = 0; ortho < 2; ++ortho) {
        const cacao_lens lens = {.ortho_half_height = ortho ? oh : 0.0};
        lens_buffers b;
        lens_render(&scene, &lens, &b);
        for (size_t i = 0; i < (size_t)w * h; ++i) {
            const double d = b.depth_reversed[i]; /* reversed keeps precision far away */
            distance[i + (ortho ? (size_t)w * h : 0)] = d <= 0.0 ? -1.0
                                                        : ortho  ? f - d * (f - n)
                                                                 : n * f / (d * (f - n) + n);
        }
        memcpy(normals + (ortho ? 3 * (size_t)w * h : 0), b.normals, sizeof(float) * 3 * w * h);
        lens_free(&b);
    }
    /* every estimator: the horizon estimators' orthographic branch is theirs alone */
    for (int est = CACAO_ESTIMATOR_CACAO; est <= CACAO_ESTIMATOR_BITMASK; ++est)
        conformance_matrix(dev, "embedded scene", distance, normals, w, h, aspect * ty, ty, aspect * oh, oh, n, f,
                           (float)scene.ao_radius_world, true, (cacao_estimator)est);
    free(distance);
    free(normals);
}

/* One real scene (street_track): its standard depth turned back into distances with its own
 * projection; perspective conventions only (the scene has no orthographic rendering). */
static void test_conformance_shared(vkdev *dev, const char *shared) {
    cacao_img depth = {0}, gt = {0};
    cacao_camera_file cam;
    if (!load_shared_scene(shared, "street_track", &depth, &gt, &cam)) return;
    const size_t count = (size_t)depth.width * depth.height;
    double *distance = malloc(sizeof(double) * count);
    const double p22 = cam.projection[10], p23 = cam.projection[11]; /* RH: d = -p22 + p23 / z */
    for (size_t i = 0; i < count; ++i) distance[i] = depth.data[i] >= 1.0f ? -1.0 : p23 / ((double)depth.data[i] + p22);
    conformance_matrix(dev, "street_track", distance, NULL, depth.width, depth.height, 1.0 / cam.projection[0],
                       1.0 / cam.projection[5], 0.0, 0.0, cam.near_z, cam.far_z, (float)cam.ao_radius_world, false,
                       CACAO_ESTIMATOR_CACAO);
    free(distance);
    cacao_img_free(&depth);
    cacao_img_free(&gt);
}

/* A sub-pixel TAA jitter cannot shift an image by whole pixels, so the jittered output is
 * compared with the centred output resampled (bilinear) at the jittered positions, on smooth
 * surfaces (away from depth edges and borders); and, to show the comparison sees the jitter, the
 * same with the jitter left out of the projection (depth jittered, matrix centred), printed: at
 * 0.4 px the two are within the resampling error, which is the point of a TAA jitter. */
static void subpixel_diff(const float *jit, const float *cen, const float *depth, uint32_t w, uint32_t h, double px,
                          double py, double *mean, double *p99) {
    double *d = malloc(sizeof(double) * w * h);
    size_t count = 0;
    double sum = 0.0;
    for (uint32_t y = 8; y < h - 8; ++y)
        for (uint32_t x = 8; x < w - 8; ++x) {
            bool smooth = true;
            const float c = depth[(size_t)y * w + x];
            for (int dy = -2; dy <= 2 && smooth; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const float o = depth[(size_t)(y + dy) * w + x + dx];
                    if (!(o > 0.0f) || fabsf(o - c) > 0.05f * c) smooth = false; /* reversed: ~ 1 / z */
                }
            if (!smooth) continue;
            const double sx = x - px, sy = y + py; /* content moved right by px, up by py */
            const int x0 = (int)floor(sx), y0 = (int)floor(sy);
            const double fx = sx - x0, fy = sy - y0;
            const double v = (1 - fy) * ((1 - fx) * cen[(size_t)y0 * w + x0] + fx * cen[(size_t)y0 * w + x0 + 1]) +
                             fy * ((1 - fx) * cen[(size_t)(y0 + 1) * w + x0] + fx * cen[(size_t)(y0 + 1) * w + x0 + 1]);
            d[count] = fabs(jit[(size_t)y * w + x] - v);
            sum += d[count++];
        }
    qsort(d, count, sizeof *d, cmp_double);
    CHECK(count > (size_t)w * h / 10); /* enough smooth surface to measure on */
    *mean = count ? sum / (double)count : 0.0;
    *p99 = count ? d[(size_t)(0.99 * (double)(count - 1))] : 0.0;
    free(d);
}

static void test_subpixel_jitter(vkdev *dev) {
    const uint32_t w = 160, h = 90;
    const cacao_scene scene = cacao_default_scene(w, h);
    const double px = 0.37, py = -0.21;
    const cacao_lens centred = {0}, jittered = {.jitter_ndc = {2.0 * px / w, 2.0 * py / h}};
    lens_buffers a, b;
    lens_render(&scene, &centred, &a);
    lens_render(&scene, &jittered, &b);
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q) {
        const cacao_settings s = {.quality = q, .radius = 0.5f};
        double mean, p99, mean_wrong, p99_wrong;
        if (!lens_run(dev, &scene, &centred, &a, false, &s) || !lens_run(dev, &scene, &jittered, &b, false, &s))
            continue;
        subpixel_diff(b.ao, a.ao, a.depth_reversed, w, h, px, py, &mean, &p99);
        if (!lens_run(dev, &scene, &centred, &b, false, &s)) continue; /* jitter ignored */
        subpixel_diff(b.ao, a.ao, a.depth_reversed, w, h, px, py, &mean_wrong, &p99_wrong);
        printf(
            "sub-pixel jitter (%.2f, %.2f) px, quality %d: mean |diff| %.5f, p99 %.5f (jitter ignored: %.5f, %.5f)\n",
            px, py, q, mean, p99, mean_wrong, p99_wrong);
        /* Resampling adds its own error (the per-pixel sample pattern stays put); the exact check of
         * a sub-pixel jitter is test_constants' (view positions) and the whole-pixel shifts above. */
        CHECK(mean <= 1.0 / 255.0);
    }
    lens_free(&a);
    lens_free(&b);
}

int main(int argc, char **argv) {
    vkdev dev;
    open_device(&dev);
    test_ortho_crease(&dev);
    test_tiny_world_scale(&dev);
    test_ortho_vs_long_focal(&dev);
    test_off_centre_shift(&dev);
    test_subpixel_jitter(&dev);
    test_conformance_embedded(&dev);
    struct stat st;
    if (argc > 1 && stat(argv[1], &st) == 0)
        test_conformance_shared(&dev, argv[1]);
    else
        printf("conformance matrix on a real scene: skipped (shared data directory not found)\n");
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_projections");
}
