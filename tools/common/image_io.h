/* image_io.h - float images read from and written to PFM and PNG files (tools only).
 *
 * Every image is held as 32-bit floats, channels interleaved, row 0 = the TOP row of the picture
 * (the readers flip PFM, whose rows run bottom to top in the file).
 *
 * Each function returns true on success. On failure it returns false and writes one message into
 * err (err may be NULL; err_size counts the terminating zero) that names the file and the problem.
 * Readers validate every length against the file before reading and never trust the header;
 * widths and heights are limited to 1..CACAO_IMG_MAX_SIZE.
 *
 * Writers never leave a partial file behind: they write `path` + ".tmp" in the same directory and
 * rename() it into place only once it is complete; on any failure the temporary is deleted and
 * an existing file at `path` is left untouched.
 */
#ifndef CACAO_IMAGE_IO_H
#define CACAO_IMAGE_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "text_file.h"

#define CACAO_IMG_MAX_SIZE 16384u /* largest width or height accepted or written */

/* A float image. data holds width*height*channels floats, top row first, channels interleaved. */
typedef struct cacao_img {
    uint32_t width;    /* pixels per row */
    uint32_t height;   /* rows */
    uint32_t channels; /* floats per pixel */
    float *data;       /* malloc'ed by the readers; release with cacao_img_free */
} cacao_img;

/* Frees img->data and zeroes *img. Safe on a zeroed image and on NULL. */
void cacao_img_free(cacao_img *img);

/* Reads a PFM: "Pf" (1 channel) or "PF" (3 channels); scale < 0 little-endian, > 0 big-endian.
 * Pixel values are returned as stored (the scale's magnitude is ignored). On failure *out is
 * zeroed. Bytes after the pixel data are ignored. */
bool cacao_pfm_read(const char *path, cacao_img *out, char *err, size_t err_size);

/* Writes a 1- or 3-channel image as PFM, little-endian (scale -1.0), rows bottom to top. */
bool cacao_pfm_write(const char *path, const cacao_img *img, char *err, size_t err_size);

/* Reads an 8- or 16-bit PNG. Gray, gray+alpha, RGB and RGBA keep their channel count (1, 2, 3,
 * 4); palette images become RGB (RGBA where they carry transparency); gray below 8 bits is
 * expanded. Values are normalised to [0,1] (sample / 255 or / 65535). *is16bit (may be NULL)
 * says whether the file stored 16-bit samples. On failure *out is zeroed. */
bool cacao_png_read(const char *path, cacao_img *out, bool *is16bit, char *err, size_t err_size);

/* Writes a PNG with bits = 8 or 16 per sample: 1 channel gray, 2 gray+alpha, 3 RGB, 4 RGBA.
 * Each sample is round(clamp(v, 0, 1) * (2^bits - 1)); NaN is written as 0. */
bool cacao_png_write(const char *path, const cacao_img *img, int bits, char *err, size_t err_size);

/* Atomic writes, shared by every writer: the temporary a writer fills (path + ".tmp"; NULL when
 * out of memory), and its commit: renamed to path if written_ok, else deleted. Frees temp. */
char *cacao_temp_path_for(const char *path);
bool cacao_commit_temp(char *temp, const char *path, bool written_ok, char *err, size_t err_size);

/* Input files (cacao_check_input, cacao_open_input, cacao_read_whole_file): text_file.h. */

/* Copies text into out (size bytes, always terminated), writing every byte outside printable
 * ASCII as \xNN, so that names taken from inputs stay on one line and carry no terminal escapes. */
void cacao_escape_text(const char *text, char *out, size_t size);

/* cacao_escape_text into a value, for a message: printf("%s", cacao_shown(arg).text). Cut at 255
 * bytes. */
typedef struct cacao_shown_text {
    char text[256];
} cacao_shown_text;
static inline cacao_shown_text cacao_shown(const char *text) {
    cacao_shown_text s;
    cacao_escape_text(text, s.text, sizeof s.text);
    return s;
}

/* Whether text taken from an input can be shown as it is (a name in a table, CSV, plot): not
 * empty, and no control bytes (below 0x20, or 0x7f), which would break a line or carry a terminal
 * escape. Bytes from 0x80 (UTF-8) are kept. */
bool cacao_text_is_printable(const char *text);

#endif /* CACAO_IMAGE_IO_H */
