/* test_robust_io - the readers and writers of tools/common hold up against inputs a hostile tester
 * found breaking them (issue 16), each case written here from its description:
 *   - an RGBA HALF scanline EXR (the most common layout) read for depth (R) and for a vector (RGB):
 *     OpenEXR 3.1.5 crashed when the reader skipped the unused channels;
 *   - many small random images written by cacao_exr_write read back bit for bit: a ZIP chunk that
 *     compresses to exactly its raw size used to be stored unreadably while the write succeeded;
 *   - a 65-byte PNG whose header claims 16384x16384 RGBA16 is refused from its size, before the
 *     ~6 GiB of pixels are allocated (the address space is capped at 1 GiB so that allocating them
 *     would fail with a different message);
 *   - a FIFO given to any reader is refused at once (an alarm turns a hang into a failure), a
 *     directory is called a directory, and "cannot open" carries the system's reason;
 *   - names taken from files are escaped: an EXR channel named with control bytes and a terminal
 *     escape gives a one-line message;
 *   - JSON: a key given twice and text after the object are refused, naming the key or position. */
#include <OpenEXR/openexr.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "camera_json.h"
#include "exr_io.h"
#include "image_io.h"
#include "test_util.h"

static char dir[4096];

static const char *in_dir(const char *name) { return test_path(dir, name); }

static bool contains(const char *text, const char *needle) { return strstr(text, needle) != NULL; }

static bool has_control_bytes(const char *text) {
    for (const unsigned char *c = (const unsigned char *)text; *c; ++c)
        if (*c < 0x20 || *c == 0x7f) return true;
    return false;
}

/* Writes a scanline EXR (ZIP) with `count` HALF channels named `names`, from interleaved floats. */
static bool write_half_exr(const char *path, uint32_t w, uint32_t h, int count, const char *const *names,
                           const float *values) {
    exr_context_t ctx = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, NULL);
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, (int32_t)w, (int32_t)h, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < count && rv == EXR_ERR_SUCCESS; ++c)
        rv = exr_add_channel(ctx, part, names[c], EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (uint32_t y = 0; y < h && rv == EXR_ERR_SUCCESS; y += (uint32_t)lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctx, part, (int)y, &chunk);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_encoding_update(ctx, part, &chunk, &enc)
                         : exr_encoding_initialize(ctx, part, &chunk, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        for (int e = 0; e < enc.channel_count; ++e)
            for (int c = 0; c < count; ++c) {
                if (strcmp(enc.channels[e].channel_name, names[c]) != 0) continue;
                enc.channels[e].encode_from_ptr = (const uint8_t *)(values + (size_t)y * w * (size_t)count + c);
                enc.channels[e].user_pixel_stride = (int32_t)(count * sizeof(float));
                enc.channels[e].user_line_stride = (int32_t)(w * count * sizeof(float));
                enc.channels[e].user_bytes_per_element = sizeof(float);
                enc.channels[e].user_data_type = EXR_PIXEL_FLOAT;
            }
        if (!started) rv = exr_encoding_choose_default_routines(ctx, part, &enc);
        started = true;
        if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctx, part, &enc);
    }
    if (started) exr_encoding_destroy(ctx, &enc);
    const exr_result_t finished = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    return rv == EXR_ERR_SUCCESS && finished == EXR_ERR_SUCCESS;
}

/* Defect 1: RGBA and RGB HALF files give their R (depth) and R,G,B (normals) values. The values are
 * multiples of 1/64 below 32, which half stores exactly. */
static void exr_rgba_half(void) {
    enum { w = 29, h = 35 };
    static const char *const rgba[] = {"A", "B", "G", "R"};
    float *values = malloc(sizeof(float) * w * h * 4);
    for (size_t i = 0; i < (size_t)w * h * 4; ++i) values[i] = (float)((i * 7) % 2048) / 64.0f;
    for (int count = 3; count <= 4; ++count) {
        const char *path = in_dir(count == 4 ? "rgba_half.exr" : "rgb_half.exr");
        const char *const *names = count == 4 ? rgba : rgba + 1; /* B, G, R for three */
        CHECK(write_half_exr(path, w, h, count, names, values));
        cacao_img depth = {0}, vec = {0};
        char err[512] = "";
        CHECK(cacao_exr_read_scalar(path, &depth, err, sizeof err));
        if (err[0]) fprintf(stderr, "%s\n", err);
        CHECK(cacao_exr_read_vector(path, &vec, err, sizeof err));
        if (err[0]) fprintf(stderr, "%s\n", err);
        const int r = count - 1, g = count - 2, b = count - 3; /* positions of R, G, B in names */
        bool same = depth.data && vec.data && depth.width == w && depth.height == h && vec.channels == 3;
        for (size_t p = 0; same && p < (size_t)w * h; ++p) {
            const float *in = values + p * (size_t)count;
            same = depth.data[p] == in[r] && vec.data[3 * p] == in[r] && vec.data[3 * p + 1] == in[g] &&
                   vec.data[3 * p + 2] == in[b];
        }
        CHECK(same);
        cacao_img_free(&depth);
        cacao_img_free(&vec);
    }
    free(values);
}

/* Defect 2: small random images, mixing runs (compressible) with noise (not), so that some of the
 * 16-line ZIP chunks compress to about their raw size; every one must read back bit for bit. */
static void exr_random_round_trips(void) {
    uint64_t state = 0x9e3779b97f4a7c15ull;
    int failures = 0;
    for (int n = 0; n < 3000 && failures < 5; ++n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const uint32_t w = 1 + (uint32_t)(state >> 60), h = 1 + (uint32_t)((state >> 54) % 40);
        const uint32_t channels = (state >> 40) & 1 ? 3 : 1;
        const uint32_t noise_percent = (uint32_t)((state >> 30) % 101);
        cacao_img img = {w, h, channels, malloc(sizeof(float) * w * h * channels)}, back = {0};
        for (size_t i = 0; i < (size_t)w * h * channels; ++i) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            uint32_t bits = (uint32_t)(state >> 32);
            if ((state >> 20) % 100 >= noise_percent) bits = 0x3f800000u;  /* 1.0 */
            if ((bits & 0x7f800000u) == 0x7f800000u) bits &= ~0x00800000u; /* no NaN/inf: exact compare */
            memcpy(&img.data[i], &bits, sizeof bits);
        }
        char err[512] = "";
        const char *path = in_dir("random.exr");
        const bool ok = cacao_exr_write(path, &img, err, sizeof err) &&
                        (channels == 3 ? cacao_exr_read_vector(path, &back, err, sizeof err)
                                       : cacao_exr_read_scalar(path, &back, err, sizeof err)) &&
                        memcmp(img.data, back.data, sizeof(float) * w * h * channels) == 0;
        if (!ok) {
            fprintf(stderr, "random image %d (%ux%u, %u channels, %u%% noise) did not round-trip: %s\n", n, w, h,
                    channels, noise_percent, err);
            ++failures;
        }
        cacao_img_free(&img);
        cacao_img_free(&back);
    }
    CHECK(failures == 0);
}

static uint32_t crc32_of(const unsigned char *bytes, size_t n) {
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        crc ^= bytes[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1)));
    }
    return ~crc;
}

static void put32(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* Defect 6: signature, IHDR 16384x16384 RGBA 16-bit, an empty IDAT and IEND: 65 bytes. */
static void png_huge_header(void) {
    unsigned char file[65] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char *ihdr = file + 8;
    put32(ihdr, 13);
    memcpy(ihdr + 4, "IHDR", 4);
    put32(ihdr + 8, 16384);
    put32(ihdr + 12, 16384);
    ihdr[16] = 16; /* bits */
    ihdr[17] = 6;  /* RGBA */
    put32(ihdr + 21, crc32_of(ihdr + 4, 17));
    unsigned char *idat = ihdr + 25;
    put32(idat, 8);
    memcpy(idat + 4, "IDAT", 4);
    memcpy(idat + 8, "\x78\x9c\x03\x00\x00\x00\x00\x01", 8); /* an empty zlib stream */
    put32(idat + 16, crc32_of(idat + 4, 12));
    unsigned char *iend = idat + 20;
    memcpy(iend + 4, "IEND", 4);
    put32(iend + 8, crc32_of(iend + 4, 4));
    FILE *f = fopen(in_dir("huge.png"), "wb");
    CHECK(f && fwrite(file, 1, sizeof file, f) == sizeof file);
    if (f) fclose(f);
    struct rlimit old;
#ifdef __SANITIZE_ADDRESS__
    const bool capped = false; /* ASan reserves far more address space than the cap */
#else
    const bool capped =
        getrlimit(RLIMIT_AS, &old) == 0 && setrlimit(RLIMIT_AS, &(struct rlimit){(rlim_t)1 << 30, old.rlim_max}) == 0;
#endif
    cacao_img img;
    char err[512] = "";
    CHECK(!cacao_png_read(in_dir("huge.png"), &img, NULL, err, sizeof err));
    if (capped) setrlimit(RLIMIT_AS, &old);
    printf("huge.png: %s\n", err);
    CHECK(contains(err, "huge.png") && contains(err, "file can hold"));
}

static void on_alarm(int sig) {
    (void)sig;
    static const char message[] = "test_robust_io: a reader blocked on a FIFO\n";
    if (write(2, message, sizeof message - 1) < 0) _exit(2);
    _exit(1);
}

typedef bool (*reader)(const char *, cacao_img *, char *, size_t);

static bool read_png(const char *path, cacao_img *out, char *err, size_t n) {
    return cacao_png_read(path, out, NULL, err, n);
}

static bool read_camera(const char *path, cacao_img *out, char *err, size_t n) {
    cacao_camera_file camera;
    memset(out, 0, sizeof *out);
    return cacao_camera_json_read(path, &camera, err, n);
}

/* Defects 7 and 8: a FIFO, a directory and a missing file, given to every reader. */
static void special_files(void) {
    static const struct {
        const char *ext;
        reader read;
    } readers[] = {{"pfm", cacao_pfm_read}, {"png", read_png}, {"exr", cacao_exr_read_scalar}, {"json", read_camera}};
    signal(SIGALRM, on_alarm);
    for (size_t i = 0; i < sizeof readers / sizeof readers[0]; ++i) {
        char name[64], err[512] = "";
        cacao_img img;
        snprintf(name, sizeof name, "fifo.%s", readers[i].ext);
        CHECK(mkfifo(in_dir(name), 0600) == 0);
        alarm(10);
        CHECK(!readers[i].read(in_dir(name), &img, err, sizeof err));
        alarm(0);
        printf("%s\n", err);
        CHECK(contains(err, name) && contains(err, "not a regular file"));
        snprintf(name, sizeof name, "folder.%s", readers[i].ext);
        CHECK(mkdir(in_dir(name), 0700) == 0);
        CHECK(!readers[i].read(in_dir(name), &img, err, sizeof err));
        printf("%s\n", err);
        CHECK(contains(err, name) && contains(err, "is a directory"));
        snprintf(name, sizeof name, "missing.%s", readers[i].ext);
        CHECK(!readers[i].read(in_dir(name), &img, err, sizeof err));
        printf("%s\n", err);
        CHECK(contains(err, name) && contains(err, "cannot open") && contains(err, strerror(ENOENT)));
    }
}

/* Defect 8: an EXR whose channel names carry a newline and a terminal escape. */
static void escaped_names(void) {
    static const char *const names[] = {"\x1b[31mred\n", "two\nlines"};
    float values[4 * 2] = {0};
    CHECK(write_half_exr(in_dir("evil.exr"), 2, 2, 2, names, values));
    cacao_img img;
    char err[512] = "";
    CHECK(!cacao_exr_read_scalar(in_dir("evil.exr"), &img, err, sizeof err));
    printf("%s\n", err);
    CHECK(contains(err, "wrong channels") && contains(err, "\\x1b[31mred\\x0a") && !has_control_bytes(err));
    char escaped[64];
    cacao_escape_text("a\\b\tc\xff", escaped, sizeof escaped);
    CHECK(strcmp(escaped, "a\\x5cb\\x09c\\xff") == 0);
}

static void write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    CHECK(f && fputs(text, f) >= 0);
    if (f) fclose(f);
}

/* Defect 9: duplicate keys and trailing text in a camera file. */
static void json_objects(void) {
    cacao_camera_file camera;
    char err[512] = "";
    write_text(in_dir("good.json"), "{\"fov_y_deg\": 60, \"near\": 0.1, \"far\": 100}\n\n");
    CHECK(cacao_camera_json_read(in_dir("good.json"), &camera, err, sizeof err));
    write_text(in_dir("twice.json"), "{\"fov_y_deg\": 60, \"near\": 0.1, \"far\": 100, \"near\": 5}");
    CHECK(!cacao_camera_json_read(in_dir("twice.json"), &camera, err, sizeof err));
    printf("%s\n", err);
    CHECK(contains(err, "twice.json") && contains(err, "\"near\" is given more than once"));
    write_text(in_dir("trailing.json"), "{\"fov_y_deg\": 60, \"near\": 0.1, \"far\": 100}\n  x");
    CHECK(!cacao_camera_json_read(in_dir("trailing.json"), &camera, err, sizeof err));
    printf("%s\n", err);
    CHECK(contains(err, "trailing.json") && contains(err, "line 2, column 3"));
}

int main(int argc, char **argv) {
    test_scratch_dir(argc, argv, dir, sizeof dir);
    exr_rgba_half();
    exr_random_round_trips();
    png_huge_header();
    special_files();
    escaped_names();
    json_objects();
    return test_report("test_robust_io");
}
