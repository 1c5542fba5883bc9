/* plot.c - cacao-bench's plot (see bench.h): error against GPU time, one panel per scene, with the
 * Pareto front and the reference points, drawn by gnuplot with tools/bench/pareto.gp.
 *
 * No text from the inputs is ever gnuplot syntax: the data file holds numbers only (a point's name
 * is a number indexing the script's `labels` array), and the script spells every name as a string
 * literal whose bytes outside [A-Za-z0-9 _.,:;+=()/-] are octal escapes, so a quote, backslash,
 * backquote (gnuplot runs `...` as a shell command even inside double quotes), @ or line break in
 * a name stays a character of a title. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "text_buffer.h"
#include "text_file.h"

extern char **environ;
extern const char cacao_bench_pareto_gp[]; /* tools/bench/pareto.gp, embedded at build time */

#define fail_with(err, ...) cacao_set_err(err, BENCH_ERR, __VA_ARGS__)

int bench_plot_truth(const bench_scene *scene) {
    for (int t = 0; t < BENCH_TRUTHS; ++t)
        if (scene->has_truth[t]) return t;
    return -1;
}

/* ---- Data: numbers only ------------------------------------------------------------------------- */

/* Entries of the script's `labels` array: 1 is empty (the NaN line of a scene without reference
 * points), then one per configuration, then one per reference point. */
static uint32_t config_label(uint32_t config) { return config + 2; }
static uint32_t point_label(const bench_run *run, uint32_t point) { return run->config_count + 2 + point; }

typedef struct plot_point {
    double ms, error;
    uint32_t label;
} plot_point;

static int by_time(const void *a, const void *b) {
    const plot_point *x = a, *y = b;
    if (x->ms != y->ms) return x->ms < y->ms ? -1 : 1;
    return (x->error > y->error) - (x->error < y->error);
}

static void append_point(text_buffer *b, const plot_point *p) {
    append(b, "%.6f %.6f %u\n", p->ms, p->error, p->label);
}

/* One scene's three blocks of the data file: configurations, Pareto front, reference points. */
static void append_scene_blocks(text_buffer *b, const bench_run *run, uint32_t scene, int truth, plot_point *points) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < run->result_count; ++i) {
        const bench_result *r = &run->results[i];
        if (r->scene != scene || !r->has_error[truth]) continue;
        points[n] = (plot_point){r->timings.total.median_ms, r->error[truth].rmse, config_label(r->config)};
        append_point(b, &points[n++]);
    }
    append(b, "\n\n");
    qsort(points, n, sizeof *points, by_time);
    double best = INFINITY;
    for (uint32_t i = 0; i < n; ++i) /* non-dominated: lower error than every faster configuration */
        if (points[i].error < best) {
            best = points[i].error;
            append_point(b, &points[i]);
        }
    append(b, "\n\n");
    bool any = false;
    for (uint32_t i = 0; i < run->point_count; ++i) {
        const bench_point *p = &run->points[i];
        if (strcmp(p->scene, run->scenes[scene].name) != 0 || p->rmse[truth] < 0) continue;
        append_point(b, &(plot_point){p->total_ms, p->rmse[truth], point_label(run, i)});
        any = true;
    }
    if (!any) append(b, "NaN NaN 1\n");
    append(b, "\n\n");
}

static void append_plot_data(text_buffer *b, const bench_run *run) {
    plot_point *points = calloc(run->result_count ? run->result_count : 1, sizeof *points);
    if (!points) {
        b->failed = true;
        return;
    }
    for (uint32_t s = 0; s < run->scene_count; ++s) {
        const int truth = bench_plot_truth(&run->scenes[s]);
        if (truth >= 0) append_scene_blocks(b, run, s, truth, points);
    }
    free(points);
}

/* ---- Script: names as escaped literals ------------------------------------------------------- */

static bool plain_byte(unsigned char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           (c && strchr(" _.,:;+=()/-", c));
}

/* A gnuplot string literal of text: double quotes, every byte that is not plain as \ooo. */
static void append_gp_string(text_buffer *b, const char *text) {
    append(b, "\"");
    for (const unsigned char *c = (const unsigned char *)text; *c; ++c) {
        if (plain_byte(*c))
            append(b, "%c", *c);
        else
            append(b, "\\%03o", *c);
    }
    append(b, "\"");
}

static void append_gp_assignment(text_buffer *b, const char *name, const char *text) {
    append(b, "%s = ", name);
    append_gp_string(b, text);
    append(b, "\n");
}

bool bench_plot_script(const bench_run *run, const char *data_path, const char *image_path, bool svg,
                       text_buffer *script) {
    uint32_t shown = 0;
    int shown_truth = -1;
    for (uint32_t s = 0; s < run->scene_count; ++s) {
        const int truth = bench_plot_truth(&run->scenes[s]);
        if (truth < 0) continue;
        ++shown;
        if (shown_truth < 0 || truth < shown_truth) shown_truth = truth;
    }
    if (!shown) return false;
    append_gp_assignment(script, "datafile", data_path);
    append_gp_assignment(script, "outfile", image_path);
    append(script, "format = \"%s\"\nylabel = \"RMSE against %s (non-background pixels)\"\n", svg ? "svg" : "png",
           bench_truth_names[shown_truth]);
    append_gp_assignment(script, "refname", run->point_count ? run->reference_name : "");
    append(script, "n = %u\narray scene_names[%u]\n", shown, shown);
    for (uint32_t s = 0, k = 0; s < run->scene_count; ++s) {
        if (bench_plot_truth(&run->scenes[s]) < 0) continue;
        char name[32];
        snprintf(name, sizeof name, "scene_names[%u]", ++k);
        append_gp_assignment(script, name, run->scenes[s].name);
    }
    append(script, "array labels[%u]\nlabels[1] = \"\"\n", point_label(run, run->point_count) - 1);
    for (uint32_t c = 0; c < run->config_count; ++c) {
        char name[32];
        snprintf(name, sizeof name, "labels[%u]", config_label(c));
        append_gp_assignment(script, name, run->configs[c].name);
    }
    for (uint32_t i = 0; i < run->point_count; ++i) {
        char name[32];
        snprintf(name, sizeof name, "labels[%u]", point_label(run, i));
        append_gp_assignment(script, name, run->points[i].label);
    }
    append(script, "%s", cacao_bench_pareto_gp);
    return !script->failed;
}

/* ---- Running gnuplot ------------------------------------------------------------------------- */

/* gnuplot's error in one line, from what it wrote on stderr: the text after the first
 * '<script>" line N: ' (with a "system error: ..." line after it), else its last line. */
static void gnuplot_message(const char *text, char *out, size_t size) {
    const char *at = strstr(text, "\" line "), *message = NULL;
    if (at) {
        const char *colon = strstr(at, ": "), *end_of_line = strchr(at, '\n');
        if (colon && (!end_of_line || colon < end_of_line)) message = colon + 2;
    }
    char line[512] = "";
    if (message) {
        const size_t length = strcspn(message, "\n");
        snprintf(line, sizeof line, "%.*s", (int)length, message);
        const char *system_error = strstr(message, "\nsystem error: ");
        if (system_error)
            snprintf(line + strlen(line), sizeof line - strlen(line), " (%.*s)", (int)strcspn(system_error + 1, "\n"),
                     system_error + 1);
    } else {
        const char *last = text, *p = text;
        for (; *p; ++p)
            if (*p == '\n' && p[1] && p[1] != '\n') last = p + 1;
        snprintf(line, sizeof line, "%.*s", (int)strcspn(last, "\n"), last);
    }
    cacao_escape_text(line[0] ? line : "no message", out, size);
}

/* Runs gnuplot with args (args[0] = "gnuplot") in this environment less LD_PRELOAD (a sanitizer
 * build preloads its runtime into cacao-bench; gnuplot is not ours to check), stdin and stdout
 * /dev/null and stderr read here: its warnings are dropped, its error becomes one line. `what`
 * starts the message ("--plot r.png"). */
static bool run_gnuplot(char *const *args, const char *what, char *err) {
    size_t count = 0;
    while (environ[count]) ++count;
    char **env = calloc(count + 1, sizeof *env);
    int pipe_fds[2] = {-1, -1};
    posix_spawn_file_actions_t actions;
    if (!env || pipe2(pipe_fds, O_CLOEXEC) != 0 || posix_spawn_file_actions_init(&actions) != 0) {
        free(env);
        if (pipe_fds[0] >= 0) close(pipe_fds[0]), close(pipe_fds[1]);
        return fail_with(err, "%s: cannot run gnuplot: %s", what, strerror(errno));
    }
    for (size_t i = 0, j = 0; i < count; ++i)
        if (strncmp(environ[i], "LD_PRELOAD=", 11) != 0) env[j++] = environ[i];
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
    pid_t pid;
    const int spawned = posix_spawnp(&pid, "gnuplot", &actions, NULL, args, env);
    posix_spawn_file_actions_destroy(&actions);
    free(env);
    close(pipe_fds[1]);
    text_buffer said = {0};
    char chunk[4096];
    ssize_t got;
    while (spawned == 0 && ((got = read(pipe_fds[0], chunk, sizeof chunk)) > 0 || (got < 0 && errno == EINTR)))
        if (got > 0 && said.length < 65536) append(&said, "%.*s", (int)got, chunk);
    close(pipe_fds[0]);
    int status = 0;
    bool ok = spawned == 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (spawned != 0)
        fail_with(err, "%s: cannot run gnuplot (%s); install the gnuplot-nox package", what, strerror(spawned));
    else if (!ok) {
        char message[600];
        gnuplot_message(said.data ? said.data : "", message, sizeof message);
        fail_with(err, "%s: gnuplot failed: %s", what, message);
    }
    free(said.data);
    return ok;
}

bool bench_plot_check(const char *shown, bool svg, char *err) {
    char what[600];
    snprintf(what, sizeof what, "--plot %s", shown);
    char *args[] = {"gnuplot", "-e", svg ? "set terminal svg" : "set terminal pngcairo", NULL};
    return run_gnuplot(args, what, err);
}

/* Writes text to a new temporary file (TMPDIR or /tmp) with the suffix; its path in *path_out
 * (caller removes and frees). */
static bool write_temp(const char *text, const char *suffix, char **path_out, char *err) {
    const char *dir = getenv("TMPDIR");
    const size_t size = (dir && dir[0] ? strlen(dir) : 4) + 64;
    char *path = malloc(size);
    if (!path) return fail_with(err, "--plot: out of memory");
    snprintf(path, size, "%s/cacao-bench-XXXXXX%s", dir && dir[0] ? dir : "/tmp", suffix);
    const int fd = mkstemps(path, (int)strlen(suffix));
    if (fd < 0) {
        fail_with(err, "--plot: cannot create a temporary file: %s", strerror(errno));
        free(path);
        return false;
    }
    const size_t n = strlen(text);
    const bool ok = write(fd, text, n) == (ssize_t)n;
    close(fd);
    if (!ok) {
        remove(path);
        free(path);
        return fail_with(err, "--plot: cannot write a temporary file");
    }
    *path_out = path;
    return true;
}

bool bench_write_plot(const char *image_path, const char *shown, bool svg, const bench_run *run, char *err) {
    char what[600];
    snprintf(what, sizeof what, "--plot %s", shown);
    text_buffer data = {0}, script = {0};
    char *data_path = NULL, *script_path = NULL;
    append_plot_data(&data, run);
    bool ok = !data.failed ? true : fail_with(err, "%s: out of memory", what);
    if (ok) ok = write_temp(data.data ? data.data : "", ".dat", &data_path, err);
    if (ok && !bench_plot_script(run, data_path, image_path, svg, &script))
        ok = fail_with(err, "%s: %s", what, script.failed ? "out of memory" : "no scene has a truth to plot");
    if (ok) ok = write_temp(script.data, ".gp", &script_path, err);
    if (ok) ok = run_gnuplot((char *[]){"gnuplot", script_path, NULL}, what, err);
    if (data_path) remove(data_path);
    if (script_path) remove(script_path);
    free(data_path);
    free(script_path);
    free(data.data);
    free(script.data);
    return ok;
}
