/* inputs_json.c - the JSON cacao-bench is given: --reference points and --plot-from results (see
 * bench.h). Every field is checked before use; a name is kept only if it is printable and fits. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "camera_json.h"
#include "image_io.h"

const char *const bench_truth_names[BENCH_TRUTHS] = {"ao_gt_falloff", "ao_gt"};

/* One JSON file being read: the flag and path every message starts with. */
typedef struct reader {
    const char *flag;
    char shown[512];
    char *err;
} reader;

static bool refuse(const reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static bool refuse(const reader *r, const char *fmt, ...) {
    char why[BENCH_ERR];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    return cacao_set_err(r->err, BENCH_ERR, "%s %s: %s", r->flag, r->shown, why);
}

/* The root object of the file (NULL after the message: unreadable, not JSON with its position,
 * not an object, a key given twice). */
static cJSON *read_root(reader *r, const char *flag, const char *path, char *err) {
    *r = (reader){.flag = flag, .err = err};
    cacao_escape_text(path, r->shown, sizeof r->shown);
    char why[BENCH_ERR];
    cJSON *root = cacao_json_read_object(path, 256u << 20, why, sizeof why);
    if (!root) cacao_set_err(err, BENCH_ERR, "%s %s", flag, why);
    return root;
}

/* Copies the string item `key` of object into out (size bytes): present, printable, and short
 * enough to keep whole. `where` names the object in the message ("points[3]"; "" for the root). */
static bool take_name(const reader *r, const cJSON *object, const char *key, const char *where, char *out,
                      size_t size) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(object, key);
    const char *dot = where[0] ? "." : "";
    if (!cJSON_IsString(item)) return refuse(r, "%s%s%s: needs a string", where, dot, key);
    if (!cacao_text_is_printable(item->valuestring))
        return refuse(r, "%s%s%s: empty or holds control characters, which the table, CSV and plot cannot show", where,
                      dot, key);
    const size_t length = strlen(item->valuestring);
    if (length >= size) return refuse(r, "%s%s%s: longer than %zu bytes", where, dot, key, size - 1);
    memcpy(out, item->valuestring, length + 1);
    return true;
}

/* A figure: a finite number, not negative. */
static bool take_figure(const reader *r, const cJSON *item, const char *where, const char *key, double *out) {
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble) || item->valuedouble < 0)
        return refuse(r, "%s.%s: needs a finite number, 0 or more", where, key);
    *out = item->valuedouble;
    return true;
}

/* An array item of the root: an array of min..max entries. */
static const cJSON *take_array(const reader *r, const cJSON *root, const char *key, int min, int max) {
    const cJSON *array = cJSON_GetObjectItemCaseSensitive(root, key);
    const int n = cJSON_GetArraySize(array);
    if (!cJSON_IsArray(array) || n < min || n > max) {
        refuse(r, "needs an array \"%s\" of %d to %d entries", key, min, max);
        return NULL;
    }
    return array;
}

/* Entry i of the array under key, item, which must be an object; where becomes "key[i]". */
static bool take_object(const reader *r, const cJSON *item, const char *key, int i, char *where, size_t where_size) {
    snprintf(where, where_size, "%s[%d]", key, i);
    return cJSON_IsObject(item) || refuse(r, "%s: not an object", where);
}

/* ---- --reference ------------------------------------------------------------------------------ */

static bool read_point(const reader *r, const cJSON *p, const char *where, bench_point *q) {
    if (!take_name(r, p, "scene", where, q->scene, sizeof q->scene) ||
        !take_name(r, p, "config", where, q->label, sizeof q->label) ||
        !take_figure(r, cJSON_GetObjectItemCaseSensitive(p, "total_ms"), where, "total_ms", &q->total_ms))
        return false;
    for (int t = 0; t < BENCH_TRUTHS; ++t) {
        char key[64];
        snprintf(key, sizeof key, "rmse_%s", bench_truth_names[t]);
        const cJSON *e = cJSON_GetObjectItemCaseSensitive(p, key);
        q->rmse[t] = -1.0; /* absent */
        if (e && !take_figure(r, e, where, key, &q->rmse[t])) return false;
    }
    return true;
}

bool bench_load_reference(const char *path, char *name, size_t name_size, bench_point **points, uint32_t *count,
                          char *err) {
    *points = NULL;
    *count = 0;
    reader r;
    cJSON *root = read_root(&r, "--reference", path, err);
    if (!root) return false;
    const cJSON *list = NULL;
    bool ok = take_name(&r, root, "name", "", name, name_size) &&
              (list = take_array(&r, root, "points", 0, BENCH_MAX_POINTS)) != NULL;
    const int n = ok ? cJSON_GetArraySize(list) : 0;
    *points = ok ? calloc(n ? (size_t)n : 1, sizeof **points) : NULL;
    if (ok && !*points) ok = refuse(&r, "out of memory");
    int i = 0;
    for (const cJSON *p = ok ? list->child : NULL; ok && p; p = p->next, ++i) {
        char where[32];
        ok = take_object(&r, p, "points", i, where, sizeof where) && read_point(&r, p, where, &(*points)[i]);
    }
    cJSON_Delete(root);
    if (ok) *count = (uint32_t)n;
    return ok;
}

/* ---- --plot-from ------------------------------------------------------------------------------ */

static int index_of_name(const char *name, const char *names, size_t stride, int count) {
    for (int i = 0; i < count; ++i)
        if (strcmp(names + (size_t)i * stride, name) == 0) return i;
    return -1;
}

static bool read_scenes(const reader *r, const cJSON *list, bench_scene *scenes) {
    int i = 0;
    for (const cJSON *js = list->child; js; js = js->next, ++i) {
        char where[32];
        const cJSON *t;
        bench_scene *s = &scenes[i];
        *s = (bench_scene){0};
        if (!take_object(r, js, "scenes", i, where, sizeof where) ||
            !take_name(r, js, "name", where, s->name, sizeof s->name))
            return false;
        if (index_of_name(s->name, scenes[0].name, sizeof scenes[0], i) >= 0)
            return refuse(r, "%s.name: \"%s\" is given twice", where, s->name);
        cJSON_ArrayForEach(t, cJSON_GetObjectItemCaseSensitive(js, "truths")) {
            for (int g = 0; g < BENCH_TRUTHS; ++g)
                if (cJSON_IsString(t) && strcmp(t->valuestring, bench_truth_names[g]) == 0) s->has_truth[g] = true;
        }
    }
    return true;
}

static bool read_configs(const reader *r, const cJSON *list, bench_config *configs) {
    int i = 0;
    for (const cJSON *jc = list->child; jc; jc = jc->next, ++i) {
        char where[48];
        configs[i] = (bench_config){0};
        if (!take_object(r, jc, "configurations", i, where, sizeof where) ||
            !take_name(r, jc, "name", where, configs[i].name, sizeof configs[i].name))
            return false;
        if (index_of_name(configs[i].name, configs[0].name, sizeof configs[0], i) >= 0)
            return refuse(r, "%s.name: \"%s\" is given twice", where, configs[i].name);
    }
    return true;
}

/* Index of the name that result item jr gives under key among count names; -1 after the message. */
static int listed_name(const reader *r, const cJSON *jr, const char *key, const char *where, const char *names,
                       size_t stride, int count, const char *list) {
    char name[256];
    if (!take_name(r, jr, key, where, name, sizeof name)) return -1;
    const int i = index_of_name(name, names, stride, count);
    if (i < 0) refuse(r, "%s.%s: \"%s\" is not in \"%s\"", where, key, name, list);
    return i;
}

static bool read_result(const reader *r, const cJSON *jr, const char *where, const bench_run *run, bool *seen,
                        bench_result *out) {
    const int scene =
        listed_name(r, jr, "scene", where, run->scenes[0].name, sizeof run->scenes[0], (int)run->scene_count, "scenes");
    const int config = scene < 0 ? -1
                                 : listed_name(r, jr, "config", where, run->configs[0].name, sizeof run->configs[0],
                                               (int)run->config_count, "configurations");
    if (config < 0) return false;
    bool *pair = &seen[(size_t)scene * run->config_count + (size_t)config];
    if (*pair)
        return refuse(r, "%s: scene \"%s\" with config \"%s\" is given twice", where, run->scenes[scene].name,
                      run->configs[config].name);
    *pair = true;
    *out = (bench_result){.scene = (uint32_t)scene, .config = (uint32_t)config};
    if (!take_figure(r, cJSON_GetObjectItemCaseSensitive(jr, "total_ms"), where, "total_ms",
                     &out->timings.total.median_ms))
        return false;
    const cJSON *errors = cJSON_GetObjectItemCaseSensitive(jr, "errors");
    for (int t = 0; t < BENCH_TRUTHS; ++t) {
        const cJSON *rmse =
            cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(errors, bench_truth_names[t]), "rmse");
        char key[64];
        snprintf(key, sizeof key, "errors.%s.rmse", bench_truth_names[t]);
        if (rmse && !take_figure(r, rmse, where, key, &out->error[t].rmse)) return false;
        out->has_error[t] = rmse != NULL;
    }
    return true;
}

bool bench_load_plot_from(const char *path, bench_scene *scenes, bench_config *configs, bench_result **results,
                          bench_run *run, char *err) {
    *results = NULL;
    run->scenes = scenes;
    run->configs = configs;
    run->scene_count = run->config_count = run->result_count = 0;
    reader r;
    cJSON *root = read_root(&r, "--plot-from", path, err);
    if (!root) return false;
    const cJSON *jscenes = take_array(&r, root, "scenes", 1, BENCH_MAX_SCENES);
    const cJSON *jconfigs = jscenes ? take_array(&r, root, "configurations", 1, SWEEP_FULL_SIZE) : NULL;
    const int ns = cJSON_GetArraySize(jscenes), nc = cJSON_GetArraySize(jconfigs);
    bool ok = jconfigs && read_scenes(&r, jscenes, scenes) && read_configs(&r, jconfigs, configs);
    run->scene_count = ok ? (uint32_t)ns : 0;
    run->config_count = ok ? (uint32_t)nc : 0;
    const cJSON *jresults = ok ? take_array(&r, root, "results", 1, ns * nc) : NULL;
    const int nr = cJSON_GetArraySize(jresults);
    bool *seen = jresults ? calloc((size_t)ns * (size_t)nc, sizeof *seen) : NULL;
    *results = seen ? calloc((size_t)nr, sizeof **results) : NULL;
    ok = jresults != NULL;
    if (ok && !*results) ok = refuse(&r, "out of memory");
    int i = 0;
    for (const cJSON *jr = ok ? jresults->child : NULL; ok && jr; jr = jr->next, ++i) {
        char where[32];
        ok = take_object(&r, jr, "results", i, where, sizeof where) &&
             read_result(&r, jr, where, run, seen, &(*results)[i]);
    }
    free(seen);
    cJSON_Delete(root);
    run->results = *results;
    run->result_count = ok ? (uint32_t)nr : 0;
    if (!ok) run->scene_count = run->config_count = 0;
    return ok;
}
