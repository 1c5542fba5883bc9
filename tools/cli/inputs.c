/* inputs.c - loading the `cacao` command's depth, normals and camera (see inputs.h). */
#include "inputs.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "camera_json.h"
#include "exr_io.h"
#include "scene.h"
#include "text_file.h"

const char *const cli_scene_file_names[CLI_SCENE_FILE_COUNT] = {"depth.pfm", "depth_reversed.pfm", "normals.pfm",
                                                                 "camera.json"};

void cli_extension(const char *path, char *out, size_t out_size) {
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    out[0] = '\0';
    if (!dot || (slash && dot < slash) || out_size == 0) return;
    size_t i = 0;
    for (; dot[i] && i + 1 < out_size; ++i) out[i] = (char)tolower((unsigned char)dot[i]);
    out[i] = '\0';
}

static bool check_channels(const cacao_img *img, uint32_t want, const char *path, const char *role, char *err,
                           size_t n) {
    if (img->channels == want) return true;
    cacao_set_err(err, n, "%s: wrong channel count for %s: needs %u, the file has %u", path, role, want, img->channels);
    return false;
}

static bool read_png_scalar(const char *path, const char *role, bool allow_8bit, cacao_img *out, char *err, size_t n) {
    bool is16 = false;
    if (!cacao_png_read(path, out, &is16, err, n)) return false;
    if (!is16 && !allow_8bit) {
        cacao_set_err(err, n, "%s: 8-bit PNG %s is too coarse; use a 16-bit grey PNG (value/65535 = raw depth), PFM or EXR",
                path, role);
        return false;
    }
    return check_channels(out, 1, path, role, err, n);
}

bool cli_read_scalar_image(const char *path, const char *role, bool allow_8bit, cacao_img *out, char *err, size_t n) {
    char ext[16];
    cli_extension(path, ext, sizeof ext);
    bool ok;
    if (strcmp(ext, ".pfm") == 0)
        ok = cacao_pfm_read(path, out, err, n) && check_channels(out, 1, path, role, err, n);
    else if (strcmp(ext, ".exr") == 0)
        ok = cacao_exr_read_scalar(path, out, err, n);
    else if (strcmp(ext, ".png") == 0)
        ok = read_png_scalar(path, role, allow_8bit, out, err, n);
    else {
        cacao_set_err(err, n, "%s: unknown %s format '%s' (use .pfm, .exr or .png)", path, role, ext);
        ok = false;
    }
    if (!ok) cacao_img_free(out);
    return ok;
}

static bool read_normals_image(const char *path, cacao_img *out, char *err, size_t n) {
    char ext[16];
    cli_extension(path, ext, sizeof ext);
    bool ok;
    if (strcmp(ext, ".pfm") == 0)
        ok = cacao_pfm_read(path, out, err, n) && check_channels(out, 3, path, "normals", err, n);
    else if (strcmp(ext, ".exr") == 0)
        ok = cacao_exr_read_vector(path, out, err, n);
    else {
        cacao_set_err(err, n, "%s: unknown normals format '%s' (use float .pfm or .exr)", path, ext);
        ok = false;
    }
    if (!ok) cacao_img_free(out);
    return ok;
}

/* ---- Projection ------------------------------------------------------------------------------ */

/* The projection of the run: the camera file's matrix for the depth convention when the file has
 * it and no --fov/--near/--far overrides it, else the scenes' perspective built from the
 * effective fov/near/far with aspect = width/height. */
static bool build_projection(const cli_options *o, const cacao_camera_file *file, const char *camera_path,
                             uint32_t width, uint32_t height, float out[16], char *source, size_t source_size,
                             char *err, size_t n) {
    const bool overridden = o->fov_y_deg > 0 || o->near_z > 0 || o->far_z > 0;
    const double fov = o->fov_y_deg > 0 ? o->fov_y_deg : file ? file->fov_y_deg : 0;
    const double near_z = o->near_z > 0 ? o->near_z : file ? file->near_z : 0;
    const double far_z = o->far_z > 0 ? o->far_z : file ? file->far_z : 0;
    if (!file && !(fov > 0 && near_z > 0 && far_z > 0)) {
        cacao_set_err(err, n, "--depth: needs --camera FILE, or all of --fov, --near and --far");
        return false;
    }
    if (!(fov < 180) || !(far_z > near_z)) {
        cacao_set_err(err, n, "--fov/--near/--far: need fov below 180 degrees and near < far (fov %g, near %g, far %g)", fov,
                near_z, far_z);
        return false;
    }
    if (file && (file->width || file->height) && ((uint32_t)file->width != width || (uint32_t)file->height != height)) {
        cacao_set_err(err, n, "%s: camera is %dx%d but the depth is %ux%u", camera_path, file->width, file->height, width,
                height);
        return false;
    }
    const bool has_matrix = file && (o->reverse_z ? file->has_projection_reversed : file->has_projection);
    if (has_matrix && !overridden) {
        memcpy(out, o->reverse_z ? file->projection_reversed : file->projection, 16 * sizeof(float));
        snprintf(source, source_size, "%s: field '%s'", camera_path,
                 o->reverse_z ? "projection_reversed" : "projection");
    } else {
        cacao_perspective(fov, (double)width / height, near_z, far_z, o->reverse_z, out);
        if (overridden)
            snprintf(source, source_size, "--fov/--near/--far (fov %g, near %g, far %g)", fov, near_z, far_z);
        else
            snprintf(source, source_size, "%s: fields 'fov_y_deg', 'near', 'far' (%g, %g, %g)", camera_path, fov,
                     near_z, far_z);
    }
    return true;
}

/* ---- Sources ------------------------------------------------------------------------------- */

static bool load_default_scene(const cli_options *o, cli_inputs *in, char *err, size_t n) {
    if (o->fov_y_deg > 0 || o->near_z > 0 || o->far_z > 0) {
        cacao_set_err(err, n, "--fov/--near/--far: the default scene has its own camera; give --depth or --scene");
        return false;
    }
    const cacao_scene scene_value = cacao_default_scene(1280, 720);
    const cacao_scene *scene = &scene_value;
    const uint32_t w = scene->camera.width, h = scene->camera.height;
    in->depth = (cacao_img){w, h, 1, malloc(sizeof(float) * w * h)};
    in->normals = (cacao_img){w, h, 3, malloc(sizeof(float) * 3 * w * h)};
    if (!in->depth.data || !in->normals.data) {
        cacao_set_err(err, n, "default scene: out of memory");
        return false;
    }
    float *standard = o->reverse_z ? malloc(sizeof(float) * w * h) : in->depth.data; /* always rendered */
    if (!standard) {
        cacao_set_err(err, n, "default scene: out of memory");
        return false;
    }
    cacao_scene_render(scene, standard, o->reverse_z ? in->depth.data : NULL, in->normals.data);
    if (standard != in->depth.data) free(standard);
    cacao_camera_projection(&scene->camera, o->reverse_z, in->projection);
    snprintf(in->projection_source, sizeof in->projection_source, "the default scene's camera");
    in->ao_radius_world = scene->ao_radius_world;
    return true;
}

/* Whether path is there (a stat, not an open: a FIFO must not block here; the reader refuses it). */
static bool file_exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* Depth and normals go to the device through one staging buffer of 20 bytes a pixel, and a
 * buffer must stay below 4 GiB (lavapipe's limit): depth alone reaches 16384x16384, with normals less. */
#define MAX_PIXELS_WITH_NORMALS (((uint64_t)1 << 32) / 20)

static bool check_same_size(const cacao_img *depth, const cacao_img *normals, const char *depth_path,
                            const char *normals_path, char *err, size_t n) {
    if (normals->data && (uint64_t)depth->width * depth->height > MAX_PIXELS_WITH_NORMALS) {
        cacao_set_err(err, n, "%s: %ux%u with normals is more than the %llu pixels the tools stage at once; give the depth "
                "alone (normals are then reconstructed)", normals_path, depth->width, depth->height,
                (unsigned long long)MAX_PIXELS_WITH_NORMALS);
        return false;
    }
    if (!normals->data || (normals->width == depth->width && normals->height == depth->height)) return true;
    cacao_set_err(err, n, "%s: normals are %ux%u but the depth (%s) is %ux%u", normals_path, normals->width, normals->height,
            depth_path, depth->width, depth->height);
    return false;
}

/* Depth, optional normals and the camera from their paths (camera_path may be NULL). */
static bool load_files(const cli_options *o, const char *depth_path, const char *normals_path, const char *camera_path,
                       cli_inputs *in, char *err, size_t n) {
    cacao_camera_file camera;
    if (camera_path && !cacao_camera_json_read(camera_path, &camera, err, n)) return false;
    if (!cli_read_scalar_image(depth_path, "depth", false, &in->depth, err, n)) return false;
    if (normals_path && !read_normals_image(normals_path, &in->normals, err, n)) return false;
    if (!check_same_size(&in->depth, &in->normals, depth_path, normals_path, err, n)) return false;
    in->ao_radius_world = camera_path ? camera.ao_radius_world : 0.0;
    return build_projection(o, camera_path ? &camera : NULL, camera_path, in->depth.width, in->depth.height,
                            in->projection, in->projection_source, sizeof in->projection_source, err, n);
}

static bool load_scene_dir(const cli_options *o, cli_inputs *in, char *err, size_t n) {
    char depth[4096], normals[4096], camera[4096];
    snprintf(depth, sizeof depth, "%s/%s", o->scene_dir, o->reverse_z ? "depth_reversed.pfm" : "depth.pfm");
    snprintf(normals, sizeof normals, "%s/normals.pfm", o->scene_dir);
    snprintf(camera, sizeof camera, "%s/camera.json", o->scene_dir);
    if (!file_exists(depth)) {
        cacao_set_err(err, n, "--scene %s: no %s in the folder", o->scene_dir,
                o->reverse_z ? "depth_reversed.pfm" : "depth.pfm");
        return false;
    }
    if (!file_exists(camera)) {
        cacao_set_err(err, n, "--scene %s: no camera.json in the folder", o->scene_dir);
        return false;
    }
    return load_files(o, depth, file_exists(normals) ? normals : NULL, camera, in, err, n);
}

static bool check_source_flags(const cli_options *o, char *err, size_t n) {
    if (o->scene_dir && (o->depth_path || o->normals_path || o->camera_path)) {
        cacao_set_err(err, n, "--scene: cannot be combined with --depth, --normals or --camera");
        return false;
    }
    if (!o->depth_path && (o->normals_path || o->camera_path)) {
        cacao_set_err(err, n, "%s: needs --depth", o->normals_path ? "--normals" : "--camera");
        return false;
    }
    return true;
}

bool cli_inputs_load(const cli_options *o, cli_inputs *in, char *err, size_t n) {
    memset(in, 0, sizeof *in);
    bool ok = check_source_flags(o, err, n);
    if (ok && o->scene_dir) ok = load_scene_dir(o, in, err, n);
    else if (ok && o->depth_path) ok = load_files(o, o->depth_path, o->normals_path, o->camera_path, in, err, n);
    else if (ok) ok = load_default_scene(o, in, err, n);
    in->depth_reversed = o->reverse_z;
    if (!ok) cli_inputs_free(in);
    return ok;
}

void cli_inputs_free(cli_inputs *in) {
    cacao_img_free(&in->depth);
    cacao_img_free(&in->normals);
}

cacao_settings cli_inputs_settings(const cli_options *o, const cli_inputs *in) {
    cacao_settings s = o->settings;
    if (!o->radius_given && in->ao_radius_world > 0) s.radius = (float)in->ao_radius_world;
    if (!in->normals.data) s.generate_normals = true;
    return s;
}

vkdev_frame cli_inputs_frame(const cli_inputs *in, const cacao_settings *encoded, uint32_t frame_index) {
    vkdev_frame frame = {.width = in->depth.width,
                         .height = in->depth.height,
                         .depth = in->depth.data,
                         .depth_reversed = in->depth_reversed,
                         .frame_index = frame_index};
    memcpy(frame.projection, in->projection, sizeof frame.projection);
    if (in->normals.data && !encoded->generate_normals) vkdev_frame_set_view_normals(&frame, in->normals.data);
    return frame;
}

bool cli_inputs_reuse_frame(const cli_options *o, const cli_inputs *in, vkdev_frame *frame, float **moved, char *err,
                            size_t err_size) {
    frame->output_holds_previous = o->keep_output;
    frame->alternate_camera = o->move_camera;
    *moved = NULL;
    if (!o->move_box) return true;
    unsigned x, y, w, h;
    char end;
    const uint32_t iw = in->depth.width, ih = in->depth.height;
    if (sscanf(o->move_box, "%u,%u,%u,%u%c", &x, &y, &w, &h, &end) != 4 || w == 0 || h == 0 || x >= iw || y >= ih ||
        w > iw - x || h > ih - y) {
        cacao_set_err(err, err_size, "--move-box %s: expected X,Y,W,H, a box of at least one pixel inside the %ux%u depth",
                      o->move_box, iw, ih);
        return false;
    }
    *moved = malloc(sizeof(float) * iw * ih);
    if (!*moved) {
        cacao_set_err(err, err_size, "--move-box: out of memory");
        return false;
    }
    memcpy(*moved, in->depth.data, sizeof(float) * iw * ih);
    for (uint32_t r = y; r < y + h; ++r)
        for (uint32_t c = x; c < x + w; ++c)
            (*moved)[(size_t)r * iw + c] = in->depth.data[(size_t)r * iw + (c >= 8 ? c - 8 : c)];
    frame->alternate_depth = *moved;
    return true;
}
