/* test_misuse - user errors return the documented result code and a last-error message naming the
 * offending field, and leave the context usable; nothing crashes. (Programmer errors inside the
 * library are asserts; these are all user errors.) "Usable" is checked on the very context that
 * took every error: a real frame on it must give exactly the image a fresh context gives for the
 * same settings and inputs (both run the same shaders on the same device, so every pixel agrees). */
#include <string.h>

#include "gpu_scene.h"

static void check_result(int line, const char *expr, cacao_result got, cacao_result want, const cacao_context *ctx,
                         const char *needle) {
    if (got != want) {
        fprintf(stderr, "line %d: %s returned '%s', expected '%s'\n", line, expr, cacao_result_string(got),
                cacao_result_string(want));
        ++test_failures;
    }
    if (ctx && needle && !strstr(cacao_context_last_error(ctx), needle)) {
        fprintf(stderr, "line %d: last error '%s' does not name '%s'\n", line, cacao_context_last_error(ctx), needle);
        ++test_failures;
    }
}
#define CHECK_RESULT(expr, want, ctx, needle) check_result(__LINE__, #expr, (expr), (want), (ctx), (needle))

static void test_settings_errors(void) {
    char err[256];
    cacao_settings out;
    struct {
        cacao_settings in;
        const char *field;
    } cases[] = {
        {{.radius = NAN}, "settings.radius"},
        {{.radius = -1.0f}, "settings.radius"},
        {{.shadow_power = INFINITY}, "settings.shadow_power"},
        {{.blur_pass_count = 9}, "settings.blur_pass_count"},
        {{.blur_pass_count = -2}, "settings.blur_pass_count"},
        {{.quality = (cacao_quality)6}, "settings.quality"},
        {{.quality = (cacao_quality)-1}, "settings.quality"},
        {{.precision = (cacao_precision)3}, "settings.precision"},
        {{.sharpness = 1.5f}, "settings.sharpness"},
        {{.fade_out_from = 10.0f, .fade_out_to = 5.0f}, "settings.fade_out_to"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        err[0] = 0;
        CHECK(cacao_settings_resolve(&cases[i].in, &out, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT);
        if (!strstr(err, cases[i].field)) fprintf(stderr, "message '%s' lacks '%s'\n", err, cases[i].field);
        CHECK(strstr(err, cases[i].field) != NULL);
    }
    /* Zero means default; CACAO_ZERO and CACAO_BLUR_NONE ask for a literal zero and stay encoded
     * in the resolved settings (test_settings_roundtrip checks they still mean zero). */
    CHECK(cacao_settings_resolve(&(cacao_settings){0}, &out, err, sizeof err) == CACAO_SUCCESS);
    CHECK(out.radius == 1.2f && out.blur_pass_count == 2 && out.quality == CACAO_QUALITY_HIGHEST &&
          out.precision == CACAO_PRECISION_FP32 && out.horizon_angle_threshold == 0.06f);
    CHECK(cacao_settings_resolve(
              &(cacao_settings){.horizon_angle_threshold = CACAO_ZERO, .blur_pass_count = CACAO_BLUR_NONE}, &out, err,
              sizeof err) == CACAO_SUCCESS);
    CHECK(out.horizon_angle_threshold == CACAO_ZERO && out.blur_pass_count == CACAO_BLUR_NONE);
    CHECK(cacao_settings_resolve(NULL, &out, err, sizeof err) == CACAO_ERROR_INVALID_ARGUMENT);
}

/* Returns the context that took every error (NULL if it could not be created). */
static cacao_context *test_context_errors(vkdev *dev) {
    cacao_context *ctx = NULL;
    CHECK_RESULT(cacao_context_create(NULL, &ctx), CACAO_ERROR_INVALID_ARGUMENT, (cacao_context *)NULL, NULL);
    CHECK(ctx == NULL);
    const cacao_context_desc desc = {.physical_device = dev->physical_device, .device = dev->device};
    CHECK_RESULT(cacao_context_create(&desc, NULL), CACAO_ERROR_INVALID_ARGUMENT, (cacao_context *)NULL, NULL);
    CHECK_RESULT(cacao_context_create(&(cacao_context_desc){.device = dev->device}, &ctx), CACAO_ERROR_INVALID_ARGUMENT,
                 (cacao_context *)NULL, NULL);
    /* With no context to ask, creation's message goes to desc.error, naming the field. */
    char create_error[128] = "";
    CHECK(cacao_context_create(&(cacao_context_desc){.device = dev->device, .error = create_error,
                                                    .error_size = sizeof create_error},
                               &ctx) == CACAO_ERROR_INVALID_ARGUMENT &&
          ctx == NULL && strstr(create_error, "context_desc.physical_device") != NULL);
    CHECK(cacao_context_create(&(cacao_context_desc){.physical_device = dev->physical_device, .device = dev->device,
                                                    .get_instance_proc_addr = vkGetInstanceProcAddr,
                                                    .error = create_error, .error_size = sizeof create_error},
                               &ctx) == CACAO_ERROR_INVALID_ARGUMENT &&
          ctx == NULL && strstr(create_error, "context_desc.instance") != NULL);
    CHECK_RESULT(cacao_context_create(&desc, &ctx), CACAO_SUCCESS, (cacao_context *)NULL, NULL);
    if (!ctx) return NULL;

    /* NULL context and inputs. */
    CHECK_RESULT(cacao_record(NULL, dev->cmd, NULL), CACAO_ERROR_INVALID_ARGUMENT, (cacao_context *)NULL, NULL);
    CHECK_RESULT(cacao_context_resize(NULL, 64, 64, NULL), CACAO_ERROR_INVALID_ARGUMENT, (cacao_context *)NULL, NULL);
    CHECK_RESULT(cacao_context_set_settings(NULL, &(cacao_settings){0}), CACAO_ERROR_INVALID_ARGUMENT,
                 (cacao_context *)NULL, NULL);
    CHECK(cacao_context_plan(ctx) == NULL);

    /* Recording before a resize. */
    cacao_inputs in = {0};
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_NOT_READY, ctx, "resize");

    /* Sizes: zero, too large (65536 and beyond the 16384 limit); 1x1 is the smallest that works. */
    CHECK_RESULT(cacao_context_resize(ctx, 0, 0, NULL), CACAO_ERROR_INVALID_SIZE, ctx, "size 0x0");
    CHECK_RESULT(cacao_context_resize(ctx, 65536, 64, NULL), CACAO_ERROR_INVALID_SIZE, ctx, "65536");
    CHECK_RESULT(cacao_context_resize(ctx, 64, 16385, NULL), CACAO_ERROR_INVALID_SIZE, ctx, "16385");
    CHECK_RESULT(cacao_context_resize(ctx, 5, 0, NULL), CACAO_ERROR_INVALID_SIZE, ctx, "size 5x0");
    CHECK_RESULT(cacao_context_resize(ctx, 1, 1, NULL), CACAO_SUCCESS, ctx, NULL);

    /* Bad settings are refused and the previous (default) settings stay in force. */
    CHECK_RESULT(cacao_context_set_settings(ctx, &(cacao_settings){.radius = NAN}), CACAO_ERROR_INVALID_ARGUMENT, ctx,
                 "settings.radius");
    CHECK_RESULT(cacao_context_set_settings(ctx, &(cacao_settings){.blur_pass_count = 9}), CACAO_ERROR_INVALID_ARGUMENT,
                 ctx, "settings.blur_pass_count");
    CHECK_RESULT(cacao_context_set_settings(ctx, &(cacao_settings){.quality = (cacao_quality)7}),
                 CACAO_ERROR_INVALID_ARGUMENT, ctx, "settings.quality");
    CHECK_RESULT(cacao_context_set_settings(ctx, NULL), CACAO_ERROR_INVALID_ARGUMENT, ctx, NULL);
    cacao_memory_info info;
    CHECK_RESULT(cacao_context_resize(ctx, 64, 48, &info), CACAO_SUCCESS, ctx, NULL);
    CHECK(cacao_context_plan(ctx) && cacao_context_plan(ctx)->settings.quality == CACAO_QUALITY_HIGHEST);
    /* one pipeline per distinct permutation: the tile fill runs twice (ping, then pong) on one;
     * a clear (the importance map's, at HIGHEST) is a transfer, with no pipeline */
    const cacao_plan *plan = cacao_context_plan(ctx);
    uint32_t distinct = 0;
    for (uint32_t i = 0; plan && i < plan->step_count; ++i) {
        bool seen = false;
        for (uint32_t j = 0; j < i; ++j) seen = seen || strcmp(plan->steps[j].key_name, plan->steps[i].key_name) == 0;
        distinct += !seen && !plan->steps[i].clear;
    }
    CHECK(plan && plan->uses_tiles && distinct < plan->step_count);
    CHECK(info.total_bytes > 0 && info.pipeline_count == distinct);

    /* Inputs: missing images, unsupported formats, unreadable layouts, bad projection. These are
     * refused before anything is recorded, so placeholder handles suffice. */
    const VkImage fake_image = (VkImage)(uintptr_t)0x1000;
    const VkImageView fake_view = (VkImageView)(uintptr_t)0x2000;
    const cacao_inputs good = {
        .depth = {fake_image, fake_view, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .normals = {fake_image, fake_view, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .output = {fake_image, fake_view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_GENERAL},
        .projection = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -0.1f, 0, 0, -1, 0},
        .matrices_row_major = true,
    };
    in = good;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, NULL), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs");
    in.depth.view = VK_NULL_HANDLE;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.depth");
    in = good;
    in.depth.format = VK_FORMAT_R8_UNORM;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_UNSUPPORTED_FORMAT, ctx, "inputs.depth.format");
    in = good;
    in.output.format = VK_FORMAT_R8G8B8A8_SRGB;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_UNSUPPORTED_FORMAT, ctx, "inputs.output.format");
    in = good;
    in.normals.format = VK_FORMAT_R8_UINT;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_UNSUPPORTED_FORMAT, ctx, "inputs.normals.format");
    in = good;
    in.depth.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.depth.layout");
    in = good; /* needs separateDepthStencilLayouts, which this context was not told is enabled */
    in.depth.layout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "separateDepthStencilLayouts");
    in = good; /* a pool one query short of plan.step_count + 1 from timestamp_first_query */
    in.timestamp_query_pool = (VkQueryPool)(uintptr_t)0x3000;
    in.timestamp_first_query = 2;
    in.timestamp_query_count = 2 + cacao_context_plan(ctx)->step_count;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.timestamp_query_count");
    in = good;
    in.output.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.output.layout");
    in = good;
    in.projection[5] = NAN;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.projection[5]");
    in = good;
    in.projection[5] = -1.0f;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.projection");
    in = good;
    in.projection[11] = 0.0f;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "P(2,3)");
    in = good;
    in.normals_to_view[3] = INFINITY;
    CHECK_RESULT(cacao_record(ctx, dev->cmd, &in), CACAO_ERROR_INVALID_ARGUMENT, ctx, "inputs.normals_to_view[3]");
    CHECK_RESULT(cacao_record(ctx, VK_NULL_HANDLE, &good), CACAO_ERROR_INVALID_ARGUMENT, ctx, "command_buffer");

    /* The inspection accessor refuses resources the plan lacks. */
    VkImage image;
    VkBuffer buffer;
    CHECK_RESULT(cacao_context_intermediate(ctx, CACAO_RES_OUTPUT, &image, &buffer), CACAO_ERROR_INVALID_ARGUMENT,
                 (cacao_context *)NULL, NULL);
    return ctx;
}

/* The context that took every error above still works: after one more refused resize and
 * refused settings, it renders the default scene pixel for pixel like a fresh context. */
static void test_still_usable(vkdev *dev, cacao_context *ctx) {
    scene_buffers b;
    const float radius = scene_buffers_default(64, 48, &b);
    const cacao_settings s = {.quality = CACAO_QUALITY_HIGH, .generate_normals = true, .radius = radius};
    CHECK_RESULT(cacao_context_set_settings(ctx, &s), CACAO_SUCCESS, ctx, NULL);
    CHECK_RESULT(cacao_context_resize(ctx, 0, 48, NULL), CACAO_ERROR_INVALID_SIZE, ctx, "0x48");
    CHECK_RESULT(cacao_context_set_settings(ctx, &(cacao_settings){.sharpness = 2.0f}), CACAO_ERROR_INVALID_ARGUMENT,
                 ctx, "settings.sharpness");
    CHECK_RESULT(cacao_context_resize(ctx, 64, 48, NULL), CACAO_SUCCESS, ctx, NULL);
    const size_t n = 64 * 48;
    float reused[64 * 48], fresh[64 * 48];
    char err[512];
    vkdev_frame f = scene_frame(&b, false, false);
    const cacao_result r = vkdev_run_context(dev, ctx, &f, 1, reused, NULL, err, sizeof err);
    if (r != CACAO_SUCCESS) fprintf(stderr, "the misused context cannot run a frame: %s\n", err);
    CHECK(r == CACAO_SUCCESS);
    if (r == CACAO_SUCCESS && run(dev, &s, &f, fresh)) {
        size_t differ = 0;
        for (size_t i = 0; i < n; ++i) differ += reused[i] != fresh[i];
        if (differ) fprintf(stderr, "the misused context differs from a fresh one in %zu of %zu pixels\n", differ, n);
        CHECK(differ == 0);
        CHECK(all_finite_unit(reused, n));
        float darkest = 1.0f;
        for (size_t i = 0; i < n; ++i) darkest = fminf(darkest, reused[i]);
        printf("misused context: %zu of %zu pixels differ from a fresh context's, darkest AO %.3f\n", differ, n,
               darkest);
        CHECK(darkest < 0.9f); /* the scene has creases: a blank image would not count as a match */
    }
    scene_buffers_free(&b);
}

int main(void) {
    test_settings_errors();
    vkdev dev;
    open_device(&dev);
    const VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(dev.cmd, &begin);
    cacao_context *ctx = test_context_errors(&dev);
    vkEndCommandBuffer(dev.cmd);
    if (ctx) test_still_usable(&dev, ctx);
    cacao_context_destroy(ctx);
    cacao_context_destroy(NULL); /* allowed, does nothing */
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    return test_report("test_misuse");
}
