/* camera_json.c - camera.json reading with cJSON; every field is checked before use. */
#include "camera_json.h"

#include "image_io.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Line and column (from 1) of position at in text. */
static void line_column(const char *text, const char *at, int *line, int *column) {
    *line = 1;
    *column = 1;
    for (const char *c = text; c < at && *c; ++c) {
        if (*c == '\n') {
            ++*line;
            *column = 1;
        } else {
            ++*column;
        }
    }
}

static int compare_keys(const void *a, const void *b) {
    return strcmp((*(const cJSON *const *)a)->string, (*(const cJSON *const *)b)->string);
}

/* The first key (in sorted order) that the object holds twice, or NULL. */
static const char *duplicate_key(const cJSON *object, bool *out_of_memory) {
    const int count = cJSON_GetArraySize(object);
    *out_of_memory = false;
    if (count < 2) return NULL;
    const cJSON **items = malloc((size_t)count * sizeof *items);
    if (!items) {
        *out_of_memory = true;
        return NULL;
    }
    int k = 0;
    for (const cJSON *item = object->child; item && k < count; item = item->next) items[k++] = item;
    qsort(items, (size_t)k, sizeof *items, compare_keys);
    const char *found = NULL;
    for (int i = 1; i < k && !found; ++i)
        if (strcmp(items[i - 1]->string, items[i]->string) == 0) found = items[i]->string;
    free(items);
    return found;
}

cJSON *cacao_json_read_object(const char *path, size_t max_bytes, char *err, size_t n) {
    char *text = cacao_read_whole_file(path, max_bytes, err, n);
    if (!text) return NULL;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, false);
    while (root && end && (*end == ' ' || *end == '\t' || *end == '\n' || *end == '\r')) ++end;
    const bool trailing = root && end && *end;
    if (!root || trailing || !cJSON_IsObject(root)) {
        int line = 0, column = 0;
        line_column(text, end ? end : text, &line, &column);
        if (trailing)
            snprintf(err, n, "%s: unexpected text after the JSON value at line %d, column %d", path, line, column);
        else if (root)
            snprintf(err, n, "%s: not a JSON object", path);
        else
            snprintf(err, n, "%s: not valid JSON (error at line %d, column %d)", path, line, column);
        cJSON_Delete(root);
        free(text);
        return NULL;
    }
    free(text);
    bool out_of_memory = false;
    const char *twice = duplicate_key(root, &out_of_memory);
    if (twice || out_of_memory) {
        char key[256];
        cacao_escape_text(twice, key, sizeof key);
        if (twice)
            snprintf(err, n, "%s: key \"%s\" is given more than once", path, key);
        else
            snprintf(err, n, "%s: out of memory", path);
        cJSON_Delete(root);
        return NULL;
    }
    return root;
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
    cJSON *root = cacao_json_read_object(path, (size_t)1 << 24, err, n);
    if (!root) return false;
    double w = 0, h = 0;
    bool ok =
        get_number(root, "width", false, &w, path, err, n) && get_number(root, "height", false, &h, path, err, n) &&
        get_number(root, "fov_y_deg", true, &out->fov_y_deg, path, err, n) &&
        get_number(root, "near", true, &out->near_z, path, err, n) &&
        get_number(root, "far", true, &out->far_z, path, err, n) &&
        get_number(root, "ao_radius_world", false, &out->ao_radius_world, path, err, n) &&
        get_matrix(root, "projection", &out->has_projection, out->projection, path, err, n) &&
        get_matrix(root, "projection_reversed", &out->has_projection_reversed, out->projection_reversed, path, err, n);
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
