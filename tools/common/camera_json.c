/* camera_json.c - camera.json reading with cJSON; every field is checked before use. */
#include "camera_json.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *read_text(const char *path, char *err, size_t n) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, n, "%s: cannot open", path);
        return NULL;
    }
    char *buf = NULL;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (size < 0 || size > (1 << 24) || fseek(f, 0, SEEK_SET) != 0) {
        snprintf(err, n, "%s: cannot read (or larger than 16 MiB)", path);
    } else if ((buf = malloc((size_t)size + 1)) && fread(buf, 1, (size_t)size, f) == (size_t)size) {
        buf[size] = '\0';
    } else {
        free(buf);
        buf = NULL;
        snprintf(err, n, "%s: cannot read", path);
    }
    fclose(f);
    return buf;
}

static bool get_number(const cJSON *root, const char *name, bool required, double *out, const char *path, char *err,
                       size_t n) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(root, name);
    if (!item) {
        if (required) snprintf(err, n, "%s: field '%s' is missing", path, name);
        return !required;
    }
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble)) {
        snprintf(err, n, "%s: field '%s' must be a finite number", path, name);
        return false;
    }
    *out = item->valuedouble;
    return true;
}

static bool get_matrix(const cJSON *root, const char *name, bool *present, float out[16], const char *path, char *err,
                       size_t n) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(root, name);
    *present = false;
    if (!item) return true;
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != 16) {
        snprintf(err, n, "%s: field '%s' must be an array of 16 numbers", path, name);
        return false;
    }
    for (int i = 0; i < 16; ++i) {
        const cJSON *v = cJSON_GetArrayItem(item, i);
        if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) {
            snprintf(err, n, "%s: field '%s'[%d] must be a finite number", path, name, i);
            return false;
        }
        out[i] = (float)v->valuedouble;
    }
    *present = true;
    return true;
}

void cacao_perspective(double fov_y_deg, double aspect, double near_z, double far_z, bool reversed, float out[16]) {
    const double t = tan(fov_y_deg * 3.14159265358979323846 / 360.0);
    memset(out, 0, 16 * sizeof(float));
    out[0] = (float)(1.0 / (aspect * t));
    out[5] = (float)(1.0 / t);
    out[10] = (float)(reversed ? near_z / (far_z - near_z) : -far_z / (far_z - near_z));
    out[11] = (float)(reversed ? far_z * near_z / (far_z - near_z) : -far_z * near_z / (far_z - near_z));
    out[14] = -1.0f;
}

bool cacao_camera_json_read(const char *path, cacao_camera_file *out, char *err, size_t n) {
    memset(out, 0, sizeof *out);
    char *text = read_text(path, err, n);
    if (!text) return false;
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root || !cJSON_IsObject(root)) {
        snprintf(err, n, "%s: not a JSON object", path);
        cJSON_Delete(root);
        return false;
    }
    double w = 0, h = 0;
    bool ok = get_number(root, "width", false, &w, path, err, n) && get_number(root, "height", false, &h, path, err, n) &&
              get_number(root, "fov_y_deg", true, &out->fov_y_deg, path, err, n) &&
              get_number(root, "near", true, &out->near_z, path, err, n) &&
              get_number(root, "far", true, &out->far_z, path, err, n) &&
              get_number(root, "ao_radius_world", false, &out->ao_radius_world, path, err, n) &&
              get_matrix(root, "projection", &out->has_projection, out->projection, path, err, n) &&
              get_matrix(root, "projection_reversed", &out->has_projection_reversed, out->projection_reversed, path,
                         err, n);
    cJSON_Delete(root);
    if (!ok) return false;
    if (w < 0 || h < 0 || w > 16384 || h > 16384 || w != floor(w) || h != floor(h)) {
        snprintf(err, n, "%s: width/height must be whole numbers in 1..16384", path);
        return false;
    }
    out->width = (int)w;
    out->height = (int)h;
    if (!(out->fov_y_deg > 0 && out->fov_y_deg < 180)) {
        snprintf(err, n, "%s: field 'fov_y_deg' must be in (0, 180)", path);
        return false;
    }
    if (!(out->near_z > 0 && out->far_z > out->near_z)) {
        snprintf(err, n, "%s: fields 'near' and 'far' must satisfy 0 < near < far", path);
        return false;
    }
    if (out->ao_radius_world < 0 || !isfinite((float)out->ao_radius_world)) {
        snprintf(err, n, "%s: field 'ao_radius_world' must be a non-negative number below 3.4e38 (single precision)",
                 path);
        return false;
    }
    return true;
}
