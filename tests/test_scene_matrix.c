/* test_scene_matrix - every quality level paired with every value of every other axis
 * (native/downsampled, normals given/reconstructed, blur 0/1/4/8, fp16/fp32, standard/reverse-Z)
 * on the real shared scenes: output has no NaN/Inf and lies in [0,1], with zero validation
 * messages. Four configurations per quality cover each axis value at least once (a covering
 * design, not the full product, to keep lavapipe time low); the scenes rotate between them.
 * usage: test_scene_matrix SHARED_DIR   (exit 77 = skipped when SHARED_DIR is absent) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_scene.h"

static const char *const scenes[] = {"interior_fzkhaus", "statues_scanned", "street_track"};
static const char *const quality_names[] = {"", "lowest", "low", "medium", "high", "highest"};

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
            float *ao = malloc(n * sizeof *ao);
            cacao_result r = vkdev_run(&dev, &s, &f, 1, ao, NULL, err, sizeof err);
            CHECK(r == CACAO_SUCCESS);
            size_t bad = 0;
            double sum = 0;
            for (size_t i = 0; r == CACAO_SUCCESS && i < n; ++i) {
                if (!(ao[i] >= 0.0f && ao[i] <= 1.0f)) ++bad;
                else sum += ao[i];
            }
            printf("%-17s %-7s %-11s normals %-5s blur %d %s %s: mean AO %.4f, %zu values outside [0,1]\n",
                   scenes[run % 3], quality_names[q], a->downsample ? "downsampled" : "native",
                   a->normals_given ? "given" : "depth", a->blur, a->fp16 ? "fp16" : "fp32",
                   a->reversed ? "reverse-Z" : "standard", sum / (double)n, bad);
            CHECK(bad == 0);
            free(ao);
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
