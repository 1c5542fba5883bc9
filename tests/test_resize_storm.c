/* test_resize_storm - one context through 1,000 resizes (issue 32, "Faults and load"): random
 * sizes from 1x1 to 2048x2048 (always 1x1, 2048x2048, 1x2048 and 2048x1), random settings
 * (estimator, quality, downsampling, blur, precision, normals given or generated, every tile)
 * set before some of the resizes, and after each resize one frame recorded, submitted and waited
 * on, into an output image made for that size. A context that an engine resizes all day must
 * hold exactly what its current plan needs and nothing of earlier sizes, so:
 *   - every frame succeeds, writes AO in [0,1] to every pixel, and the validation layer (with
 *     synchronization validation) reports nothing;
 *   - device memory: cacao_memory_info.total_bytes after each resize is the sum of the memory
 *     requirements the device states for the plan's own images and buffers (created here, apart,
 *     from the plan's description), plus at most the alignment padding of placing them in one
 *     block (each one's alignment, and one bufferImageGranularity page); in 1 or 2 allocations
 *     (cacao_memory_info.allocation_count, cacao.h's promise); its image count the plan's; and
 *     the figure is the same whenever a size and settings come back;
 *   - host memory: the context's allocations go through counting VkAllocationCallbacks; after
 *     each resize + frame the live count and bytes are those of the first time that size and
 *     settings ran (a leak grows them, as each resize frees and recreates), and nothing is live
 *     once the context is destroyed;
 *   - now and then the frame is compared, byte for byte, with a fresh context's at the same size
 *     and settings: whatever a resize keeps must not change the result.
 * Under ASan (the sanitizer build) LeakSanitizer checks the whole run at exit, as for the soak.
 * The seed is printed; `test_resize_storm SEED` reruns one storm. */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <time.h>

#include "counting_allocator.h"
#include "gpu_scene.h"

#define STORM_RESIZES 1000
#define STORM_MAX_SIZE 2048
#define STORM_SETTINGS_POOL 24
#define STORM_REFERENCE_EVERY 40         /* a fresh-context comparison every so many steps ... */
#define STORM_REFERENCE_MAX_PIXELS 65536 /* ... at sizes up to this many pixels */
#define STORM_DEFAULT_SEED 0x32u         /* issue 32 */
#define STORM_RENDER_MAX 256             /* inputs are ray-cast up to this size a side (see storm_inputs) */

/* ---- A small seeded PRNG (splitmix64): the storm is reproducible from its seed ---- */

static uint64_t rng_next(uint64_t *state) {
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in lo..hi (inclusive). */
static uint32_t rng_range(uint64_t *state, uint32_t lo, uint32_t hi) {
    return lo + (uint32_t)(rng_next(state) % ((uint64_t)hi - lo + 1));
}

/* True with probability percent / 100. */
static bool rng_chance(uint64_t *state, uint32_t percent) { return rng_next(state) % 100 < percent; }

/* ---- Settings and sizes ---- */

/* Random settings; radius is the scene's. */
static cacao_settings random_settings(uint64_t *rng, float radius) {
    cacao_settings s = {0};
    const uint32_t pick = rng_range(rng, 0, 9);
    s.estimator = pick < 6 ? CACAO_ESTIMATOR_CACAO : pick < 8 ? CACAO_ESTIMATOR_GTAO : CACAO_ESTIMATOR_BITMASK;
    s.quality = (cacao_quality)rng_range(rng, CACAO_QUALITY_LOWEST, CACAO_QUALITY_HIGHEST);
    static const int blurs[] = {CACAO_BLUR_NONE, 0, 1, 2, 3, 4, 8};
    s.blur_pass_count = blurs[rng_range(rng, 0, sizeof blurs / sizeof blurs[0] - 1)];
    s.precision = rng_chance(rng, 40) ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32;
    s.generate_normals = rng_chance(rng, 50);
    s.radius = radius * (0.5f + 0.25f * (float)rng_range(rng, 0, 4));
    if (s.estimator == CACAO_ESTIMATOR_CACAO) {
        s.downsample = rng_chance(rng, 35);
        s.compute_all_tiles = rng_chance(rng, 25);
    } else {
        s.visibility = rng_chance(rng, 30) ? CACAO_VISIBILITY_BINARY : CACAO_VISIBILITY_FALLOFF;
    }
    return s;
}

/* Settings in a few words for the summary: "cacao highest ds blur 2 fp16 gen all" (blur 0: the
 * default, -1: none). */
static void settings_label(const cacao_settings *s, char *out, size_t n) {
    snprintf(out, n, "%s %s%s blur %d %s%s%s", cacao_estimator_name(s->estimator), cacao_quality_name(s->quality),
             s->downsample ? " ds" : "", s->blur_pass_count, cacao_precision_name(s->precision),
             s->generate_normals ? " gen" : "", s->compute_all_tiles ? " all" : "");
}

/* Sizes: lavapipe's frame time grows with the pixels, so most are at most 256 a side, some up to
 * 768, a few up to the limit (each side drawn alone: long thin ones come up too). */
static void random_size(uint64_t *rng, uint32_t *w, uint32_t *h) {
    const uint32_t band = rng_range(rng, 0, 99);
    const uint32_t top = band < 85 ? 256 : band < 97 ? 768 : STORM_MAX_SIZE;
    *w = rng_range(rng, 1, top);
    *h = rng_range(rng, 1, top);
}

/* ---- What a plan needs on this device, found apart from the context ---- */

/* The memory requirements of the plan's images and buffers, created here (images with the usage
 * the context gives them: storage, sampled, copied from; buffers with every usage a plan's buffer
 * has) and destroyed again: what total_bytes must be, less the padding of placing them in one
 * block, of which *slack is a bound (the sum of their alignments). */
static uint64_t plan_device_bytes(vkdev *dev, const cacao_plan *plan, uint64_t *slack) {
    uint64_t total = 0;
    *slack = 0;
    for (uint32_t i = 0; i < plan->image_count; ++i) {
        const cacao_plan_image *pi = &plan->images[i];
        const VkImageCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
            .imageType = VK_IMAGE_TYPE_2D,
            .format = pi->format,
            .extent = {pi->width, pi->height, 1},
            .mipLevels = 1,
            .arrayLayers = pi->layers,
            .samples = VK_SAMPLE_COUNT_1_BIT,
            .tiling = VK_IMAGE_TILING_OPTIMAL,
            .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
        };
        VkImage image;
        if (vkCreateImage(dev->device, &info, NULL, &image) != VK_SUCCESS) return 0;
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(dev->device, image, &req);
        vkDestroyImage(dev->device, image, NULL);
        total += req.size;
        *slack += req.alignment;
    }
    for (uint32_t i = 0; i < plan->buffer_count; ++i) {
        const VkBufferCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
            .size = plan->buffers[i].bytes,
            .usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        };
        VkBuffer buffer;
        if (vkCreateBuffer(dev->device, &info, NULL, &buffer) != VK_SUCCESS) return 0;
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(dev->device, buffer, &req);
        vkDestroyBuffer(dev->device, buffer, NULL);
        total += req.size;
        *slack += req.alignment;
    }
    return total;
}

/* ---- The storm ---- */

/* A size and settings the storm has run, with what it held after the first frame there. */
typedef struct storm_config {
    uint32_t width, height, settings;
    uint64_t device_bytes;
    int64_t host_count, host_bytes;
} storm_config;

typedef struct storm_stats {
    uint32_t resizes, frames, settings_changes, revisits, large_frames, references, extremes, packed;
    uint64_t device_min, device_max;
    int64_t host_count_min, host_count_max, host_bytes_min, host_bytes_max;
    double seconds, resize_s, inputs_s, frame_s, reference_s; /* wall time, in all and by part */
} storm_stats;

typedef struct storm {
    vkdev dev; /* the validation layer reports into it: the storm stays where it is allocated */
    VkDeviceSize granularity; /* the device's bufferImageGranularity */
    host_counter counter;
    VkAllocationCallbacks callbacks;
    cacao_context *ctx;
    uint64_t rng;
    cacao_settings pool[STORM_SETTINGS_POOL]; /* the settings steps choose from */
    uint32_t sizes[STORM_RESIZES][2];         /* each step's size, unless it returns to an earlier one */
    bool extreme[STORM_RESIZES];              /* the step runs one of the four extreme sizes */
    storm_config configs[STORM_RESIZES];
    uint32_t config_count, current; /* current: the pool index the context has */
    float *ao, *reference;
    storm_stats st;
} storm;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static storm_config *find_config(storm *sm, uint32_t w, uint32_t h, uint32_t settings) {
    for (uint32_t i = 0; i < sm->config_count; ++i) {
        storm_config *c = &sm->configs[i];
        if (c->width == w && c->height == h && c->settings == settings) return c;
    }
    return NULL;
}

/* The settings pool and every step's size, the four extremes at random steps among the first 100
 * (so that a leak they cause shows in the rest). */
static void storm_plan(storm *sm) {
    const cacao_scene scene = cacao_default_scene(64, 64);
    for (int i = 0; i < STORM_SETTINGS_POOL; ++i) sm->pool[i] = random_settings(&sm->rng, (float)scene.ao_radius_world);
    for (int i = 0; i < STORM_RESIZES; ++i) random_size(&sm->rng, &sm->sizes[i][0], &sm->sizes[i][1]);
    static const uint32_t extremes[4][2] = {
        {1, 1}, {STORM_MAX_SIZE, STORM_MAX_SIZE}, {1, STORM_MAX_SIZE}, {STORM_MAX_SIZE, 1}};
    for (uint32_t e = 0; e < 4; ++e) {
        const uint32_t at = rng_range(&sm->rng, 25 * e, 25 * e + 24);
        sm->sizes[at][0] = extremes[e][0];
        sm->sizes[at][1] = extremes[e][1];
        sm->extreme[at] = true;
    }
}

/* Step step's size and settings: its own size, or now and then a size and settings run before;
 * new settings from the pool now and then. */
static void storm_pick(storm *sm, uint32_t step, uint32_t *w, uint32_t *h, uint32_t *settings) {
    *w = sm->sizes[step][0], *h = sm->sizes[step][1], *settings = sm->current;
    if (step > 0 && !sm->extreme[step] && rng_chance(&sm->rng, 25)) {
        const storm_config *c = &sm->configs[rng_range(&sm->rng, 0, sm->config_count - 1)];
        *w = c->width, *h = c->height, *settings = c->settings;
        sm->st.revisits++;
    } else if (step == 0 || rng_chance(&sm->rng, 20)) {
        *settings = rng_range(&sm->rng, 0, STORM_SETTINGS_POOL - 1);
    }
    sm->st.extremes += sm->extreme[step];
}

/* Sets the settings if they change and resizes; the context must then hold what the plan's
 * images and buffers need on this device, no more. */
static bool storm_resize(storm *sm, uint32_t step, uint32_t w, uint32_t h, uint32_t settings, cacao_memory_info *info) {
    if (settings != sm->current) {
        CHECK(cacao_context_set_settings(sm->ctx, &sm->pool[settings]) == CACAO_SUCCESS);
        sm->current = settings;
        sm->st.settings_changes++;
    }
    const double t = now_s();
    const cacao_result r = cacao_context_resize(sm->ctx, w, h, info);
    sm->st.resize_s += now_s() - t;
    if (r != CACAO_SUCCESS) {
        fprintf(stderr, "step %u: resize to %ux%u: %s: %s\n", step, w, h, cacao_result_string(r),
                cacao_context_last_error(sm->ctx));
        ++test_failures;
        return false;
    }
    sm->st.resizes++;
    const cacao_plan *plan = cacao_context_plan(sm->ctx);
    CHECK(plan && plan->width == w && plan->height == h && info->image_count == plan->image_count);
    uint64_t slack = 0;
    const uint64_t needed = plan ? plan_device_bytes(&sm->dev, plan, &slack) : 0;
    slack += sm->granularity; /* the first buffer after an image starts a new page */
    CHECK(info->allocation_count >= 1 && info->allocation_count <= 2);
    if (!plan || info->total_bytes < needed || info->total_bytes > needed + slack ||
        info->total_bytes < plan->total_bytes) {
        fprintf(stderr,
                "step %u: %ux%u: the context holds %llu bytes; its plan's images and buffers need %llu "
                "(%llu packed)\n",
                step, w, h, (unsigned long long)info->total_bytes, (unsigned long long)needed,
                plan ? (unsigned long long)plan->total_bytes : 0ull);
        ++test_failures;
    }
    sm->st.packed += plan && info->total_bytes == plan->total_bytes;
    return true;
}

/* The frame's inputs at w x h: the default scene ray-cast at that size, or, above
 * STORM_RENDER_MAX a side, at 1/k of it (k the smallest integer that brings it there) with each
 * texel repeated k x k: ray-casting 2048x2048 on the CPU (in the sanitizer build above all) costs
 * more than the frame it feeds, and the storm is about sizes, not about the picture. */
static void storm_inputs(uint32_t w, uint32_t h, scene_buffers *out) {
    const uint32_t side = w > h ? w : h, k = (side + STORM_RENDER_MAX - 1) / STORM_RENDER_MAX;
    if (k == 1) {
        scene_buffers_default(w, h, out);
        return;
    }
    scene_buffers low;
    scene_buffers_default((w + k - 1) / k, (h + k - 1) / k, &low);
    *out = low; /* the projections */
    out->width = w;
    out->height = h;
    const size_t n = (size_t)w * h;
    out->depth = malloc(n * sizeof(float));
    out->depth_reversed = malloc(n * sizeof(float));
    out->normals = malloc(3 * n * sizeof(float));
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = (size_t)y * w + x, j = (size_t)(y / k) * low.width + x / k;
            out->depth[i] = low.depth[j];
            out->depth_reversed[i] = low.depth_reversed[j];
            memcpy(&out->normals[3 * i], &low.normals[3 * j], 3 * sizeof(float));
        }
    scene_buffers_free(&low);
}

/* A fresh context's frame at this size and settings equals the storm context's, byte for byte. */
static void check_against_fresh(storm *sm, uint32_t step, const vkdev_frame *f) {
    char err[512];
    const double t = now_s();
    const cacao_result r = vkdev_run(&sm->dev, &sm->pool[sm->current], f, 1, sm->reference, NULL, err, sizeof err);
    sm->st.reference_s += now_s() - t;
    sm->st.references++;
    CHECK(r == CACAO_SUCCESS);
    if (r == CACAO_SUCCESS && memcmp(sm->ao, sm->reference, sizeof(float) * f->width * f->height) != 0) {
        fprintf(stderr, "step %u: %ux%u: the storm context's AO differs from a fresh context's\n", step, f->width,
                f->height);
        ++test_failures;
    }
}

/* One frame at the context's size and settings, recorded, submitted and waited on (vkdev makes
 * the inputs and the output image for the size); AO in [0,1] everywhere. */
static bool storm_frame(storm *sm, uint32_t step, uint32_t w, uint32_t h) {
    scene_buffers scene;
    double t = now_s();
    storm_inputs(w, h, &scene);
    sm->st.inputs_s += now_s() - t;
    const vkdev_frame f = scene_frame(&scene, false, !sm->pool[sm->current].generate_normals);
    char err[512];
    t = now_s();
    const cacao_result r = vkdev_run_context(&sm->dev, sm->ctx, &f, 1, sm->ao, NULL, err, sizeof err);
    sm->st.frame_s += now_s() - t;
    if (r != CACAO_SUCCESS) {
        fprintf(stderr, "step %u: frame at %ux%u: %s: %s\n", step, w, h, cacao_result_string(r), err);
        ++test_failures;
    } else {
        sm->st.frames++;
        sm->st.large_frames += (uint64_t)w * h > 256 * 256;
        CHECK(all_finite_unit(sm->ao, (size_t)w * h));
        if (step % STORM_REFERENCE_EVERY == 0 && (uint64_t)w * h <= STORM_REFERENCE_MAX_PIXELS)
            check_against_fresh(sm, step, &f);
    }
    scene_buffers_free(&scene);
    return r == CACAO_SUCCESS;
}

/* After the frame: the device bytes and live host allocations are those of the first time this
 * size and settings ran (recorded then). */
static void storm_memory(storm *sm, uint32_t step, uint32_t w, uint32_t h, uint64_t device_bytes) {
    const int64_t count = __atomic_load_n(&sm->counter.live_count, __ATOMIC_RELAXED);
    const int64_t bytes = __atomic_load_n(&sm->counter.live_bytes, __ATOMIC_RELAXED);
    const storm_config *seen = find_config(sm, w, h, sm->current);
    if (!seen) {
        sm->configs[sm->config_count++] = (storm_config){w, h, sm->current, device_bytes, count, bytes};
    } else if (seen->device_bytes != device_bytes || seen->host_count != count || seen->host_bytes != bytes) {
        fprintf(stderr,
                "step %u: back at %ux%u, settings %u: device %llu bytes (was %llu), host %lld live "
                "allocations of %lld bytes (were %lld of %lld)\n",
                step, w, h, sm->current, (unsigned long long)device_bytes, (unsigned long long)seen->device_bytes,
                (long long)count, (long long)bytes, (long long)seen->host_count, (long long)seen->host_bytes);
        ++test_failures;
    }
    storm_stats *st = &sm->st;
    if (device_bytes < st->device_min) st->device_min = device_bytes;
    if (device_bytes > st->device_max) st->device_max = device_bytes;
    if (count < st->host_count_min) st->host_count_min = count;
    if (count > st->host_count_max) st->host_count_max = count;
    if (bytes < st->host_bytes_min) st->host_bytes_min = bytes;
    if (bytes > st->host_bytes_max) st->host_bytes_max = bytes;
}

static void storm_run(storm *sm) {
    const double start = now_s();
    for (uint32_t step = 0; step < STORM_RESIZES && test_failures < 10; ++step) {
        uint32_t w, h, settings;
        storm_pick(sm, step, &w, &h, &settings);
        cacao_memory_info info;
        if (storm_resize(sm, step, w, h, settings, &info) && storm_frame(sm, step, w, h))
            storm_memory(sm, step, w, h, info.total_bytes);
    }
    sm->st.seconds = now_s() - start;
}

static void storm_print(const storm *sm, uint64_t seed, int64_t final_count, int64_t final_bytes,
                        const storm_config *first, int64_t after_destroy) {
    const storm_stats *st = &sm->st;
    printf("resize storm summary (seed 0x%llx)\n", (unsigned long long)seed);
    printf("  %-38s %u (the 4 extreme sizes: %u)\n", "resizes", st->resizes, st->extremes);
    printf("  %-38s %u (%u above 256x256 pixels)\n", "frames", st->frames, st->large_frames);
    printf("  %-38s %u\n", "settings changes", st->settings_changes);
    printf("  %-38s %u (%u distinct sizes+settings)\n", "returns to an earlier size+settings", st->revisits,
           sm->config_count);
    printf("  %-38s %u\n", "frames compared with a fresh context", st->references);
    printf("  %-38s %.1f (resizes %.1f, inputs %.1f, frames %.1f, fresh contexts %.1f)\n", "seconds", st->seconds,
           st->resize_s, st->inputs_s, st->frame_s, st->reference_s);
    printf("  %-38s %llu .. %llu (= the plan's packed bytes at %u resizes)\n", "device bytes min .. max",
           (unsigned long long)st->device_min, (unsigned long long)st->device_max, st->packed);
    printf("  %-38s %lld .. %lld, final %lld (first pass there: %lld)\n", "host live allocations min .. max",
           (long long)st->host_count_min, (long long)st->host_count_max, (long long)final_count,
           first ? (long long)first->host_count : -1LL);
    printf("  %-38s %lld .. %lld, final %lld (first pass there: %lld)\n", "host live bytes min .. max",
           (long long)st->host_bytes_min, (long long)st->host_bytes_max, (long long)final_bytes,
           first ? (long long)first->host_bytes : -1LL);
    printf("  %-38s %lld (%lld allocations in all)\n", "host live after destroy", (long long)after_destroy,
           (long long)sm->counter.total_count);
    printf("  %-38s %u\n", "validation messages", sm->dev.validation_messages);
    char label[128];
    settings_label(&sm->pool[sm->current], label, sizeof label);
    printf("  last settings: %s\n", label);
}

int main(int argc, char **argv) {
    const uint64_t seed = argc > 1 ? strtoull(argv[1], NULL, 0) : STORM_DEFAULT_SEED;
    printf("resize storm: seed 0x%llx (rerun: test_resize_storm 0x%llx)\n", (unsigned long long)seed,
           (unsigned long long)seed);
    storm *sm = calloc(1, sizeof *sm);
    sm->rng = seed;
    sm->current = UINT32_MAX;
    sm->st = (storm_stats){.device_min = UINT64_MAX, .host_count_min = INT64_MAX, .host_bytes_min = INT64_MAX};
    sm->ao = malloc(sizeof(float) * STORM_MAX_SIZE * STORM_MAX_SIZE);
    sm->reference = malloc(sizeof(float) * STORM_REFERENCE_MAX_PIXELS);
    storm_plan(sm);
    open_device(&sm->dev);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(sm->dev.physical_device, &props);
    sm->granularity = props.limits.bufferImageGranularity;
    sm->callbacks = counting_callbacks(&sm->counter);
    sm->dev.allocation_callbacks = &sm->callbacks; /* for the storm's context and the fresh ones */
    if (vkdev_context_create(&sm->dev, &sm->ctx) != CACAO_SUCCESS) {
        fprintf(stderr, "cannot create the context\n");
        return 1;
    }
    storm_run(sm);

    /* The end state is that of the first pass through its size and settings; destroyed, nothing. */
    const int64_t final_count = sm->counter.live_count, final_bytes = sm->counter.live_bytes;
    const cacao_plan *last = cacao_context_plan(sm->ctx);
    const storm_config *first = last ? find_config(sm, last->width, last->height, sm->current) : NULL;
    CHECK(first && first->host_count == final_count && first->host_bytes == final_bytes);
    cacao_context_destroy(sm->ctx);
    const int64_t after_destroy = sm->counter.live_count;
    CHECK(after_destroy == 0);
    vkdev_destroy(&sm->dev);
    CHECK(sm->dev.validation_messages == 0);
    CHECK(sm->st.resizes == STORM_RESIZES && sm->st.frames == STORM_RESIZES && sm->st.extremes == 4);
    storm_print(sm, seed, final_count, final_bytes, first, after_destroy);
    free(sm->ao);
    free(sm->reference);
    free(sm);
    return test_report("test_resize_storm");
}
