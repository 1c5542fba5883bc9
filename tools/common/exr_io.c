/* exr_io.c - OpenEXR reading and writing through the OpenEXR C API (see exr_io.h). */
#include "exr_io.h"

#include <OpenEXR/openexr.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"

#define MAX_CHANNELS 4

/* Receives the library's first error message for the file at hand (via the context's user data). */
typedef struct exr_job {
    char message[256];
} exr_job;

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg) {
    void *user = NULL;
    if (!ctxt || exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user) return;
    exr_job *job = user;
    if (!job->message[0])
        snprintf(job->message, sizeof job->message, "%s", msg ? msg : exr_get_default_error_message(code));
}

static exr_context_initializer_t job_initializer(exr_job *job) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = job;
    return init;
}

/* Reports a failed library call, preferring the library's own detailed message. */
static bool exr_fail(const exr_job *job, exr_result_t rv, const char *path, const char *what, char *err,
                     size_t err_size) {
    cacao_set_err(err, err_size, "%s: %s: %s", path, what,
            job->message[0] ? job->message : exr_get_default_error_message(rv));
    return false;
}

/* ---- Reading ---------------------------------------------------------------------------- */

/* Where a chosen set of channels goes: channel_index[k] is the file's channel for output k. */
typedef struct exr_selection {
    int count;
    int channel_index[MAX_CHANNELS];
} exr_selection;

static int find_channel(const exr_attr_chlist_t *list, const char *name) {
    for (int i = 0; i < list->num_channels; ++i)
        if (strcmp(list->entries[i].name.str, name) == 0) return i;
    return -1;
}

/* Picks the first of `sets` (each `count` names) that the file has completely. */
static bool select_channels(const exr_attr_chlist_t *list, const char *const *sets, int set_count, int count,
                            exr_selection *out) {
    for (int s = 0; s < set_count; ++s) {
        out->count = count;
        bool complete = true;
        for (int k = 0; k < count && complete; ++k) {
            out->channel_index[k] = find_channel(list, sets[s * count + k]);
            complete = out->channel_index[k] >= 0;
        }
        if (complete) return true;
    }
    return false;
}

static void list_channel_names(const exr_attr_chlist_t *list, char *text, size_t size) {
    text[0] = '\0';
    for (int i = 0; i < list->num_channels; ++i) {
        size_t used = strlen(text);
        char name[64];
        cacao_escape_text(list->entries[i].name.str, name, sizeof name);
        snprintf(text + used, size - used, "%s%s", i ? ", " : "", name);
    }
}

static bool choose_scalar_channel(const exr_attr_chlist_t *list, const char *path, exr_selection *sel, char *err,
                                  size_t err_size) {
    static const char *const names[] = {"Z", "R", "Y"};
    if (select_channels(list, names, 3, 1, sel)) return true;
    if (list->num_channels == 1) {
        *sel = (exr_selection){.count = 1, .channel_index = {0}};
        return true;
    }
    char found[256];
    list_channel_names(list, found, sizeof found);
    cacao_set_err(err, err_size,
            "%s: wrong channels: expected one channel named Z, R or Y (or a single channel), found %d (%s)", path,
            list->num_channels, found);
    return false;
}

static bool choose_vector_channels(const exr_attr_chlist_t *list, const char *path, exr_selection *sel, char *err,
                                   size_t err_size) {
    static const char *const names[] = {"R", "G", "B", "X", "Y", "Z"};
    if (select_channels(list, names, 2, 3, sel)) return true;
    char found[256];
    list_channel_names(list, found, sizeof found);
    cacao_set_err(err, err_size, "%s: wrong channels: expected R, G, B or X, Y, Z, found %d (%s)", path, list->num_channels,
            found);
    return false;
}

/* The part's geometry: data window origin and size, and how it is cut into chunks. */
typedef struct exr_layout {
    int32_t x0, y0;
    uint32_t width, height;
    bool tiled;
    int32_t tile_width, tile_height; /* tiled */
    int32_t lines_per_chunk;         /* scanline */
} exr_layout;

static bool read_layout(exr_const_context_t ctx, const exr_job *job, const char *path, exr_layout *layout, char *err,
                        size_t err_size) {
    exr_storage_t storage;
    exr_attr_box2i_t window;
    exr_result_t rv = exr_get_storage(ctx, 0, &storage);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_data_window(ctx, 0, &window);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(job, rv, path, "bad header", err, err_size);
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
        cacao_set_err(err, err_size, "%s: deep EXR images are not supported", path);
        return false;
    }
    const int64_t w = (int64_t)window.max.x - window.min.x + 1, h = (int64_t)window.max.y - window.min.y + 1;
    if (w < 1 || h < 1 || w > CACAO_IMG_MAX_SIZE || h > CACAO_IMG_MAX_SIZE) {
        cacao_set_err(err, err_size, "%s: image size %lldx%lld is zero or larger than %u", path, (long long)w, (long long)h,
                CACAO_IMG_MAX_SIZE);
        return false;
    }
    *layout = (exr_layout){.x0 = window.min.x,
                           .y0 = window.min.y,
                           .width = (uint32_t)w,
                           .height = (uint32_t)h,
                           .tiled = storage == EXR_STORAGE_TILED};
    rv = layout->tiled ? exr_get_tile_sizes(ctx, 0, 0, 0, &layout->tile_width, &layout->tile_height)
                       : exr_get_scanlines_per_chunk(ctx, 0, &layout->lines_per_chunk);
    if (rv != EXR_ERR_SUCCESS) return exr_fail(job, rv, path, "bad header", err, err_size);
    if ((layout->tiled && (layout->tile_width < 1 || layout->tile_height < 1)) ||
        (!layout->tiled && layout->lines_per_chunk < 1)) {
        cacao_set_err(err, err_size, "%s: bad header: invalid chunk size", path);
        return false;
    }
    return true;
}

static bool check_sampling(const exr_attr_chlist_t *list, const exr_selection *sel, const char *path, char *err,
                           size_t err_size) {
    for (int k = 0; k < sel->count; ++k) {
        const exr_attr_chlist_entry_t *e = &list->entries[sel->channel_index[k]];
        if (e->x_sampling != 1 || e->y_sampling != 1) {
            char name[64];
            cacao_escape_text(e->name.str, name, sizeof name);
            cacao_set_err(err, err_size, "%s: channel %s is subsampled, which is not supported", path, name);
            return false;
        }
    }
    return true;
}

/* Points the decoder's selected channels at the image (pixel x, y of the data window) and every
 * other channel at scratch (a chunk's worth of floats). Unused channels are decoded too, not
 * skipped: OpenEXR 3.1.5 writes through a NULL pointer when some channels of a chunk are skipped. */
static void aim_decoder(exr_decode_pipeline_t *dec, const exr_attr_chlist_t *list, const exr_selection *sel,
                        cacao_img *img, uint32_t x, uint32_t y, float *scratch) {
    for (int c = 0; c < dec->channel_count; ++c) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        ch->decode_to_ptr = (uint8_t *)scratch;
        ch->user_pixel_stride = (int32_t)sizeof(float);
        ch->user_line_stride = (int32_t)(ch->width * sizeof(float));
        ch->user_bytes_per_element = (int16_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        for (int k = 0; k < sel->count; ++k) {
            if (strcmp(ch->channel_name, list->entries[sel->channel_index[k]].name.str) != 0) continue;
            float *first = img->data + ((size_t)y * img->width + x) * img->channels + (size_t)k;
            ch->decode_to_ptr = (uint8_t *)first;
            ch->user_pixel_stride = (int32_t)(img->channels * sizeof(float));
            ch->user_line_stride = (int32_t)(img->width * img->channels * sizeof(float));
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
    }
}

/* Decodes one chunk whose top-left pixel is (x, y) in the data window. */
static exr_result_t decode_chunk(exr_const_context_t ctx, const exr_chunk_info_t *chunk, const exr_attr_chlist_t *list,
                                 const exr_selection *sel, cacao_img *img, uint32_t x, uint32_t y) {
    if (chunk->width < 1 || chunk->height < 1 || x + (uint32_t)chunk->width > img->width ||
        y + (uint32_t)chunk->height > img->height)
        return EXR_ERR_CORRUPT_CHUNK;
    float *scratch = malloc((size_t)chunk->width * (size_t)chunk->height * sizeof(float));
    if (!scratch) return EXR_ERR_OUT_OF_MEMORY;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_result_t rv = exr_decoding_initialize(ctx, 0, chunk, &dec);
    if (rv == EXR_ERR_SUCCESS) {
        aim_decoder(&dec, list, sel, img, x, y, scratch);
        rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(ctx, 0, &dec);
    exr_decoding_destroy(ctx, &dec);
    free(scratch);
    return rv;
}

static exr_result_t decode_all(exr_const_context_t ctx, const exr_layout *layout, const exr_attr_chlist_t *list,
                               const exr_selection *sel, cacao_img *img) {
    exr_chunk_info_t chunk;
    exr_result_t rv = EXR_ERR_SUCCESS;
    if (!layout->tiled) {
        for (uint32_t y = 0; y < layout->height && rv == EXR_ERR_SUCCESS; y += (uint32_t)layout->lines_per_chunk) {
            rv = exr_read_scanline_chunk_info(ctx, 0, layout->y0 + (int32_t)y, &chunk);
            if (rv == EXR_ERR_SUCCESS)
                rv = decode_chunk(ctx, &chunk, list, sel, img, 0, (uint32_t)(chunk.start_y - layout->y0));
        }
        return rv;
    }
    const uint32_t tw = (uint32_t)layout->tile_width, th = (uint32_t)layout->tile_height;
    for (uint32_t ty = 0; ty * th < layout->height && rv == EXR_ERR_SUCCESS; ++ty)
        for (uint32_t tx = 0; tx * tw < layout->width && rv == EXR_ERR_SUCCESS; ++tx) {
            rv = exr_read_tile_chunk_info(ctx, 0, (int)tx, (int)ty, 0, 0, &chunk);
            if (rv == EXR_ERR_SUCCESS) rv = decode_chunk(ctx, &chunk, list, sel, img, tx * tw, ty * th);
        }
    return rv;
}

typedef bool (*channel_chooser)(const exr_attr_chlist_t *, const char *, exr_selection *, char *, size_t);

static bool read_part(exr_context_t ctx, const exr_job *job, const char *path, channel_chooser choose, cacao_img *out,
                      char *err, size_t err_size) {
    exr_layout layout;
    const exr_attr_chlist_t *list = NULL;
    exr_selection sel;
    if (!read_layout(ctx, job, path, &layout, err, err_size)) return false;
    exr_result_t rv = exr_get_channels(ctx, 0, &list);
    if (rv != EXR_ERR_SUCCESS || !list) return exr_fail(job, rv, path, "bad channel list", err, err_size);
    if (!choose(list, path, &sel, err, err_size) || !check_sampling(list, &sel, path, err, err_size)) return false;
    const size_t floats = (size_t)layout.width * layout.height * (size_t)sel.count;
    *out = (cacao_img){.width = layout.width,
                       .height = layout.height,
                       .channels = (uint32_t)sel.count,
                       .data = calloc(floats, sizeof(float))};
    if (!out->data) {
        cacao_set_err(err, err_size, "%s: out of memory", path);
        return false;
    }
    rv = decode_all(ctx, &layout, list, &sel, out);
    if (rv != EXR_ERR_SUCCESS)
        return exr_fail(job, rv, path, "cannot decode the pixels (truncated or corrupt?)", err, err_size);
    return true;
}

static bool read_exr(const char *path, channel_chooser choose, cacao_img *out, char *err, size_t err_size) {
    memset(out, 0, sizeof *out);
    if (!cacao_check_input(path, err, err_size)) return false; /* the library opens it, once */
    exr_job job = {{0}};
    const exr_context_initializer_t init = job_initializer(&job);
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_read(&ctx, path, &init);
    bool ok = rv == EXR_ERR_SUCCESS ? read_part(ctx, &job, path, choose, out, err, err_size)
                                    : exr_fail(&job, rv, path, "not a readable OpenEXR file", err, err_size);
    exr_finish(&ctx);
    if (!ok) cacao_img_free(out);
    return ok;
}

bool cacao_exr_read_scalar(const char *path, cacao_img *out, char *err, size_t err_size) {
    return read_exr(path, choose_scalar_channel, out, err, err_size);
}

bool cacao_exr_read_vector(const char *path, cacao_img *out, char *err, size_t err_size) {
    return read_exr(path, choose_vector_channels, out, err, err_size);
}

/* ---- Writing ---------------------------------------------------------------------------- */

static bool check_writable(const char *path, const cacao_img *img, const char *const *names, char *err,
                           size_t err_size) {
    if (!img || !img->data) {
        cacao_set_err(err, err_size, "%s: nothing to write (image or its data is NULL)", path);
        return false;
    }
    if (img->width < 1 || img->height < 1 || img->width > CACAO_IMG_MAX_SIZE || img->height > CACAO_IMG_MAX_SIZE) {
        cacao_set_err(err, err_size, "%s: image size %ux%u is zero or larger than %u", path, img->width, img->height,
                CACAO_IMG_MAX_SIZE);
        return false;
    }
    if (img->channels < 1 || img->channels > MAX_CHANNELS) {
        cacao_set_err(err, err_size, "%s: cannot write an image with %u channels as EXR (1 to %d)", path, img->channels,
                MAX_CHANNELS);
        return false;
    }
    for (uint32_t k = 0; k < img->channels; ++k)
        if (!names[k] || !names[k][0]) {
            cacao_set_err(err, err_size, "%s: channel %u has no name", path, k);
            return false;
        }
    return true;
}

static exr_result_t write_header(exr_context_t ctx, const cacao_img *img, const char *const *names) {
    int part = 0;
    exr_result_t rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, (int32_t)img->width, (int32_t)img->height,
                                                 EXR_COMPRESSION_ZIP);
    for (uint32_t k = 0; k < img->channels && rv == EXR_ERR_SUCCESS; ++k)
        rv = exr_add_channel(ctx, part, names[k], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    return rv;
}

/* Points the encoder's channels at rows y.. of the image. */
static void aim_encoder(exr_encode_pipeline_t *enc, const cacao_img *img, const char *const *names, uint32_t y) {
    for (int c = 0; c < enc->channel_count; ++c) {
        exr_coding_channel_info_t *ch = &enc->channels[c];
        for (uint32_t k = 0; k < img->channels; ++k) {
            if (strcmp(ch->channel_name, names[k]) != 0) continue;
            ch->encode_from_ptr = (const uint8_t *)(img->data + (size_t)y * img->width * img->channels + k);
            ch->user_pixel_stride = (int32_t)(img->channels * sizeof(float));
            ch->user_line_stride = (int32_t)(img->width * img->channels * sizeof(float));
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
    }
}

/* OpenEXR 3.1.5 stores a chunk whose compressed size equals its raw size with the compressed bytes,
 * which every reader takes for raw data (the file reads back as garbage). This wraps the library's
 * compressor: in that one case the raw bytes are stored instead, as a raw-size chunk must be. */
typedef struct exr_compressor {
    exr_result_t (*fn)(exr_encode_pipeline_t *);
} exr_compressor;

static exr_result_t compress_or_store_raw(exr_encode_pipeline_t *enc) {
    const exr_compressor *library = enc->encoding_user_data;
    const exr_result_t rv = library->fn(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rv;
}

static exr_result_t write_pixels(exr_context_t ctx, const cacao_img *img, const char *const *names) {
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    if (rv == EXR_ERR_SUCCESS && lines < 1) rv = EXR_ERR_INVALID_ARGUMENT;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_compressor library = {NULL};
    bool started = false;
    for (uint32_t y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += (uint32_t)lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctx, 0, (int)y, &chunk);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = started ? exr_encoding_update(ctx, 0, &chunk, &enc) : exr_encoding_initialize(ctx, 0, &chunk, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        aim_encoder(&enc, img, names, y);
        if (!started) rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
        if (rv == EXR_ERR_SUCCESS && enc.compress_fn && enc.compress_fn != compress_or_store_raw) {
            library = (exr_compressor){enc.compress_fn};
            enc.encoding_user_data = &library;
            enc.compress_fn = compress_or_store_raw;
        }
        started = true;
        if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctx, 0, &enc);
    }
    if (started) exr_encoding_destroy(ctx, &enc);
    return rv;
}

bool cacao_exr_write(const char *path, const cacao_img *img, char *err, size_t err_size) {
    static const char *const scalar[] = {"Y"}, *const vector[] = {"R", "G", "B"};
    if (img && img->channels != 1 && img->channels != 3) {
        cacao_set_err(err, err_size, "%s: cannot write an image with %u channels as EXR (1 or 3)", path, img->channels);
        return false;
    }
    return cacao_exr_write_named(path, img, img && img->channels == 1 ? scalar : vector, err, err_size);
}

bool cacao_exr_write_named(const char *path, const cacao_img *img, const char *const *names, char *err,
                           size_t err_size) {
    if (!check_writable(path, img, names, err, err_size)) return false;
    char *temp = cacao_temp_path_for(path);
    if (!temp) {
        cacao_set_err(err, err_size, "%s: out of memory", path);
        return false;
    }
    exr_job job = {{0}};
    const exr_context_initializer_t init = job_initializer(&job);
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_write(&ctx, temp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = write_header(ctx, img, names);
    if (rv == EXR_ERR_SUCCESS) rv = write_pixels(ctx, img, names);
    const exr_result_t finished = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    if (rv == EXR_ERR_SUCCESS) rv = finished;
    bool ok = rv == EXR_ERR_SUCCESS;
    if (!ok) exr_fail(&job, rv, path, "cannot write", err, err_size);
    return cacao_commit_temp(temp, path, ok, err, err_size);
}
