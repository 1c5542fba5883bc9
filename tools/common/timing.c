/* timing.c - statistics, table and JSON of GPU timings (see timing.h). */
#include "timing.h"

#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

static int compare_doubles(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

cacao_time_stats cacao_time_stats_of(double *v, uint32_t n) {
    if (!n) return (cacao_time_stats){0};
    qsort(v, n, sizeof *v, compare_doubles);
    const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return (cacao_time_stats){median, v[0], v[n - 1]};
}

void cacao_timings_summarise(const double *samples, uint32_t steps, uint32_t warmup, uint32_t repeat,
                             cacao_timings *out) {
    const uint32_t frames = warmup + repeat;
    out->warmup = warmup;
    out->repeat = repeat;
    out->step_count = steps < CACAO_PLAN_MAX_STEPS ? steps : CACAO_PLAN_MAX_STEPS;
    double *timed = malloc((repeat ? repeat : 1) * sizeof *timed);
    double *totals = calloc(repeat ? repeat : 1, sizeof *totals);
    if (!timed || !totals) {
        free(timed);
        free(totals);
        memset(out->step, 0, sizeof out->step);
        out->total = (cacao_time_stats){0};
        return;
    }
    for (uint32_t s = 0; s < out->step_count; ++s) {
        for (uint32_t f = 0; f < repeat; ++f) {
            timed[f] = samples[(size_t)s * frames + warmup + f];
            totals[f] += timed[f];
        }
        out->step[s] = cacao_time_stats_of(timed, repeat);
    }
    out->total = cacao_time_stats_of(totals, repeat);
    free(timed);
    free(totals);
}

static double share(uint32_t part, uint32_t whole) { return whole ? 100.0 * part / whole : 0.0; }

void cacao_timings_print(FILE *out, const cacao_plan *plan, const cacao_timings *t) {
    fprintf(out, "%-34s %10s %10s %10s   (%u frames timed after %u warm-up)\n", "pass", "median_ms", "min_ms", "max_ms",
            t->repeat, t->warmup);
    for (uint32_t s = 0; s < t->step_count && s < plan->step_count; ++s)
        fprintf(out, "%-34s %10.3f %10.3f %10.3f\n", plan->steps[s].key_name, t->step[s].median_ms, t->step[s].min_ms,
                t->step[s].max_ms);
    fprintf(out, "%-34s %10.3f %10.3f %10.3f\n", "total", t->total.median_ms, t->total.min_ms, t->total.max_ms);
    if (t->has_tiles) cacao_tile_counts_print(out, &t->tiles);
    if (t->has_tiles && plan->settings.reuse_unchanged) /* docs/tiles.md "Reusing the previous frame" */
        fprintf(out, "reuse (the last frame): %u of %u tiles changed, %u recomputed (%.1f%%), %u reused\n",
                t->tiles.changed, t->tiles.tiles, t->tiles.recomputed, share(t->tiles.recomputed, t->tiles.tiles),
                t->tiles.tiles - t->tiles.recomputed);
}


void cacao_tile_counts_print(FILE *out, const cacao_tile_counts *c) {
    fprintf(out, "tiles: %u: %u active, %u faded, %u background; skipped: generate %u of %u tiles (%.1f%%), ", c->tiles,
            c->active, c->faded, c->background, c->generate_total - c->generate_run, c->generate_total,
            share(c->generate_total - c->generate_run, c->generate_total));
    if (c->blur_total)
        fprintf(out, "blur %u of %u groups (%.1f%%)", c->blur_total - c->blur_run, c->blur_total,
                share(c->blur_total - c->blur_run, c->blur_total));
    else
        fprintf(out, "no blur");
    if (c->blocks_total)
        fprintf(out, ", %u of %u %s (%.1f%%)", c->blocks_total - c->blocks_run, c->blocks_total,
                c->blocks_total == c->tiles ? "tiles of the Q3 base pass" : "blocks of 2x2 tiles",
                share(c->blocks_total - c->blocks_run, c->blocks_total));
    if (c->fill_run)
        fprintf(out, ", AO 1 filled into %u of the %u skipped tiles (those a pass reads)", c->fill_run,
                c->generate_total - c->generate_run);
    if (c->quiet) fprintf(out, "; a quiet frame (no pixel can be occluded): no tile classified, only the quiet test ran (it wrote the output)");
    fprintf(out, "\n");
}

void cacao_tile_counts_add_json(cJSON *object, const cacao_tile_counts *c) {
    cJSON *o = cJSON_AddObjectToObject(object, "tiles");
    if (!o) return;
    cJSON_AddNumberToObject(o, "tiles", c->tiles);
    cJSON_AddNumberToObject(o, "active", c->active);
    cJSON_AddNumberToObject(o, "faded", c->faded);
    cJSON_AddNumberToObject(o, "background", c->background);
    cJSON_AddNumberToObject(o, "generate_run", c->generate_run);
    cJSON_AddNumberToObject(o, "generate_total", c->generate_total);
    cJSON_AddNumberToObject(o, "blur_run", c->blur_run);
    cJSON_AddNumberToObject(o, "changed", c->changed);       /* reuse_unchanged; 0 without */
    cJSON_AddNumberToObject(o, "recomputed", c->recomputed);
    cJSON_AddNumberToObject(o, "blur_total", c->blur_total);
    cJSON_AddNumberToObject(o, "fill_run", c->fill_run); /* CACAO's CPU forms; 0 where no fill runs */
    cJSON_AddNumberToObject(o, "blocks_run", c->blocks_run); /* 0 of 0 where no step runs over blocks */
    cJSON_AddNumberToObject(o, "blocks_total", c->blocks_total);
    cJSON_AddBoolToObject(o, "quiet", c->quiet); /* docs/tiles.md "A quiet frame" */
}

void cacao_timings_add_json(cJSON *object, const cacao_plan *plan, const cacao_timings *t) {
    cJSON_AddNumberToObject(object, "warmup", t->warmup);
    cJSON_AddNumberToObject(object, "repeat", t->repeat);
    cJSON *frames = cJSON_AddArrayToObject(object, "timed_frames");
    for (uint32_t f = 0; frames && f < t->repeat; ++f) cJSON_AddItemToArray(frames, cJSON_CreateNumber(t->warmup + f));
    cJSON *passes = cJSON_AddArrayToObject(object, "passes");
    for (uint32_t s = 0; passes && s < t->step_count && s < plan->step_count; ++s) {
        cJSON *pass = cJSON_CreateObject();
        cJSON_AddStringToObject(pass, "name", plan->steps[s].key_name);
        cJSON_AddNumberToObject(pass, "time_ms", t->step[s].median_ms);
        cJSON_AddNumberToObject(pass, "min_ms", t->step[s].min_ms);
        cJSON_AddNumberToObject(pass, "max_ms", t->step[s].max_ms);
        cJSON_AddItemToArray(passes, pass);
    }
    cJSON_AddNumberToObject(object, "total_ms", t->total.median_ms);
    cJSON_AddNumberToObject(object, "total_min_ms", t->total.min_ms);
    cJSON_AddNumberToObject(object, "total_max_ms", t->total.max_ms);
    if (t->has_tiles) cacao_tile_counts_add_json(object, &t->tiles);
}
