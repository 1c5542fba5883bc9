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
 * itself) between any quality and the next; and in both modes each level's RMSE stays within 2%
 * of the value measured when this table was written (lavapipe, Mesa 22.3): about 0.001-0.0025,
 * under the 0.005 noise bound, so a regression that moves any level is caught while another
 * LLVM's rounding is not. Printed: the full table of both modes.
 * usage: test_ground_truth SHARED_DIR   (exit 77 = skipped when SHARED_DIR is absent) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

#define TOLERANCE 0.005
#define ESTIMATE_MULTIPLIER 0.5f

static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};

/* RMSE per scene (order of scenes[]) and quality: {look, estimate}, as printed by this test. */
static const double measured_rmse[3][5][2] = {
    {{0.10377, 0.12612},
     {0.10308, 0.11849},
     {0.10668, 0.11599},
     {0.10662, 0.11485},
     {0.10619, 0.11492}}, /* interior_fzkhaus */
    {{0.06423, 0.04937},
     {0.06796, 0.04611},
     {0.07455, 0.04631},
     {0.07397, 0.04584},
     {0.07197, 0.04598}}, /* statues_scanned */
    {{0.08432, 0.09703},
     {0.07811, 0.09388},
     {0.07071, 0.09112},
     {0.06944, 0.09027},
     {0.06901, 0.09043}}, /* street_track */
};
#define RMSE_MARGIN 1.02

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

static void run_scene(vkdev *dev, const char *shared, int index) {
    const char *scene = scenes[index];
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
        const char *quality = cacao_quality_name(CACAO_QUALITY_LOWEST + q);
        printf("  %-8s | %.5f             | %.5f\n", quality, look[q], estimate[q]);
        for (int mode = 0; mode < 2; ++mode) {
            const double got = (mode ? estimate : look)[q], bound = RMSE_MARGIN * measured_rmse[index][q][mode];
            if (!(got <= bound)) {
                fprintf(stderr, "  ^ %s %s: %s RMSE %.5f above its bound %.5f (measured %.5f)\n", scene, quality,
                        mode ? "estimate" : "look", got, bound, measured_rmse[index][q][mode]);
                ++test_failures;
            }
        }
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
    for (int i = 0; i < 3; ++i) run_scene(&dev, argv[1], i);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_ground_truth");
}
