/* test_ground_truth - error against the ray-traced ground truth (ao_gt_falloff.pfm, same distance
 * falloff as CACAO) per quality level, on every shared scene, with two kinds of settings:
 *
 *  - "look": AMD's defaults (shadow power 1.5, strength x4.3, clamp 0.98, horizon threshold,
 *    detail AO): an artistic look, reported for information;
 *  - "estimate": settings under which CACAO estimates the quantity the ground truth measures
 *    (power 1, clamp 1, no horizon threshold, no detail AO, blur 2, a fixed strength): more
 *    samples per pixel should then mean a better estimate.
 *
 * Asserted: in "estimate" mode the RMSE over non-background pixels does not grow from LOWEST to
 * HIGHEST by more than a tolerance of 0.005 (the scenes README's bound for noise of the truth
 * itself) between any quality and the next. Printed: the full table of both modes.
 * usage: test_ground_truth SHARED_DIR   (exit 77 = skipped when SHARED_DIR is absent) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

#define TOLERANCE 0.005
#define ESTIMATE_MULTIPLIER 0.5f

static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};
static const char *const qualities[] = {"lowest", "low", "medium", "high", "highest"};

static double rmse(const float *ao, const cacao_img *gt, const cacao_img *depth) {
    double se = 0;
    size_t n = 0;
    for (size_t i = 0; i < (size_t)depth->width * depth->height; ++i) {
        if (depth->data[i] >= 1.0f) continue;
        se += ((double)ao[i] - gt->data[i]) * ((double)ao[i] - gt->data[i]);
        ++n;
    }
    return sqrt(se / (double)n);
}

static void run_scene(vkdev *dev, const char *shared, const char *scene) {
    char err[512];
    cacao_img depth = {0}, gt = {0};
    cacao_camera_file cam;
    if (!load_shared_scene(shared, scene, &depth, &gt, &cam)) return;
    vkdev_frame frame = {.width = depth.width, .height = depth.height, .depth = depth.data};
    memcpy(frame.projection, cam.projection, sizeof frame.projection);
    float *ao = malloc(sizeof(float) * depth.width * depth.height);
    double look[5], estimate[5];
    for (int q = 0; q < 5; ++q)
        for (int mode = 0; mode < 2; ++mode) {
            cacao_settings s = {.radius = (float)cam.ao_radius_world,
                                .fade_out_from = (float)(2 * cam.far_z),
                                .fade_out_to = (float)(4 * cam.far_z),
                                .quality = (cacao_quality)(CACAO_QUALITY_LOWEST + q),
                                .generate_normals = true};
            if (mode == 1) {
                s.shadow_power = 1.0f;
                s.shadow_clamp = 1.0f;
                s.shadow_multiplier = ESTIMATE_MULTIPLIER;
                s.horizon_angle_threshold = CACAO_ZERO;
                s.detail_shadow_strength = CACAO_ZERO;
            }
            cacao_result r = vkdev_run(dev, &s, &frame, 1, ao, NULL, err, sizeof err);
            CHECK(r == CACAO_SUCCESS);
            (mode ? estimate : look)[q] = r == CACAO_SUCCESS ? rmse(ao, &gt, &depth) : NAN;
        }
    printf("%s: RMSE vs ao_gt_falloff, native\n  quality  | look (AMD defaults) | estimate\n", scene);
    for (int q = 0; q < 5; ++q) {
        printf("  %-8s | %.4f              | %.4f\n", qualities[q], look[q], estimate[q]);
        if (q > 0 && !(estimate[q] <= estimate[q - 1] + TOLERANCE)) {
            fprintf(stderr, "  ^ %s: estimate RMSE grew from %.4f to %.4f (tolerance %.3f)\n", scene, estimate[q - 1],
                    estimate[q], TOLERANCE);
            ++test_failures;
        }
    }
    free(ao);
    cacao_img_free(&depth);
    cacao_img_free(&gt);
}

int main(int argc, char **argv) {
    require_shared_dir(argc, argv);
    vkdev dev;
    open_device(&dev);
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; ++i) run_scene(&dev, argv[1], scenes[i]);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_ground_truth");
}
