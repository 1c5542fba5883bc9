/* report.c - cacao-bench's table, JSON and CSV (see bench.h). */
#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "options.h"
#include "text_buffer.h"

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
    cJSON_AddNumberToObject(o, "memory_allocations", r->timings.memory_allocations);
    cJSON_AddNumberToObject(o, "pipeline_count", r->timings.pipeline_count);
    cJSON_AddNumberToObject(o, "pipeline_creation_ms", r->timings.setup_ms);
    cJSON_AddNumberToObject(o, "nonfinite", (double)r->nonfinite);
    /* the frames the errors' AO averages: 1, or with temporal accumulation the frames run (warm-up
     * and timed, each a new sample pattern, a still camera) up to temporal_frames */
    const unsigned run_frames = run->warmup + (run->repeat ? run->repeat : 1);
    const unsigned cap = (unsigned)r->resolved.temporal_frames;
    cJSON_AddNumberToObject(o, "frames_accumulated", cap ? (run_frames < cap ? run_frames : cap) : 1);
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

char *bench_json_text(const bench_run *run) {
    cJSON *root = run_json(run);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return NULL;
    const size_t n = strlen(text);
    char *line = realloc(text, n + 2);
    if (!line) {
        cJSON_free(text);
        return NULL;
    }
    memcpy(line + n, "\n", 2);
    return line;
}

/* ---- CSV -------------------------------------------------------------------------------------- */

/* A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break. */
static void append_field(text_buffer *b, const char *text) {
    if (!strpbrk(text, ",\"\n\r")) {
        append(b, "%s,", text);
        return;
    }
    append(b, "\"");
    for (const char *p = text; *p; ++p) append(b, "%s", *p == '"' ? "\"\"" : (char[]){*p, 0});
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

char *bench_csv_text(const bench_run *run) {
    text_buffer b = {0};
    append(&b, "%s", csv_header);
    for (uint32_t i = 0; i < run->result_count; ++i) append_row(&b, run, &run->results[i]);
    if (!b.failed) return b.data;
    free(b.data);
    return NULL;
}
