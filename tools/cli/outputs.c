/* outputs.c - AO image, comparison, timings and JSON report of the `cacao` command (see outputs.h). */
#include "outputs.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "exr_io.h"
#include "inputs.h"
#include "options.h"
#include "text_file.h"

cli_format cli_output_format(const char *path) {
    char ext[16];
    cli_extension(path, ext, sizeof ext);
    if (strcmp(ext, ".png") == 0) return CLI_FORMAT_PNG;
    if (strcmp(ext, ".pfm") == 0) return CLI_FORMAT_PFM;
    if (strcmp(ext, ".exr") == 0) return CLI_FORMAT_EXR;
    return CLI_FORMAT_UNKNOWN;
}

bool cli_write_ao(cli_format format, const char *path, const cacao_img *ao, unsigned png_bits, char *err, size_t n) {
    switch (format) {
    case CLI_FORMAT_PNG:
        return cacao_png_write(path, ao, (int)png_bits, err, n);
    case CLI_FORMAT_PFM:
        return cacao_pfm_write(path, ao, err, n);
    case CLI_FORMAT_EXR:
        return cacao_exr_write(path, ao, err, n);
    default:
        cacao_set_err(err, n, "%s: unknown output format", path);
        return false;
    }
}

/* ---- Comparison --------------------------------------------------------------------------------- */

static bool is_background(float depth, bool reverse_z) {
    return !isfinite(depth) || (reverse_z ? depth <= 0.0f : depth >= 1.0f);
}

static int compare_doubles(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

bool cli_compare_ao(const cacao_img *ao, const cacao_img *gt, const cacao_img *depth, bool reverse_z,
                    cli_ao_errors *out) {
    const size_t count = (size_t)ao->width * ao->height;
    double *diffs = malloc((count ? count : 1) * sizeof *diffs);
    if (!diffs) return false;
    size_t used = 0, skipped = 0;
    double sum_sq = 0, sum_abs = 0;
    for (size_t i = 0; i < count; ++i) {
        if (is_background(depth->data[i], reverse_z)) continue;
        if (!isfinite(gt->data[i])) { /* a NaN or infinite truth pixel has no error to measure */
            ++skipped;
            continue;
        }
        const double d = fabs((double)ao->data[i] - (double)gt->data[i]);
        diffs[used++] = d;
        sum_sq += d * d;
        sum_abs += d;
    }
    qsort(diffs, used, sizeof *diffs, compare_doubles);
    *out = (cli_ao_errors){.pixels = used, .skipped_truth = skipped};
    if (used) {
        out->rmse = sqrt(sum_sq / (double)used);
        out->mean_abs = sum_abs / (double)used;
        out->p99 = diffs[(size_t)ceil(0.99 * (double)used) - 1];
    }
    free(diffs);
    return true;
}

void cli_print_errors(FILE *out, const char *gt_path, const cli_ao_errors *e) {
    fprintf(out, "compare %s over %zu non-background pixels: rmse %.6f mean_abs %.6f p99 %.6f", gt_path, e->pixels,
            e->rmse, e->mean_abs, e->p99);
    if (e->skipped_truth) fprintf(out, " (%zu non-finite truth pixels skipped)", e->skipped_truth);
    fputc('\n', out);
}

/* ---- JSON report ------------------------------------------------------------------------------ */

static cJSON *errors_json(const char *gt_path, const cli_ao_errors *e) {
    cJSON *compare = cJSON_CreateObject();
    cJSON_AddStringToObject(compare, "ground_truth", gt_path);
    cJSON_AddNumberToObject(compare, "pixels", (double)e->pixels);
    cJSON_AddNumberToObject(compare, "skipped_nonfinite_truth", (double)e->skipped_truth);
    cJSON_AddNumberToObject(compare, "rmse", e->rmse);
    cJSON_AddNumberToObject(compare, "mean_abs", e->mean_abs);
    cJSON_AddNumberToObject(compare, "p99", e->p99);
    return compare;
}

static cJSON *report_json(const cli_report *r) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "settings", cli_settings_to_json(r->resolved));
    cJSON_AddStringToObject(root, "device", r->device_name);
    cJSON_AddNumberToObject(root, "width", r->width);
    cJSON_AddNumberToObject(root, "height", r->height);
    if (r->plan && r->timings) cacao_timings_add_json(root, r->plan, r->timings);
    cJSON_AddStringToObject(root, "output", r->output_path);
    if (r->errors) cJSON_AddItemToObject(root, "compare", errors_json(r->ground_truth_path, r->errors));
    return root;
}

/* Writes text to path + ".tmp" and renames it into place. */
static bool write_text_atomically(const char *path, const char *text, char *err, size_t n) {
    char temp[4200];
    snprintf(temp, sizeof temp, "%s.tmp", path);
    FILE *f = fopen(temp, "wb");
    if (!f) {
        cacao_set_err(err, n, "%s: cannot create: %s", path, strerror(errno));
        return false;
    }
    const size_t length = strlen(text);
    bool ok = fwrite(text, 1, length, f) == length && fputc('\n', f) != EOF;
    ok = fclose(f) == 0 && ok;
    if (ok && rename(temp, path) != 0) ok = false;
    if (!ok) {
        cacao_set_err(err, n, "%s: write failed: %s", path, strerror(errno));
        remove(temp);
    }
    return ok;
}

bool cli_write_report(const char *path, const cli_report *report, char *err, size_t n) {
    cJSON *root = report_json(report);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) {
        cacao_set_err(err, n, "%s: out of memory", path);
        return false;
    }
    const bool ok = write_text_atomically(path, text, err, n);
    cJSON_free(text);
    return ok;
}
