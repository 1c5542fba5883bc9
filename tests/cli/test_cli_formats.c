/* test_cli_formats - every image format the `cacao` command reads round-trips: what a writer
 * stores, the reader gives back bit for bit (PFM 1 and 3 channels, EXR depth and normals, 16-bit
 * PNG on its 1/65535 grid). Float formats store IEEE floats, so anything but identity would be a
 * bug; the PNG grid values k/65535 are exactly what a 16-bit sample means. It also checks the EXR
 * channel rules the CLI documents (depth: Z, else R, else Y, else the only channel; normals:
 * R,G,B or X,Y,Z by name, not position), that tiled files with HALF channels are read into the
 * right pixels, and that bad EXR files are refused with the file named. */
#include <OpenEXR/openexr.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "exr_io.h"
#include "image_io.h"
#include "test_util.h"

#define W 37
#define H 23

static char dir[4096];

static const char *in_dir(const char *name) {
    static char path[8192];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* Values that exercise the float encoding: signs, tiny, huge, fractions, NaN, -0. */
static cacao_img pattern(uint32_t channels) {
    cacao_img img = {W, H, channels, malloc(sizeof(float) * W * H * channels)};
    for (size_t i = 0; i < (size_t)W * H * channels; ++i) img.data[i] = (float)sin((double)i * 0.37) * powf(10.0f, (float)(i % 60) - 30.0f);
    img.data[1] = NAN;
    img.data[2] = -0.0f;
    img.data[3] = 3.4e38f;
    return img;
}

static bool same_bits(const cacao_img *a, const cacao_img *b) {
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->data, b->data, sizeof(float) * a->width * a->height * a->channels) == 0;
}

typedef bool (*writer)(const char *, const cacao_img *, char *, size_t);
typedef bool (*reader)(const char *, cacao_img *, char *, size_t);

static void round_trip(const char *name, uint32_t channels, writer write, reader read) {
    cacao_img img = pattern(channels), back = {0};
    char err[512] = "";
    CHECK(write(in_dir(name), &img, err, sizeof err));
    CHECK(read(in_dir(name), &back, err, sizeof err));
    if (!same_bits(&img, &back)) fprintf(stderr, "%s: values differ after the round trip (%s)\n", name, err);
    CHECK(same_bits(&img, &back));
    cacao_img_free(&img);
    cacao_img_free(&back);
}

static bool read_png16(const char *path, cacao_img *out, char *err, size_t n) {
    bool is16 = false;
    return cacao_png_read(path, out, &is16, err, n) && is16;
}

static void png16_round_trip(void) {
    cacao_img img = {W, H, 1, malloc(sizeof(float) * W * H)}, back = {0};
    for (size_t i = 0; i < (size_t)W * H; ++i) img.data[i] = (float)((i * 7919u) % 65536u) / 65535.0f;
    img.data[0] = 0.0f;
    img.data[1] = 1.0f;
    char err[512] = "";
    CHECK(cacao_png_write(in_dir("depth16.png"), &img, 16, err, sizeof err));
    CHECK(read_png16(in_dir("depth16.png"), &back, err, sizeof err));
    CHECK(same_bits(&img, &back));
    cacao_img_free(&img);
    cacao_img_free(&back);
}

/* Writes channel c of a W x H image with value c + 1 everywhere, under the given names. */
static void write_labelled(const char *name, const char *const *names, uint32_t channels) {
    cacao_img img = {W, H, channels, malloc(sizeof(float) * W * H * channels)};
    for (size_t i = 0; i < (size_t)W * H * channels; ++i) img.data[i] = (float)(i % channels + 1);
    char err[512];
    CHECK(cacao_exr_write_named(in_dir(name), &img, names, err, sizeof err));
    cacao_img_free(&img);
}

/* Reads and returns the first pixel's channels (as labels 1, 2, ...), or 0 when refused. */
static float first_label(const char *name, bool vector, uint32_t k, char *err, size_t n) {
    cacao_img img = {0};
    const bool ok = vector ? cacao_exr_read_vector(in_dir(name), &img, err, n)
                           : cacao_exr_read_scalar(in_dir(name), &img, err, n);
    const float label = ok && k < img.channels ? img.data[k] : 0.0f;
    cacao_img_free(&img);
    return label;
}

static void exr_channel_rules(void) {
    char err[512];
    write_labelled("rzy.exr", (const char *const[]){"R", "Y", "Z"}, 3);
    CHECK(first_label("rzy.exr", false, 0, err, sizeof err) == 3.0f); /* Z wins over R and Y */
    write_labelled("ry.exr", (const char *const[]){"Y", "R"}, 2);
    CHECK(first_label("ry.exr", false, 0, err, sizeof err) == 2.0f); /* then R */
    write_labelled("gy.exr", (const char *const[]){"G", "Y"}, 2);
    CHECK(first_label("gy.exr", false, 0, err, sizeof err) == 2.0f); /* then Y */
    write_labelled("only.exr", (const char *const[]){"depth.V"}, 1);
    CHECK(first_label("only.exr", false, 0, err, sizeof err) == 1.0f); /* the only channel */
    write_labelled("ab.exr", (const char *const[]){"A", "B"}, 2);
    CHECK(first_label("ab.exr", false, 0, err, sizeof err) == 0.0f);
    CHECK(strstr(err, "ab.exr") && strstr(err, "wrong channels"));
    /* Normals by name: channels stored as B, G, R must come back as R, G, B. */
    write_labelled("bgr.exr", (const char *const[]){"B", "G", "R"}, 3);
    CHECK(first_label("bgr.exr", true, 0, err, sizeof err) == 3.0f && first_label("bgr.exr", true, 2, err, sizeof err) == 1.0f);
    write_labelled("xyz.exr", (const char *const[]){"X", "Y", "Z"}, 3);
    CHECK(first_label("xyz.exr", true, 1, err, sizeof err) == 2.0f);
    CHECK(first_label("ab.exr", true, 0, err, sizeof err) == 0.0f && strstr(err, "wrong channels"));
}

/* Writes a tiled (16x16 tiles, one level) EXR with one HALF channel "Z", which cacao_exr_write
 * never produces, through the OpenEXR C API; the encoder converts the floats to half. */
static bool write_tiled_half(const char *path, const float *values) {
    exr_context_t ctx = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, NULL);
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, NULL, EXR_STORAGE_TILED, &part);
    if (rv == EXR_ERR_SUCCESS) rv = exr_initialize_required_attr_simple(ctx, part, W, H, EXR_COMPRESSION_ZIP);
    if (rv == EXR_ERR_SUCCESS) rv = exr_set_tile_descriptor(ctx, part, 16, 16, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_channel(ctx, part, "Z", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (int ty = 0; ty * 16 < H && rv == EXR_ERR_SUCCESS; ++ty)
        for (int tx = 0; tx * 16 < W && rv == EXR_ERR_SUCCESS; ++tx) {
            exr_chunk_info_t chunk;
            rv = exr_write_tile_chunk_info(ctx, part, tx, ty, 0, 0, &chunk);
            if (rv == EXR_ERR_SUCCESS)
                rv = started ? exr_encoding_update(ctx, part, &chunk, &enc) : exr_encoding_initialize(ctx, part, &chunk, &enc);
            if (rv != EXR_ERR_SUCCESS) break;
            enc.channels[0].encode_from_ptr = (const uint8_t *)(values + ty * 16 * W + tx * 16);
            enc.channels[0].user_pixel_stride = sizeof(float);
            enc.channels[0].user_line_stride = W * sizeof(float);
            enc.channels[0].user_bytes_per_element = sizeof(float);
            enc.channels[0].user_data_type = EXR_PIXEL_FLOAT;
            if (!started) rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            started = true;
            if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctx, part, &enc);
        }
    if (started) exr_encoding_destroy(ctx, &enc);
    const exr_result_t finished = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    return rv == EXR_ERR_SUCCESS && finished == EXR_ERR_SUCCESS;
}

/* Tiles (with partial edge tiles, as 37x23 is not a multiple of 16) and HALF samples are read into
 * the right pixels: values that half stores exactly (multiples of 1/64 below 32) must come back. */
static void exr_tiled_half(void) {
    cacao_img img = {W, H, 1, malloc(sizeof(float) * W * H)}, back = {0};
    for (size_t i = 0; i < (size_t)W * H; ++i) img.data[i] = (float)(i % 2048) / 64.0f;
    char err[512] = "";
    CHECK(write_tiled_half(in_dir("tiled.exr"), img.data));
    CHECK(cacao_exr_read_scalar(in_dir("tiled.exr"), &back, err, sizeof err));
    if (err[0]) fprintf(stderr, "tiled.exr: %s\n", err);
    CHECK(same_bits(&img, &back));
    cacao_img_free(&img);
    cacao_img_free(&back);
}

static void bad_exr_files(void) {
    char err[512] = "";
    cacao_img img = {0};
    CHECK(!cacao_exr_read_scalar(in_dir("missing.exr"), &img, err, sizeof err) && strstr(err, "missing.exr"));
    FILE *f = fopen(in_dir("garbage.exr"), "wb");
    fputs("this is not an EXR file at all, just some text long enough to look at", f);
    fclose(f);
    CHECK(!cacao_exr_read_scalar(in_dir("garbage.exr"), &img, err, sizeof err) && strstr(err, "garbage.exr"));
    /* A truncated copy of a valid file: header intact, pixel chunks cut off. */
    FILE *src = fopen(in_dir("y.exr"), "rb");
    char bytes[400];
    const size_t got = src ? fread(bytes, 1, sizeof bytes, src) : 0;
    if (src) fclose(src);
    f = fopen(in_dir("truncated.exr"), "wb");
    fwrite(bytes, 1, got, f);
    fclose(f);
    CHECK(!cacao_exr_read_scalar(in_dir("truncated.exr"), &img, err, sizeof err) && strstr(err, "truncated.exr"));
    CHECK(img.data == NULL);
    /* A failed write leaves nothing behind. */
    cacao_img one = pattern(1);
    CHECK(!cacao_exr_write(in_dir("no/such/dir/out.exr"), &one, err, sizeof err) && strstr(err, "out.exr"));
    cacao_img_free(&one);
}

int main(int argc, char **argv) {
    if (argc != 2) return fprintf(stderr, "usage: test_cli_formats WORKDIR\n"), 2;
    snprintf(dir, sizeof dir, "%s", argv[1]);
    mkdir(dir, 0755); /* may exist already */
    round_trip("d1.pfm", 1, cacao_pfm_write, cacao_pfm_read);
    round_trip("n3.pfm", 3, cacao_pfm_write, cacao_pfm_read);
    round_trip("y.exr", 1, cacao_exr_write, cacao_exr_read_scalar);
    round_trip("rgb.exr", 3, cacao_exr_write, cacao_exr_read_vector);
    png16_round_trip();
    exr_channel_rules();
    exr_tiled_half();
    bad_exr_files();
    return test_report("test_cli_formats");
}
