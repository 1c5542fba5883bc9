/* test_normals_formats - CACAO_NORMALS_FORMATS in cacao.h is the list cacao_record checks: every
 * listed format passes the normals check and formats outside it (sRGB, two-channel, three-channel,
 * packed float, integer) fail with UNSUPPORTED_FORMAT naming inputs.normals. Each listed format is
 * also one the device can sample (format properties), so the header promises nothing unusable.
 * The check runs before any command is recorded: the output format is left invalid on purpose, so
 * a normals format that passes stops at the output check and nothing reaches the command buffer. */
#include <string.h>

#include "gpu_scene.h"

static const VkFormat listed[] = {CACAO_NORMALS_FORMATS};

/* Which field cacao_record's input check stops at for this normals format. */
static cacao_result check_normals(cacao_context *ctx, VkCommandBuffer cmd, VkFormat format, const char **field) {
    const VkImage img = (VkImage)(uintptr_t)0x1000; /* never used: the check fails first */
    const VkImageView view = (VkImageView)(uintptr_t)0x2000;
    cacao_inputs in = {
        .depth = {img, view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .normals = {img, view, format, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .output = {img, view, VK_FORMAT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL},
    };
    const cacao_result r = cacao_record(ctx, cmd, &in);
    const char *msg = cacao_context_last_error(ctx);
    *field = strstr(msg, "inputs.normals") ? "normals" : strstr(msg, "inputs.output") ? "output" : msg;
    return r;
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    cacao_context *ctx = NULL;
    CHECK(vkdev_context_create(&dev, &ctx) == CACAO_SUCCESS);
    CHECK(cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_LOW}) == CACAO_SUCCESS);
    CHECK(cacao_context_resize(ctx, 64, 64, NULL) == CACAO_SUCCESS);

    const char *field = NULL;
    for (size_t i = 0; i < sizeof listed / sizeof listed[0]; ++i) {
        CHECK(check_normals(ctx, dev.cmd, listed[i], &field) == CACAO_ERROR_UNSUPPORTED_FORMAT);
        if (strcmp(field, "output") != 0) fprintf(stderr, "listed format %d refused: %s\n", (int)listed[i], field);
        CHECK(strcmp(field, "output") == 0);
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(dev.physical_device, listed[i], &props);
        CHECK(props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT);
    }
    const VkFormat unlisted[] = {VK_FORMAT_R8G8B8A8_SRGB,           VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32G32B32_SFLOAT,
                                 VK_FORMAT_B10G11R11_UFLOAT_PACK32, VK_FORMAT_R8G8B8A8_UINT, VK_FORMAT_UNDEFINED};
    for (size_t i = 0; i < sizeof unlisted / sizeof unlisted[0]; ++i) {
        CHECK(check_normals(ctx, dev.cmd, unlisted[i], &field) == CACAO_ERROR_UNSUPPORTED_FORMAT);
        if (strcmp(field, "normals") != 0) fprintf(stderr, "unlisted format %d: %s\n", (int)unlisted[i], field);
        CHECK(strcmp(field, "normals") == 0);
    }
    cacao_context_destroy(ctx);
    CHECK(dev.validation_messages == 0);
    vkdev_destroy(&dev);
    return test_report("test_normals_formats");
}
