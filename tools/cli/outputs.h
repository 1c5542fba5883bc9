/* outputs.h - what the `cacao` command writes: the AO image, the --compare errors and the --json
 * report (the --timings table and the timing figures are tools/common/timing.h, shared with cacao-bench). */
#ifndef CACAO_CLI_OUTPUTS_H
#define CACAO_CLI_OUTPUTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "image_io.h"
#include "vkdev.h"

typedef enum cli_format { CLI_FORMAT_UNKNOWN, CLI_FORMAT_PNG, CLI_FORMAT_PFM, CLI_FORMAT_EXR } cli_format;

/* The output format by the path's extension (.png, .pfm, .exr, any case). */
cli_format cli_output_format(const char *path);

/* Writes the 1-channel AO image atomically (temp + rename) to path in the given format; png_bits 8 or 16. */
bool cli_write_ao(cli_format format, const char *path, const cacao_img *ao, unsigned png_bits, char *err,
                  size_t err_size);

/* Errors of the AO against a ground truth over the non-background pixels: depth < 1 for standard
 * depth, depth > 0 for reverse-Z (and finite), whose truth is finite. p99 is the nearest-rank 99th percentile of |AO -
 * GT|. */
typedef struct cli_ao_errors {
    size_t pixels;
    size_t skipped_truth; /* non-background pixels whose truth is NaN or infinite (not counted) */
    double rmse, mean_abs, p99;
} cli_ao_errors;

bool cli_compare_ao(const cacao_img *ao, const cacao_img *ground_truth, const cacao_img *depth, bool reverse_z,
                    cli_ao_errors *out);

void cli_print_errors(FILE *out, const char *ground_truth_path, const cli_ao_errors *errors);

/* What --json records. errors and plan/timings may be NULL. */
typedef struct cli_report {
    const cacao_settings *resolved;
    const char *device_name;
    uint32_t width, height;
    const cacao_plan *plan;
    const cacao_timings *timings; /* timing.h: warm-up, timed frames, per-pass statistics */
    const char *output_path;
    const char *ground_truth_path;
    const cli_ao_errors *errors;
} cli_report;

/* Writes the report as JSON atomically. */
bool cli_write_report(const char *path, const cli_report *report, char *err, size_t err_size);

#endif /* CACAO_CLI_OUTPUTS_H */
