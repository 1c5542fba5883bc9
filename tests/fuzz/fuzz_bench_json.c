/* fuzz_bench_json - libFuzzer harness for the JSON cacao-bench is given (issue 35): the same bytes
 * are read as a --reference file and as a --plot-from file. Each reader must accept or refuse with
 * one line (no control bytes: names from the file are escaped or refused). What it accepts must
 * be what the plot can show: names printable, figures finite and not negative. And the gnuplot
 * script of an accepted --plot-from run (with the reference's points where that read too) must
 * keep every name as data: each line before the template is one assignment or array declaration
 * whose string literal holds only plain bytes and octal escapes, the lines are as many as the
 * names, and each literal decodes to its name. (Before the fix, a name with a line break added
 * lines of gnuplot commands; one with a backquote ran a shell command.) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "fuzz_input.h"
#include "image_io.h"
#include "text_buffer.h"

const char cacao_bench_pareto_gp[] = "# the template: its own lines, after the names\nplot 1\n";

static void check_message(const char *err) {
    if (!err[0] || strchr(err, '\n') || !cacao_text_is_printable(err)) abort();
}

/* Reads the gnuplot literal at *p ("..." with \ooo escapes, nothing else) into out; advances. */
static void decode_literal(const char **p, char *out, size_t size) {
    const char *c = *p;
    if (*c++ != '"') abort();
    size_t n = 0;
    for (; *c != '"'; ++c) {
        unsigned char byte = (unsigned char)*c;
        if (byte == '\\') {
            if (c[1] < '0' || c[1] > '3' || c[2] < '0' || c[2] > '7' || c[3] < '0' || c[3] > '7') abort();
            byte = (unsigned char)((c[1] - '0') * 64 + (c[2] - '0') * 8 + (c[3] - '0'));
            c += 3;
        } else if (!((byte >= 'a' && byte <= 'z') || (byte >= 'A' && byte <= 'Z') || (byte >= '0' && byte <= '9') ||
                     (byte && strchr(" _.,:;+=()/-", byte)))) {
            abort(); /* a raw quote, backquote, backslash, @, $ or control byte */
        }
        if (n + 1 >= size) abort();
        out[n++] = (char)byte;
    }
    out[n] = '\0';
    *p = c + 1;
}

/* Checks the line at *p: "NAME = <literal>\n" decoding to expected, or (expected NULL) any line
 * without a literal ("n = 2", "array labels[3]"); advances past it. */
static void check_line(const char **p, const char *expected) {
    const char *line = *p, *end = strchr(line, '\n');
    if (!end) abort();
    const char *quote = memchr(line, '"', (size_t)(end - line));
    if (expected) {
        static char decoded[4096];
        if (!quote || quote - line < 4 || memcmp(quote - 3, " = ", 3) != 0) abort();
        const char *c = quote;
        decode_literal(&c, decoded, sizeof decoded);
        if (c != end || strcmp(decoded, expected) != 0) abort();
    } else if (quote && strncmp(line, "format", 6) != 0 && strncmp(line, "ylabel", 6) != 0) {
        abort();
    }
    *p = end + 1;
}

static void check_script(const bench_run *run) {
    text_buffer script = {0};
    const char *data = "/tmp/d \"`x`\".dat", *image = "out.png\n.tmp";
    if (!bench_plot_script(run, data, image, false, &script)) {
        free(script.data);
        return; /* no scene with a truth: nothing to plot (main.c refuses that before) */
    }
    const char *p = script.data;
    check_line(&p, data);
    check_line(&p, image);
    check_line(&p, NULL); /* format */
    check_line(&p, NULL); /* ylabel */
    check_line(&p, run->point_count ? run->reference_name : "");
    check_line(&p, NULL); /* n */
    check_line(&p, NULL); /* array scene_names */
    for (uint32_t s = 0; s < run->scene_count; ++s)
        if (bench_plot_truth(&run->scenes[s]) >= 0) check_line(&p, run->scenes[s].name);
    check_line(&p, NULL); /* array labels */
    check_line(&p, "");
    for (uint32_t c = 0; c < run->config_count; ++c) check_line(&p, run->configs[c].name);
    for (uint32_t i = 0; i < run->point_count; ++i) check_line(&p, run->points[i].label);
    if (strcmp(p, cacao_bench_pareto_gp) != 0) abort();
    free(script.data);
}

static void check_figure(double v) {
    if (!isfinite(v) || v < 0) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const char *path = fuzz_input_file(data, size, ".json");
    char err[BENCH_ERR] = "", name[256] = "";
    bench_point *points = NULL;
    uint32_t point_count = 0;
    const bool have_points = bench_load_reference(path, name, sizeof name, &points, &point_count, err);
    if (!have_points) check_message(err);
    for (uint32_t i = 0; have_points && i < point_count; ++i) {
        if (!cacao_text_is_printable(points[i].scene) || !cacao_text_is_printable(points[i].label)) abort();
        check_figure(points[i].total_ms);
    }

    static bench_scene scenes[BENCH_MAX_SCENES];
    static bench_config configs[SWEEP_FULL_SIZE];
    bench_result *results = NULL;
    bench_run run = {
        .reference_name = name, .points = have_points ? points : NULL, .point_count = have_points ? point_count : 0};
    err[0] = '\0';
    if (bench_load_plot_from(path, scenes, configs, &results, &run, err)) {
        for (uint32_t s = 0; s < run.scene_count; ++s)
            if (!cacao_text_is_printable(scenes[s].name)) abort();
        for (uint32_t r = 0; r < run.result_count; ++r) {
            if (results[r].scene >= run.scene_count || results[r].config >= run.config_count) abort();
            check_figure(results[r].timings.total.median_ms);
        }
        check_script(&run);
    } else {
        check_message(err);
    }
    free(results);
    free(points);
    return 0;
}
