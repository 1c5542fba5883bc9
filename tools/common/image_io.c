/* image_io.c - PFM and PNG reading and writing for the tools (see image_io.h). */
#include "image_io.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

_Static_assert(sizeof(float) == 4, "PFM stores IEEE-754 binary32 floats");

/* ---- Shared helpers ------------------------------------------------------------------------ */

void cacao_img_free(cacao_img *img) {
    if (!img) return;
    free(img->data);
    memset(img, 0, sizeof(*img));
}

static bool size_in_range(uint32_t n) { return n >= 1 && n <= CACAO_IMG_MAX_SIZE; }

/* Checks an image handed to a writer; channel_ok says which channel counts the format takes. */
static bool check_image(const char *path, const cacao_img *img, bool channel_ok, char *err, size_t err_size) {
    if (!img || !img->data) {
        cacao_set_err(err, err_size, "%s: nothing to write (image or its data is NULL)", path);
        return false;
    }
    if (!size_in_range(img->width) || !size_in_range(img->height)) {
        cacao_set_err(err, err_size, "%s: image size %ux%u is zero or larger than %u", path, img->width, img->height,
                CACAO_IMG_MAX_SIZE);
        return false;
    }
    if (!channel_ok) {
        cacao_set_err(err, err_size, "%s: cannot write an image with %u channels in this format", path, img->channels);
        return false;
    }
    return true;
}

char *cacao_temp_path_for(const char *path) {
    static const char suffix[] = ".tmp";
    size_t length = strlen(path);
    char *temp = malloc(length + sizeof(suffix));
    if (temp) {
        memcpy(temp, path, length);
        memcpy(temp + length, suffix, sizeof(suffix));
    }
    return temp;
}

/* Opens the temporary for path; on failure writes err and returns NULL (and *temp_out = NULL). */
static FILE *open_temp(const char *path, char **temp_out, char *err, size_t err_size) {
    *temp_out = cacao_temp_path_for(path);
    if (!*temp_out) {
        cacao_set_err(err, err_size, "%s: out of memory", path);
        return NULL;
    }
    FILE *file = fopen(*temp_out, "wb");
    if (!file) {
        cacao_set_err(err, err_size, "%s: cannot create temporary file %s: %s", path, *temp_out, strerror(errno));
        free(*temp_out);
        *temp_out = NULL;
    }
    return file;
}

/* Closes the temporary and, if everything was written (written_ok), renames it to path.
 * Any failure deletes the temporary. Frees temp. */
static bool finish_temp(FILE *file, char *temp, const char *path, bool written_ok, char *err, size_t err_size) {
    bool ok = written_ok;
    if (ok && (fflush(file) != 0 || ferror(file))) {
        cacao_set_err(err, err_size, "%s: write failed: %s", path, strerror(errno));
        ok = false;
    }
    if (fclose(file) != 0 && ok) {
        cacao_set_err(err, err_size, "%s: closing the written file failed: %s", path, strerror(errno));
        ok = false;
    }
    return cacao_commit_temp(temp, path, ok, err, err_size);
}

bool cacao_commit_temp(char *temp, const char *path, bool written_ok, char *err, size_t err_size) {
    bool ok = written_ok;
    if (ok && rename(temp, path) != 0) {
        cacao_set_err(err, err_size, "%s: cannot rename %s into place: %s", path, temp, strerror(errno));
        ok = false;
    }
    if (!ok) remove(temp);
    free(temp);
    return ok;
}

void cacao_escape_text(const char *text, char *out, size_t size) {
    static const char hex[] = "0123456789abcdef";
    size_t used = 0;
    if (size == 0) return;
    for (const unsigned char *c = (const unsigned char *)(text ? text : ""); *c; ++c) {
        const bool plain = *c >= 0x20 && *c < 0x7f && *c != '\\';
        if (used + (plain ? 1 : 4) >= size) break;
        if (plain) {
            out[used++] = (char)*c;
        } else {
            out[used++] = '\\';
            out[used++] = 'x';
            out[used++] = hex[*c >> 4];
            out[used++] = hex[*c & 15];
        }
    }
    out[used] = '\0';
}

bool cacao_text_is_printable(const char *text) {
    if (!text || !text[0]) return false;
    for (const unsigned char *c = (const unsigned char *)text; *c; ++c)
        if (*c < 0x20 || *c == 0x7f) return false;
    return true;
}

/* ---- PFM ---------------------------------------------------------------------------------- */

typedef struct pfm_header {
    uint32_t width, height, channels;
    bool little_endian;
} pfm_header;

static bool is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* Reads one whitespace-terminated header field (the terminator is consumed, as PFM requires
 * exactly one whitespace byte between the scale and the pixel data). */
static bool pfm_read_field(FILE *file, const char *path, const char *name, char *field, size_t capacity, char *err,
                           size_t err_size) {
    int c = getc(file);
    while (is_space(c)) c = getc(file);
    size_t length = 0;
    while (c != EOF && !is_space(c)) {
        if (length + 1 >= capacity) {
            cacao_set_err(err, err_size, "%s: bad PFM header: %s field is too long", path, name);
            return false;
        }
        field[length++] = (char)c;
        c = getc(file);
    }
    field[length] = '\0';
    if (c == EOF) {
        cacao_set_err(err, err_size, "%s: truncated: file ends in the PFM header (reading the %s)", path, name);
        return false;
    }
    return true;
}

static bool pfm_parse_size(const char *field, const char *path, const char *name, uint32_t *out, char *err,
                           size_t err_size) {
    uint32_t value = 0;
    size_t length = strlen(field);
    for (size_t i = 0; i < length; i++) {
        if (field[i] < '0' || field[i] > '9') {
            cacao_set_err(err, err_size, "%s: bad PFM header: %s \"%s\" is not a number", path, name, field);
            return false;
        }
        if (value <= CACAO_IMG_MAX_SIZE) value = value * 10 + (uint32_t)(field[i] - '0');
    }
    if (!size_in_range(value)) {
        cacao_set_err(err, err_size, "%s: bad PFM header: %s %s is zero or larger than %u", path, name, field,
                CACAO_IMG_MAX_SIZE);
        return false;
    }
    *out = value;
    return true;
}

static bool pfm_read_header(FILE *file, const char *path, pfm_header *header, char *err, size_t err_size) {
    int magic[3]; /* read one at a time: initialiser evaluation order is unspecified */
    for (int i = 0; i < 3; i++) magic[i] = getc(file);
    if (magic[0] != 'P' || (magic[1] != 'f' && magic[1] != 'F') || !is_space(magic[2])) {
        cacao_set_err(err, err_size, "%s: bad header: not a PFM file (does not start with \"Pf\" or \"PF\")", path);
        return false;
    }
    header->channels = magic[1] == 'F' ? 3 : 1;

    char field[64];
    if (!pfm_read_field(file, path, "width", field, sizeof(field), err, err_size) ||
        !pfm_parse_size(field, path, "width", &header->width, err, err_size) ||
        !pfm_read_field(file, path, "height", field, sizeof(field), err, err_size) ||
        !pfm_parse_size(field, path, "height", &header->height, err, err_size) ||
        !pfm_read_field(file, path, "scale", field, sizeof(field), err, err_size))
        return false;

    char *end = NULL;
    double scale = strtod(field, &end);
    if (end == field || *end != '\0') {
        cacao_set_err(err, err_size, "%s: bad PFM header: scale \"%s\" is not a number", path, field);
        return false;
    }
    if (isnan(scale) || isinf(scale) || scale == 0.0) {
        cacao_set_err(err, err_size, "%s: bad PFM header: scale \"%s\" is NaN, infinite or zero (no byte order)", path,
                field);
        return false;
    }
    header->little_endian = scale < 0.0;
    return true;
}

static float pfm_decode_float(const unsigned char *bytes, bool little_endian) {
    uint32_t bits =
        little_endian
            ? (uint32_t)bytes[0] | (uint32_t)bytes[1] << 8 | (uint32_t)bytes[2] << 16 | (uint32_t)bytes[3] << 24
            : (uint32_t)bytes[3] | (uint32_t)bytes[2] << 8 | (uint32_t)bytes[1] << 16 | (uint32_t)bytes[0] << 24;
    float value;
    memcpy(&value, &bits, sizeof(value));
    return value;
}

static void pfm_encode_float_le(float value, unsigned char *bytes) {
    uint32_t bits;
    memcpy(&bits, &value, sizeof(bits));
    for (int i = 0; i < 4; i++) bytes[i] = (unsigned char)(bits >> (8 * i));
}

/* Bytes left in the file from the current position, or -1 when it cannot be told. */
static long bytes_remaining(FILE *file) {
    long position = ftell(file);
    if (position < 0 || fseek(file, 0, SEEK_END) != 0) return -1;
    long end = ftell(file);
    if (end < position || fseek(file, position, SEEK_SET) != 0) return -1;
    return end - position;
}

/* Reads the pixel rows (bottom to top in the file) into a new top-row-first image. */
static bool pfm_read_pixels(FILE *file, const char *path, const pfm_header *header, cacao_img *out, char *err,
                            size_t err_size) {
    size_t row_floats = (size_t)header->width * header->channels;
    size_t row_bytes = row_floats * 4;
    unsigned long long data_bytes = (unsigned long long)row_bytes * header->height;
    if (data_bytes > SIZE_MAX) {
        cacao_set_err(err, err_size, "%s: image of %llu bytes is too large for this machine", path, data_bytes);
        return false;
    }
    long remaining = bytes_remaining(file);
    if (remaining < 0) {
        cacao_set_err(err, err_size, "%s: cannot determine the file size", path);
        return false;
    }
    if ((unsigned long long)remaining < data_bytes) {
        cacao_set_err(err, err_size,
                "%s: truncated: header says %ux%u with %u channel(s) (%llu bytes of pixels), "
                "but only %ld bytes follow the header",
                path, header->width, header->height, header->channels, data_bytes, remaining);
        return false;
    }

    float *data = malloc((size_t)data_bytes);
    unsigned char *row = malloc(row_bytes);
    bool ok = data && row;
    if (!ok) cacao_set_err(err, err_size, "%s: out of memory for %llu bytes", path, data_bytes);
    for (uint32_t file_row = 0; ok && file_row < header->height; file_row++) {
        if (fread(row, 1, row_bytes, file) != row_bytes) {
            cacao_set_err(err, err_size, "%s: truncated: file ends in pixel row %u", path, file_row);
            ok = false;
            break;
        }
        float *image_row = data + (size_t)(header->height - 1 - file_row) * row_floats;
        for (size_t i = 0; i < row_floats; i++) image_row[i] = pfm_decode_float(row + 4 * i, header->little_endian);
    }
    free(row);
    if (!ok) {
        free(data);
        return false;
    }
    *out = (cacao_img){header->width, header->height, header->channels, data};
    return true;
}

bool cacao_pfm_read(const char *path, cacao_img *out, char *err, size_t err_size) {
    memset(out, 0, sizeof(*out));
    FILE *file = cacao_open_input(path, err, err_size);
    if (!file) return false;
    pfm_header header;
    bool ok =
        pfm_read_header(file, path, &header, err, err_size) && pfm_read_pixels(file, path, &header, out, err, err_size);
    fclose(file);
    return ok;
}

static bool pfm_write_rows(FILE *file, const char *path, const cacao_img *img, char *err, size_t err_size) {
    if (fprintf(file, "%s\n%u %u\n-1.0\n", img->channels == 3 ? "PF" : "Pf", img->width, img->height) < 0) {
        cacao_set_err(err, err_size, "%s: write failed: %s", path, strerror(errno));
        return false;
    }
    size_t row_floats = (size_t)img->width * img->channels;
    unsigned char *row = malloc(row_floats * 4);
    if (!row) {
        cacao_set_err(err, err_size, "%s: out of memory", path);
        return false;
    }
    bool ok = true;
    for (uint32_t file_row = 0; ok && file_row < img->height; file_row++) {
        const float *image_row = img->data + (size_t)(img->height - 1 - file_row) * row_floats;
        for (size_t i = 0; i < row_floats; i++) pfm_encode_float_le(image_row[i], row + 4 * i);
        if (fwrite(row, 4, row_floats, file) != row_floats) {
            cacao_set_err(err, err_size, "%s: write failed: %s", path, strerror(errno));
            ok = false;
        }
    }
    free(row);
    return ok;
}

bool cacao_pfm_write(const char *path, const cacao_img *img, char *err, size_t err_size) {
    if (!check_image(path, img, img && (img->channels == 1 || img->channels == 3), err, err_size)) return false;
    char *temp;
    FILE *file = open_temp(path, &temp, err, err_size);
    if (!file) return false;
    bool written = pfm_write_rows(file, path, img, err, err_size);
    return finish_temp(file, temp, path, written, err, err_size);
}

/* ---- PNG ---------------------------------------------------------------------------------- */

/* Everything a libpng read or write owns, kept outside the function that calls setjmp so that
 * it is still valid after libpng longjmps out on an error. */
typedef struct png_job {
    FILE *file;
    png_structp png;
    png_infop info;
    unsigned char *pixels; /* decoded or to-be-encoded samples */
    png_bytep *rows;       /* row pointers into pixels (reading) */
    float *data;           /* the float image being built (reading) */
    char message[256];     /* libpng's error, or ours */
    char warning[128];     /* libpng's last warning: often the reason behind a generic error */
} png_job;

static void png_job_error(png_structp png, png_const_charp message) {
    png_job *job = png_get_error_ptr(png);
    snprintf(job->message, sizeof(job->message), "%s", message);
    png_longjmp(png, 1);
}

/* Warnings do not stop decoding; the last one is kept because libpng reports, for example, an
 * oversized IHDR as a warning naming the field followed by the error "Invalid IHDR data". */
static void png_job_warning(png_structp png, png_const_charp message) {
    png_job *job = png_get_error_ptr(png);
    snprintf(job->warning, sizeof(job->warning), "%s", message);
}

/* Formats a failed job's error as "<prefix>: <error> (<last warning>)". */
static void png_job_report(const png_job *job, const char *path, const char *prefix, char *err, size_t err_size) {
    if (!job->info)
        cacao_set_err(err, err_size, "%s: %s: cannot initialise libpng", path, prefix);
    else if (job->warning[0])
        cacao_set_err(err, err_size, "%s: %s: %s (%s)", path, prefix, job->message, job->warning);
    else
        cacao_set_err(err, err_size, "%s: %s: %s", path, prefix, job->message);
}

static void png_job_read(png_structp png, png_bytep bytes, size_t count) {
    png_job *job = png_get_io_ptr(png);
    if (fread(bytes, 1, count, job->file) != count)
        png_error(png, feof(job->file) ? "truncated: unexpected end of file" : "read error");
}

static void png_job_write(png_structp png, png_bytep bytes, size_t count) {
    png_job *job = png_get_io_ptr(png);
    if (fwrite(bytes, 1, count, job->file) != count) {
        snprintf(job->warning, sizeof(job->warning), "%s", strerror(errno));
        png_error(png, "write failed");
    }
}

static void png_job_flush(png_structp png) { (void)png; }

/* Deflate expands at most about 1032 to 1: a header claiming more pixel bytes than the file could
 * hold that way is refused before anything is allocated for it. */
static bool png_fits_file(png_job *job, size_t row_bytes, png_uint_32 height) {
    struct stat st;
    const unsigned long long needed = ((unsigned long long)row_bytes + 1) * height;
    if (fstat(fileno(job->file), &st) != 0 || needed / 1032 <= (unsigned long long)st.st_size) return true;
    snprintf(job->message, sizeof(job->message),
             "header says %u rows of %zu bytes (%llu bytes of pixels), more than the %lld-byte file can hold",
             (unsigned)height, row_bytes, needed, (long long)st.st_size);
    return false;
}

static bool png_decode(png_job *job, cacao_img *out, bool *is16bit) {
    if (setjmp(png_jmpbuf(job->png))) return false;
    png_structp png = job->png;
    png_infop info = job->info;
    png_set_read_fn(png, job, png_job_read);
    png_set_sig_bytes(png, 8);
    png_set_user_limits(png, CACAO_IMG_MAX_SIZE, CACAO_IMG_MAX_SIZE);
    png_read_info(png, info);

    png_uint_32 width = png_get_image_width(png, info);
    png_uint_32 height = png_get_image_height(png, info);
    if (!png_fits_file(job, png_get_rowbytes(png, info), height)) return false;
    int color_type = png_get_color_type(png, info);
    if (color_type == PNG_COLOR_TYPE_PALETTE) {
        png_set_palette_to_rgb(png);
        if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    }
    if (color_type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);

    unsigned channels = png_get_channels(png, info);
    unsigned bit_depth = png_get_bit_depth(png, info);
    size_t bytes_per_sample = bit_depth / 8;
    if ((bit_depth != 8 && bit_depth != 16) || channels < 1 || channels > 4 ||
        png_get_rowbytes(png, info) != (size_t)width * channels * bytes_per_sample) {
        snprintf(job->message, sizeof(job->message), "unsupported layout (%u channels, %u bits)", channels, bit_depth);
        return false;
    }
    size_t row_bytes = (size_t)width * channels * bytes_per_sample;
    size_t sample_count = (size_t)width * height * channels;
    job->pixels = malloc(row_bytes * height);
    job->rows = malloc(height * sizeof(*job->rows));
    job->data = malloc(sample_count * sizeof(float));
    if (!job->pixels || !job->rows || !job->data) {
        snprintf(job->message, sizeof(job->message), "out of memory");
        return false;
    }
    for (png_uint_32 y = 0; y < height; y++) job->rows[y] = job->pixels + y * row_bytes;
    png_read_image(png, job->rows);
    png_read_end(png, NULL);

    for (size_t i = 0; i < sample_count; i++) {
        const unsigned char *sample = job->pixels + i * bytes_per_sample;
        job->data[i] = bit_depth == 16 ? (float)((sample[0] << 8) | sample[1]) / 65535.0f : (float)sample[0] / 255.0f;
    }
    *out = (cacao_img){width, height, channels, job->data};
    job->data = NULL;
    if (is16bit) *is16bit = bit_depth == 16;
    return true;
}

bool cacao_png_read(const char *path, cacao_img *out, bool *is16bit, char *err, size_t err_size) {
    memset(out, 0, sizeof(*out));
    if (is16bit) *is16bit = false;
    png_job job = {.file = cacao_open_input(path, err, err_size)};
    if (!job.file) return false;
    unsigned char signature[8];
    size_t signature_bytes = fread(signature, 1, sizeof(signature), job.file);
    if (signature_bytes != sizeof(signature) || png_sig_cmp(signature, 0, sizeof(signature)) != 0) {
        cacao_set_err(err, err_size, "%s: bad header: not a PNG file (%s)", path,
                signature_bytes != sizeof(signature) ? "shorter than the PNG signature" : "wrong signature");
        fclose(job.file);
        return false;
    }
    job.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, png_job_error, png_job_warning);
    job.info = job.png ? png_create_info_struct(job.png) : NULL;
    bool ok = job.info && png_decode(&job, out, is16bit);
    if (!ok) png_job_report(&job, path, "bad PNG", err, err_size);
    png_destroy_read_struct(job.png ? &job.png : NULL, job.info ? &job.info : NULL, NULL);
    free(job.data);
    free(job.rows);
    free(job.pixels);
    fclose(job.file);
    return ok;
}

/* round(clamp(v, 0, 1) * max_value); NaN becomes 0. */
static uint32_t quantise(float value, uint32_t max_value) {
    double v = value > 0.0f ? (value < 1.0f ? (double)value : 1.0) : 0.0;
    return (uint32_t)(v * max_value + 0.5);
}

static bool png_encode(png_job *job, const cacao_img *img, int bits) {
    if (setjmp(png_jmpbuf(job->png))) return false;
    static const int color_types[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                       PNG_COLOR_TYPE_RGB_ALPHA};
    png_structp png = job->png;
    png_set_write_fn(png, job, png_job_write, png_job_flush);
    png_set_IHDR(png, job->info, img->width, img->height, bits, color_types[img->channels], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, job->info);

    size_t row_samples = (size_t)img->width * img->channels;
    job->pixels = malloc(row_samples * (size_t)(bits / 8));
    if (!job->pixels) {
        snprintf(job->message, sizeof(job->message), "out of memory");
        return false;
    }
    uint32_t max_value = bits == 16 ? 65535u : 255u;
    for (uint32_t y = 0; y < img->height; y++) {
        const float *row = img->data + (size_t)y * row_samples;
        for (size_t i = 0; i < row_samples; i++) {
            uint32_t sample = quantise(row[i], max_value);
            if (bits == 16) {
                job->pixels[2 * i] = (unsigned char)(sample >> 8);
                job->pixels[2 * i + 1] = (unsigned char)sample;
            } else {
                job->pixels[i] = (unsigned char)sample;
            }
        }
        png_write_row(png, job->pixels);
    }
    png_write_end(png, NULL);
    return true;
}

bool cacao_png_write(const char *path, const cacao_img *img, int bits, char *err, size_t err_size) {
    if (!check_image(path, img, img && img->channels >= 1 && img->channels <= 4, err, err_size)) return false;
    if (bits != 8 && bits != 16) {
        cacao_set_err(err, err_size, "%s: PNG bits per sample must be 8 or 16, not %d", path, bits);
        return false;
    }
    char *temp;
    png_job job = {.file = open_temp(path, &temp, err, err_size)};
    if (!job.file) return false;
    job.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, png_job_error, png_job_warning);
    job.info = job.png ? png_create_info_struct(job.png) : NULL;
    bool written = job.info && png_encode(&job, img, bits);
    if (!written) png_job_report(&job, path, "PNG encoding failed", err, err_size);
    png_destroy_write_struct(job.png ? &job.png : NULL, job.info ? &job.info : NULL);
    free(job.pixels);
    return finish_temp(job.file, temp, path, written, err, err_size);
}
