/* options.h - the `cacao` command's flags and its settings JSON.
 *
 * One table (options.c) defines every flag: its name, value, help text and, for the runtime's
 * settings, the cacao_settings field and the JSON key. --help, parsing, --settings and
 * --print-settings all read that table, so each setting is defined once.
 *
 * Values on the command line and in the JSON are literal (--horizon 0 means 0, --blur 0 means no
 * blur); they are stored in cacao_settings' encoding (0 = default, CACAO_ZERO, CACAO_BLUR_NONE).
 * Precedence: the --settings file is applied first, then every settings flag, wherever it stands
 * on the command line.
 */
#ifndef CACAO_CLI_OPTIONS_H
#define CACAO_CLI_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "cacao.h"

#define CLI_FLAG_SLOTS 64 /* at least the entries of the flag table (options.c checks) */

typedef struct cli_options {
    /* Input: a scene folder, or separate files; neither = the embedded default scene. */
    const char *scene_dir;
    const char *depth_path;
    const char *normals_path;
    const char *camera_path;
    double fov_y_deg, near_z, far_z; /* 0 = not given */
    bool reverse_z;
    /* Output. */
    const char *output_path;         /* default cacao-out.png */
    uint32_t png_bits;               /* 8 or 16 (0 = 8) */
    bool png16;
    const char *json_path;
    const char *compare_path;
    bool print_settings;
    bool timings;
    uint32_t repeat;                 /* timed frames; 0 = 1 */
    uint32_t warmup;                 /* untimed frames before them; default 2 */
    uint32_t frame_index;            /* cacao_inputs.frame_index (gtao/bitmask sample pattern) */
    const char *move_box;            /* --move-box X,Y,W,H (with --reuse): parsed by main */
    bool keep_output;                /* --keep-output: cacao_inputs.output_holds_previous */
    bool move_camera;                /* --move-camera: every other frame another projection */
    /* Device. */
    const char *device;
    bool validate;
    /* Actions that replace the run. */
    bool help, version, list_devices;
    /* Runtime settings, in cacao_settings' encoding. radius_given: the radius came from a flag
     * or the settings file (otherwise the camera's ao_radius_world is the default). */
    const char *settings_path;
    cacao_settings settings;
    bool radius_given;
    bool given[CLI_FLAG_SLOTS]; /* by flag table entry: on the command line (ask with cli_given) */
} cli_options;

/* Parses argv (the --settings file first, then the flags). On error writes one line naming the
 * flag or file into err and returns false. */
bool cli_parse(int argc, char **argv, cli_options *options, char *err, size_t err_size);

/* Whether the command line gave the flag ("--output" or its alias "-o"); keys of the --settings
 * file do not count (a file from --print-settings holds every key). */
bool cli_given(const cli_options *options, const char *flag);

/* Refuses a flag given on the command line that the estimator does not use (--visibility, --frame,
 * --slices and --steps: gtao and bitmask; --thickness: bitmask), with one line naming the flag and,
 * by `what` ("this run", "configuration low_native"), where the estimator comes from. */
bool cli_check_estimator_flags(const cli_options *options, cacao_estimator estimator, const char *what, char *err,
                               size_t err_size);

/* Writes the --help text, generated from the flag table. */
void cli_print_help(FILE *out);

/* The resolved settings as a JSON object in the --settings schema (cJSON *, caller deletes). */
struct cJSON *cli_settings_to_json(const cacao_settings *resolved);

/* The flag that sets a cacao_settings field named in a runtime message ("settings.downsample ..."
 * -> "--downsample"), or NULL when the message names none. */
const char *cli_flag_of_message(const char *message);

#endif /* CACAO_CLI_OPTIONS_H */
