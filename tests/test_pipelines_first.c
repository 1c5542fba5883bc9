/* test_pipelines_first - pipelines created before any size is known (cacao_context_create_pipelines,
 * an engine's load-time warm-up), on lavapipe with validation:
 *   - they are the pipelines of the settings' plan: one per step, steps of one permutation sharing
 *     one, none for a clear step, as many as a resize of a fresh context creates; cacao_context_plan stays NULL and
 *     cacao_record refuses (NOT_READY) until a resize;
 *   - a later resize with the same settings keeps every one of them (the same handles, the same
 *     count) and its frame is bit-identical to a context that never called it;
 *   - calling it again with the same settings keeps them; after a settings change
 *     cacao_context_pipeline says none until it replaces them with the new plan's;
 * for every quality (native and downsampled) and both horizon estimators. */
#include <string.h>

#include "gpu_scene.h"

static void check_settings(vkdev *dev, const cacao_settings *s, const vkdev_frame *f, float *plain, float *warm) {
    cacao_context *fresh = NULL, *ctx = NULL;
    cacao_memory_info fresh_mem = {0}, warm_mem = {0}, resized_mem = {0};
    char err[512] = "";
    bool ok = vkdev_context_create(dev, &fresh) == CACAO_SUCCESS && cacao_context_set_settings(fresh, s) == CACAO_SUCCESS &&
              cacao_context_resize(fresh, f->width, f->height, &fresh_mem) == CACAO_SUCCESS &&
              vkdev_run_context(dev, fresh, f, 1, plain, NULL, err, sizeof err) == CACAO_SUCCESS;
    ok = ok && vkdev_context_create(dev, &ctx) == CACAO_SUCCESS && cacao_context_set_settings(ctx, s) == CACAO_SUCCESS;
    CHECK(ok);
    if (!ok) goto done;
    CHECK(cacao_context_pipeline(ctx, 0) == VK_NULL_HANDLE); /* none yet */
    CHECK(cacao_context_create_pipelines(ctx, &warm_mem) == CACAO_SUCCESS);
    CHECK(cacao_context_plan(ctx) == NULL);
    CHECK(warm_mem.pipeline_count == fresh_mem.pipeline_count && warm_mem.image_count == 0 && warm_mem.total_bytes == 0);
    const cacao_plan *plan = cacao_context_plan(fresh);
    VkPipeline before[CACAO_PLAN_MAX_STEPS] = {0};
    for (uint32_t i = 0; plan && i < plan->step_count; ++i) {
        before[i] = cacao_context_pipeline(ctx, i);
        CHECK((before[i] != VK_NULL_HANDLE) == !plan->steps[i].clear); /* a clear step has none */
        for (uint32_t j = 0; j < i && !plan->steps[i].clear; ++j) /* shared exactly where the permutation is the same */
            CHECK((before[j] == before[i]) == (strcmp(plan->steps[j].key_name, plan->steps[i].key_name) == 0));
    }
    CHECK(plan && cacao_context_pipeline(ctx, plan->step_count) == VK_NULL_HANDLE);
    cacao_memory_info again = {0};
    CHECK(cacao_context_create_pipelines(ctx, &again) == CACAO_SUCCESS && again.pipeline_count == warm_mem.pipeline_count);
    for (uint32_t i = 0; plan && i < plan->step_count; ++i) CHECK(cacao_context_pipeline(ctx, i) == before[i]);
    /* no frame before a resize */
    CHECK(vkdev_run_context(dev, ctx, f, 1, warm, NULL, err, sizeof err) == CACAO_ERROR_NOT_READY);
    err[0] = '\0'; /* the expected refusal */
    CHECK(cacao_context_resize(ctx, f->width, f->height, &resized_mem) == CACAO_SUCCESS);
    CHECK(resized_mem.pipeline_count == fresh_mem.pipeline_count && resized_mem.total_bytes == fresh_mem.total_bytes);
    for (uint32_t i = 0; plan && i < plan->step_count; ++i) CHECK(cacao_context_pipeline(ctx, i) == before[i]);
    CHECK(vkdev_run_context(dev, ctx, f, 1, warm, NULL, err, sizeof err) == CACAO_SUCCESS);
    CHECK(memcmp(plain, warm, sizeof(float) * f->width * f->height) == 0);
    /* other settings: the new plan's pipelines replace them */
    cacao_settings other = *s;
    other.blur_pass_count = s->blur_pass_count == 3 ? 5 : 3;
    CHECK(cacao_context_set_settings(ctx, &other) == CACAO_SUCCESS);
    CHECK(cacao_context_pipeline(ctx, 0) == VK_NULL_HANDLE); /* the old ones are not the new settings' */
    CHECK(cacao_context_create_pipelines(ctx, NULL) == CACAO_SUCCESS);
    CHECK(cacao_context_plan(ctx) == NULL);
    cacao_plan other_plan;
    CHECK(cacao_plan_build(&other, f->width, f->height, &other_plan, NULL, 0) == CACAO_SUCCESS);
    for (uint32_t i = 0; i < other_plan.step_count; ++i)
        CHECK((cacao_context_pipeline(ctx, i) != VK_NULL_HANDLE) == !other_plan.steps[i].clear);
    CHECK(cacao_context_pipeline(ctx, other_plan.step_count) == VK_NULL_HANDLE);
done:
    if (ctx && cacao_context_last_error(ctx)[0]) fprintf(stderr, "context: %s\n", cacao_context_last_error(ctx));
    if (err[0]) fprintf(stderr, "frame: %s\n", err);
    cacao_context_destroy(ctx);
    cacao_context_destroy(fresh);
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    scene_buffers sb;
    scene_buffers_default(96, 64, &sb);
    const vkdev_frame f = scene_frame(&sb, false, false);
    float *plain = malloc(sizeof(float) * f.width * f.height), *warm = malloc(sizeof(float) * f.width * f.height);
    unsigned configs = 0;
    for (int est = CACAO_ESTIMATOR_CACAO; est <= CACAO_ESTIMATOR_BITMASK; ++est)
        for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
            for (int ds = 0; ds < (est == CACAO_ESTIMATOR_CACAO ? 2 : 1); ++ds) {
                const cacao_settings s = {.estimator = (cacao_estimator)est, .quality = (cacao_quality)q,
                                          .downsample = ds != 0, .generate_normals = true};
                check_settings(&dev, &s, &f, plain, warm);
                ++configs;
            }
    printf("%u configurations: pipelines created first, kept by the resize, output bit-identical\n", configs);
    free(plain);
    free(warm);
    scene_buffers_free(&sb);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("pipelines_first");
}
