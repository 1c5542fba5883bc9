/* main.c - cacao-bench: what accuracy costs in time. Runs configurations of cacao (quality,
 * resolution, blur, precision, normals) on scenes through the public API (vkdev + cacao.h) and
 * reports per-pass GPU time (median, min, max of --repeat frames after --warmup), memory, pipeline
 * count and creation time, and the error against the scenes' ground truths; as a table on stdout,
 * JSON and CSV (report.c), and an error-against-time plot with its Pareto front (plot.c).
 *
 * Before the first frame runs, every flag is checked, every input loaded, and every output checked
 * against the inputs and the other outputs and created (empty, beside its destination: see
 * output_files.h), with gnuplot tried when there is a plot. The outputs are filled as the run goes
 * and after it, and renamed into place only when all are complete: a bad flag, input or output
 * path, or a failure at any point, costs no run time it need not and leaves the old files as they
 * were and no new one. */
#include <errno.h>
#include <fnmatch.h>
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
#include "output_files.h"
#include "text_file.h"
#include "vkdev.h"


/* Prints one line "cacao-bench: ..." to stderr; returns false. */
#define fail(...) cacao_error_line("cacao-bench: ", __VA_ARGS__)

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
    "                     gtao_* and bitmask_* are the horizon-slice estimators (fp32; blur = denoise passes)\n"
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
    "                     interleaved runs by tools/accuracy-report.py); takes only --plot and --reference\n"
    "  --device N|NAME    Vulkan device (default lavapipe); --validate: validation layer on\n"
    "Settings flags (--radius, --strength, --power, --fade-out, ... see cacao --help) apply to every\n"
    "configuration. The configuration sets estimator, quality, resolution, blur and precision: their\n"
    "flags are refused, and a --settings file's keys for them are replaced. Flags of the gtao and\n"
    "bitmask estimators (--slices, --steps, --visibility, --frame; --thickness: bitmask) are refused\n"
    "when a selected configuration runs another estimator. No output may name an input or another\n"
    "output; outputs are written all or nothing, after the run.\n";

static bool parse_count(const char *flag, const char *value, uint32_t low, uint32_t *out) {
    char *end;
    const long v = value ? strtol(value, &end, 10) : -1;
    if (!value || !value[0] || *end || v < (long)low || v > 100000) {
        fail("%s %s: must be a whole number from %u to 100000", flag, cacao_shown(value ? value : "(missing)").text,
             low);
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

/* What cacao-bench does: runs (the default), re-plots (--plot-from) or lists (--list-configs); a
 * flag outside the mode it is given in would be ignored, so it is refused. */
enum { MODE_RUN = 1, MODE_PLOT_FROM = 2, MODE_LIST = 4, MODE_ANY = 7 };

typedef struct bench_flag {
    const char *name;
    bool takes_value;
    unsigned modes;
} bench_flag;

static const bench_flag bench_flags[] = {
    {"--scene", true, MODE_RUN},
    {"--configs", true, MODE_RUN | MODE_LIST},
    {"--sweep", true, MODE_RUN | MODE_LIST},
    {"--list-configs", false, MODE_LIST},
    {"--warmup", true, MODE_RUN},
    {"--repeat", true, MODE_RUN},
    {"--pipeline-cache", true, MODE_RUN},
    {"--json", true, MODE_RUN},
    {"--csv", true, MODE_RUN},
    {"--plot", true, MODE_RUN | MODE_PLOT_FROM},
    {"--reference", true, MODE_RUN | MODE_PLOT_FROM},
    {"--save-ao", true, MODE_RUN},
    {"--plot-from", true, MODE_PLOT_FROM},
    {"--help", false, MODE_ANY},
    {"-h", false, MODE_ANY},
};

static const bench_flag *find_bench_flag(const char *arg) {
    for (size_t i = 0; i < sizeof bench_flags / sizeof bench_flags[0]; ++i)
        if (strcmp(arg, bench_flags[i].name) == 0) return &bench_flags[i];
    return NULL;
}

/* Settings every configuration sets for itself (a flag for them would be replaced). */
static bool refuse_config_set_flags(const cli_options *cli) {
    static const char *const set_by_config[] = {"--estimator", "--quality", "--downsample", "--blur", "--precision"};
    for (size_t i = 0; i < sizeof set_by_config / sizeof set_by_config[0]; ++i)
        if (cli_given(cli, set_by_config[i]))
            return fail("%s: each configuration sets it; choose configurations with --configs (see --list-configs "
                        "--sweep full)",
                        set_by_config[i]);
    return true;
}

/* Applies one flag of cacao-bench's own (its value in v, checked present). */
static bool apply_bench_flag(const char *a, const char *v, bench_options *o) {
    const char **path = strcmp(a, "--json") == 0        ? &o->json_path
                        : strcmp(a, "--csv") == 0       ? &o->csv_path
                        : strcmp(a, "--plot") == 0      ? &o->plot_path
                        : strcmp(a, "--reference") == 0 ? &o->reference_path
                        : strcmp(a, "--save-ao") == 0   ? &o->save_dir
                        : strcmp(a, "--configs") == 0   ? &o->configs
                        : strcmp(a, "--plot-from") == 0 ? &o->plot_from
                                                        : NULL;
    if (path) {
        *path = v;
        return true;
    }
    if (strcmp(a, "--scene") == 0) {
        if (o->scene_count == BENCH_MAX_SCENES) return fail("--scene: at most %d scenes", BENCH_MAX_SCENES);
        o->scenes[o->scene_count++] = v;
        return true;
    }
    if (strcmp(a, "--sweep") == 0) {
        o->full_sweep = strcmp(v, "full") == 0;
        return o->full_sweep || strcmp(v, "default") == 0
                   ? true
                   : fail("--sweep %s: use default or full", cacao_shown(v).text);
    }
    if (strcmp(a, "--warmup") == 0) return parse_count(a, v, 0, &o->warmup);
    if (strcmp(a, "--repeat") == 0) return parse_count(a, v, 1, &o->repeat);
    if (strcmp(a, "--pipeline-cache") == 0) return parse_count(a, v, 1, &o->cache_trials);
    if (strcmp(a, "--list-configs") == 0)
        o->list_configs = true;
    else
        o->help = true;
    return true;
}

/* Refuses a flag given outside the mode (outside[m]: the first flag not taken by mode 1 << m). */
static bool check_mode(const bench_options *o, const char *const outside[3]) {
    if (o->help) return true;
    if (o->plot_from && outside[1])
        return fail("%s: not with --plot-from, which runs nothing and takes only --plot and --reference",
                    cacao_shown(outside[1]).text);
    if (!o->plot_from && o->list_configs && outside[2])
        return fail("%s: not with --list-configs, which runs nothing and takes only --configs and --sweep",
                    cacao_shown(outside[2]).text);
    return true;
}

static bool parse_flags(int argc, char **argv, bench_options *o) {
    memset(o, 0, sizeof *o);
    o->warmup = 2;
    o->repeat = 7;
    char **rest = calloc((size_t)argc + 1, sizeof *rest);
    if (!rest) return fail("out of memory");
    int n = 0;
    rest[n++] = "cacao-bench";
    const char *outside[3] = {NULL, NULL, NULL}; /* the first flag given outside each mode */
    bool ok = true;
    for (int i = 1; ok && i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        const bench_flag *flag = find_bench_flag(a);
        for (int m = 0; m < 3; ++m)
            if (!outside[m] && !((flag ? flag->modes : MODE_RUN) >> m & 1)) outside[m] = a;
        if (flag && flag->takes_value && (!v || !v[0]))
            ok = fail("%s: needs a value", a);
        else if (flag)
            ok = apply_bench_flag(a, flag->takes_value ? argv[++i] : NULL, o);
        else if (refused_cacao_flag(a))
            ok = fail("%s: a flag of cacao, not of cacao-bench (see --help)", a); /* a known name: printable */
        else
            rest[n++] = argv[i];
    }
    char err[BENCH_ERR];
    if (ok && !cli_parse(n, rest, &o->cli, err, sizeof err)) ok = fail("%s", err);
    free(rest);
    if (!ok || !check_mode(o, outside) || !refuse_config_set_flags(&o->cli)) return false;
    if (o->plot_path && !has_extension(o->plot_path, ".png") && !has_extension(o->plot_path, ".svg"))
        return fail("--plot %s: use a .png or .svg file", cacao_shown(o->plot_path).text);
    if (o->plot_from && !o->plot_path && !o->help)
        return fail("--plot-from %s: needs --plot FILE (it runs nothing and only plots)",
                    cacao_shown(o->plot_from).text);
    struct stat st;
    if (o->save_dir && (stat(o->save_dir, &st) != 0 || !S_ISDIR(st.st_mode)))
        return fail("--save-ao %s: not a folder", cacao_shown(o->save_dir).text);
    return true;
}

/* ---- Configurations --------------------------------------------------------------------------- */

/* The configurations the options select, in sweep order (each once); the flags of one estimator
 * are refused when a selected configuration runs another. */
static bool select_configs(const bench_options *o, bench_config *out, uint32_t *count) {
    char err[BENCH_ERR], what[96];
    if (!sweep_select(o->configs, o->full_sweep, out, count, err, sizeof err))
        return fail("--configs: %s (see --list-configs --sweep full)", err);
    for (uint32_t c = 0; c < *count; ++c) {
        snprintf(what, sizeof what, "configuration %s", out[c].name);
        if (!cli_check_estimator_flags(&o->cli, out[c].estimator, what, err, sizeof err)) return fail("%s", err);
    }
    return true;
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

/* A scene's name: its folder's own name ("default" for the embedded scene). It names the scene
 * in the table, JSON, CSV, plot and --save-ao files, so it must be printable and differ from the
 * names of the scenes before it. */
static bool name_scene(const char *dir, const bench_scene *earlier, uint32_t earlier_count, char *name, size_t size) {
    if (!dir) {
        snprintf(name, size, "default");
        return true;
    }
    size_t end = strlen(dir);
    while (end > 1 && dir[end - 1] == '/') --end;
    size_t start = end;
    while (start > 0 && dir[start - 1] != '/') --start;
    const cacao_shown_text shown = cacao_shown(dir);
    if (end - start >= size)
        return fail("--scene %s: the folder's name is longer than %zu bytes", shown.text, size - 1);
    memcpy(name, dir + start, end - start);
    name[end - start] = '\0';
    if (!cacao_text_is_printable(name))
        return fail("--scene %s: the folder's name is empty or holds control characters, which the table, CSV and "
                    "plot cannot show",
                    shown.text);
    for (uint32_t k = 0; k < earlier_count; ++k)
        if (strcmp(earlier[k].name, name) == 0)
            return fail("--scene %s: named '%s' like --scene %s (a scene is named by its folder; rename one)",
                        shown.text, name, cacao_shown(earlier[k].path).text);
    return true;
}

/* Loads scenes[index] (the scenes before it loaded). */
static bool load_scene(const bench_options *o, bench_scene *scenes, uint32_t index) {
    bench_scene *s = &scenes[index];
    memset(s, 0, sizeof *s);
    const char *dir = o->scene_count ? o->scenes[index] : NULL;
    s->path = dir;
    if (!name_scene(dir, scenes, index, s->name, sizeof s->name)) return false;
    cli_options io = o->cli;
    io.scene_dir = dir;
    char err[BENCH_ERR];
    if (!cli_inputs_load(&io, &s->inputs, err, sizeof err)) return fail("%s", err);
    for (int t = 0; dir && t < BENCH_TRUTHS; ++t) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s.pfm", dir, bench_truth_names[t]);
        if (!file_exists(path)) continue;
        if (!cli_read_scalar_image(path, "ground truth", false, &s->truth[t], err, sizeof err)) return fail("%s", err);
        if (s->truth[t].width != s->inputs.depth.width || s->truth[t].height != s->inputs.depth.height)
            return fail("%s: ground truth is %ux%u but the depth is %ux%u", cacao_shown(path).text, s->truth[t].width,
                        s->truth[t].height, s->inputs.depth.width, s->inputs.depth.height);
        s->has_truth[t] = true;
    }
    return true;
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

/* Runs one configuration on one scene into r; its AO goes to ao_path (a staged file) unless NULL. */
static bool run_one(vkdev *dev, const bench_options *o, const bench_scene *s, const bench_config *c, float *ao,
                    const char *ao_path, bench_result *r) {
    char err[BENCH_ERR];
    const cacao_settings set = config_settings(o, c, s);
    if (cacao_settings_resolve(&set, &r->resolved, err, sizeof err) != CACAO_SUCCESS)
        return fail("%s on %s: %s", c->name, s->name, err);
    const cli_inputs *in = &s->inputs;
    vkdev_frame frame = cli_inputs_frame(in, &set, o->cli.frame_index);
    frame.plan_out = &r->plan; /* the plan the context ran, fallbacks included */
    frame.advance_frame_index = (&set)->temporal_frames != 0; /* a new sample pattern every frame */
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
    if (ao_path && !cacao_pfm_write(ao_path, &image, err, sizeof err)) return fail("--save-ao: %s", err);
    return true;
}

static void progress(uint32_t done, uint32_t total, double started, const char *what) {
    const double elapsed = seconds_now() - started;
    const double left = done ? elapsed / done * (total - done) : 0;
    fprintf(stderr, "\r\033[K[%u/%u] %s  elapsed %.0f s, about %.0f s left", done, total, what, elapsed, left);
    if (done == total) fputc('\n', stderr);
    fflush(stderr);
}

/* Runs every configuration on every scene into results (configuration-major), the AO of each to
 * ao_paths[same index] where ao_paths is not NULL. */
static bool run_all(const bench_options *o, const bench_config *configs, uint32_t config_count,
                    const bench_scene *scenes, uint32_t scene_count, const char *const *ao_paths, bench_result *results,
                    vkdev_cache_timing *cache, bench_run *run) {
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
            const uint32_t k = c * scene_count + s;
            results[k] = (bench_result){.scene = s, .config = c};
            if (show) progress(k, total, started, configs[c].name);
            ok = run_one(&dev, o, &scenes[s], &configs[c], ao, ao_paths ? ao_paths[k] : NULL, &results[k]);
        }
    if (ok && cache) {
        run->cache_width = scenes[0].inputs.depth.width;
        run->cache_height = scenes[0].inputs.depth.height;
    }
    for (uint32_t c = 0; ok && cache && c < config_count; ++c) {
        const bench_config *config = &configs[c];
        const cacao_settings set = config_settings(o, config, &scenes[0]);
        if (vkdev_time_pipeline_cache(&dev, &set, run->cache_width, run->cache_height, o->cache_trials, &cache[c], err,
                                      sizeof err) != CACAO_SUCCESS)
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

/* ---- Outputs --------------------------------------------------------------------------------- */

/* Every file the run reads, for the outputs to be checked against: each scene folder and the
 * files in it, the truths, --reference, --settings and --plot-from. */
typedef struct input_list {
    cacao_named_path paths[4 + BENCH_MAX_SCENES * (1 + CLI_SCENE_FILE_COUNT + BENCH_TRUTHS)];
    char scene_files[BENCH_MAX_SCENES][CLI_SCENE_FILE_COUNT + BENCH_TRUTHS][4200];
    size_t count;
} input_list;

static void list_inputs(const bench_options *o, input_list *in) {
    in->count = 0;
    in->paths[in->count++] = (cacao_named_path){"--reference", o->reference_path};
    in->paths[in->count++] = (cacao_named_path){"--settings", o->cli.settings_path};
    in->paths[in->count++] = (cacao_named_path){"--plot-from", o->plot_from};
    for (uint32_t s = 0; s < o->scene_count; ++s) {
        in->paths[in->count++] = (cacao_named_path){"--scene", o->scenes[s]};
        for (int f = 0; f < CLI_SCENE_FILE_COUNT + BENCH_TRUTHS; ++f) {
            char *path = in->scene_files[s][f];
            if (f < CLI_SCENE_FILE_COUNT)
                snprintf(path, sizeof in->scene_files[s][f], "%s/%s", o->scenes[s], cli_scene_file_names[f]);
            else
                snprintf(path, sizeof in->scene_files[s][f], "%s/%s.pfm", o->scenes[s],
                         bench_truth_names[f - CLI_SCENE_FILE_COUNT]);
            in->paths[in->count++] = (cacao_named_path){"--scene", path};
        }
    }
}

/* The outputs of one run: their paths and their staged files. */
typedef struct bench_outputs {
    cacao_stage stage;
    const char *json, *csv, *plot; /* staged files; NULL where not asked */
    char **ao_paths;               /* --save-ao: DIR/<scene>.<config>.pfm per result, then staged */
    const char **ao_staged;
    size_t ao_count;
} bench_outputs;

static void free_outputs(bench_outputs *out) {
    for (size_t i = 0; out->ao_paths && i < out->ao_count; ++i) free(out->ao_paths[i]);
    free(out->ao_paths);
    free(out->ao_staged);
    cacao_stage_abandon(&out->stage); /* nothing left to delete after a commit */
}

/* The --save-ao path of every result, in the order of the results. */
static bool name_saved_ao(const bench_options *o, const bench_config *configs, uint32_t config_count,
                          const bench_scene *scenes, uint32_t scene_count, bench_outputs *out) {
    out->ao_count = o->save_dir ? (size_t)config_count * scene_count : 0;
    out->ao_paths = calloc(out->ao_count + 1, sizeof *out->ao_paths);
    out->ao_staged = calloc(out->ao_count + 1, sizeof *out->ao_staged);
    if (!out->ao_paths || !out->ao_staged) return fail("out of memory");
    for (size_t k = 0; k < out->ao_count; ++k) {
        const bench_scene *s = &scenes[k % scene_count];
        const bench_config *c = &configs[k / scene_count];
        const size_t size = strlen(o->save_dir) + strlen(s->name) + strlen(c->name) + 8;
        if (!(out->ao_paths[k] = malloc(size))) return fail("out of memory");
        snprintf(out->ao_paths[k], size, "%s/%s.%s.pfm", o->save_dir, s->name, c->name);
    }
    return true;
}

/* Checks every output against the inputs and each other, then creates each one's staged file. */
static bool stage_outputs(const bench_options *o, bench_outputs *out) {
    static input_list inputs;
    list_inputs(o, &inputs);
    cacao_named_path *outputs = calloc(3 + out->ao_count, sizeof *outputs);
    if (!outputs) return fail("out of memory");
    outputs[0] = (cacao_named_path){"--json", o->json_path};
    outputs[1] = (cacao_named_path){"--csv", o->csv_path};
    outputs[2] = (cacao_named_path){"--plot", o->plot_path};
    for (size_t k = 0; k < out->ao_count; ++k) outputs[3 + k] = (cacao_named_path){"--save-ao", out->ao_paths[k]};
    char err[BENCH_ERR];
    bool ok = cacao_check_outputs(outputs, 3 + out->ao_count, inputs.paths, inputs.count, err, sizeof err);
    const char **staged[3] = {&out->json, &out->csv, &out->plot};
    for (size_t k = 0; ok && k < 3 + out->ao_count; ++k) {
        if (!outputs[k].path) continue;
        const char *temp = cacao_stage_add(&out->stage, outputs[k].flag, outputs[k].path, err, sizeof err);
        ok = temp != NULL;
        *(k < 3 ? staged[k] : &out->ao_staged[k - 3]) = temp;
    }
    free(outputs);
    if (ok && o->plot_path) ok = bench_plot_check(o->plot_path, has_extension(o->plot_path, ".svg"), err);
    return ok ? true : fail("%s", err);
}

/* Fills a staged file with text (NULL: out of memory); `flag` and `shown` name it in messages. */
static bool write_staged(const char *staged, char *text, const char *flag, const char *shown) {
    if (!text) return fail("%s %s: out of memory", flag, shown);
    FILE *f = fopen(staged, "wb");
    const size_t length = strlen(text);
    bool ok = f && fwrite(text, 1, length, f) == length;
    ok = f && fclose(f) == 0 && ok;
    free(text);
    return ok ? true : fail("%s %s: cannot write: %s", flag, shown, strerror(errno));
}

/* Fills the JSON, CSV and plot; then renames every staged file into place. */
static bool write_outputs(const bench_options *o, const bench_run *run, bench_outputs *out) {
    char err[BENCH_ERR];
    bool ok = true;
    if (ok && out->json) ok = write_staged(out->json, bench_json_text(run), "--json", o->json_path);
    if (ok && out->csv) ok = write_staged(out->csv, bench_csv_text(run), "--csv", o->csv_path);
    if (ok && out->plot)
        ok =
            bench_write_plot(out->plot, o->plot_path, has_extension(o->plot_path, ".svg"), run, err) || fail("%s", err);
    if (ok) ok = cacao_stage_commit(&out->stage, err, sizeof err) || fail("%s", err);
    return ok;
}

static bool plot_possible(const bench_options *o, const bench_scene *scenes, uint32_t scene_count) {
    if (!o->plot_path) return true;
    for (uint32_t s = 0; s < scene_count; ++s)
        if (bench_plot_truth(&scenes[s]) >= 0) return true;
    return fail("--plot: no scene has ao_gt_falloff.pfm or ao_gt.pfm, so there is no error to plot");
}

/* ---- Modes ------------------------------------------------------------------------------------ */

/* --plot-from: the plot of an earlier run's JSON, with the reference points in run. */
static bool plot_from(const bench_options *o, bench_run *run) {
    static bench_scene scenes[BENCH_MAX_SCENES];
    static bench_config configs[SWEEP_FULL_SIZE];
    bench_result *results = NULL;
    bench_outputs out = {0};
    char err[BENCH_ERR];
    bool ok = bench_load_plot_from(o->plot_from, scenes, configs, &results, run, err) || fail("%s", err);
    ok = ok && plot_possible(o, scenes, run->scene_count) && stage_outputs(o, &out) && write_outputs(o, run, &out);
    free_outputs(&out);
    free(results);
    return ok;
}

/* A run: the configurations on the scenes, the files, then the table. */
static bool run_and_report(const bench_options *o, const bench_config *configs, uint32_t config_count, bench_run *run) {
    static bench_scene scenes[BENCH_MAX_SCENES];
    const uint32_t scene_count = o->scene_count ? o->scene_count : 1;
    uint32_t loaded = 0;
    bool ok = true;
    for (; ok && loaded < scene_count; ++loaded) ok = load_scene(o, scenes, loaded);
    ok = ok && plot_possible(o, scenes, scene_count);
    bench_outputs out = {0};
    ok = ok && name_saved_ao(o, configs, config_count, scenes, scene_count, &out) && stage_outputs(o, &out);
    bench_result *results = ok ? calloc((size_t)config_count * scene_count, sizeof *results) : NULL;
    vkdev_cache_timing *cache = ok && o->cache_trials ? calloc(config_count, sizeof *cache) : NULL;
    if (ok && (!results || (o->cache_trials && !cache))) ok = fail("out of memory");
    if (ok) {
        run->scenes = scenes;
        run->scene_count = scene_count;
        run->results = results;
        run->result_count = config_count * scene_count;
        run->cache = cache;
        ok = run_all(o, configs, config_count, scenes, scene_count, o->save_dir ? out.ao_staged : NULL, results, cache,
                     run) &&
             write_outputs(o, run, &out);
        if (ok) bench_print_table(stdout, run);
    }
    free_outputs(&out);
    for (uint32_t s = 0; s < loaded; ++s) free_scene(&scenes[s]);
    free(results);
    free(cache);
    return ok;
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
    if (!o.plot_from && !select_configs(&o, configs, &config_count)) return 1;
    if (o.list_configs) {
        for (uint32_t c = 0; c < config_count; ++c) printf("%s\n", configs[c].name);
        return 0;
    }
    bench_run run = {.configs = configs, .config_count = config_count, .warmup = o.warmup, .repeat = o.repeat};
    char reference_name[256] = "", err[BENCH_ERR];
    bench_point *points = NULL;
    bool ok =
        !o.reference_path ||
        bench_load_reference(o.reference_path, reference_name, sizeof reference_name, &points, &run.point_count, err) ||
        fail("%s", err);
    run.reference_name = reference_name;
    run.points = points;
    if (ok) ok = o.plot_from ? plot_from(&o, &run) : run_and_report(&o, configs, config_count, &run);
    free(points);
    return ok ? 0 : 1;
}
