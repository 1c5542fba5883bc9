/* bench.h - cacao-bench's model: configurations, scenes, results, and the writers of its table,
 * JSON, CSV and plot (report.c). The runs themselves are in main.c. */
#ifndef CACAO_BENCH_H
#define CACAO_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "inputs.h"
#include "outputs.h"
#include "sweep.h"
#include "timing.h"
#include "vkdev.h"

#define BENCH_MAX_SCENES 16
#define BENCH_ERR 1024

/* The truths a scene folder may hold, in the order results keep their errors. */
enum { BENCH_GT_FALLOFF, BENCH_GT, BENCH_TRUTHS };
extern const char *const bench_truth_names[BENCH_TRUTHS]; /* "ao_gt_falloff", "ao_gt" */

/* One configuration (sweep.h). */
typedef sweep_config bench_config;

typedef struct bench_scene {
    char name[256];
    const char *path; /* NULL: the embedded scene */
    cli_inputs inputs;
    cacao_img truth[BENCH_TRUTHS]; /* data NULL where the folder has none */
    bool has_truth[BENCH_TRUTHS];  /* the folder has it (set also by --plot-from, which loads no image) */
} bench_scene;

typedef struct bench_result {
    uint32_t scene, config;
    cacao_settings resolved;
    cacao_plan plan;
    cacao_timings timings;
    size_t nonfinite;
    bool has_error[BENCH_TRUTHS];
    cli_ao_errors error[BENCH_TRUTHS];
} bench_result;

/* A named point from --reference: a configuration's time and errors on one scene. */
typedef struct bench_point {
    char scene[256], label[96];
    double total_ms;
    double rmse[BENCH_TRUTHS]; /* negative: absent */
} bench_point;

typedef struct bench_run {
    const bench_config *configs;
    uint32_t config_count;
    const bench_scene *scenes;
    uint32_t scene_count;
    const bench_result *results;
    uint32_t result_count;
    char device[256], driver[1024];
    double load_before[3], load_after[3];
    uint32_t warmup, repeat;
    const char *reference_name;
    const bench_point *points;
    uint32_t point_count;
    /* --pipeline-cache: per configuration, pipeline creation without a cache, on an empty one and
     * on one started from a previous context's data, at the first scene's size; NULL: not asked */
    const vkdev_cache_timing *cache;
    uint32_t cache_width, cache_height;
} bench_run;

/* Writers: every one writes atomically (temporary + rename) and names the file in err. */
void bench_print_table(FILE *out, const bench_run *run);
bool bench_write_json(const char *path, const bench_run *run, char *err);
bool bench_write_csv(const char *path, const bench_run *run, char *err);
bool bench_write_plot(const char *path, const bench_run *run, char *err);

/* The error a plot shows for a scene: its ao_gt_falloff RMSE, else its ao_gt RMSE (-1: neither). */
int bench_plot_truth(const bench_scene *scene);

#endif /* CACAO_BENCH_H */
