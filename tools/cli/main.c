/* main.c - the `cacao` command: screen-space AO of a depth buffer (and optional normals) on a
 * Vulkan device, written as an image. Flags: options.c (or `cacao --help`).
 *
 * Order of work, so that a failure at any step leaves no output file: parse the flags (and the
 * --settings file), load and check every input, resolve the settings, load the ground truth, run
 * on the device, check the validation layer's count, and only then write the image and the JSON
 * report (both staged beside their destinations and renamed into place only when both are complete). */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "inputs.h"
#include "options.h"
#include "output_files.h"
#include "outputs.h"
#include "text_file.h"
#include "vkdev.h"

#define ERR_SIZE 1024

static int fail(const char *message) {
    fprintf(stderr, "cacao: %s\n", message);
    return 1;
}

static unsigned png_bits(const cli_options *o) { return o->png16 ? 16u : o->png_bits ? o->png_bits : 8u; }

/* -o and --json must not name each other or any input (the output would overwrite it), the files
 * of a --scene folder included. */
static bool check_output_collisions(const cli_options *o, char *err) {
    char scene_files[CLI_SCENE_FILE_COUNT][4200];
    cacao_named_path inputs[6 + CLI_SCENE_FILE_COUNT] = {
        {"--depth", o->depth_path},     {"--normals", o->normals_path},   {"--camera", o->camera_path},
        {"--compare", o->compare_path}, {"--settings", o->settings_path}, {"--scene", o->scene_dir}};
    for (int i = 0; o->scene_dir && i < CLI_SCENE_FILE_COUNT; ++i) {
        snprintf(scene_files[i], sizeof scene_files[i], "%s/%s", o->scene_dir, cli_scene_file_names[i]);
        inputs[6 + i] = (cacao_named_path){"--scene", scene_files[i]};
    }
    const cacao_named_path outputs[] = {{"--output", o->output_path}, {"--json", o->json_path}};
    return cacao_check_outputs(outputs, 2, inputs, sizeof inputs / sizeof inputs[0], err, ERR_SIZE);
}

static bool check_output_flags(const cli_options *o, char *err) {
    if (!check_output_collisions(o, err)) return false;
    const cli_format format = cli_output_format(o->output_path);
    if (format == CLI_FORMAT_UNKNOWN) {
        cacao_set_err(err, ERR_SIZE, "--output %s: unknown format (use .png, .pfm or .exr)", o->output_path);
        return false;
    }
    if ((o->png16 || o->png_bits) && format != CLI_FORMAT_PNG) {
        cacao_set_err(err, ERR_SIZE, "--bits/--png16: only for .png output, not %s", o->output_path);
        return false;
    }
    if (o->png16 && o->png_bits == 8) {
        cacao_set_err(err, ERR_SIZE, "--png16 contradicts --bits 8");
        return false;
    }
    return true;
}

/* The settings the runtime gets (its encoding) and their resolved literal values. The camera's
 * ao_radius_world is the default radius; without normals they are reconstructed from depth. */
static bool effective_settings(const cli_options *o, const cli_inputs *in, cacao_settings *encoded,
                               cacao_settings *resolved, char *err) {
    *encoded = cli_inputs_settings(o, in);
    char why[512];
    if (cacao_settings_resolve(encoded, resolved, why, sizeof why) == CACAO_SUCCESS) return true;
    const char *flag = cli_flag_of_message(why); /* name what the user gave */
    if (flag) cacao_set_err(err, ERR_SIZE, "%s (or its key in --settings): %s", flag, why);
    else cacao_set_err(err, ERR_SIZE, "settings: %s", why);
    return false;
}

static int print_settings(const cacao_settings *resolved) {
    cJSON *json = cli_settings_to_json(resolved);
    char *text = json ? cJSON_Print(json) : NULL;
    cJSON_Delete(json);
    if (!text) return fail("--print-settings: out of memory");
    printf("%s\n", text);
    cJSON_free(text);
    return 0;
}

static bool load_ground_truth(const cli_options *o, const cli_inputs *in, cacao_img *gt, char *err) {
    if (!cli_read_scalar_image(o->compare_path, "ground truth", true, gt, err, ERR_SIZE)) return false;
    if (gt->width == in->depth.width && gt->height == in->depth.height) return true;
    cacao_set_err(err, ERR_SIZE, "%s: ground truth is %ux%u but the depth is %ux%u", o->compare_path, gt->width, gt->height,
            in->depth.width, in->depth.height);
    cacao_img_free(gt);
    return false;
}

/* ---- The device run ------------------------------------------------------------------------- */

typedef struct render_result {
    cacao_img ao;                 /* 1 channel */
    cacao_plan plan;              /* the steps that ran (their key names label the timings) */
    cacao_timings timings;
    char device_name[256];
} render_result;

static bool run_on_device(vkdev *dev, const cli_options *o, const cli_inputs *in, const cacao_settings *encoded,
                          render_result *out, char *err) {
    vkdev_frame frame = cli_inputs_frame(in, encoded, o->frame_index);
    frame.plan_out = &out->plan; /* the plan the context ran, fallbacks included */
    frame.advance_frame_index = encoded->temporal_frames != 0; /* a new sample pattern every frame */
    float *moved = NULL;
    if (!cli_inputs_reuse_frame(o, in, &frame, &moved, err, ERR_SIZE)) return false;
    char why[ERR_SIZE - 128];
    const cacao_result r = vkdev_run_timed(dev, encoded, &frame, o->warmup, o->repeat ? o->repeat : 1, out->ao.data,
                                           &out->timings, why, sizeof why);
    free(moved);
    if (r == CACAO_SUCCESS) return true;
    if (strncmp(why, "inputs.projection", 17) == 0) /* name what the user gave, then why */
        cacao_set_err(err, ERR_SIZE, "%s: the projection is refused (%s)", in->projection_source, why);
    else
        cacao_set_err(err, ERR_SIZE, "%s: %s", cacao_result_string(r), why);
    return false;
}

static bool render(const cli_options *o, const cli_inputs *in, const cacao_settings *encoded, render_result *out,
                   char *err) {
    const uint32_t w = in->depth.width, h = in->depth.height;
    out->ao = (cacao_img){w, h, 1, malloc(sizeof(float) * w * h)};
    if (!out->ao.data) {
        cacao_set_err(err, ERR_SIZE, "out of memory for the %ux%u output", w, h);
        return false;
    }
    vkdev dev;
    if (!vkdev_create(&(vkdev_options){.validation = o->validate, .device = o->device}, &dev, err, ERR_SIZE))
        return false;
    snprintf(out->device_name, sizeof out->device_name, "%s", dev.device_name);
    bool ok = run_on_device(&dev, o, in, encoded, out, err);
    vkdev_destroy(&dev); /* keeps validation_messages, which counts messages from teardown too */
    if (ok && dev.validation_messages) {
        cacao_set_err(err, ERR_SIZE, "--validate: the validation layer reported %u message(s) (above); no output written",
                dev.validation_messages);
        ok = false;
    }
    return ok;
}

/* ---- Reporting and writing ------------------------------------------------------------------ */

/* All or nothing: the image and the report are written beside their destinations (path + ".new")
 * and renamed into place only once both are complete, so a failure touches no existing file. */
static bool write_outputs(const cli_options *o, const cli_report *report, const cacao_img *ao, char *err) {
    char image_new[4200], json_new[4200];
    snprintf(image_new, sizeof image_new, "%s.new", o->output_path);
    snprintf(json_new, sizeof json_new, "%s.new", o->json_path ? o->json_path : "");
    bool ok = cli_write_ao(cli_output_format(o->output_path), image_new, ao, png_bits(o), err, ERR_SIZE);
    if (ok && o->json_path) ok = cli_write_report(json_new, report, err, ERR_SIZE);
    if (ok && o->json_path && rename(json_new, o->json_path) != 0) {
        cacao_set_err(err, ERR_SIZE, "%s: cannot rename %s into place: %s", o->json_path, json_new, strerror(errno));
        ok = false;
    }
    if (ok && rename(image_new, o->output_path) != 0) {
        cacao_set_err(err, ERR_SIZE, "%s: cannot rename %s into place: %s", o->output_path, image_new, strerror(errno));
        ok = false;
    }
    remove(image_new);
    if (o->json_path) remove(json_new);
    return ok;
}

static int render_and_write(const cli_options *o, const cli_inputs *in, const cacao_settings *encoded,
                            const cacao_settings *resolved, const cacao_img *gt) {
    char err[ERR_SIZE];
    render_result result = {0};
    if (!render(o, in, encoded, &result, err)) {
        cacao_img_free(&result.ao);
        return fail(err);
    }
    cli_ao_errors errors = {0};
    if (gt->data && !cli_compare_ao(&result.ao, gt, &in->depth, o->reverse_z, &errors)) {
        cacao_img_free(&result.ao);
        return fail("--compare: out of memory");
    }
    const cli_report report = {resolved, result.device_name, in->depth.width, in->depth.height, &result.plan,
                               &result.timings, o->output_path, o->compare_path, gt->data ? &errors : NULL};
    const bool written = write_outputs(o, &report, &result.ao, err);
    cacao_img_free(&result.ao);
    if (!written) return fail(err);
    if (o->timings) cacao_timings_print(stdout, &result.plan, &result.timings);
    if (gt->data) cli_print_errors(stdout, o->compare_path, &errors);
    printf("cacao: wrote %s (%ux%u AO on %s)\n", o->output_path, in->depth.width, in->depth.height, result.device_name);
    return 0;
}

static int run_with_inputs(const cli_options *o, const cli_inputs *in) {
    char err[ERR_SIZE];
    cacao_settings encoded, resolved;
    if (!effective_settings(o, in, &encoded, &resolved, err)) return fail(err);
    if (o->print_settings) return print_settings(&resolved);
    cacao_img gt = {0};
    if (o->compare_path && !load_ground_truth(o, in, &gt, err)) return fail(err);
    const int rc = render_and_write(o, in, &encoded, &resolved, &gt);
    cacao_img_free(&gt);
    return rc;
}

static int run(const cli_options *o) {
    char err[ERR_SIZE];
    if (!cli_check_estimator_flags(o, o->settings.estimator, "this run", err, sizeof err)) return fail(err);
    if (!check_output_flags(o, err)) return fail(err);
    if (o->keep_output && !o->settings.reuse_unchanged)
        return fail("--keep-output: only with --reuse (it tells the reusing context that the output holds its last frame)");
    cli_inputs in;
    if (!cli_inputs_load(o, &in, err, sizeof err)) return fail(err);
    const int rc = run_with_inputs(o, &in);
    cli_inputs_free(&in);
    return rc;
}

static int list_devices(void) {
    char err[ERR_SIZE];
    return vkdev_list(stdout, err, sizeof err) ? 0 : fail(err);
}

int main(int argc, char **argv) {
    char err[ERR_SIZE];
    cli_options o;
    if (!cli_parse(argc, argv, &o, err, sizeof err)) return fail(err);
    if (o.help) {
        cli_print_help(stdout);
        return 0;
    }
    if (o.version) {
        printf("cacao %d.%d.%d (%u embedded shader permutations)\n", CACAO_VERSION_MAJOR, CACAO_VERSION_MINOR,
               CACAO_VERSION_PATCH, cacao_embedded_permutation_count());
        return 0;
    }
    if (o.list_devices) return list_devices();
    return run(&o);
}
