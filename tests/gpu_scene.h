/* gpu_scene.h - shared helpers of the GPU tests: render a procedural scene on the CPU, run cacao
 * on lavapipe (validation on), and simple image statistics. Header-only, tests only. */
#ifndef CACAO_GPU_SCENE_H
#define CACAO_GPU_SCENE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sys/stat.h>

#include "camera_json.h"
#include "image_io.h"
#include "scene.h"
#include "test_util.h"
#include "vkdev.h"

typedef struct scene_buffers {
    uint32_t width, height;
    float *depth, *depth_reversed, *normals;
    float projection[16], projection_reversed[16], view_from_world[16];
} scene_buffers;

/* The scene through a lens (orthographic, off-centre; all zero: the centred perspective). */
static inline void scene_buffers_render_lens(const cacao_scene *scene, const cacao_lens *lens, scene_buffers *b) {
    b->width = scene->camera.width;
    b->height = scene->camera.height;
    const size_t n = (size_t)b->width * b->height;
    b->depth = malloc(n * sizeof(float));
    b->depth_reversed = malloc(n * sizeof(float));
    b->normals = malloc(3 * n * sizeof(float));
    cacao_scene_render_lens(scene, lens, b->depth, b->depth_reversed, b->normals);
    cacao_camera_projection_lens(&scene->camera, lens, false, b->projection);
    cacao_camera_projection_lens(&scene->camera, lens, true, b->projection_reversed);
    cacao_camera_view_from_world(&scene->camera, b->view_from_world);
}

static inline void scene_buffers_render(const cacao_scene *scene, scene_buffers *b) {
    const cacao_lens centred = {0};
    scene_buffers_render_lens(scene, &centred, b);
}

/* Renders the embedded default scene at w x h into b; returns its AO radius. */
static inline float scene_buffers_default(uint32_t w, uint32_t h, scene_buffers *b) {
    const cacao_scene scene = cacao_default_scene(w, h);
    scene_buffers_render(&scene, b);
    return (float)scene.ao_radius_world;
}

/* The scene scaled by sc about the world origin: primitives, eye, target, near and far (far_z then
 * set by the caller where it must differ). prims holds up to prim_cap primitives. */
static inline cacao_scene scene_scaled(const cacao_scene *base, double sc, cacao_prim *prims, uint32_t prim_cap) {
    cacao_scene scene = *base;
    scene.prim_count = base->prim_count < prim_cap ? base->prim_count : prim_cap;
    for (uint32_t i = 0; i < scene.prim_count; ++i) {
        prims[i] = base->prims[i];
        for (int j = 0; j < 3; ++j) {
            prims[i].a[j] *= sc;
            if (prims[i].kind != CACAO_PRIM_PLANE) prims[i].b[j] *= sc;
        }
        prims[i].r *= sc;
    }
    scene.prims = prims;
    for (int j = 0; j < 3; ++j) scene.camera.eye[j] *= sc, scene.camera.target[j] *= sc;
    scene.camera.near_z *= sc;
    scene.camera.far_z *= sc;
    return scene;
}

static inline void scene_buffers_free(scene_buffers *b) {
    free(b->depth);
    free(b->depth_reversed);
    free(b->normals);
}

/* The scenes' normals are right-handed view space (camera-facing +z); cacao's view space has
 * camera-facing normals at -z: N = diag(1, 1, -1). Float normals: unpack 1, 0. */
static inline vkdev_frame scene_frame(const scene_buffers *b, bool reversed, bool with_normals) {
    vkdev_frame f = {.width = b->width,
                     .height = b->height,
                     .depth = reversed ? b->depth_reversed : b->depth,
                     .depth_reversed = reversed};
    memcpy(f.projection, reversed ? b->projection_reversed : b->projection, sizeof f.projection);
    if (with_normals) vkdev_frame_set_view_normals(&f, b->normals);
    return f;
}

/* World position of pixel i from the standard depth (for selecting regions by geometry). */
static inline bool scene_world_position(const cacao_scene *scene, const scene_buffers *b, size_t i, double out[3]) {
    const cacao_camera *c = &scene->camera;
    const double d = b->depth[i];
    if (d >= 1.0) return false;
    const double z = c->near_z * c->far_z / (c->far_z - d * (c->far_z - c->near_z));
    const double t = tan(c->fov_y_deg * 3.14159265358979323846 / 360.0), aspect = (double)b->width / b->height;
    const double u = ((double)(i % b->width) + 0.5) / b->width, v = ((double)(i / b->width) + 0.5) / b->height;
    const double view[3] = {(2 * u - 1) * aspect * t * z, (1 - 2 * v) * t * z, -z};
    const float *m = b->view_from_world; /* [R | t]: world = R^T (view - t) */
    for (int k = 0; k < 3; ++k)
        out[k] = m[0 * 4 + k] * (view[0] - m[3]) + m[1 * 4 + k] * (view[1] - m[7]) + m[2 * 4 + k] * (view[2] - m[11]);
    return true;
}

/* Mean |a - b| over n values. */
static inline double mean_abs_diff(const float *a, const float *b, size_t n) {
    double m = 0;
    for (size_t i = 0; i < n; ++i) m += fabs((double)a[i] - b[i]);
    return m / (double)n;
}

static inline bool all_finite_unit(const float *ao, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!(ao[i] >= 0.0f && ao[i] <= 1.0f)) return false; /* also catches NaN */
    return true;
}

/* Opens lavapipe with validation; the vkdev must stay where it is (the layer reports into it). */
static inline void open_device(vkdev *dev) {
    char err[512];
    if (!vkdev_create(&(vkdev_options){.validation = true}, dev, err, sizeof err)) {
        fprintf(stderr, "cannot open the Vulkan device: %s\n", err);
        exit(1);
    }
}

/* Runs cacao; a failure is a test failure (message printed). */
static inline bool run(vkdev *dev, const cacao_settings *s, const vkdev_frame *f, float *ao) {
    char err[512];
    cacao_result r = vkdev_run(dev, s, f, 1, ao, NULL, err, sizeof err);
    if (r != CACAO_SUCCESS) {
        fprintf(stderr, "cacao run failed: %s: %s\n", cacao_result_string(r), err);
        ++test_failures;
        return false;
    }
    return true;
}

/* Tests of the shared data (scenes, AMD reference): argv[1] is CACAO_SHARED_DIR; exits with the
 * "skipped" code when it is absent, so a clone without ../shared reports skips, not failures. */
static inline const char *require_shared_dir(int argc, char **argv) {
    struct stat st;
    if (argc < 2 || stat(argv[1], &st) != 0) {
        printf("skipped: shared data directory '%s' not found (set CACAO_SHARED_DIR)\n", argc > 1 ? argv[1] : "");
        exit(TEST_SKIP_CODE);
    }
    return argv[1];
}

/* A shared scene's standard depth, ray-traced ao_gt_falloff and camera (a failure is a test failure). */
static inline bool load_shared_scene(const char *shared, const char *scene, cacao_img *depth, cacao_img *gt,
                                     cacao_camera_file *cam) {
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s/scenes/%s/depth.pfm", shared, scene);
    bool ok = cacao_pfm_read(path, depth, err, sizeof err);
    snprintf(path, sizeof path, "%s/scenes/%s/ao_gt_falloff.pfm", shared, scene);
    ok = ok && cacao_pfm_read(path, gt, err, sizeof err);
    snprintf(path, sizeof path, "%s/scenes/%s/camera.json", shared, scene);
    ok = ok && cacao_camera_json_read(path, cam, err, sizeof err) && cam->has_projection;
    if (!ok) {
        fprintf(stderr, "%s: %s\n", scene, err);
        ++test_failures;
    }
    return ok;
}

#endif
