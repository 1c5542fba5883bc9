/* main.c - cacao-bench: what accuracy costs in time. Runs configurations of cacao (quality,
 * resolution, blur, precision, normals) on scenes through the public API (vkdev + cacao.h) and
 * reports per-pass GPU time (median, min, max of --repeat frames after --warmup), memory, pipeline
 * count and creation time, and the error against the scenes' ground truths; as a table on stdout,
 * JSON, CSV and an error-against-time plot with its Pareto front (report.c).
 *
 * Every flag is checked and every input loaded before the first frame runs, and the files are
 * written only after the last one, so a bad flag or input leaves no file behind. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "options.h"
#include "text_file.h"
#include "vkdev.h"

const char *const bench_truth_names[BENCH_TRUTHS] = {"ao_gt_falloff", "ao_gt"};

/* Prints one line "cacao-bench: ..." to stderr; returns false. */
static bool fail(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fputs("cacao-bench: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return false;
}

/* ---- Flags ---------------------------------------------------------------------------------- */

typedef struct bench_options {
    const char *scenes[BENCH_MAX_SCENES];
    uint32_t scene_count;
    const char *configs; /* comma list of names or globs; NULL = the sweep */
    bool full_sweep, list_configs, help;
    uint32_t warmup, repeat;
    uint32_t cache_trials; /* --pipeline-cache N; 0: not measured */
    const char *json_path, *csv_path, *plot_path, *reference_path, *save_dir, *plot_from;
    cli_options cli; /* settings flags (and --device, --validate, camera overrides) as `cacao` takes them */
} bench_options;

static const char *const help_text =
    "usage: cacao-bench [options] [settings flags of cacao]\n"
    "Runs cacao configurations on scenes and reports GPU time per pass (median, min, max of the timed\n"
    "frames), memory, pipelines and the error against the scenes' ground truths.\n"
    "  --scene DIR        scene folder (repeatable; default: the embedded scene); ao_gt_falloff.pfm and\n"
    "                     ao_gt.pfm there give RMSE, MAE and p99 over the non-background pixels\n"
    "  --configs LIST     comma list of configuration names or globs (e.g. high_native,*_downsampled);\n"
    "                     default: the sweep\n"
    "  --sweep default|full  default: every quality x native/downsampled at the default blur, fp32;\n"
    "                     full adds blur 0..8, fp16 and reconstructed normals (_blurN, _fp16, _gennormals);\n"
    "                     gtao_* and bitmask_* are the horizon-slice estimators (native, fp32; blur = denoise passes)\n"
    "  --list-configs     print the configurations the flags select and exit\n"
    "  --warmup N         untimed frames first (default 2: lavapipe compiles shader variants then)\n"
    "  --repeat N         timed frames (default 7)\n"
    "  --pipeline-cache N also time pipeline creation per configuration (median of N trials at the first\n"
    "                     scene's size) without a VkPipelineCache, on an empty one and on one started from\n"
    "                     the data an earlier context left in it (a warm cache)\n"
    "  --json FILE        every figure, with device, driver, size, settings and load average\n"
    "  --csv FILE         one row per scene and configuration\n"
    "  --plot FILE        .png or .svg: error against time, one panel per scene, Pareto front (gnuplot)\n"
    "  --reference FILE   named points for the plot and JSON: {\"name\": ..., \"points\": [{\"scene\",\n"
    "                     \"config\", \"total_ms\", \"rmse_ao_gt_falloff\", \"rmse_ao_gt\"}]}\n"
    "  --save-ao DIR      write each AO image as DIR/<scene>.<config>.pfm\n"
    "  --plot-from FILE   run nothing: --plot the results of a cacao-bench JSON (e.g. one merged from\n"
    "                     interleaved runs by tools/accuracy-report.py)\n"
    "  --device N|NAME    Vulkan device (default lavapipe); --validate: validation layer on\n"
    "Settings flags (--radius, --strength, --power, --fade-out, ... see cacao --help) apply to every\n"
    "configuration; the configuration sets quality, resolution, blur and precision.\n";

static bool parse_count(const char *flag, const char *value, uint32_t low, uint32_t *out) {
    char *end;
    const long v = value ? strtol(value, &end, 10) : -1;
    if (!value || !value[0] || *end || v < (long)low || v > 100000) {
        fail("%s %s: must be a whole number from %u to 100000", flag, value ? value : "(missing)", low);
        return false;
    }
    *out = (uint32_t)v;
    return true;
}

static bool has_extension(const char *path, const char *ext) {
    const size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

/* Flags of `cacao` that make no sense here (the bench owns inputs per scene and its outputs). */
static bool refused_cacao_flag(const char *arg) {
    static const char *const refused[] = {"--depth",   "--normals",        "--camera",       "--output",
                                          "-o",        "--bits",           "--png16",        "--compare",
                                          "--timings", "--print-settings", "--list-devices", "--version"};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; ++i)
        if (strcmp(arg, refused[i]) == 0) return true;
    return false;
}

static bool parse_flags(int argc, char **argv, bench_options *o) {
    memset(o, 0, sizeof *o);
    o->warmup = 2;
    o->repeat = 7;
    char **rest = calloc((size_t)argc + 1, sizeof *rest);
    if (!rest) return fail("out of memory");
    int n = 0;
    rest[n++] = "cacao-bench";
    bool ok = true;
    for (int i = 1; ok && i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char **path = strcmp(a, "--json") == 0        ? &o->json_path
                            : strcmp(a, "--csv") == 0       ? &o->csv_path
                            : strcmp(a, "--plot") == 0      ? &o->plot_path
                            : strcmp(a, "--reference") == 0 ? &o->reference_path
                            : strcmp(a, "--save-ao") == 0   ? &o->save_dir
                            : strcmp(a, "--configs") == 0   ? &o->configs
                            : strcmp(a, "--plot-from") == 0 ? &o->plot_from
                                                            : NULL;
        if (path || strcmp(a, "--scene") == 0 || strcmp(a, "--sweep") == 0 || strcmp(a, "--warmup") == 0 ||
            strcmp(a, "--repeat") == 0 || strcmp(a, "--pipeline-cache") == 0) {
            if (!v || !v[0]) {
                ok = fail("%s: needs a value", a);
                break;
            }
            ++i;
        }
        if (path)
            *path = v;
        else if (strcmp(a, "--scene") == 0) {
            if (o->scene_count == BENCH_MAX_SCENES)
                ok = fail("--scene: at most %d scenes", BENCH_MAX_SCENES);
            else
                o->scenes[o->scene_count++] = v;
        } else if (strcmp(a, "--sweep") == 0) {
            if (strcmp(v, "full") == 0)
                o->full_sweep = true;
            else if (strcmp(v, "default") != 0)
                ok = fail("--sweep %s: use default or full", v);
        } else if (strcmp(a, "--warmup") == 0)
            ok = parse_count(a, v, 0, &o->warmup);
        else if (strcmp(a, "--repeat") == 0)
            ok = parse_count(a, v, 1, &o->repeat);
        else if (strcmp(a, "--pipeline-cache") == 0)
            ok = parse_count(a, v, 1, &o->cache_trials);
        else if (strcmp(a, "--list-configs") == 0)
            o->list_configs = true;
        else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0)
            o->help = true;
        else if (refused_cacao_flag(a))
            ok = fail("%s: a flag of cacao, not of cacao-bench (see --help)", a);
        else
            rest[n++] = argv[i];
    }
    char err[BENCH_ERR];
    if (ok && !cli_parse(n, rest, &o->cli, err, sizeof err)) ok = fail("%s", err);
    free(rest);
    if (!ok) return false;
    if (o->plot_path && !has_extension(o->plot_path, ".png") && !has_extension(o->plot_path, ".svg"))
        return fail("--plot %s: use a .png or .svg file", o->plot_path);
    if (o->plot_from && (!o->plot_path || o->json_path || o->csv_path || o->save_dir || o->scene_count || o->configs))
        return fail("--plot-from %s: takes only --plot (and --reference); it runs nothing", o->plot_from);
    struct stat st;
    if (o->save_dir && (stat(o->save_dir, &st) != 0 || !S_ISDIR(st.st_mode)))
        return fail("--save-ao %s: not a folder", o->save_dir);
    return true;
}

/* ---- Configurations --------------------------------------------------------------------------- */

/* The configurations the options select, in sweep order (each once): sweep.h. */
static bool select_configs(const bench_options *o, bench_config *out, uint32_t *count) {
    char err[BENCH_ERR];
    if (sweep_select(o->configs, o->full_sweep, out, count, err, sizeof err)) return true;
    return fail("--configs: %s (see --list-configs --sweep full)", err);
}

/* ---- Scenes ---------------------------------------------------------------------------------- */

static bool file_exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static void free_scene(bench_scene *s) {
    cli_inputs_free(&s->inputs);
    for (int t = 0; t < BENCH_TRUTHS; ++t) cacao_img_free(&s->truth[t]);
}

static bool load_scene(const bench_options *o, const char *dir, bench_scene *s) {
    memset(s, 0, sizeof *s);
    s->path = dir;
    cli_options io = o->cli;
    io.scene_dir = dir;
    char err[BENCH_ERR];
    if (!cli_inputs_load(&io, &s->inputs, err, sizeof err)) return fail("%s", err);
    if (!dir) {
        snprintf(s->name, sizeof s->name, "default");
        return true;
    }
    char trimmed[4096];
    snprintf(trimmed, sizeof trimmed, "%s", dir);
    for (size_t len = strlen(trimmed); len > 1 && trimmed[len - 1] == '/'; --len) trimmed[len - 1] = 0;
    const char *base = strrchr(trimmed, '/');
    const char *name = base ? base + 1 : trimmed;
    const size_t length = strnlen(name, sizeof s->name - 1); /* the folder's name, cut to fit */
    memcpy(s->name, name, length);
    s->name[length] = 0;
    for (int t = 0; t < BENCH_TRUTHS; ++t) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s.pfm", dir, bench_truth_names[t]);
        if (!file_exists(path)) continue;
        if (!cli_read_scalar_image(path, "ground truth", false, &s->truth[t], err, sizeof err)) return fail("%s", err);
        if (s->truth[t].width != s->inputs.depth.width || s->truth[t].height != s->inputs.depth.height)
            return fail("%s: ground truth is %ux%u but the depth is %ux%u", path, s->truth[t].width, s->truth[t].height,
                        s->inputs.depth.width, s->inputs.depth.height);
        s->has_truth[t] = true;
    }
    return true;
}

/* ---- Reference points ------------------------------------------------------------------------ */

/* The JSON in path, or NULL after one line naming the flag and the file. */
static cJSON *read_json(const char *flag, const char *path) {
    char err[BENCH_ERR];
    char *text = cacao_read_whole_file(path, 256u << 20, err, sizeof err);
    if (!text) return fail("%s %s", flag, err), NULL;
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root) fail("%s %s: not valid JSON", flag, path);
    return root;
}

static bool load_reference(const char *path, char *name, size_t name_size, bench_point **points, uint32_t *count) {
    cJSON *root = read_json("--reference", path);
    if (!root) return false;
    const cJSON *jname = cJSON_GetObjectItemCaseSensitive(root, "name");
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(root, "points");
    if (!cJSON_IsString(jname) || !cJSON_IsArray(list)) {
        cJSON_Delete(root);
        return fail("--reference %s: not JSON with a string \"name\" and an array \"points\"", path);
    }
    snprintf(name, name_size, "%s", jname->valuestring);
    const int n = cJSON_GetArraySize(list);
    *points = calloc(n ? (size_t)n : 1, sizeof **points);
    *count = 0;
    for (int i = 0; *points && i < n; ++i) {
        const cJSON *p = cJSON_GetArrayItem(list, i);
        const cJSON *scene = cJSON_GetObjectItemCaseSensitive(p, "scene");
        const cJSON *config = cJSON_GetObjectItemCaseSensitive(p, "config");
        const cJSON *ms = cJSON_GetObjectItemCaseSensitive(p, "total_ms");
        if (!cJSON_IsString(scene) || !cJSON_IsString(config) || !cJSON_IsNumber(ms) || !isfinite(ms->valuedouble)) {
            cJSON_Delete(root);
            return fail("--reference %s: points[%d] needs \"scene\", \"config\" (strings) and \"total_ms\" (a "
                        "number)",
                        path, i);
        }
        bench_point *q = &(*points)[(*count)++];
        snprintf(q->scene, sizeof q->scene, "%s", scene->valuestring);
        snprintf(q->label, sizeof q->label, "%s", config->valuestring);
        q->total_ms = ms->valuedouble;
        for (int t = 0; t < BENCH_TRUTHS; ++t) {
            char key[64];
            snprintf(key, sizeof key, "rmse_%s", bench_truth_names[t]);
            const cJSON *e = cJSON_GetObjectItemCaseSensitive(p, key);
            q->rmse[t] = cJSON_IsNumber(e) ? e->valuedouble : -1.0;
        }
    }
    cJSON_Delete(root);
    return *points ? true : fail("out of memory");
}

/* ---- --plot-from: a plot of an earlier (or merged) cacao-bench JSON ---------------------------- */

static int index_of_name(const char *name, const char *names, size_t stride, uint32_t count) {
    for (uint32_t i = 0; name && i < count; ++i)
        if (strcmp(names + i * stride, name) == 0) return (int)i;
    return -1;
}

/* Reads what the plot needs from a cacao-bench JSON: scenes (name, truths), configurations (name)
 * and results (scene, config, total_ms, errors.<truth>.rmse). */
static bool load_plot_from(const char *path, bench_scene *scenes, bench_config *configs, bench_result **results,
                           bench_run *run) {
    cJSON *root = read_json("--plot-from", path);
    if (!root) return false;
    const cJSON *jscenes = cJSON_GetObjectItemCaseSensitive(root, "scenes");
    const cJSON *jconfigs = cJSON_GetObjectItemCaseSensitive(root, "configurations");
    const cJSON *jresults = cJSON_GetObjectItemCaseSensitive(root, "results");
    const int ns = cJSON_GetArraySize(jscenes), nc = cJSON_GetArraySize(jconfigs), nr = cJSON_GetArraySize(jresults);
    bool ok = cJSON_IsArray(jscenes) && cJSON_IsArray(jconfigs) && cJSON_IsArray(jresults) && ns > 0 &&
              ns <= BENCH_MAX_SCENES && nc > 0 && nc <= SWEEP_FULL_SIZE && nr > 0;
    if (!ok)
        fail("--plot-from %s: needs arrays \"scenes\" (1..%d), \"configurations\" and \"results\"", path,
             BENCH_MAX_SCENES);
    for (int i = 0; ok && i < ns; ++i) {
        const cJSON *js = cJSON_GetArrayItem(jscenes, i), *t;
        const char *name = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(js, "name"));
        if (!(ok = name != NULL))
            fail("--plot-from %s: scenes[%d] has no name", path, i);
        else
            snprintf(scenes[i].name, sizeof scenes[i].name, "%s", name);
        cJSON_ArrayForEach(t, cJSON_GetObjectItemCaseSensitive(js, "truths")) {
            for (int g = 0; g < BENCH_TRUTHS; ++g)
                if (cJSON_IsString(t) && strcmp(t->valuestring, bench_truth_names[g]) == 0)
                    scenes[i].has_truth[g] = true;
        }
    }
    for (int i = 0; ok && i < nc; ++i) {
        const char *name =
            cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(jconfigs, i), "name"));
        if (!(ok = name != NULL))
            fail("--plot-from %s: configurations[%d] has no name", path, i);
        else
            snprintf(configs[i].name, sizeof configs[i].name, "%s", name);
    }
    *results = ok ? calloc((size_t)nr, sizeof **results) : NULL;
    if (ok && !*results) ok = fail("out of memory");
    for (int i = 0; ok && i < nr; ++i) {
        const cJSON *jr = cJSON_GetArrayItem(jresults, i);
        bench_result *r = &(*results)[i];
        const int scene = index_of_name(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(jr, "scene")),
                                        scenes[0].name, sizeof scenes[0], (uint32_t)ns);
        const int config = index_of_name(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(jr, "config")),
                                         configs[0].name, sizeof configs[0], (uint32_t)nc);
        const cJSON *ms = cJSON_GetObjectItemCaseSensitive(jr, "total_ms");
        if (!(ok = scene >= 0 && config >= 0 && cJSON_IsNumber(ms))) {
            fail("--plot-from %s: results[%d] needs a listed scene and config and a total_ms", path, i);
            break;
        }
        r->scene = (uint32_t)scene;
        r->config = (uint32_t)config;
        r->timings.total.median_ms = ms->valuedouble;
        for (int t = 0; t < BENCH_TRUTHS; ++t) {
            const cJSON *e =
                cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(jr, "errors"), bench_truth_names[t]);
            const cJSON *rmse = cJSON_GetObjectItemCaseSensitive(e, "rmse");
            if (cJSON_IsNumber(rmse)) {
                r->has_error[t] = true;
                r->error[t].rmse = rmse->valuedouble;
            }
        }
    }
    cJSON_Delete(root);
    run->scenes = scenes;
    run->scene_count = ok ? (uint32_t)ns : 0;
    run->configs = configs;
    run->config_count = ok ? (uint32_t)nc : 0;
    run->results = *results;
    run->result_count = ok ? (uint32_t)nr : 0;
    return ok;
}

/* ---- Runs ------------------------------------------------------------------------------------ */

static void load_average(double out[3]) {
    out[0] = out[1] = out[2] = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (fscanf(f, "%lf %lf %lf", &out[0], &out[1], &out[2]) != 3) out[0] = out[1] = out[2] = -1;
    fclose(f);
}

static double seconds_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The settings one configuration runs with on one scene: the flags' settings, the scene's radius
 * unless --radius was given, then the configuration's own fields. */
static cacao_settings config_settings(const bench_options *o, const bench_config *c, const bench_scene *s) {
    return sweep_settings(c, cli_inputs_settings(&o->cli, &s->inputs));
}

static bool save_ao(const bench_options *o, const bench_scene *s, const bench_config *c, const cacao_img *ao) {
    char path[4200], err[BENCH_ERR];
    snprintf(path, sizeof path, "%s/%s.%s.pfm", o->save_dir, s->name, c->name);
    return cacao_pfm_write(path, ao, err, sizeof err) ? true : fail("--save-ao: %s", err);
}

static bool run_one(vkdev *dev, const bench_options *o, const bench_scene *s, const bench_config *c, float *ao,
                    bench_result *r) {
    char err[BENCH_ERR];
    const cacao_settings set = config_settings(o, c, s);
    if (cacao_settings_resolve(&set, &r->resolved, err, sizeof err) != CACAO_SUCCESS)
        return fail("%s on %s: %s", c->name, s->name, err);
    const cli_inputs *in = &s->inputs;
    vkdev_frame frame = cli_inputs_frame(in, &set, o->cli.frame_index);
    frame.plan_out = &r->plan; /* the plan the context ran, fallbacks included */
    const cacao_result res = vkdev_run_timed(dev, &set, &frame, o->warmup, o->repeat, ao, &r->timings, err, sizeof err);
    if (res != CACAO_SUCCESS) return fail("%s on %s: %s: %s", c->name, s->name, cacao_result_string(res), err);
    const size_t pixels = (size_t)frame.width * frame.height;
    for (size_t i = 0; i < pixels; ++i) r->nonfinite += !isfinite(ao[i]);
    const cacao_img image = {frame.width, frame.height, 1, ao};
    for (int t = 0; t < BENCH_TRUTHS; ++t) {
        if (!s->truth[t].data) continue;
        if (!cli_compare_ao(&image, &s->truth[t], &in->depth, o->cli.reverse_z, &r->error[t]))
            return fail("out of memory comparing %s", s->name);
        r->has_error[t] = true;
    }
    return !o->save_dir || save_ao(o, s, c, &image);
}

static void progress(uint32_t done, uint32_t total, double started, const char *what) {
    const double elapsed = seconds_now() - started;
    const double left = done ? elapsed / done * (total - done) : 0;
    fprintf(stderr, "\r\033[K[%u/%u] %s  elapsed %.0f s, about %.0f s left", done, total, what, elapsed, left);
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

static bool run_all(const bench_options *o, const bench_config *configs, uint32_t config_count,
                    const bench_scene *scenes, uint32_t scene_count, bench_result *results, vkdev_cache_timing *cache,
                    bench_run *run) {
    char err[BENCH_ERR];
    vkdev dev;
    if (!vkdev_create(&(vkdev_options){.validation = o->cli.validate, .device = o->cli.device}, &dev, err, sizeof err))
        return fail("%s", err);
    snprintf(run->device, sizeof run->device, "%s", dev.device_name);
    vkdev_driver(&dev, run->driver, sizeof run->driver);
    size_t largest = 1;
    for (uint32_t s = 0; s < scene_count; ++s) {
        const size_t p = (size_t)scenes[s].inputs.depth.width * scenes[s].inputs.depth.height;
        if (p > largest) largest = p;
    }
    float *ao = malloc(largest * sizeof *ao);
    bool ok = ao != NULL;
    if (!ok) fail("out of memory");
    const bool show = isatty(STDERR_FILENO);
    const uint32_t total = config_count * scene_count;
    const double started = seconds_now();
    load_average(run->load_before);
    for (uint32_t c = 0; ok && c < config_count; ++c)
        for (uint32_t s = 0; ok && s < scene_count; ++s) {
            bench_result *r = &results[c * scene_count + s];
            *r = (bench_result){.scene = s, .config = c};
            if (show) progress(c * scene_count + s, total, started, configs[c].name);
            ok = run_one(&dev, o, &scenes[s], &configs[c], ao, r);
        }
    if (ok && cache) {
        run->cache_width = scenes[0].inputs.depth.width;
        run->cache_height = scenes[0].inputs.depth.height;
    }
    for (uint32_t c = 0; ok && cache && c < config_count; ++c) {
        const bench_config *config = &configs[c];
        const cacao_settings set = config_settings(o, config, &scenes[0]);
        if (vkdev_time_pipeline_cache(&dev, &set, run->cache_width, run->cache_height, o->cache_trials, &cache[c],
                                      err, sizeof err) != CACAO_SUCCESS)
            ok = fail("%s: pipeline cache timing: %s", config->name, err);
    }
    load_average(run->load_after);
    if (ok && show) progress(total, total, started, "done");
    free(ao);
    vkdev_destroy(&dev);
    if (ok && dev.validation_messages)
        ok = fail("--validate: the validation layer reported %u message(s) (above); nothing written",
                  dev.validation_messages);
    return ok;
}

/* ---- Writing --------------------------------------------------------------------------------- */

static bool write_files(const bench_options *o, const bench_run *run) {
    char err[BENCH_ERR];
    const char *written[3];
    int count = 0;
    bool ok = true;
    if (ok && o->json_path) ok = bench_write_json(o->json_path, run, err) && (written[count++] = o->json_path);
    if (ok && o->csv_path) ok = bench_write_csv(o->csv_path, run, err) && (written[count++] = o->csv_path);
    if (ok && o->plot_path) ok = bench_write_plot(o->plot_path, run, err) && (written[count++] = o->plot_path);
    if (ok) return true;
    for (int i = 0; i < count; ++i) remove(written[i]); /* all or nothing */
    return fail("%s", err);
}

static bool plot_possible(const bench_options *o, const bench_scene *scenes, uint32_t scene_count) {
    if (!o->plot_path) return true;
    for (uint32_t s = 0; s < scene_count; ++s)
        if (bench_plot_truth(&scenes[s]) >= 0) return true;
    return fail("--plot: no scene has ao_gt_falloff.pfm or ao_gt.pfm, so there is no error to plot");
}

int main(int argc, char **argv) {
    bench_options o;
    if (!parse_flags(argc, argv, &o)) return 1;
    if (o.help) {
        fputs(help_text, stdout);
        return 0;
    }
    static bench_config configs[SWEEP_FULL_SIZE];
    uint32_t config_count = 0;
    if (!select_configs(&o, configs, &config_count)) return 1;
    if (o.list_configs) {
        for (uint32_t c = 0; c < config_count; ++c) printf("%s\n", configs[c].name);
        return 0;
    }
    bench_run run = {.configs = configs, .config_count = config_count, .warmup = o.warmup, .repeat = o.repeat};
    char reference_name[256] = "";
    bench_point *points = NULL;
    if (o.reference_path &&
        !load_reference(o.reference_path, reference_name, sizeof reference_name, &points, &run.point_count)) {
        free(points);
        return 1;
    }
    run.reference_name = reference_name;
    run.points = points;
    if (o.plot_from) {
        static bench_scene plot_scenes[BENCH_MAX_SCENES];
        bench_result *plot_results = NULL;
        char err[BENCH_ERR];
        bool ok = load_plot_from(o.plot_from, plot_scenes, configs, &plot_results, &run) &&
                  plot_possible(&o, plot_scenes, run.scene_count);
        if (ok && !bench_write_plot(o.plot_path, &run, err)) ok = fail("%s", err);
        free(plot_results);
        free(points);
        return ok ? 0 : 1;
    }
    static bench_scene scenes[BENCH_MAX_SCENES];
    const uint32_t scene_count = o.scene_count ? o.scene_count : 1;
    uint32_t loaded = 0;
    bool ok = true;
    for (; ok && loaded < scene_count; ++loaded)
        ok = load_scene(&o, o.scene_count ? o.scenes[loaded] : NULL, &scenes[loaded]);
    ok = ok && plot_possible(&o, scenes, scene_count);
    bench_result *results = ok ? calloc((size_t)config_count * scene_count, sizeof *results) : NULL;
    vkdev_cache_timing *cache = ok && o.cache_trials ? calloc(config_count, sizeof *cache) : NULL;
    if (ok && (!results || (o.cache_trials && !cache))) ok = fail("out of memory");
    if (ok) {
        run.scenes = scenes;
        run.scene_count = scene_count;
        run.results = results;
        run.result_count = config_count * scene_count;
        run.cache = cache;
        ok = run_all(&o, configs, config_count, scenes, scene_count, results, cache, &run) && write_files(&o, &run);
        if (ok) bench_print_table(stdout, &run);
    }
    for (uint32_t s = 0; s < loaded; ++s) free_scene(&scenes[s]);
    free(results);
    free(cache);
    free(points);
    return ok ? 0 : 1;
}
