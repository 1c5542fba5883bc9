/* bench_check - checks what cacao-bench wrote, independently of its code (cJSON, image_io only):
 *
 *   bench_check JSON CSV PLOT|- WARMUP REPEAT [SCENE_DIR AO_DIR]
 *
 * JSON: every key of the schema (tools/bench/bench.h, README) with sane values; each result's
 *   timed_frames is exactly WARMUP .. WARMUP+REPEAT-1 (the warm-up frames are not timed) and its
 *   per-pass and total min <= median <= max.
 * CSV: a header and one row per JSON result, every row as many fields as the header, the scene,
 *   config and total_ms columns equal to the JSON's.
 * PLOT: a PNG (signature, non-empty IHDR) or an SVG (an <svg element).
 * SCENE_DIR AO_DIR: recomputes RMSE, MAE and p99 of every AO_DIR/<scene>.<config>.pfm against
 *   SCENE_DIR/ao_gt_falloff.pfm and ao_gt.pfm over the pixels with depth < 1 (here, not with the
 *   bench's code) and requires the JSON's figures to match. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"

static int failures;
#define CHECK(cond, ...)                                                                                               \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            fprintf(stderr, "bench_check: " __VA_ARGS__);                                                              \
            fputc('\n', stderr);                                                                                       \
            ++failures;                                                                                                \
        }                                                                                                              \
    } while (0)

/* The whole file, or NULL (the message printed). */
static char *slurp(const char *path, size_t *size) {
    char err[512];
    char *text = cacao_read_file(path, 1u << 30, size, err, sizeof err);
    if (!text) fprintf(stderr, "%s\n", err);
    return text;
}

static const cJSON *get(const cJSON *o, const char *key) { return cJSON_GetObjectItemCaseSensitive(o, key); }
static double num(const cJSON *o, const char *key) {
    const cJSON *v = get(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static void check_stats(const char *what, double median, double low, double high) {
    CHECK(isfinite(median) && low <= median && median <= high && low > 0, "%s: min %g median %g max %g", what, low,
          median, high);
}

static void check_result(const cJSON *r, int warmup, int repeat) {
    const char *config = cJSON_GetStringValue(get(r, "config"));
    CHECK(config && cJSON_IsString(get(r, "scene")), "result without scene/config");
    CHECK(cJSON_IsObject(get(r, "settings")) && cJSON_IsString(get(get(r, "settings"), "quality")), "%s: no settings",
          config);
    CHECK(num(r, "warmup") == warmup && num(r, "repeat") == repeat, "%s: warmup/repeat", config);
    const cJSON *frames = get(r, "timed_frames");
    CHECK(cJSON_GetArraySize(frames) == repeat, "%s: %d timed frames, expected %d", config, cJSON_GetArraySize(frames),
          repeat);
    for (int i = 0; i < cJSON_GetArraySize(frames); ++i)
        CHECK(cJSON_GetArrayItem(frames, i)->valuedouble == warmup + i, "%s: timed frame %d is %g, expected %d", config,
              i, cJSON_GetArrayItem(frames, i)->valuedouble, warmup + i);
    const cJSON *passes = get(r, "passes");
    CHECK(cJSON_GetArraySize(passes) >= 3, "%s: fewer than 3 passes", config);
    const cJSON *p;
    cJSON_ArrayForEach(p, passes) {
        CHECK(cJSON_IsString(get(p, "name")), "%s: pass without name", config);
        check_stats("pass", num(p, "time_ms"), num(p, "min_ms"), num(p, "max_ms"));
    }
    check_stats("total", num(r, "total_ms"), num(r, "total_min_ms"), num(r, "total_max_ms"));
    /* cacao_memory_info's promise: all intermediates in one VkDeviceMemory per memory type, at
     * most 2 (lavapipe has one device-local type: 1). */
    CHECK(num(r, "memory_allocations") >= 1 && num(r, "memory_allocations") <= 2, "%s: %g device allocations", config,
          num(r, "memory_allocations"));
    CHECK(num(r, "memory_bytes") > 0 && num(r, "pipeline_count") >= 3 && num(r, "pipeline_creation_ms") >= 0,
          "%s: memory %g pipelines %g creation %g", config, num(r, "memory_bytes"), num(r, "pipeline_count"),
          num(r, "pipeline_creation_ms"));
    CHECK(num(r, "nonfinite") == 0, "%s: %g non-finite pixels", config, num(r, "nonfinite"));
    CHECK(cJSON_IsObject(get(r, "errors")), "%s: no errors object", config);
}

/* Splits one CSV line into fields (quoted fields with doubled quotes); returns the count. */
static int csv_fields(const char *line, char fields[][256], int max) {
    int n = 0;
    const char *p = line;
    for (;;) {
        char *out = n < max ? fields[n] : NULL;
        size_t k = 0;
        if (*p == '"') {
            for (++p; *p && !(*p == '"' && p[1] != '"'); ++p) {
                if (*p == '"') ++p;
                if (out && k < 255) out[k++] = *p;
            }
            if (*p == '"') ++p;
        } else {
            for (; *p && *p != ','; ++p)
                if (out && k < 255) out[k++] = *p;
        }
        if (out) out[k] = 0;
        ++n;
        if (*p != ',') return n;
        ++p;
    }
}

static void check_csv(const char *path, const cJSON *results) {
    char *text = slurp(path, NULL);
    CHECK(text, "%s: cannot read", path);
    if (!text) return;
    static char header[64][256], row[64][256];
    char *save = NULL;
    char *line = strtok_r(text, "\n", &save);
    const int columns = line ? csv_fields(line, header, 64) : 0;
    int scene_col = -1, config_col = -1, total_col = -1;
    for (int i = 0; i < columns && i < 64; ++i) {
        if (strcmp(header[i], "scene") == 0) scene_col = i;
        if (strcmp(header[i], "config") == 0) config_col = i;
        if (strcmp(header[i], "total_ms") == 0) total_col = i;
    }
    CHECK(scene_col >= 0 && config_col >= 0 && total_col >= 0 && columns >= 20, "%s: header lacks columns", path);
    int rows = 0;
    while ((line = strtok_r(NULL, "\n", &save))) {
        const int n = csv_fields(line, row, 64);
        CHECK(n == columns, "%s: row %d has %d fields, the header %d", path, rows + 1, n, columns);
        const cJSON *r = cJSON_GetArrayItem(results, rows);
        if (r && n == columns && scene_col >= 0 && config_col >= 0 && total_col >= 0) {
            CHECK(strcmp(row[scene_col], cJSON_GetStringValue(get(r, "scene"))) == 0, "%s: row %d scene", path, rows);
            CHECK(strcmp(row[config_col], cJSON_GetStringValue(get(r, "config"))) == 0, "%s: row %d config", path,
                  rows);
            CHECK(fabs(atof(row[total_col]) - num(r, "total_ms")) < 1e-5, "%s: row %d total_ms %s vs %g", path, rows,
                  row[total_col], num(r, "total_ms"));
        }
        ++rows;
    }
    CHECK(rows == cJSON_GetArraySize(results), "%s: %d rows for %d results", path, rows, cJSON_GetArraySize(results));
    free(text);
}

static void check_plot(const char *path) {
    size_t size = 0;
    char *data = slurp(path, &size);
    CHECK(data, "%s: cannot read", path);
    if (!data) return;
    if (size >= 24 && memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0) {
        const unsigned char *u = (const unsigned char *)data;
        const unsigned w = (unsigned)u[16] << 24 | u[17] << 16 | u[18] << 8 | u[19];
        const unsigned h = (unsigned)u[20] << 24 | u[21] << 16 | u[22] << 8 | u[23];
        CHECK(memcmp(data + 12, "IHDR", 4) == 0 && w >= 200 && h >= 200, "%s: PNG is %ux%u", path, w, h);
    } else {
        CHECK(strstr(data, "<svg") != NULL, "%s: neither a PNG nor an SVG", path);
    }
    free(data);
}

/* RMSE, MAE and nearest-rank p99 of |ao - gt| over depth < 1, here. */
static int compare_doubles(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void check_errors(const cJSON *r, const char *scene_dir, const char *ao_dir) {
    char path[4096], err[512];
    cacao_img depth = {0}, ao = {0};
    snprintf(path, sizeof path, "%s/depth.pfm", scene_dir);
    CHECK(cacao_pfm_read(path, &depth, err, sizeof err), "%s", err);
    snprintf(path, sizeof path, "%s/%s.%s.pfm", ao_dir, cJSON_GetStringValue(get(r, "scene")),
             cJSON_GetStringValue(get(r, "config")));
    CHECK(cacao_pfm_read(path, &ao, err, sizeof err), "%s", err);
    const char *truths[] = {"ao_gt_falloff", "ao_gt"};
    for (int t = 0; depth.data && ao.data && t < 2; ++t) {
        cacao_img gt = {0};
        snprintf(path, sizeof path, "%s/%s.pfm", scene_dir, truths[t]);
        if (!cacao_pfm_read(path, &gt, err, sizeof err)) continue;
        const size_t count = (size_t)gt.width * gt.height;
        double *d = malloc(count * sizeof *d), sq = 0, ab = 0;
        size_t used = 0;
        for (size_t i = 0; i < count; ++i)
            if (depth.data[i] < 1.0f) {
                d[used] = fabs((double)ao.data[i] - gt.data[i]);
                sq += d[used] * d[used];
                ab += d[used++];
            }
        qsort(d, used, sizeof *d, compare_doubles);
        const double rmse = sqrt(sq / used), mae = ab / used, p99 = d[(size_t)ceil(0.99 * used) - 1];
        const cJSON *e = get(get(r, "errors"), truths[t]);
        CHECK(e, "%s: no errors.%s", cJSON_GetStringValue(get(r, "config")), truths[t]);
        printf("%s %s: rmse %.7f (json %.7f) mae %.7f (json %.7f) p99 %.7f (json %.7f) over %zu pixels\n",
               cJSON_GetStringValue(get(r, "config")), truths[t], rmse, num(e, "rmse"), mae, num(e, "mae"), p99,
               num(e, "p99"), used);
        CHECK(fabs(rmse - num(e, "rmse")) <= 1e-6 * rmse + 1e-9 && fabs(mae - num(e, "mae")) <= 1e-6 * mae + 1e-9 &&
                  fabs(p99 - num(e, "p99")) <= 1e-6 && num(e, "pixels") == (double)used,
              "%s %s: JSON errors differ from the recomputation", cJSON_GetStringValue(get(r, "config")), truths[t]);
        CHECK(rmse > 1e-3, "%s: rmse %g: the truth should differ from the AO", truths[t], rmse);
        free(d);
        cacao_img_free(&gt);
    }
    cacao_img_free(&depth);
    cacao_img_free(&ao);
}

int main(int argc, char **argv) {
    if (argc != 6 && argc != 8) {
        fprintf(stderr, "usage: bench_check JSON CSV PLOT|- WARMUP REPEAT [SCENE_DIR AO_DIR]\n");
        return 2;
    }
    const int warmup = atoi(argv[4]), repeat = atoi(argv[5]);
    char *text = slurp(argv[1], NULL);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    CHECK(root, "%s: not JSON", argv[1]);
    if (!root) return 1;
    const char *strings[] = {"tool", "version", "device", "driver"};
    for (int i = 0; i < 4; ++i) CHECK(cJSON_IsString(get(root, strings[i])), "JSON lacks string '%s'", strings[i]);
    CHECK(num(root, "warmup") == warmup && num(root, "repeat") == repeat, "JSON warmup/repeat");
    CHECK(cJSON_GetArraySize(get(root, "load_average_before")) == 3 &&
              cJSON_GetArraySize(get(root, "load_average_after")) == 3,
          "JSON load averages");
    const cJSON *scene;
    cJSON_ArrayForEach(scene, get(root, "scenes")) {
        CHECK(cJSON_IsString(get(scene, "name")) && num(scene, "width") > 0 && num(scene, "height") > 0 &&
                  cJSON_IsArray(get(scene, "truths")),
              "scene entry incomplete");
    }
    const cJSON *results = get(root, "results");
    const int expected = cJSON_GetArraySize(get(root, "scenes")) * cJSON_GetArraySize(get(root, "configurations"));
    CHECK(cJSON_GetArraySize(results) == expected && expected > 0, "%d results, expected %d",
          cJSON_GetArraySize(results), expected);
    const cJSON *r;
    cJSON_ArrayForEach(r, results) {
        check_result(r, warmup, repeat);
        if (argc == 8) check_errors(r, argv[6], argv[7]);
    }
    check_csv(argv[2], results);
    if (strcmp(argv[3], "-") != 0) check_plot(argv[3]);
    cJSON_Delete(root);
    if (failures)
        fprintf(stderr, "bench_check: %d failure(s)\n", failures);
    else
        printf("bench_check: %s, %s%s%s all as the schema says\n", argv[1], argv[2], argc ? ", " : "", argv[3]);
    return failures ? 1 : 0;
}
