/* inputs.h - what the `cacao` command renders: depth, optional normals and a projection, from a
 * scene folder, separate files or the embedded default scene (options.h says which). */
#ifndef CACAO_CLI_INPUTS_H
#define CACAO_CLI_INPUTS_H

#include <stdbool.h>
#include <stddef.h>

#include "image_io.h"
#include "options.h"
#include "vkdev.h"

typedef struct cli_inputs {
    cacao_img depth;          /* 1 channel, raw [0,1] depth in the run's convention */
    cacao_img normals;        /* 3 channels, right-handed view space; data NULL when none */
    float projection[16];     /* row-major, acting on column vectors */
    bool depth_reversed;      /* --reverse-z: depth 1 is near (tells an orthographic matrix's convention) */
    char projection_source[320]; /* the flags or camera file field the projection came from */
    double ao_radius_world;   /* the scene's radius; 0 = none given */
} cli_inputs;

/* The files a scene folder's inputs are read from (depth.pfm or depth_reversed.pfm, normals.pfm,
 * camera.json): what an output must not name. */
#define CLI_SCENE_FILE_COUNT 4
extern const char *const cli_scene_file_names[CLI_SCENE_FILE_COUNT];

/* Loads and checks everything the options name. On error writes one line naming the file or
 * flag into err and returns false (with nothing held). */
bool cli_inputs_load(const cli_options *options, cli_inputs *inputs, char *err, size_t err_size);

void cli_inputs_free(cli_inputs *inputs);

/* The settings the runtime gets for these inputs (their encoding, not resolved): the flags', with
 * the camera's ao_radius_world as the radius unless --radius was given, and normals reconstructed
 * from depth when the inputs have none. Shared by cacao, cacao-bench and cacao-inspect. */
cacao_settings cli_inputs_settings(const cli_options *options, const cli_inputs *inputs);

/* A device frame of these inputs (pointing into them) for a run with these encoded settings:
 * normals passed only where the settings do not reconstruct them. */
vkdev_frame cli_inputs_frame(const cli_inputs *inputs, const cacao_settings *encoded, uint32_t frame_index);

/* The reuse flags' frames (--keep-output, --move-camera, --move-box X,Y,W,H: every other frame the
 * box's depth shifted 8 pixels right, an object moving) into *frame; *moved holds the alternate
 * depth (NULL without --move-box; the caller frees it). A box that is not X,Y,W,H inside the
 * depth is an error naming the flag. */
bool cli_inputs_reuse_frame(const cli_options *options, const cli_inputs *inputs, vkdev_frame *frame, float **moved,
                            char *err, size_t err_size);

/* Reads a 1-channel image by extension: .pfm, .exr (channel Z, R, Y or the only one) or .png.
 * PNG must be 16-bit grey unless allow_8bit (values are sample / 65535 or / 255). `role` names
 * the image in messages ("depth", "ground truth"). */
bool cli_read_scalar_image(const char *path, const char *role, bool allow_8bit, cacao_img *out, char *err,
                           size_t err_size);

/* Lower-case extension of path including the dot (".pfm"), or "" when it has none. */
void cli_extension(const char *path, char *out, size_t out_size);

#endif /* CACAO_CLI_INPUTS_H */
