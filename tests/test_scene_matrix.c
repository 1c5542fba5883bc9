/* test_scene_matrix - every quality level paired with every value of every other axis
 * (native/downsampled, normals given/reconstructed, blur 0/1/4/8, fp16/fp32, standard/reverse-Z)
 * on the real shared scenes: output has no NaN/Inf and lies in [0,1], with zero validation
 * messages, and it stays close to the same scene at the same quality in the reference
 * configuration (native, normals from depth, blur 2, fp32, standard depth): every axis changes
 * the estimate only a little (noise, resolution, normal source, rounding, depth encoding), so the
 * mean |AO - reference| over non-background pixels may be at most 1.5x its measured value plus
 * 0.25/255, while a broken axis (wrong reverse-Z unpack, fp16 overflow, swapped normals, a lost
 * slice) moves it by far more. Four configurations per quality cover each axis value at least
 * once (a covering design, not the full product, to keep lavapipe time low); the scenes rotate.
 * usage: test_scene_matrix SHARED_DIR   (exit 77 = skipped when SHARED_DIR is absent) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};

typedef struct axes {
    bool downsample, normals_given, reversed, fp16;
    int blur; /* 0 = none */
} axes;

/* Each column value of every axis appears at least once per quality. */
static const axes designs[4] = {
    {false, false, false, false, 0},
    {true, true, true, true, 1},
    {false, true, false, true, 4},
    {true, false, true, false, 8},
};

/* mean |AO - reference| of each run, in run order (quality-major, then designs[]), as printed by
 * this test on lavapipe; the bound is 1.5x this plus 0.25/255. */
static const double measured_diff[20] = {
    0.022997, 0.010598, 0.000983, 0.030923, 0.011258, 0.002123, 0.007054, 0.021272, 0.004787, 0.014365,
    0.004901, 0.004456, 0.013595, 0.009732, 0.000912, 0.027792, 0.007425, 0.001985, 0.005859, 0.018658,
};
#define DIFF_BOUND(measured) (1.5 * (measured) + 0.25 / 255.0)

typedef struct scene_data {
    cacao_img depth, depth_reversed, normals;
    cacao_camera_file cam;
} scene_data;

static bool load(const char *shared, const char *scene, scene_data *d) {
    char path[4096], err[512];
    memset(d, 0, sizeof *d);
    bool ok = true;
    snprintf(path, sizeof path, "%s/scenes/%s/depth.pfm", shared, scene);
    ok = ok && cacao_pfm_read(path, &d->depth, err, sizeof err);
    snprintf(path, sizeof path, "%s/scenes/%s/depth_reversed.pfm", shared, scene);
    ok = ok && cacao_pfm_read(path, &d->depth_reversed, err, sizeof err);
    snprintf(path, sizeof path, "%s/scenes/%s/normals.pfm", shared, scene);
    ok = ok && cacao_pfm_read(path, &d->normals, err, sizeof err) && d->normals.channels == 3;
    snprintf(path, sizeof path, "%s/scenes/%s/camera.json", shared, scene);
    ok = ok && cacao_camera_json_read(path, &d->cam, err, sizeof err) && d->cam.has_projection &&
         d->cam.has_projection_reversed;
    if (!ok) fprintf(stderr, "%s: %s\n", scene, err);
    return ok;
}

int main(int argc, char **argv) {
    require_shared_dir(argc, argv);
    scene_data data[3];
    for (int i = 0; i < 3; ++i)
        if (!load(argv[1], scenes[i], &data[i])) return 1;
    vkdev dev;
    char err[512];
    open_device(&dev);
    if (!dev.fp16) printf("skipped: fp16 coverage (device has no shaderFloat16; fp16 configurations run as fp32)\n");
    unsigned run = 0;
    for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (int k = 0; k < 4; ++k, ++run) {
            const axes *a = &designs[k];
            const scene_data *d = &data[run % 3];
            const size_t n = (size_t)d->depth.width * d->depth.height;
            vkdev_frame f = {.width = d->depth.width,
                             .height = d->depth.height,
                             .depth = a->reversed ? d->depth_reversed.data : d->depth.data};
            memcpy(f.projection, a->reversed ? d->cam.projection_reversed : d->cam.projection, sizeof f.projection);
            if (a->normals_given) vkdev_frame_set_view_normals(&f, d->normals.data);
            const cacao_settings s = {.quality = (cacao_quality)q,
                                      .downsample = a->downsample,
                                      .generate_normals = !a->normals_given,
                                      .blur_pass_count = a->blur ? a->blur : CACAO_BLUR_NONE,
                                      .precision = a->fp16 ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32,
                                      .radius = (float)d->cam.ao_radius_world};
            float *ao = malloc(n * sizeof *ao), *ref = malloc(n * sizeof *ref);
            cacao_result r = vkdev_run(&dev, &s, &f, 1, ao, NULL, err, sizeof err);
            CHECK(r == CACAO_SUCCESS);
            vkdev_frame fr = {.width = d->depth.width, .height = d->depth.height, .depth = d->depth.data};
            memcpy(fr.projection, d->cam.projection, sizeof fr.projection);
            const cacao_settings sr = {
                .quality = (cacao_quality)q, .generate_normals = true, .radius = (float)d->cam.ao_radius_world};
            const cacao_result rr = vkdev_run(&dev, &sr, &fr, 1, ref, NULL, err, sizeof err);
            CHECK(rr == CACAO_SUCCESS);
            double diff = 0;
            size_t counted = 0;
            for (size_t i = 0; r == CACAO_SUCCESS && rr == CACAO_SUCCESS && i < n; ++i)
                if (d->depth.data[i] < 1.0f) diff += fabs((double)ao[i] - ref[i]), ++counted;
            diff = counted ? diff / (double)counted : 0.0;
            size_t bad = 0;
            double sum = 0;
            for (size_t i = 0; r == CACAO_SUCCESS && i < n; ++i) {
                if (!(ao[i] >= 0.0f && ao[i] <= 1.0f))
                    ++bad;
                else
                    sum += ao[i];
            }
            printf("%-17s %-7s %-11s normals %-5s blur %d %s %s: mean AO %.4f, %zu values outside [0,1], "
                   "mean |AO - reference| %.6f\n",
                   scenes[run % 3], cacao_quality_name(q), a->downsample ? "downsampled" : "native",
                   a->normals_given ? "given" : "depth", a->blur, a->fp16 ? "fp16" : "fp32",
                   a->reversed ? "reverse-Z" : "standard", sum / (double)n, bad, diff);
            CHECK(bad == 0);
            if (!(diff <= DIFF_BOUND(measured_diff[run]))) {
                fprintf(stderr, "  ^ mean |AO - reference| %.6f above its bound %.6f (measured %.6f)\n", diff,
                        DIFF_BOUND(measured_diff[run]), measured_diff[run]);
                ++test_failures;
            }
            free(ao);
            free(ref);
        }
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    for (int i = 0; i < 3; ++i) {
        cacao_img_free(&data[i].depth);
        cacao_img_free(&data[i].depth_reversed);
        cacao_img_free(&data[i].normals);
    }
    return test_report("test_scene_matrix");
}
