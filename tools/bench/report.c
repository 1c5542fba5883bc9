/* report.c - cacao-bench's table, JSON, CSV and plot (see bench.h). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "options.h"
#include "text_file.h"

extern char **environ;
extern const char cacao_bench_pareto_gp[]; /* tools/bench/pareto.gp, embedded at build time */

/* cacao_set_err into a BENCH_ERR buffer, as a failed result. */
#define fail_with(err, ...) cacao_set_err(err, BENCH_ERR, __VA_ARGS__)

int bench_plot_truth(const bench_scene *scene) {
    for (int t = 0; t < BENCH_TRUTHS; ++t)
        if (scene->has_truth[t]) return t;
    return -1;
}

/* ---- Table ------------------------------------------------------------------------------------ */

static void print_error_cells(FILE *out, const bench_result *r, int t) {
    if (r->has_error[t])
        fprintf(out, " %8.4f %8.4f %8.4f", r->error[t].rmse, r->error[t].mean_abs, r->error[t].p99);
    else
        fprintf(out, " %8s %8s %8s", "-", "-", "-");
}

void bench_print_table(FILE *out, const bench_run *run) {
    fprintf(out, "cacao-bench on %s (%s); median, min and max of %u frames after %u warm-up\n", run->device,
            run->driver, run->repeat, run->warmup);
    fprintf(out, "%-18s %-34s %9s %9s %9s %9s %5s %9s %8s %8s %8s %8s %8s %8s %9s  %s\n", "scene", "config", "total_ms",
            "min_ms", "max_ms", "mem_MiB", "pipes", "create_ms", "rmse_gtf", "mae_gtf", "p99_gtf", "rmse_gt", "mae_gt",
            "p99_gt", "nonfinite", "per-pass median ms");
    for (uint32_t i = 0; i < run->result_count; ++i) {
        const bench_result *r = &run->results[i];
        const cacao_timings *t = &r->timings;
        fprintf(out, "%-18s %-34s %9.3f %9.3f %9.3f %9.2f %5u %9.1f", run->scenes[r->scene].name,
                run->configs[r->config].name, t->total.median_ms, t->total.min_ms, t->total.max_ms,
                (double)t->memory_bytes / (1024.0 * 1024.0), t->pipeline_count, t->setup_ms);
        print_error_cells(out, r, BENCH_GT_FALLOFF);
        print_error_cells(out, r, BENCH_GT);
        fprintf(out, " %9zu ", r->nonfinite);
        for (uint32_t s = 0; s < t->step_count; ++s)
            fprintf(out, " %s=%.3f", r->plan.steps[s].key_name, t->step[s].median_ms);
        fputc('\n', out);
    }
    if (run->scene_count && bench_plot_truth(&run->scenes[0]) < 0 && run->scene_count == 1)
        fprintf(out, "(no ao_gt_falloff.pfm / ao_gt.pfm in the scene: no errors)\n");
    if (!run->cache) return;
    fprintf(out, "\npipeline creation at %ux%u (cacao_context_resize), median (min..max) ms of %u trials:\n",
            run->cache_width, run->cache_height, run->cache[0].trials);
    fprintf(out, "%-34s %5s %20s %20s %20s %11s\n", "config", "pipes", "no_cache", "empty_cache", "warm_cache",
            "cache_bytes");
    for (uint32_t c = 0; c < run->config_count; ++c) {
        const vkdev_cache_timing *t = &run->cache[c];
        const cacao_time_stats *s[3] = {&t->no_cache, &t->cold_cache, &t->warm_cache};
        fprintf(out, "%-34s %5u", run->configs[c].name, t->pipeline_count);
        for (int k = 0; k < 3; ++k) {
            char cell[32];
            snprintf(cell, sizeof cell, "%.1f (%.1f..%.1f)", s[k]->median_ms, s[k]->min_ms, s[k]->max_ms);
            fprintf(out, " %20s", cell);
        }
        fprintf(out, " %11zu\n", t->cache_bytes);
    }
    if (run->cache[0].cache_bytes <= VKDEV_PIPELINE_CACHE_HEADER_BYTES)
        fprintf(out, "(this driver's cache data is only its %u-byte header: it keeps no pipeline)\n",
                VKDEV_PIPELINE_CACHE_HEADER_BYTES);
}

static cJSON *time_stats_json(const cacao_time_stats *s) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "median_ms", s->median_ms);
    cJSON_AddNumberToObject(o, "min_ms", s->min_ms);
    cJSON_AddNumberToObject(o, "max_ms", s->max_ms);
    return o;
}

/* "pipeline_cache": {width, height, trials, configurations: [{config, pipeline_count, no_cache,
 * empty_cache, warm_cache (each median/min/max ms), cache_bytes, header_valid}]} */
static void add_cache_json(cJSON *root, const bench_run *run) {
    cJSON *o = cJSON_AddObjectToObject(root, "pipeline_cache");
    cJSON_AddNumberToObject(o, "width", run->cache_width);
    cJSON_AddNumberToObject(o, "height", run->cache_height);
    cJSON_AddNumberToObject(o, "trials", run->cache[0].trials);
    cJSON *list = cJSON_AddArrayToObject(o, "configurations");
    for (uint32_t c = 0; list && c < run->config_count; ++c) {
        const vkdev_cache_timing *t = &run->cache[c];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "config", run->configs[c].name);
        cJSON_AddNumberToObject(e, "pipeline_count", t->pipeline_count);
        cJSON_AddItemToObject(e, "no_cache", time_stats_json(&t->no_cache));
        cJSON_AddItemToObject(e, "empty_cache", time_stats_json(&t->cold_cache));
        cJSON_AddItemToObject(e, "warm_cache", time_stats_json(&t->warm_cache));
        cJSON_AddNumberToObject(e, "cache_bytes", (double)t->cache_bytes);
        cJSON_AddBoolToObject(e, "header_valid", t->header_valid);
        cJSON_AddItemToArray(list, e);
    }
}

/* ---- Text files ------------------------------------------------------------------------------- */

static bool write_text(const char *path, const char *text, char *err) {
    char *temp = cacao_temp_path_for(path);
    if (!temp) return fail_with(err, "%s: out of memory", path);
    FILE *f = fopen(temp, "wb");
    if (!f) {
        fail_with(err, "%s: cannot create: %s", path, strerror(errno));
        free(temp);
        return false;
    }
    const size_t length = strlen(text);
    bool ok = fwrite(text, 1, length, f) == length;
    ok = fclose(f) == 0 && ok;
    return cacao_commit_temp(temp, path, ok, err, BENCH_ERR);
}

/* ---- JSON ------------------------------------------------------------------------------------- */

static cJSON *numbers(const double *v, int n) {
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; a && i < n; ++i) cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

static cJSON *result_json(const bench_run *run, const bench_result *r) {
    const bench_scene *s = &run->scenes[r->scene];
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "scene", s->name);
    cJSON_AddStringToObject(o, "config", run->configs[r->config].name);
    cJSON_AddNumberToObject(o, "width", s->inputs.depth.width);
    cJSON_AddNumberToObject(o, "height", s->inputs.depth.height);
    cJSON_AddItemToObject(o, "settings", cli_settings_to_json(&r->resolved));
    cacao_timings_add_json(o, &r->plan, &r->timings);
    cJSON_AddNumberToObject(o, "memory_bytes", (double)r->timings.memory_bytes);
    cJSON_AddNumberToObject(o, "pipeline_count", r->timings.pipeline_count);
    cJSON_AddNumberToObject(o, "pipeline_creation_ms", r->timings.setup_ms);
    cJSON_AddNumberToObject(o, "nonfinite", (double)r->nonfinite);
    cJSON *errors = cJSON_AddObjectToObject(o, "errors");
    for (int t = 0; errors && t < BENCH_TRUTHS; ++t) {
        if (!r->has_error[t]) continue;
        cJSON *e = cJSON_AddObjectToObject(errors, bench_truth_names[t]);
        cJSON_AddNumberToObject(e, "pixels", (double)r->error[t].pixels);
        cJSON_AddNumberToObject(e, "rmse", r->error[t].rmse);
        cJSON_AddNumberToObject(e, "mae", r->error[t].mean_abs);
        cJSON_AddNumberToObject(e, "p99", r->error[t].p99);
    }
    return o;
}

static cJSON *run_json(const bench_run *run) {
    cJSON *root = cJSON_CreateObject();
    char version[32];
    snprintf(version, sizeof version, "%d.%d.%d", CACAO_VERSION_MAJOR, CACAO_VERSION_MINOR, CACAO_VERSION_PATCH);
    cJSON_AddStringToObject(root, "tool", "cacao-bench");
    cJSON_AddStringToObject(root, "version", version);
    cJSON_AddStringToObject(root, "device", run->device);
    cJSON_AddStringToObject(root, "driver", run->driver);
    cJSON_AddNumberToObject(root, "warmup", run->warmup);
    cJSON_AddNumberToObject(root, "repeat", run->repeat);
    cJSON_AddItemToObject(root, "load_average_before", numbers(run->load_before, 3));
    cJSON_AddItemToObject(root, "load_average_after", numbers(run->load_after, 3));
    cJSON *scenes = cJSON_AddArrayToObject(root, "scenes");
    for (uint32_t i = 0; scenes && i < run->scene_count; ++i) {
        const bench_scene *s = &run->scenes[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", s->name);
        if (s->path)
            cJSON_AddStringToObject(o, "path", s->path);
        else
            cJSON_AddNullToObject(o, "path");
        cJSON_AddNumberToObject(o, "width", s->inputs.depth.width);
        cJSON_AddNumberToObject(o, "height", s->inputs.depth.height);
        cJSON *truths = cJSON_AddArrayToObject(o, "truths");
        for (int t = 0; truths && t < BENCH_TRUTHS; ++t)
            if (s->has_truth[t]) cJSON_AddItemToArray(truths, cJSON_CreateString(bench_truth_names[t]));
        cJSON_AddItemToArray(scenes, o);
    }
    cJSON *configs = cJSON_AddArrayToObject(root, "configurations");
    for (uint32_t i = 0; configs && i < run->config_count; ++i) {
        const bench_config *c = &run->configs[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", c->name);
        cJSON_AddStringToObject(o, "quality", cacao_quality_name(c->quality));
        cJSON_AddStringToObject(o, "resolution", c->downsample ? "downsampled" : "native");
        cJSON_AddNumberToObject(o, "blur", c->blur);
        cJSON_AddStringToObject(o, "precision", c->fp16 ? "fp16" : "fp32");
        cJSON_AddStringToObject(o, "normals", c->reconstruct_normals ? "reconstructed" : "as given");
        cJSON_AddItemToArray(configs, o);
    }
    cJSON *results = cJSON_AddArrayToObject(root, "results");
    for (uint32_t i = 0; results && i < run->result_count; ++i)
        cJSON_AddItemToArray(results, result_json(run, &run->results[i]));
    if (run->cache) add_cache_json(root, run);
    if (run->point_count) {
        cJSON *ref = cJSON_AddObjectToObject(root, "reference");
        cJSON_AddStringToObject(ref, "name", run->reference_name);
        cJSON *points = cJSON_AddArrayToObject(ref, "points");
        for (uint32_t i = 0; points && i < run->point_count; ++i) {
            const bench_point *p = &run->points[i];
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "scene", p->scene);
            cJSON_AddStringToObject(o, "config", p->label);
            cJSON_AddNumberToObject(o, "total_ms", p->total_ms);
            for (int t = 0; t < BENCH_TRUTHS; ++t) {
                char key[64];
                snprintf(key, sizeof key, "rmse_%s", bench_truth_names[t]);
                if (p->rmse[t] >= 0) cJSON_AddNumberToObject(o, key, p->rmse[t]);
            }
            cJSON_AddItemToArray(points, o);
        }
    }
    return root;
}

bool bench_write_json(const char *path, const bench_run *run, char *err) {
    cJSON *root = run_json(run);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return fail_with(err, "%s: out of memory", path);
    const size_t n = strlen(text);
    char *line = realloc(text, n + 2);
    if (!line) {
        cJSON_free(text);
        return fail_with(err, "%s: out of memory", path);
    }
    memcpy(line + n, "\n", 2);
    const bool ok = write_text(path, line, err);
    free(line);
    return ok;
}

/* ---- CSV -------------------------------------------------------------------------------------- */

typedef struct text_buffer {
    char *data;
    size_t length, capacity;
    bool failed;
} text_buffer;

static void append(text_buffer *b, const char *fmt, ...) {
    if (b->failed) return;
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || b->length + (size_t)n + 1 > b->capacity) {
        const size_t want = (b->length + (size_t)(n < 0 ? 0 : n) + 1) * 2 + 4096;
        char *grown = n < 0 ? NULL : realloc(b->data, want);
        if (!grown) {
            b->failed = true;
            return;
        }
        b->data = grown;
        b->capacity = want;
    }
    va_start(ap, fmt);
    vsnprintf(b->data + b->length, b->capacity - b->length, fmt, ap);
    va_end(ap);
    b->length += (size_t)n;
}

/* A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break. */
static void append_field(text_buffer *b, const char *text) {
    if (!strpbrk(text, ",\"\n\r")) {
        append(b, "%s,", text);
        return;
    }
    append(b, "\"");
    for (const char *p = text; *p; ++p) append(b, *p == '"' ? "\"\"" : "%c", *p);
    append(b, "\",");
}

static void append_error_fields(text_buffer *b, const bench_result *r, int t) {
    if (r->has_error[t])
        append(b, "%.9g,%.9g,%.9g,", r->error[t].rmse, r->error[t].mean_abs, r->error[t].p99);
    else
        append(b, ",,,");
}

static const char csv_header[] =
    "scene,config,quality,resolution,blur,precision,normals,width,height,device,driver,warmup,repeat,"
    "total_ms,total_min_ms,total_max_ms,passes_median_ms,memory_bytes,pipeline_count,pipeline_creation_ms,"
    "nonfinite,rmse_ao_gt_falloff,mae_ao_gt_falloff,p99_ao_gt_falloff,rmse_ao_gt,mae_ao_gt,p99_ao_gt,"
    "load_average_before,load_average_after,settings\n";

static void append_row(text_buffer *b, const bench_run *run, const bench_result *r) {
    const bench_scene *s = &run->scenes[r->scene];
    const bench_config *c = &run->configs[r->config];
    const cacao_timings *t = &r->timings;
    append_field(b, s->name);
    append_field(b, c->name);
    append(b, "%s,%s,%d,%s,%s,%u,%u,", cacao_quality_name(c->quality), c->downsample ? "downsampled" : "native",
           c->blur, c->fp16 ? "fp16" : "fp32", c->reconstruct_normals ? "reconstructed" : "as given",
           s->inputs.depth.width, s->inputs.depth.height);
    append_field(b, run->device);
    append_field(b, run->driver);
    append(b, "%u,%u,%.6f,%.6f,%.6f,", t->warmup, t->repeat, t->total.median_ms, t->total.min_ms, t->total.max_ms);
    text_buffer passes = {0};
    for (uint32_t i = 0; i < t->step_count; ++i)
        append(&passes, "%s%s=%.6f", i ? ";" : "", r->plan.steps[i].key_name, t->step[i].median_ms);
    append_field(b, passes.data ? passes.data : "");
    b->failed |= passes.failed;
    free(passes.data);
    append(b, "%llu,%u,%.3f,%zu,", (unsigned long long)t->memory_bytes, t->pipeline_count, t->setup_ms, r->nonfinite);
    append_error_fields(b, r, BENCH_GT_FALLOFF);
    append_error_fields(b, r, BENCH_GT);
    append(b, "%.2f %.2f %.2f,%.2f %.2f %.2f,", run->load_before[0], run->load_before[1], run->load_before[2],
           run->load_after[0], run->load_after[1], run->load_after[2]);
    cJSON *settings = cli_settings_to_json(&r->resolved);
    char *text = settings ? cJSON_PrintUnformatted(settings) : NULL;
    cJSON_Delete(settings);
    if (!text)
        b->failed = true;
    else
        append_field(b, text);
    cJSON_free(text);
    if (!b->failed) b->data[b->length - 1] = '\n'; /* the last comma becomes the line end */
}

bool bench_write_csv(const char *path, const bench_run *run, char *err) {
    text_buffer b = {0};
    append(&b, "%s", csv_header);
    for (uint32_t i = 0; i < run->result_count; ++i) append_row(&b, run, &run->results[i]);
    const bool ok = !b.failed ? write_text(path, b.data, err) : fail_with(err, "%s: out of memory", path);
    free(b.data);
    return ok;
}

/* ---- Plot ------------------------------------------------------------------------------------- */

typedef struct plot_point {
    double ms, error;
    const char *label;
} plot_point;

static int by_time(const void *a, const void *b) {
    const plot_point *x = a, *y = b;
    if (x->ms != y->ms) return x->ms < y->ms ? -1 : 1;
    return (x->error > y->error) - (x->error < y->error);
}

/* One scene's three blocks of the data file: configurations, Pareto front, reference points. */
static void append_scene_blocks(text_buffer *b, const bench_run *run, uint32_t scene, int truth, plot_point *points) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < run->result_count; ++i) {
        const bench_result *r = &run->results[i];
        if (r->scene != scene || !r->has_error[truth]) continue;
        points[n++] = (plot_point){r->timings.total.median_ms, r->error[truth].rmse, run->configs[r->config].name};
        append(b, "%.6f %.6f \"%s\"\n", points[n - 1].ms, points[n - 1].error, points[n - 1].label);
    }
    append(b, "\n\n");
    qsort(points, n, sizeof *points, by_time);
    double best = INFINITY;
    for (uint32_t i = 0; i < n; ++i) /* non-dominated: lower error than every faster configuration */
        if (points[i].error < best) {
            best = points[i].error;
            append(b, "%.6f %.6f \"%s\"\n", points[i].ms, points[i].error, points[i].label);
        }
    append(b, "\n\n");
    bool any = false;
    for (uint32_t i = 0; i < run->point_count; ++i) {
        const bench_point *p = &run->points[i];
        if (strcmp(p->scene, run->scenes[scene].name) != 0 || p->rmse[truth] < 0) continue;
        append(b, "%.6f %.6f \"%s\"\n", p->total_ms, p->rmse[truth], p->label);
        any = true;
    }
    if (!any) append(b, "NaN NaN \"\"\n");
    append(b, "\n\n");
}

/* A gnuplot string literal (double quotes, backslash escapes). */
static void append_gp_string(text_buffer *b, const char *text) {
    append(b, "\"");
    for (const char *p = text; *p; ++p) append(b, (*p == '"' || *p == '\\') ? "\\%c" : "%c", *p);
    append(b, "\"");
}

/* Runs gnuplot on the script, in this environment less LD_PRELOAD (a sanitizer build preloads its
 * runtime into cacao-bench; gnuplot is not ours to check). */
static bool run_gnuplot(const char *script_path, char *err) {
    size_t count = 0;
    while (environ[count]) ++count;
    char **env = calloc(count + 1, sizeof *env);
    if (!env) return fail_with(err, "--plot: out of memory");
    for (size_t i = 0, j = 0; i < count; ++i)
        if (strncmp(environ[i], "LD_PRELOAD=", 11) != 0) env[j++] = environ[i];
    pid_t pid;
    char *args[] = {"gnuplot", (char *)script_path, NULL};
    const int spawned = posix_spawnp(&pid, "gnuplot", NULL, NULL, args, env);
    free(env);
    if (spawned != 0)
        return fail_with(err, "--plot: cannot run gnuplot (%s); install the gnuplot-nox package", strerror(spawned));
    int status = 0;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return fail_with(err, "--plot: gnuplot failed (its messages are above)");
    return true;
}

static bool write_temp(const char *text, char *path_out, const char *suffix, char *err) {
    snprintf(path_out, 64, "/tmp/cacao-bench-XXXXXX%s", suffix);
    const int fd = mkstemps(path_out, (int)strlen(suffix));
    if (fd < 0) return fail_with(err, "--plot: cannot create a temporary file: %s", strerror(errno));
    const size_t n = strlen(text);
    const bool ok = write(fd, text, n) == (ssize_t)n;
    close(fd);
    if (!ok) remove(path_out);
    return ok ? true : fail_with(err, "--plot: cannot write a temporary file");
}

bool bench_write_plot(const char *path, const bench_run *run, char *err) {
    plot_point *points = calloc(run->result_count ? run->result_count : 1, sizeof *points);
    text_buffer data = {0}, script = {0}, names = {0};
    int shown_truth = -1;
    for (uint32_t s = 0; points && s < run->scene_count; ++s) {
        const int truth = bench_plot_truth(&run->scenes[s]);
        if (truth < 0) continue;
        if (shown_truth < 0 || truth < shown_truth) shown_truth = truth;
        append_scene_blocks(&data, run, s, truth, points);
        append(&names, "%s%s", names.length ? " " : "", run->scenes[s].name);
    }
    const bool had_memory = points != NULL;
    free(points);
    char data_path[64] = "", script_path[64] = "";
    char *temp = cacao_temp_path_for(path);
    bool ok = had_memory && temp && !data.failed && !names.failed;
    if (!ok) fail_with(err, "%s: out of memory", path);
    if (ok) ok = write_temp(data.data, data_path, ".dat", err);
    if (ok) {
        append(&script, "datafile = ");
        append_gp_string(&script, data_path);
        append(&script, "\noutfile = ");
        append_gp_string(&script, temp);
        const size_t length = strlen(path);
        append(&script, "\nformat = \"%s\"\nscenes = ", strcasecmp(path + length - 4, ".svg") == 0 ? "svg" : "png");
        append_gp_string(&script, names.data);
        append(&script, "\nylabel = \"RMSE against %s (non-background pixels)\"\nrefname = ",
               bench_truth_names[shown_truth < 0 ? 0 : shown_truth]);
        append_gp_string(&script, run->point_count ? run->reference_name : "");
        append(&script, "\n%s", cacao_bench_pareto_gp);
        ok = !script.failed ? write_temp(script.data, script_path, ".gp", err) : fail_with(err, "out of memory");
    }
    if (ok) ok = run_gnuplot(script_path, err);
    if (data_path[0]) remove(data_path);
    if (script_path[0]) remove(script_path);
    free(data.data);
    free(script.data);
    free(names.data);
    if (!temp) return false;
    char commit_err[BENCH_ERR];
    const bool committed = cacao_commit_temp(temp, path, ok, commit_err, sizeof commit_err);
    if (ok && !committed) fail_with(err, "%s", commit_err);
    return ok && committed;
}
