/* test_pipeline_cache - the caller's VkPipelineCache (cacao_context_desc.pipeline_cache) is used
 * for every pipeline the plan creates, and never changes a result:
 *   - a context on an empty cache and a context on a cache started from the first one's data give
 *     AO bit-identical to a context without a cache, at every quality (native and downsampled);
 *   - after a context's resize the cache's data starts with a valid header for this device and the
 *     contexts with and without a cache create the same number of pipelines;
 * and, run as `test_pipeline_cache --warm` (test pipeline_cache_warm), a context whose cache starts
 * from a previous context's data creates its pipelines measurably faster (median of 5 interleaved
 * trials at most 0.8 of the empty cache's). A driver whose cache data is only the 32-byte header
 * (Mesa 22.3's lavapipe: it compiles at pipeline creation and keeps nothing) cannot show that: the
 * warm test then reports itself skipped with the measured figures. */
#include <string.h>

#include "gpu_scene.h"

static const cacao_quality qualities[] = {CACAO_QUALITY_LOWEST, CACAO_QUALITY_LOW, CACAO_QUALITY_MEDIUM,
                                          CACAO_QUALITY_HIGH, CACAO_QUALITY_HIGHEST};

/* Runs one frame on a new context created on cache (VK_NULL_HANDLE: none). */
static bool run_on_cache(vkdev *dev, VkPipelineCache cache, const cacao_settings *s, const vkdev_frame *f, float *ao,
                         uint32_t *pipelines) {
    cacao_context *ctx = NULL;
    cacao_memory_info memory = {0};
    bool ok = vkdev_context_create_on_cache(dev, cache, &ctx) == CACAO_SUCCESS &&
              cacao_context_set_settings(ctx, s) == CACAO_SUCCESS &&
              cacao_context_resize(ctx, f->width, f->height, &memory) == CACAO_SUCCESS;
    char err[512] = "";
    if (ok) ok = vkdev_run_context(dev, ctx, f, 1, ao, NULL, err, sizeof err) == CACAO_SUCCESS;
    if (!ok) fprintf(stderr, "run on a %s failed: %s %s\n", cache ? "cache" : "context without a cache",
                     ctx ? cacao_context_last_error(ctx) : "", err);
    *pipelines = memory.pipeline_count;
    cacao_context_destroy(ctx);
    CHECK(ok);
    return ok;
}

static VkPipelineCache make_cache(vkdev *dev, const void *data, size_t size) {
    const VkPipelineCacheCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO, .initialDataSize = size, .pInitialData = data};
    VkPipelineCache cache = VK_NULL_HANDLE;
    CHECK(vkCreatePipelineCache(dev->device, &info, NULL, &cache) == VK_SUCCESS);
    return cache;
}

static void test_same_output(vkdev *dev) {
    scene_buffers sb;
    scene_buffers_default(160, 96, &sb);
    const vkdev_frame f = scene_frame(&sb, false, false);
    const size_t n = (size_t)f.width * f.height;
    float *plain = malloc(n * sizeof(float)), *cold = malloc(n * sizeof(float)), *warm = malloc(n * sizeof(float));
    for (int q = 0; q < 5; ++q)
        for (int ds = 0; ds < 2; ++ds) {
            const cacao_settings s = {.quality = qualities[q], .downsample = ds, .generate_normals = true};
            uint32_t p_plain = 0, p_cold = 0, p_warm = 0;
            VkPipelineCache first = make_cache(dev, NULL, 0);
            bool ok = run_on_cache(dev, VK_NULL_HANDLE, &s, &f, plain, &p_plain) &&
                      run_on_cache(dev, first, &s, &f, cold, &p_cold);
            size_t size = 0;
            CHECK(vkGetPipelineCacheData(dev->device, first, &size, NULL) == VK_SUCCESS);
            uint8_t *data = malloc(size ? size : 1);
            CHECK(vkGetPipelineCacheData(dev->device, first, &size, data) == VK_SUCCESS);
            CHECK(size >= VKDEV_PIPELINE_CACHE_HEADER_BYTES);
            VkPipelineCache second = make_cache(dev, data, size);
            ok = ok && run_on_cache(dev, second, &s, &f, warm, &p_warm);
            if (ok) {
                CHECK(p_plain > 0 && p_cold == p_plain && p_warm == p_plain);
                CHECK(memcmp(plain, cold, n * sizeof(float)) == 0);
                CHECK(memcmp(plain, warm, n * sizeof(float)) == 0);
            }
            vkDestroyPipelineCache(dev->device, first, NULL);
            vkDestroyPipelineCache(dev->device, second, NULL);
            free(data);
        }
    free(plain);
    free(cold);
    free(warm);
    scene_buffers_free(&sb);
}

/* The cache's header through the helper the bench uses (vkdev_time_pipeline_cache). */
static void test_header(vkdev *dev) {
    char err[512];
    vkdev_cache_timing t;
    const cacao_settings s = {.quality = CACAO_QUALITY_HIGH};
    CHECK(vkdev_time_pipeline_cache(dev, &s, 320, 180, 1, &t, err, sizeof err) == CACAO_SUCCESS);
    CHECK(t.header_valid && t.cache_bytes >= VKDEV_PIPELINE_CACHE_HEADER_BYTES && t.pipeline_count > 0);
}

/* Returns the exit code: 0 passed, 1 failed, TEST_SKIP_CODE when the driver's cache holds nothing. */
static int test_warm(vkdev *dev) {
    char err[512];
    vkdev_cache_timing t;
    const cacao_settings s = {.quality = CACAO_QUALITY_HIGHEST};
    if (vkdev_time_pipeline_cache(dev, &s, 960, 540, 5, &t, err, sizeof err) != CACAO_SUCCESS) {
        fprintf(stderr, "pipeline cache timing failed: %s\n", err);
        return 1;
    }
    printf("%s: %u pipelines, cache data %zu bytes; creation median (min..max) ms: no cache %.1f (%.1f..%.1f), "
           "empty cache %.1f (%.1f..%.1f), warm cache %.1f (%.1f..%.1f)\n",
           dev->device_name, t.pipeline_count, t.cache_bytes, t.no_cache.median_ms, t.no_cache.min_ms,
           t.no_cache.max_ms, t.cold_cache.median_ms, t.cold_cache.min_ms, t.cold_cache.max_ms,
           t.warm_cache.median_ms, t.warm_cache.min_ms, t.warm_cache.max_ms);
    if (t.cache_bytes <= VKDEV_PIPELINE_CACHE_HEADER_BYTES) {
        printf("skipped: this driver's pipeline cache keeps only its %u-byte header, so a warm cache cannot "
               "be faster here\n",
               VKDEV_PIPELINE_CACHE_HEADER_BYTES);
        return TEST_SKIP_CODE;
    }
    CHECK(t.warm_cache.median_ms <= 0.8 * t.cold_cache.median_ms);
    return test_failures ? 1 : 0;
}

int main(int argc, char **argv) {
    const bool warm = argc > 1 && strcmp(argv[1], "--warm") == 0;
    vkdev dev;
    open_device(&dev);
    int code = 0;
    if (warm)
        code = test_warm(&dev);
    else {
        test_same_output(&dev);
        test_header(&dev);
    }
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    if (test_failures) return test_report("test_pipeline_cache");
    return code == TEST_SKIP_CODE ? code : test_report("test_pipeline_cache");
}
