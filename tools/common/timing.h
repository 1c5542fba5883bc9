/* timing.h - GPU time per pass from timestamp queries, shared by `cacao --timings` and cacao-bench.
 *
 * A timed run renders warmup + repeat frames, each in its own submission; frames 0..warmup-1 are
 * discarded (on lavapipe the first frames compile shader variants) and frames warmup..warmup+repeat-1
 * are timed. Per pass and in total the median, min and max over the timed frames are kept. */
#ifndef CACAO_TIMING_H
#define CACAO_TIMING_H

#include <stdint.h>
#include <stdio.h>

#include "cacao.h"

#define CACAO_TIMING_MAX_FRAMES 100000u

typedef struct cacao_time_stats {
    double median_ms, min_ms, max_ms;
} cacao_time_stats;

typedef struct cacao_timings {
    uint32_t warmup; /* frames discarded before timing */
    uint32_t repeat; /* frames timed (their indices: warmup .. warmup+repeat-1) */
    uint32_t step_count;
    cacao_time_stats step[CACAO_PLAN_MAX_STEPS];
    cacao_time_stats total;  /* per frame, the sum of its steps */
    uint64_t memory_bytes;   /* intermediates the context allocated */
    uint32_t memory_allocations; /* the VkDeviceMemory objects holding them */
    uint32_t pipeline_count; /* pipelines the context created */
    double setup_ms;         /* wall time of cacao_context_resize (pipelines + intermediates) */
    bool has_tiles;          /* the CACAO estimator: the last frame's tile counts */
    cacao_tile_counts tiles;
} cacao_timings;

/* Median, min and max of n values (sorts v in place; all zero when n is 0). */
cacao_time_stats cacao_time_stats_of(double *v, uint32_t n);

/* Summarises samples[step * frames + frame] (frames = warmup + repeat; the total comes from the
 * sum over steps of each frame) into out's statistics, discarding the warm-up frames. */
void cacao_timings_summarise(const double *samples, uint32_t steps, uint32_t warmup, uint32_t repeat,
                             cacao_timings *out);

/* One row per plan step (its permutation key, median, min, max ms), then the total. */
void cacao_timings_print(FILE *out, const cacao_plan *plan, const cacao_timings *timings);

/* Adds "warmup", "repeat", "timed_frames" (the frame indices timed), "passes" (name, time_ms =
 * median, min_ms, max_ms), "total_ms", "total_min_ms", "total_max_ms" to a cJSON object. */
struct cJSON;
void cacao_timings_add_json(struct cJSON *object, const cacao_plan *plan, const cacao_timings *timings);

/* "tiles: N: a active, f faded, b background; skipped: generate ..., blur ..., apply ..." */
void cacao_tile_counts_print(FILE *out, const cacao_tile_counts *counts);
/* Adds "tiles": {tiles, active, faded, background, generate_run, generate_total, blur_run,
 * blur_total} to a cJSON object. */
void cacao_tile_counts_add_json(struct cJSON *object, const cacao_tile_counts *counts);

#endif /* CACAO_TIMING_H */
