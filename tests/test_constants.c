/* test_constants - the constant-buffer math (cacaoi_fill_constants) against values derived by hand
 * from the spec's formulas (constants.md section 8, worked example: 960x540, fovY 65 deg, 16:9,
 * near 0.05, far 100) and, where the shared data is present, against the complete constant
 * buffers AMD's own UpdateConstants produced for the reference images (settings.json).
 * Both are independent of our code: the first is arithmetic done on paper, the second AMD's host.
 * usage: test_constants              the hand-derived values
 *        test_constants SHARED_DIR   AMD's constant buffers (exit 77 = skipped when SHARED_DIR is absent) */
#include <cjson/cJSON.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "camera_json.h"
#include "gpu_scene.h"
#include "internal.h"
#include "text_file.h"

/* Relative: |a - b| <= tol * |b|; an expected 0 must be met exactly. */
#define NEAR(a, b, tol) (fabs((double)(a) - (double)(b)) <= (tol)*fabs((double)(b)))
#include "projections.h"
#define CHECK_NEAR(a, b, tol)                                                                                          \
    do {                                                                                                               \
        if (!NEAR(a, b, tol)) {                                                                                        \
            fprintf(stderr, "%s:%d: %s = %.9g, expected %.9g\n", __FILE__, __LINE__, #a, (double)(a), (double)(b));    \
            ++test_failures;                                                                                           \
        }                                                                                                              \
    } while (0)

static cacao_constants fill(const cacao_settings *s, uint32_t w, uint32_t h, const float proj[16], bool row_major) {
    cacao_plan plan;
    char err[256];
    CHECK(cacao_plan_build(s, w, h, &plan, err, sizeof err) == CACAO_SUCCESS);
    cacao_inputs in = {.matrices_row_major = row_major};
    memcpy(in.projection, proj, sizeof in.projection);
    CHECK(cacaoi_check_projection(&in, err, sizeof err) == CACAO_SUCCESS);
    cacao_constants c;
    cacaoi_fill_constants(&plan, &in, &c);
    return c;
}

static void transpose(const float in[16], float out[16]) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[c * 4 + r] = in[r * 4 + c];
}

/* spec constants.md "Worked example". */
static void test_worked_example(void) {
    float p[16], pr[16], pt[16];
    cacao_perspective(65.0, 16.0 / 9.0, 0.05, 100.0, false, p);
    cacao_perspective(65.0, 16.0 / 9.0, 0.05, 100.0, true, pr);
    const cacao_settings s = {.quality = CACAO_QUALITY_HIGHEST};
    cacao_constants c = fill(&s, 960, 540, p, true);
    CHECK_NEAR(c.ndc_to_view_mul.x, 2.2651386, 1e-6);
    CHECK_NEAR(c.ndc_to_view_mul.y, -1.2741405, 1e-6);
    CHECK_NEAR(c.ndc_to_view_add.x, -1.1325693, 1e-6);
    CHECK_NEAR(c.ndc_to_view_add.y, 0.6370702, 1e-6);
    CHECK_NEAR(c.depth_unpack.x, 0.0500250, 1e-6);
    CHECK_NEAR(c.depth_unpack.y, 1.0005002, 1e-6);
    CHECK_NEAR(c.effect_radius, 1.2, 1e-6);
    CHECK_NEAR(c.neg_rec_effect_radius, -0.8333333, 1e-6);
    CHECK_NEAR(c.effect_shadow_strength, 4.3, 1e-6);
    CHECK_NEAR(c.effect_fade_out_mul, -0.004, 1e-6);
    CHECK_NEAR(c.effect_fade_out_add, 1.2, 1e-6);
    CHECK_NEAR(c.effect_sampling_radius_near_limit_rec, 0.4424099, 1e-6);
    CHECK_NEAR(c.inv_sharpness, 0.02, 1e-6);
    CHECK_NEAR(c.ssao_buffer_inverse_dimensions.x, 1.0 / 480, 1e-7);
    CHECK_NEAR(c.ssao_buffer_inverse_dimensions.y, 1.0 / 270, 1e-7);
    CHECK_NEAR(c.importance_map_inverse_dimensions.x, 1.0 / 240, 1e-7);
    CHECK_NEAR(c.importance_map_inverse_dimensions.y, 1.0 / 135, 1e-7);
    CHECK_NEAR(c.load_counter_avg_div, 1.0893247e-6, 1e-6);
    CHECK(c.slice_count == 4);
    /* Pattern table rows of constants.md section 4: (k=1, j=2) and (k=3, j=4). */
    CHECK_NEAR(c.pattern_rot_scale[1 * 5 + 2].x, -0.944399, 1e-5);
    CHECK_NEAR(c.pattern_rot_scale[1 * 5 + 2].y, -0.306854, 1e-5);
    CHECK_NEAR(c.pattern_rot_scale[1 * 5 + 2].w, 0.944399, 1e-5);
    CHECK_NEAR(c.pattern_rot_scale[3 * 5 + 4].x, 0.649503, 1e-5);
    CHECK_NEAR(c.pattern_rot_scale[3 * 5 + 4].z, 0.893964, 1e-5);
    CHECK_NEAR(c.per_slice_full_res_uv_offset[3].x, 1.0 / 480, 1e-7); /* float rounding */
    CHECK_NEAR(c.per_slice_full_res_uv_offset[3].y, 1.0 / 270, 1e-7);

    /* The same matrix stored column-major gives the same constants. */
    transpose(p, pt);
    cacao_constants c2 = fill(&s, 960, 540, pt, false);
    CHECK(memcmp(&c, &c2, sizeof c) == 0);

    /* Reversed Z: M = -0.0500250, A = -0.00050025, and both map their own depth of the same point
     * (view z = 3) to z = 3. */
    cacao_constants r = fill(&s, 960, 540, pr, true);
    CHECK_NEAR(r.depth_unpack.x, -0.0500250, 1e-6);
    CHECK_NEAR(r.depth_unpack.y, -0.00050025, 1e-6);
    const double n = 0.05, f = 100.0, z = 3.0;
    const double d = f * (z - n) / (z * (f - n)), dr = n * (f - z) / (z * (f - n));
    CHECK_NEAR(c.depth_unpack.x / (c.depth_unpack.y + c.depth_unpack_d.y * d), z, 1e-4);
    CHECK_NEAR(r.depth_unpack.x / (r.depth_unpack.y + r.depth_unpack_d.y * dr), z, 1e-4);

    /* Downsampled: S = 240x135, I = 120x68, LoadCounterAvgDiv = 4.3252594e-6. */
    const cacao_settings sd = {.quality = CACAO_QUALITY_HIGHEST, .downsample = true};
    cacao_constants dsc = fill(&sd, 960, 540, p, true);
    CHECK_NEAR(dsc.ssao_buffer_inverse_dimensions.x, 1.0 / 240, 1e-7);
    CHECK_NEAR(dsc.ssao_buffer_inverse_dimensions.y, 1.0 / 135, 1e-7);
    CHECK_NEAR(dsc.importance_map_inverse_dimensions.y, 1.0 / 68, 1e-7);
    CHECK_NEAR(dsc.load_counter_avg_div, 4.3252594e-6, 1e-6);

    /* LOWEST with radius 0.75: EffectRadius 0.6, NearLimitRec 0.4719039, two slices. */
    const cacao_settings sl = {.quality = CACAO_QUALITY_LOWEST, .radius = 0.75f};
    cacao_constants lc = fill(&sl, 960, 540, p, true);
    CHECK_NEAR(lc.effect_radius, 0.6, 1e-6);
    CHECK_NEAR(lc.effect_sampling_radius_near_limit_rec, 0.4719039, 1e-6);
    CHECK(lc.slice_count == 2);
}

/* A 90-degree square projection by hand: tan = 1, near 1, far 10 -> M = A = 10/9. */
static void test_simple_projection(void) {
    float p[16];
    cacao_perspective(90.0, 1.0, 1.0, 10.0, false, p);
    const cacao_settings s = {.quality = CACAO_QUALITY_HIGH};
    cacao_constants c = fill(&s, 64, 64, p, true);
    CHECK_NEAR(c.depth_unpack.x, 10.0 / 9.0, 1e-6);
    CHECK_NEAR(c.depth_unpack.y, 10.0 / 9.0, 1e-6);
    CHECK_NEAR(c.ndc_to_view_mul.x, 2.0, 1e-6);
    CHECK_NEAR(c.ndc_to_view_mul.y, -2.0, 1e-6);
    CHECK_NEAR(c.ndc_to_view_add.x, -1.0, 1e-6);
    CHECK_NEAR(c.ndc_to_view_add.y, 1.0, 1e-6);
    /* normals_to_view all zero -> identity; a given matrix N lands column-major (m[4c+r] = N(r,c)). */
    CHECK(c.normals_to_view.m[0] == 1 && c.normals_to_view.m[5] == 1 && c.normals_to_view.m[1] == 0);
    cacao_plan plan;
    char err[256];
    cacao_settings sn = {.quality = CACAO_QUALITY_HIGH, .generate_normals = false};
    CHECK(cacao_plan_build(&sn, 64, 64, &plan, err, sizeof err) == CACAO_SUCCESS);
    cacao_inputs in = {.matrices_row_major = true};
    memcpy(in.projection, p, sizeof p);
    in.normals_to_view[0 * 4 + 1] = 7.0f; /* N(0,1) = 7 */
    in.normals_to_view[10] = -1.0f;
    cacaoi_fill_constants(&plan, &in, &c);
    CHECK(c.normals_to_view.m[4 * 1 + 0] == 7.0f);
    CHECK(c.normals_to_view.m[4 * 2 + 2] == -1.0f);
    CHECK(c.normals_unpack_mul == 2.0f && c.normals_unpack_add == -1.0f);
}

/* AMD's own constant buffers for the reference images (settings.json), field by field. */
static int compare_with_amd(const char *shared, const char *scene) {
    char path[4096], err[256];
    snprintf(path, sizeof path, "%s/reference-amd/%s/settings.json", shared, scene);
    char *text = cacao_read_whole_file(path, 1u << 20, err, sizeof err);
    if (!text) {
        fprintf(stderr, "%s\n", err);
        ++test_failures;
        return 0;
    }
    cJSON *root = cJSON_Parse(text);
    free(text);
    CHECK(root != NULL);
    snprintf(path, sizeof path, "%s/scenes/%s/camera.json", shared, scene);
    cacao_camera_file cam;
    CHECK(cacao_camera_json_read(path, &cam, err, sizeof err));
    int compared = 0;
    const cJSON *config;
    cJSON_ArrayForEach(config, cJSON_GetObjectItem(root, "configurations")) {
        const cJSON *st = cJSON_GetObjectItem(config, "settings");
        const int quality = cJSON_GetObjectItem(st, "qualityLevel")->valueint;
        const cacao_settings s = {
            .radius = (float)cJSON_GetObjectItem(st, "radius")->valuedouble,
            .fade_out_from = (float)cJSON_GetObjectItem(st, "fadeOutFrom")->valuedouble,
            .fade_out_to = (float)cJSON_GetObjectItem(st, "fadeOutTo")->valuedouble,
            .quality = (cacao_quality)(quality + 1),
            .downsample = cJSON_IsTrue(cJSON_GetObjectItem(config, "useDownsampledSsao")),
            .generate_normals = true,
        };
        cacao_constants c = fill(&s, (uint32_t)cam.width, (uint32_t)cam.height, cam.projection, true);
        const cJSON *k0 = cJSON_GetArrayItem(cJSON_GetObjectItem(config, "constants_per_pass"), 3);
#define AMD(name) (cJSON_GetObjectItem(k0, name)->valuedouble)
#define AMD2(name, i) (cJSON_GetArrayItem(cJSON_GetObjectItem(k0, name), i)->valuedouble)
        CHECK_NEAR(c.depth_unpack.x, AMD2("DepthUnpackConsts", 0), 1e-6);
        CHECK_NEAR(c.depth_unpack.y, AMD2("DepthUnpackConsts", 1), 1e-6);
        CHECK_NEAR(c.ndc_to_view_mul.x, AMD2("NDCToViewMul", 0), 1e-6);
        CHECK_NEAR(c.ndc_to_view_mul.y, AMD2("NDCToViewMul", 1), 1e-6);
        CHECK_NEAR(c.ndc_to_view_add.x, AMD2("NDCToViewAdd", 0), 1e-6);
        CHECK_NEAR(c.ndc_to_view_add.y, AMD2("NDCToViewAdd", 1), 1e-6);
        CHECK_NEAR(c.effect_radius, AMD("EffectRadius"), 1e-6);
        CHECK_NEAR(c.effect_shadow_strength, AMD("EffectShadowStrength"), 1e-6);
        CHECK_NEAR(c.effect_shadow_pow, AMD("EffectShadowPow"), 1e-6);
        CHECK_NEAR(c.effect_shadow_clamp, AMD("EffectShadowClamp"), 1e-6);
        CHECK_NEAR(c.effect_fade_out_mul, AMD("EffectFadeOutMul"), 1e-6);
        CHECK_NEAR(c.effect_fade_out_add, AMD("EffectFadeOutAdd"), 1e-6);
        CHECK_NEAR(c.effect_horizon_angle_threshold, AMD("EffectHorizonAngleThreshold"), 1e-6);
        CHECK_NEAR(c.effect_sampling_radius_near_limit_rec, AMD("EffectSamplingRadiusNearLimitRec"), 1e-6);
        CHECK_NEAR(c.neg_rec_effect_radius, AMD("NegRecEffectRadius"), 1e-6);
        CHECK_NEAR(c.load_counter_avg_div, AMD("LoadCounterAvgDiv"), 1e-6);
        CHECK_NEAR(c.inv_sharpness, AMD("InvSharpness"), 1e-6);
        CHECK_NEAR(c.ssao_buffer_inverse_dimensions.x, 1.0 / AMD2("SSAOBufferDimensions", 0), 1e-7);
        CHECK_NEAR(c.ssao_buffer_inverse_dimensions.y, 1.0 / AMD2("SSAOBufferDimensions", 1), 1e-7);
        CHECK_NEAR(c.importance_map_inverse_dimensions.x, 1.0 / AMD2("ImportanceMapDimensions", 0), 1e-7);
        CHECK_NEAR(c.importance_map_inverse_dimensions.y, 1.0 / AMD2("ImportanceMapDimensions", 1), 1e-7);
        CHECK_NEAR(c.per_slice_full_res_uv_offset[3].x, AMD2("PerPassFullResUVOffset", 0), 1e-7);
        CHECK_NEAR(c.per_slice_full_res_uv_offset[3].y, AMD2("PerPassFullResUVOffset", 1), 1e-7);
        const cJSON *rot = cJSON_GetObjectItem(k0, "PatternRotScaleMatrices");
        for (int j = 0; j < 5; ++j) {
            const cJSON *m = cJSON_GetArrayItem(rot, j);
            const cacao_vec4 v = c.pattern_rot_scale[3 * 5 + j];
            CHECK_NEAR(v.x, cJSON_GetArrayItem(m, 0)->valuedouble, 1e-6);
            CHECK_NEAR(v.y, cJSON_GetArrayItem(m, 1)->valuedouble, 1e-6);
            CHECK_NEAR(v.z, cJSON_GetArrayItem(m, 2)->valuedouble, 1e-6);
            CHECK_NEAR(v.w, cJSON_GetArrayItem(m, 3)->valuedouble, 1e-6);
        }
        ++compared;
    }
    cJSON_Delete(root);
    return compared;
}

/* Every convention engines use - {standard, reversed, infinite-far, infinite-far reversed,
 * orthographic, orthographic reversed} x {RH, LH} x {row-, column-major} x {centred, jittered by
 * a sub-pixel TAA offset, a quarter-width asymmetric frustum}: points projected by the test's own
 * matrix (projections.h) come back to their view position (x, y, distance) through the constants
 * exactly as the shader's view_z / view_pos use them. */
static void test_projection_conventions(void) {
    const uint32_t w = 64, h = 48;
    const double jitters[3][2] = {{0, 0}, {0.37 * 2.0 / w, -0.21 * 2.0 / h}, {0.5, 0.0}};
    const double n = 0.1, f = 100.0;
    int cases = 0;
    for (int k = 0; k < PROJ_KIND_COUNT; ++k)
        for (int lh = 0; lh < 2; ++lh)
            for (int rm = 0; rm < 2; ++rm)
                for (int j = 0; j < 3; ++j) {
                    const bool ortho = proj_is_ortho((proj_kind)k);
                    const double sx = ortho ? 8.0 : 0.8, sy = ortho ? 6.0 : 0.6;
                    float p[16], pt[16];
                    proj_build((proj_kind)k, lh, sx, sy, n, f, jitters[j][0], jitters[j][1], p);
                    proj_transpose(p, pt);
                    const cacao_settings s = {.quality = CACAO_QUALITY_HIGH};
                    cacao_plan plan;
                    char err[256];
                    CHECK(cacao_plan_build(&s, w, h, &plan, err, sizeof err) == CACAO_SUCCESS);
                    cacao_inputs in = {.matrices_row_major = rm, .depth_reversed = proj_is_reversed((proj_kind)k)};
                    memcpy(in.projection, rm ? p : pt, sizeof in.projection);
                    if (cacaoi_check_projection(&in, err, sizeof err) != CACAO_SUCCESS) {
                        fprintf(stderr, "%s lh=%d rm=%d j=%d refused: %s\n", proj_kind_names[k], lh, rm, j, err);
                        ++test_failures;
                        continue;
                    }
                    cacao_constants c;
                    cacaoi_fill_constants(&plan, &in, &c);
                    double worst = 0.0;
                    for (int i = 0; i < 50; ++i) {
                        const double z = 0.5 + 49.5 * (double)((i * 37) % 50) / 49.0;
                        const double ndc_x = -0.9 + 1.8 * (double)((i * 13) % 50) / 49.0;
                        const double ndc_y = -0.9 + 1.8 * (double)((i * 29) % 50) / 49.0;
                        const double scale = ortho ? 1.0 : z;
                        const double x = (ndc_x - jitters[j][0]) * sx * scale, y = (ndc_y - jitters[j][1]) * sy * scale;
                        const float d = (float)proj_depth((proj_kind)k, n, f, z);
                        const float u = (float)((ndc_x + 1.0) * 0.5), v = (float)((1.0 - ndc_y) * 0.5);
                        const float vz =
                            (c.depth_unpack.x + c.depth_unpack_d.x * d) / (c.depth_unpack.y + c.depth_unpack_d.y * d);
                        const float xs = c.view_xy_z.x * vz + c.view_xy_z.y;
                        const float vx = (c.ndc_to_view_mul.x * u + c.ndc_to_view_add.x) * xs;
                        const float vy = (c.ndc_to_view_mul.y * v + c.ndc_to_view_add.y) * xs;
                        const double e = fmax(fabs(vz - z) / z, fmax(fabs(vx - x), fabs(vy - y)) / (sy * scale));
                        worst = fmax(worst, e);
                    }
                    if (!(worst <= 2e-3)) {
                        fprintf(stderr, "%s lh=%d rm=%d jitter=%d: view position off by %.3g (relative)\n",
                                proj_kind_names[k], lh, rm, j, worst);
                        ++test_failures;
                    }
                    ++cases;
                }
    printf("projection conventions: %d cases reconstruct their view positions\n", cases);
}

/* Projections the library cannot handle are refused with the matrix element named. */
static void test_projection_refusals(void) {
    float p[16];
    proj_build(PROJ_STANDARD, false, 0.8, 0.6, 0.1, 100.0, 0.0, 0.0, p);
    const struct {
        int index;
        float value;
        const char *named;
    } cases[] = {{1, 0.3f, "P(0,1)"}, {8, 0.2f, "P(2,0)"}, {15, 1.0f, "P(3,3)"}, {11, 0.0f, "P(2,3)"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        cacao_inputs in = {.matrices_row_major = true};
        memcpy(in.projection, p, sizeof p);
        in.projection[cases[i].index] = cases[i].value;
        char err[256] = "";
        CHECK(cacaoi_check_projection(&in, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(err, cases[i].named) != NULL);
    }
    /* Orthographic: oblique (P(0,2) != 0) and a non-positive w are refused. */
    proj_build(PROJ_ORTHO, false, 8.0, 6.0, 0.1, 100.0, 0.0, 0.0, p);
    cacao_inputs in = {.matrices_row_major = true};
    memcpy(in.projection, p, sizeof p);
    in.projection[2] = 0.1f;
    char err[256] = "";
    CHECK(cacaoi_check_projection(&in, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT && strstr(err, "P(0,2)"));
    in.projection[2] = 0.0f;
    in.projection[15] = -1.0f;
    CHECK(cacaoi_check_projection(&in, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT && strstr(err, "P(3,3)"));
}

/* The upsample weighs an entry outside the image 0 through exp2(+inf * multiplier) (apply.glsl):
 * the multiplier must stay a negative normal float at any similarity sigma the settings accept,
 * and otherwise grow towards 0 as sigma grows (-log2(e) / (sigma k^2), k the view scale). */
static void test_bilateral_multiplier(void) {
    float p[16];
    cacao_perspective(65.0, 16.0 / 9.0, 0.05, 100.0, false, p);
    const float sigmas[] = {1e-30f, 0.01f, 1.0f, 1e20f, 1e30f};
    float last = 0.0f;
    for (size_t i = 0; i < sizeof sigmas / sizeof sigmas[0]; ++i) {
        const cacao_settings s = {.quality = CACAO_QUALITY_HIGH, .downsample = true,
                                  .bilateral_similarity_distance_sigma = sigmas[i]};
        const cacao_constants c = fill(&s, 960, 540, p, true);
        const float m = c.bilateral_depth_exp2_mul;
        CHECK(isfinite(m) && m <= -FLT_MIN); /* never -0 or a denormal: +inf * m = -inf */
        CHECK(isinf(exp2f(INFINITY * m)) == 0 && exp2f(INFINITY * m) == 0.0f);
        if (i > 0) CHECK(m >= last); /* a wider sigma weighs depth differences less, down to the clamp */
        if (i > 0 && i < 4) CHECK(m > last);
        last = m;
    }
    /* a world scaled down (near 1e-12, far 1e-9: view scale 2^26, view_scale in constants.c) at the
     * widest sigma: without the clamp the multiplier would be -0 */
    float tiny[16];
    cacao_perspective(65.0, 16.0 / 9.0, 1e-12, 1e-9, false, tiny);
    const cacao_settings wide = {.quality = CACAO_QUALITY_HIGH, .downsample = true,
                                 .bilateral_similarity_distance_sigma = 1e30f};
    CHECK(fill(&wide, 960, 540, tiny, true).bilateral_depth_exp2_mul == -FLT_MIN);
}

/* Reuse's fixed margin (constants.c fill_reuse_constants): the GPU forms' mip chain adds a level-3
 * texel (8 slice texels: a GPU's sampler may take the neighbouring texel near an edge) to the CPU
 * forms' margin at HIGH; below HIGH no mips are read and the forms agree. */
static void test_reuse_margin(void) {
    float p[16];
    cacao_perspective(65.0, 16.0 / 9.0, 0.05, 100.0, false, p);
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGH; ++q) {
        cacao_settings cpu = {.quality = (cacao_quality)q, .reuse_unchanged = true, .blur_pass_count = 2,
                              .shader_forms = CACAO_SHADER_FORMS_CPU};
        cacao_settings gpu = cpu;
        gpu.shader_forms = CACAO_SHADER_FORMS_GPU;
        const int mc = fill(&cpu, 960, 540, p, true).reuse_margin, mg = fill(&gpu, 960, 540, p, true).reuse_margin;
        /* mips (8 at HIGH), rounding 1, edges 2, blur 2, apply 2, spare 1 */
        CHECK(mc == (q == CACAO_QUALITY_HIGH ? 8 : 0) + 8);
        CHECK(mg == mc + (q == CACAO_QUALITY_HIGH ? 8 : 0));
    }
}

/* What compact reads of the plan's output steps (docs/tiles.md "Apply over a list where the frame
 * skips much"): the list it writes, the odd output's shift and the direct apply's gate. */
static void test_output_lists(void) {
    float p[16];
    cacao_perspective(65.0, 16.0 / 9.0, 0.05, 100.0, false, p);
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (int ds = 0; ds < 2; ++ds)
            for (int reuse = 0; reuse < 2; ++reuse) {
                const cacao_settings s = {.quality = (cacao_quality)q, .downsample = ds, .reuse_unchanged = reuse,
                                          .shader_forms = CACAO_SHADER_FORMS_CPU};
                const cacao_constants c = fill(&s, 961, 540, p, true);
                const int list = reuse ? 0 : ds ? 1 : q >= CACAO_QUALITY_MEDIUM ? 2 : 3;
                CHECK(c.needed_list == list);
                CHECK(c.needed_shift == (list == 3 ? 1 : 0)); /* the width is odd */
                /* the gates: classify.quiet's, after it every direct step's, the direct apply's last of them */
                CHECK(list == 3 ? c.apply_gate == c.gate_count && c.apply_gate > 0 : c.apply_gate == 0);
            }
    const cacao_settings gpu = {.quality = CACAO_QUALITY_LOWEST, .shader_forms = CACAO_SHADER_FORMS_GPU};
    const cacao_constants c = fill(&gpu, 960, 541, p, true);
    CHECK(c.needed_list == 0 && c.apply_gate == 0 && c.needed_shift == 0);
}

int main(int argc, char **argv) {
    test_output_lists();
    test_bilateral_multiplier();
    test_reuse_margin();
    test_projection_conventions();
    test_projection_refusals();
    if (argc < 2) {
        test_worked_example();
        test_simple_projection();
        return test_report("test_constants");
    }
    const char *shared = require_shared_dir(argc, argv);
    static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};
    int compared = 0;
    for (int i = 0; i < 3; ++i) compared += compare_with_amd(shared, scenes[i]);
    printf("compared %d of AMD's constant buffers field by field\n", compared);
    CHECK(compared == 30); /* 3 scenes x 10 configurations */
    return test_report("test_constants (AMD's constant buffers)");
}
