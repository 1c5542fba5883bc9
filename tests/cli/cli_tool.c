/* cli_tool - makes the inputs of the CLI tests and inspects its outputs, independently of the
 * `cacao` command's own code (image_io, exr_io and scene.c only).
 *
 *   cli_tool scene DIR W H        the default scene at WxH as a scene folder (depth.pfm,
 *                                 depth_reversed.pfm, normals.pfm, camera.json)
 *   cli_tool plane DIR W H        a plane facing the camera, filling the view, as a scene folder
 *   cli_tool ortho DIR W H        the default scene through an orthographic lens, as a scene folder
 *   cli_tool offcentre DIR W H    the same through a quarter-width off-centre perspective lens
 *   cli_tool const FILE W H V     a 1-channel image of W x H, every pixel V (format by extension)
 *   cli_tool convert IN OUT [8]   re-writes an image in OUT's format (.png: 16-bit, or 8-bit with 8)
 *   cli_tool truncate IN OUT N    copies the first N bytes of IN
 *   cli_tool poke IN OUT X Y V    copies IN with channel 0 of pixel (X, Y) set to V (e.g. nan)
 *   cli_tool info FILE            prints "W H CHANNELS BITS" (BITS 8/16 for PNG, 32 otherwise)
 *   cli_tool diff A B             prints "mean_abs M max_abs X" over all pixels of two images
 *   cli_tool foreground DEPTH     prints the number of pixels with depth < 1 (standard depth)
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exr_io.h"
#include "image_io.h"
#include "scene.h"

static int die(const char *message) {
    fprintf(stderr, "cli_tool: %s\n", message);
    return 1;
}

static const char *ext_of(const char *path) {
    const char *dot = strrchr(path, '.');
    return dot ? dot : "";
}

static bool read_any(const char *path, cacao_img *img, bool *is16, char *err, size_t n) {
    *is16 = false;
    if (strcmp(ext_of(path), ".pfm") == 0) return cacao_pfm_read(path, img, err, n);
    if (strcmp(ext_of(path), ".png") == 0) return cacao_png_read(path, img, is16, err, n);
    if (strcmp(ext_of(path), ".exr") == 0) {
        /* Try three channels first, then one. */
        char ignored[512];
        return cacao_exr_read_vector(path, img, ignored, sizeof ignored) || cacao_exr_read_scalar(path, img, err, n);
    }
    snprintf(err, n, "%s: unknown extension", path);
    return false;
}

static bool write_any(const char *path, const cacao_img *img, int png_bits, char *err, size_t n) {
    if (strcmp(ext_of(path), ".pfm") == 0) return cacao_pfm_write(path, img, err, n);
    if (strcmp(ext_of(path), ".png") == 0) return cacao_png_write(path, img, png_bits, err, n);
    if (strcmp(ext_of(path), ".exr") == 0) return cacao_exr_write(path, img, err, n);
    snprintf(err, n, "%s: unknown extension", path);
    return false;
}

static void add_matrix(cJSON *root, const char *name, const float m[16]) {
    cJSON *array = cJSON_AddArrayToObject(root, name);
    for (int i = 0; i < 16; ++i) cJSON_AddItemToArray(array, cJSON_CreateNumber(m[i]));
}

static bool write_camera(const char *dir, const cacao_scene *scene, const cacao_lens *lens) {
    const cacao_camera *c = &scene->camera;
    float p[16], pr[16];
    cacao_camera_projection_lens(c, lens, false, p);
    cacao_camera_projection_lens(c, lens, true, pr);
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "width", c->width);
    cJSON_AddNumberToObject(root, "height", c->height);
    cJSON_AddNumberToObject(root, "fov_y_deg", c->fov_y_deg);
    cJSON_AddNumberToObject(root, "near", c->near_z);
    cJSON_AddNumberToObject(root, "far", c->far_z);
    cJSON_AddNumberToObject(root, "ao_radius_world", scene->ao_radius_world);
    add_matrix(root, "projection", p);
    add_matrix(root, "projection_reversed", pr);
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    char path[4096];
    snprintf(path, sizeof path, "%s/camera.json", dir);
    FILE *f = fopen(path, "wb");
    const bool ok = f && text && fputs(text, f) >= 0;
    if (f) fclose(f);
    cJSON_free(text);
    return ok;
}

static int write_scene_folder(const char *dir, const cacao_scene *scene, const cacao_lens *lens) {
    const uint32_t w = scene->camera.width, h = scene->camera.height;
    cacao_img depth = {w, h, 1, malloc(sizeof(float) * w * h)};
    cacao_img reversed = {w, h, 1, malloc(sizeof(float) * w * h)};
    cacao_img normals = {w, h, 3, malloc(sizeof(float) * 3 * w * h)};
    cacao_scene_render_lens(scene, lens, depth.data, reversed.data, normals.data);
    char path[4096], err[512] = "cannot write camera.json";
    bool ok = true;
    snprintf(path, sizeof path, "%s/depth.pfm", dir);
    ok = ok && cacao_pfm_write(path, &depth, err, sizeof err);
    snprintf(path, sizeof path, "%s/depth_reversed.pfm", dir);
    ok = ok && cacao_pfm_write(path, &reversed, err, sizeof err);
    snprintf(path, sizeof path, "%s/normals.pfm", dir);
    ok = ok && cacao_pfm_write(path, &normals, err, sizeof err);
    ok = ok && write_camera(dir, scene, lens);
    cacao_img_free(&depth);
    cacao_img_free(&reversed);
    cacao_img_free(&normals);
    return ok ? 0 : die(err);
}

static int make_scene(const char *dir, uint32_t w, uint32_t h, bool plane) {
    static const cacao_prim facing[] = {{CACAO_PRIM_PLANE, {0, 0, -6}, {0, 0, 1}, 0}};
    cacao_scene scene = cacao_default_scene(w, h);
    if (plane) scene = (cacao_scene){facing, 1, {w, h, 60.0, 0.1, 100.0, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 1.0};
    const cacao_lens centred = {0};
    return write_scene_folder(dir, &scene, &centred);
}

/* The default scene through an orthographic lens (half height 5) or a quarter-width off-centre
 * perspective one, with their projection matrices in camera.json. */
static int make_lens_scene(const char *dir, uint32_t w, uint32_t h, bool ortho) {
    const cacao_scene scene = cacao_default_scene(w, h);
    const cacao_lens lens = {.ortho_half_height = ortho ? 5.0 : 0.0, .jitter_ndc = {ortho ? 0.0 : 0.5, 0.0}};
    return write_scene_folder(dir, &scene, &lens);
}

static int make_const(const char *path, uint32_t w, uint32_t h, float value) {
    cacao_img img = {w, h, 1, malloc(sizeof(float) * w * h)};
    for (size_t i = 0; i < (size_t)w * h; ++i) img.data[i] = value;
    char err[512];
    const bool ok = write_any(path, &img, 16, err, sizeof err);
    cacao_img_free(&img);
    return ok ? 0 : die(err);
}

static int convert(const char *in, const char *out, int png_bits) {
    cacao_img img;
    bool is16;
    char err[512];
    bool ok = read_any(in, &img, &is16, err, sizeof err) && write_any(out, &img, png_bits, err, sizeof err);
    cacao_img_free(&img);
    return ok ? 0 : die(err);
}

static int truncate_copy(const char *in, const char *out, long bytes) {
    FILE *src = fopen(in, "rb"), *dst = fopen(out, "wb");
    char *buffer = malloc((size_t)bytes + 1);
    const bool ok = src && dst && buffer && fread(buffer, 1, (size_t)bytes, src) == (size_t)bytes &&
                    fwrite(buffer, 1, (size_t)bytes, dst) == (size_t)bytes;
    if (src) fclose(src);
    if (dst) fclose(dst);
    free(buffer);
    return ok ? 0 : die("truncate: cannot copy");
}

static int poke(const char *in, const char *out, uint32_t x, uint32_t y, float value) {
    cacao_img img;
    bool is16;
    char err[512];
    if (!read_any(in, &img, &is16, err, sizeof err)) return die(err);
    bool ok = x < img.width && y < img.height;
    if (ok) img.data[((size_t)y * img.width + x) * img.channels] = value;
    ok = ok && write_any(out, &img, 16, err, sizeof err);
    cacao_img_free(&img);
    return ok ? 0 : die(x < img.width && y < img.height ? err : "poke: pixel outside the image");
}

static int info(const char *path) {
    cacao_img img;
    bool is16;
    char err[512];
    if (!read_any(path, &img, &is16, err, sizeof err)) return die(err);
    const int bits = strcmp(ext_of(path), ".png") == 0 ? (is16 ? 16 : 8) : 32;
    printf("%u %u %u %d\n", img.width, img.height, img.channels, bits);
    cacao_img_free(&img);
    return 0;
}

static int diff(const char *a_path, const char *b_path) {
    cacao_img a = {0}, b = {0};
    bool is16;
    char err[512];
    if (!read_any(a_path, &a, &is16, err, sizeof err) || !read_any(b_path, &b, &is16, err, sizeof err)) return die(err);
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) return die("diff: sizes differ");
    double sum = 0, worst = 0;
    const size_t n = (size_t)a.width * a.height * a.channels;
    for (size_t i = 0; i < n; ++i) {
        const double d = fabs((double)a.data[i] - (double)b.data[i]);
        sum += d;
        worst = d > worst ? d : worst;
    }
    printf("mean_abs %.9f max_abs %.9f\n", sum / (double)n, worst);
    cacao_img_free(&a);
    cacao_img_free(&b);
    return 0;
}

static int foreground(const char *path) {
    cacao_img depth;
    char err[512];
    if (!cacao_pfm_read(path, &depth, err, sizeof err)) return die(err);
    size_t count = 0;
    for (size_t i = 0; i < (size_t)depth.width * depth.height; ++i) count += depth.data[i] < 1.0f;
    printf("%zu\n", count);
    cacao_img_free(&depth);
    return 0;
}

int main(int argc, char **argv) {
    const char *cmd = argc > 1 ? argv[1] : "";
    if ((strcmp(cmd, "scene") == 0 || strcmp(cmd, "plane") == 0) && argc == 5)
        return make_scene(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]), cmd[0] == 'p');
    if ((strcmp(cmd, "ortho") == 0 || strcmp(cmd, "offcentre") == 0) && argc == 5)
        return make_lens_scene(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]), strcmp(cmd, "ortho") == 0);
    if (strcmp(cmd, "const") == 0 && argc == 6)
        return make_const(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]), strtof(argv[5], NULL));
    if (strcmp(cmd, "convert") == 0 && (argc == 4 || argc == 5)) return convert(argv[2], argv[3], argc == 5 ? 8 : 16);
    if (strcmp(cmd, "truncate") == 0 && argc == 5) return truncate_copy(argv[2], argv[3], atol(argv[4]));
    if (strcmp(cmd, "poke") == 0 && argc == 7)
        return poke(argv[2], argv[3], (uint32_t)atoi(argv[4]), (uint32_t)atoi(argv[5]), strtof(argv[6], NULL));
    if (strcmp(cmd, "info") == 0 && argc == 3) return info(argv[2]);
    if (strcmp(cmd, "diff") == 0 && argc == 4) return diff(argv[2], argv[3]);
    if (strcmp(cmd, "foreground") == 0 && argc == 3) return foreground(argv[2]);
    return die("usage: see the comment at the top of cli_tool.c");
}
