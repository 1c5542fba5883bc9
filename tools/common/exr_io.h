/* exr_io.h - float images read from and written to OpenEXR files (tools only), through the
 * OpenEXR C API (OpenEXR 3.1+, <openexr.h>).
 *
 * Images are cacao_img (image_io.h): 32-bit floats, channels interleaved, row 0 = the top row.
 * The readers take the first part of the file, scanline or tiled (level 0 of a tiled file), with
 * HALF, FLOAT or UINT channels (converted to float); the data window is the image, its top row
 * first. Deep and subsampled parts are refused. Sizes are limited to 1..CACAO_IMG_MAX_SIZE.
 *
 * Each function returns true on success; on failure it returns false, zeroes *out (readers) and
 * writes one message into err that names the file and the problem.
 *
 * The writer never leaves a partial file behind: it writes `path` + ".tmp" and renames it into
 * place once complete (as the image_io writers do).
 */
#ifndef CACAO_EXR_IO_H
#define CACAO_EXR_IO_H

#include <stdbool.h>
#include <stddef.h>

#include "image_io.h"

/* Reads one channel: the channel named "Z", else "R", else "Y", else the file's only channel.
 * A file with several channels and none of those names is refused. */
bool cacao_exr_read_scalar(const char *path, cacao_img *out, char *err, size_t err_size);

/* Reads three channels: "R", "G", "B", else "X", "Y", "Z" (in that order into x, y, z). */
bool cacao_exr_read_vector(const char *path, cacao_img *out, char *err, size_t err_size);

/* Writes a 1-channel image as channel "Y" or a 3-channel image as "R", "G", "B"; 32-bit float
 * samples, ZIP compression (lossless), scanlines top to bottom. */
bool cacao_exr_write(const char *path, const cacao_img *img, char *err, size_t err_size);

/* The same with the channels named by the caller: names[k] for channel k (1 to 4 channels,
 * distinct names). */
bool cacao_exr_write_named(const char *path, const cacao_img *img, const char *const *names, char *err,
                           size_t err_size);

#endif /* CACAO_EXR_IO_H */
