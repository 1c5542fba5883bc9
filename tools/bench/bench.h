/* bench.h - cacao-bench's model: configurations, scenes, results; the readers of the JSON it is
 * given (inputs_json.c), the writers of its table, JSON and CSV (report.c) and its plot (plot.c).
 * The flags, the runs and the staging of the files are in main.c. */
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
#define BENCH_MAX_POINTS 10000                                /* --reference points */
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
    char scene[256], label[256];
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

/* Readers of the JSON given to --reference and --plot-from (inputs_json.c). Each refuses, with one
 * line in err (BENCH_ERR bytes) naming the file and the field, what it cannot show faithfully:
 * names that are not printable or too long to keep, figures that are not finite or negative, a name
 * or a (scene, config) pair given twice. --reference: the reference's name and its points (caller
 * frees *points). --plot-from: the scenes, configurations and results of an earlier run, into run
 * (caller frees *results). */
bool bench_load_reference(const char *path, char *name, size_t name_size, bench_point **points, uint32_t *count,
                          char *err);
bool bench_load_plot_from(const char *path, bench_scene *scenes, bench_config *configs, bench_result **results,
                          bench_run *run, char *err);

/* The table on stdout, and the JSON and CSV as text (NULL: out of memory; caller frees). */
void bench_print_table(FILE *out, const bench_run *run);
char *bench_json_text(const bench_run *run);
char *bench_csv_text(const bench_run *run);

/* The plot (plot.c): its data file holds only numbers, and its gnuplot script holds every name
 * (scene, configuration, reference) as a string literal with each byte outside a small safe set
 * written as an octal escape, so no input text can become a gnuplot command. bench_plot_script is
 * the script alone (text_buffer.h; pure, for the fuzz harness); bench_plot_check runs gnuplot with
 * the terminal the plot needs, before any work; bench_write_plot runs it on the results, writing
 * the image to image_path (a staged file: `shown` is the path the messages name). A failure of
 * gnuplot is one line in err, its last error message. */
struct text_buffer;
bool bench_plot_script(const bench_run *run, const char *data_path, const char *image_path, bool svg,
                       struct text_buffer *script);
bool bench_plot_check(const char *shown, bool svg, char *err);
bool bench_write_plot(const char *image_path, const char *shown, bool svg, const bench_run *run, char *err);

/* The error a plot shows for a scene: its ao_gt_falloff RMSE, else its ao_gt RMSE (-1: neither). */
int bench_plot_truth(const bench_scene *scene);

#endif /* CACAO_BENCH_H */
