/* test_amd_reference - "the same look as AMD's CACAO": runs cacao on every shared scene in the 10
 * configurations AMD's v1.2 reference images were made with (same depth, projection and settings,
 * normals reconstructed from depth) and compares over non-background pixels.
 *
 * Why this is the right check: the reference images are AMD's own code on this same lavapipe, so
 * a faithful implementation must land within a few 8-bit steps of them (goal: mean |cacao - AMD|
 * <= 2/255 in every configuration, also asserted). Asserted per scene and configuration: the mean,
 * 99th percentile and maximum of |cacao - AMD| stay within BOUND() of the values measured when
 * this table was written (lavapipe, Mesa 22.3, Debian 12): 25% above the measured value plus a
 * floor of 0.02/255 (mean), 0.25/255 (p99) and 1/255 (max), room for another LLVM's rounding.
 * 7 of the 10 configurations measure at the reference PNGs' 16-bit quantisation, so a wrong
 * column, row or slice raises the max (and a wrong region the p99) far above its bound.
 * Deliberate differences (both reported in the docs):
 *   - [quirk] BASE-SLICE-VIEW fixed: HIGHEST's slices 1-3 use their base pass (AMD loses it);
 *   - [quirk] BILATERAL-LEFT-BORDER fixed: out-of-image entries get weight 0 in the upsample.
 * Also prints the RMSE of cacao and of AMD against the ray-traced ao_gt_falloff.
 *
 * usage: test_amd_reference SHARED_DIR [scene ...]   (exit 77 = skipped when SHARED_DIR is absent) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};
static const char *const qualities[] = {"LOWEST", "LOW", "MEDIUM", "HIGH", "HIGHEST"};

static int compare_floats(const void *a, const void *b) {
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

typedef struct stats {
    double mean_abs, p99, max, rmse_gt, amd_rmse_gt;
} stats;

/* |cacao - AMD| measured per configuration, as printed by this test: {mean, p99, max} for LOWEST
 * native, LOWEST downsampled, LOW native, ..., HIGHEST downsampled. */
typedef struct measured {
    const char *scene;
    double mean_p99_max[10][3];
} measured;
static const measured measured_values[] = {
    {"interior_fzkhaus",
     {{0.000004, 0.000008, 0.001968},
      {0.000003, 0.000008, 0.001091},
      {0.000004, 0.000008, 0.001968},
      {0.000004, 0.000027, 0.001297},
      {0.000004, 0.000008, 0.002186},
      {0.000005, 0.000038, 0.001853},
      {0.000003, 0.000008, 0.002183},
      {0.000383, 0.000067, 0.216144},
      {0.002619, 0.017643, 0.071642},
      {0.002465, 0.014302, 0.216007}}},
    {"statues_scanned",
     {{0.000002, 0.000008, 0.001968},
      {0.000002, 0.000007, 0.001262},
      {0.000002, 0.000008, 0.000988},
      {0.000003, 0.000008, 0.005815},
      {0.000002, 0.000008, 0.001706},
      {0.000003, 0.000008, 0.010549},
      {0.000001, 0.000008, 0.001554},
      {0.000305, 0.000013, 0.250141},
      {0.000790, 0.009023, 0.046049},
      {0.000978, 0.008902, 0.250141}}},
    {"street_track",
     {{0.000001, 0.000008, 0.001968},
      {0.000001, 0.000007, 0.001432},
      {0.000001, 0.000008, 0.001968},
      {0.000001, 0.000007, 0.006083},
      {0.000001, 0.000008, 0.002083},
      {0.000002, 0.000007, 0.021381},
      {0.000001, 0.000008, 0.001557},
      {0.000448, 0.000008, 0.253132},
      {0.000834, 0.013733, 0.036847},
      {0.001257, 0.014695, 0.253468}}},
};
static const double bound_floor[3] = {0.02 / 255.0, 0.25 / 255.0, 1.0 / 255.0};
#define BOUND(measured, k) (1.25 * (measured) + bound_floor[k])

static const measured *measured_for(const char *scene) {
    for (size_t i = 0; i < sizeof measured_values / sizeof measured_values[0]; ++i)
        if (strcmp(measured_values[i].scene, scene) == 0) return &measured_values[i];
    return NULL;
}

static stats measure(const float *ao, const cacao_img *amd, const cacao_img *gt, const cacao_img *depth) {
    const size_t n = (size_t)depth->width * depth->height;
    float *diff = malloc(n * sizeof *diff);
    size_t count = 0;
    double sum = 0, se = 0, amd_se = 0;
    for (size_t i = 0; i < n; ++i) {
        if (depth->data[i] >= 1.0f) continue; /* background */
        float d = fabsf(ao[i] - amd->data[i]);
        diff[count++] = d;
        sum += d;
        se += (ao[i] - gt->data[i]) * (double)(ao[i] - gt->data[i]);
        amd_se += (amd->data[i] - gt->data[i]) * (double)(amd->data[i] - gt->data[i]);
    }
    qsort(diff, count, sizeof *diff, compare_floats);
    stats s = {sum / (double)count, diff[(size_t)(0.99 * (double)(count - 1))], diff[count - 1],
               sqrt(se / (double)count), sqrt(amd_se / (double)count)};
    free(diff);
    return s;
}

static bool run_scene(vkdev *dev, const char *shared, const char *scene) {
    char path[4096], err[512];
    cacao_img depth = {0}, gt = {0};
    cacao_camera_file cam;
    if (!load_shared_scene(shared, scene, &depth, &gt, &cam)) return false;
    vkdev_frame frame = {.width = depth.width, .height = depth.height, .depth = depth.data};
    memcpy(frame.projection, cam.projection, sizeof frame.projection);
    const measured *expected = measured_for(scene);
    if (!expected) {
        fprintf(stderr, "%s: no measured bounds for this scene\n", scene);
        ++test_failures;
    }
    float *ao = malloc(sizeof(float) * depth.width * depth.height);
    printf("\n%s (%ux%u): config | mean |cacao-AMD| | p99 | max | RMSE cacao vs GT | RMSE AMD vs GT | ms\n", scene,
           depth.width, depth.height);
    for (int q = 0; q < 5; ++q)
        for (int ds = 0; ds < 2; ++ds) {
            cacao_img amd = {0};
            bool amd16 = false;
            snprintf(path, sizeof path, "%s/reference-amd/%s/%s_%s.png", shared, scene, qualities[q],
                     ds ? "downsampled" : "native");
            if (!cacao_png_read(path, &amd, &amd16, err, sizeof err) || amd.channels != 1 || amd.width != depth.width ||
                amd.height != depth.height) {
                fprintf(stderr, "%s: %s\n", path, err);
                ++test_failures;
                continue;
            }
            const cacao_settings settings = {
                .radius = (float)cam.ao_radius_world,
                .fade_out_from = (float)(2.0 * cam.far_z),
                .fade_out_to = (float)(4.0 * cam.far_z),
                .quality = (cacao_quality)(CACAO_QUALITY_LOWEST + q),
                .downsample = ds != 0,
                .generate_normals = true,
                .blur_pass_count = 2,
            };
            cacao_timings t;
            cacao_result r = vkdev_run(dev, &settings, &frame, 1, ao, &t, err, sizeof err);
            CHECK(r == CACAO_SUCCESS);
            if (r != CACAO_SUCCESS) {
                fprintf(stderr, "%s %s: %s\n", scene, qualities[q], err);
                cacao_img_free(&amd);
                continue;
            }
            stats s = measure(ao, &amd, &gt, &depth);
            printf("  %-8s %-11s | %.6f (%.2f/255) | %.6f | %.6f | %.4f | %.4f | %.1f\n", qualities[q],
                   ds ? "downsampled" : "native", s.mean_abs, s.mean_abs * 255.0, s.p99, s.max, s.rmse_gt,
                   s.amd_rmse_gt, t.total.median_ms);
            if (s.mean_abs > 2.0 / 255.0) fprintf(stderr, "  ^ mean difference above 2/255\n");
            CHECK(s.mean_abs <= 2.0 / 255.0);
            const double got[3] = {s.mean_abs, s.p99, s.max};
            static const char *const what[3] = {"mean", "p99", "max"};
            for (int k = 0; expected && k < 3; ++k) {
                const double bound = BOUND(expected->mean_p99_max[q * 2 + ds][k], k);
                if (!(got[k] <= bound)) {
                    fprintf(stderr, "  ^ %s |cacao-AMD| %.6f above its bound %.6f (measured %.6f)\n", what[k], got[k],
                            bound, expected->mean_p99_max[q * 2 + ds][k]);
                    ++test_failures;
                }
            }
            cacao_img_free(&amd);
        }
    free(ao);
    cacao_img_free(&depth);
    cacao_img_free(&gt);
    return true;
}

int main(int argc, char **argv) {
    require_shared_dir(argc, argv);
    vkdev dev;
    open_device(&dev);
    if (argc > 2)
        for (int i = 2; i < argc; ++i) run_scene(&dev, argv[1], argv[i]);
    else
        for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; ++i) run_scene(&dev, argv[1], scenes[i]);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_amd_reference");
}
