/* raster.c - a rasterizing client of cacao, as a guide.
 *
 * An "engine" draws a room of real triangles with a graphics pipeline into a depth attachment and
 * a normals attachment, hands both to cacao in the same command buffer, and composites the AO over
 * a simple lit colour in a fullscreen pass. Thirty frames, one submission each: the camera moves,
 * the frame size changes twice (1280x720, 1920x1080, 1366x768) and the settings once (MEDIUM to
 * HIGH). The last frame is written as a PNG.
 *
 *   cacao-raster [-o FILE.png] [--depth-format d32|d24s8] [--dump DIR [--dump-frame N]]
 *
 * --dump writes one frame's depth, normals and camera as a scene folder the `cacao` command reads
 * (depth.pfm, normals.pfm, camera.json), the settings as a --settings file (settings.json), and
 * the AO this program got (ao.pfm): `cacao --scene DIR --settings DIR/settings.json` must give
 * the same AO (ctest raster_ao_equality).
 *
 * Vulkan 1.1 with render passes (the validation layer of Debian 12 checks their attachments'
 * synchronization; it does not yet follow dynamic rendering), VK_KHR_push_descriptor for both
 * cacao and the composite. The PNG and PFM writers come from tools/common (image_io.h). Exit 77:
 * the device cannot sample the depth format. */
#include <cacao.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "image_io.h"
#include "raster/scene.h"
/* SPIR-V of raster/gbuffer.vert, .frag and composite.vert, .frag, compiled at build time */
#include "composite_frag.h"
#include "composite_vert.h"
#include "gbuffer_frag.h"
#include "gbuffer_vert.h"

#define FRAME_COUNT 30
#define EXIT_UNSUPPORTED 77

/* What changes at which frame: a new size (the app's attachments are recreated and cacao resized)
 * or new settings (cacao_context_set_settings, then a resize at the same size). */
typedef struct frame_change {
    uint32_t frame, width, height;
    cacao_quality quality;
} frame_change;

static const frame_change schedule[] = {
    {0, 1280, 720, CACAO_QUALITY_MEDIUM},
    {10, 1920, 1080, CACAO_QUALITY_MEDIUM},
    {15, 1920, 1080, CACAO_QUALITY_HIGH},
    {20, 1366, 768, CACAO_QUALITY_HIGH},
};
#define SCHEDULE_LENGTH (sizeof schedule / sizeof schedule[0])

typedef struct options {
    const char *png_path;   /* the last frame, composited */
    VkFormat depth_format;  /* D32_SFLOAT or D24_UNORM_S8_UINT */
    const char *dump_dir;   /* NULL: no dump */
    uint32_t dump_frame;
} options;

typedef struct image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
} image;

typedef struct buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} buffer;

/* The app's per-size resources: recreated on resize. */
typedef struct targets {
    uint32_t width, height;
    image depth;        /* depth attachment, then cacao's depth input (view: the depth aspect) */
    VkImageView depth_attachment; /* every aspect of the depth format, for the framebuffer */
    image normals;      /* A2B10G10R10 attachment, then cacao's normals input */
    image ao;           /* cacao's output, R32_SFLOAT; SHADER_READ_ONLY_OPTIMAL between uses */
    image colour;       /* the composite, RGBA8 */
    buffer readback;    /* colour, depth, normals and AO, 4 bytes a texel each, in that order */
    VkFramebuffer gbuffer, composite;
    bool ao_layout_set; /* the AO image has left UNDEFINED */
} targets;

typedef struct app {
    options opt;
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_set;
    buffer vertices;
    uint32_t vertex_count;
    VkSampler sampler;
    VkDescriptorSetLayout composite_inputs;
    VkRenderPass gbuffer_pass, composite_pass;
    VkPipelineLayout gbuffer_layout, composite_layout;
    VkPipeline gbuffer, composite;
    targets t;
    cacao_context *cacao;
    cacao_settings settings;
} app;

static bool fail(const char *message) {
    fprintf(stderr, "cacao-raster: %s\n", message);
    return false;
}

static bool vk_ok(VkResult result, const char *what) {
    if (result == VK_SUCCESS) return true;
    fprintf(stderr, "cacao-raster: %s failed (VkResult %d)\n", what, (int)result);
    return false;
}

/* ---- Flags ------------------------------------------------------------------------------ */

static void usage(FILE *out) {
    fprintf(out, "usage: cacao-raster [-o FILE.png] [--depth-format d32|d24s8] [--dump DIR [--dump-frame N]]\n"
                 "Renders %d frames of a rasterized room with cacao's AO; writes the last one to FILE.png\n"
                 "(default cacao-raster.png). --dump DIR writes frame N's depth.pfm, normals.pfm, camera.json,\n"
                 "settings.json and ao.pfm into DIR (default N = %d), for `cacao --scene DIR --settings ...`.\n",
            FRAME_COUNT, FRAME_COUNT - 1);
}

/* 1: run, 0: --help given, -1: a bad flag (one line said which). */
static int parse_flags(int argc, char **argv, options *o) {
    *o = (options){"cacao-raster.png", VK_FORMAT_D32_SFLOAT, NULL, FRAME_COUNT - 1};
    bool frame_given = false;
    for (int i = 1; i < argc; ++i) {
        const char *flag = argv[i];
        if (!strcmp(flag, "-h") || !strcmp(flag, "--help")) return usage(stdout), 0;
        if (strcmp(flag, "-o") && strcmp(flag, "--depth-format") && strcmp(flag, "--dump") && strcmp(flag, "--dump-frame"))
            return fprintf(stderr, "cacao-raster: %s: unknown flag (see --help)\n", flag), -1;
        const char *value = ++i < argc ? argv[i] : NULL;
        if (!value || !value[0]) return fprintf(stderr, "cacao-raster: %s: needs a value\n", flag), -1;
        char *end = NULL;
        if (!strcmp(flag, "-o")) {
            const char *dot = strrchr(value, '.');
            if (!dot || strcmp(dot, ".png")) return fprintf(stderr, "cacao-raster: -o %s: must name a .png file\n", value), -1;
            o->png_path = value;
        } else if (!strcmp(flag, "--depth-format")) {
            if (!strcmp(value, "d32")) o->depth_format = VK_FORMAT_D32_SFLOAT;
            else if (!strcmp(value, "d24s8")) o->depth_format = VK_FORMAT_D24_UNORM_S8_UINT;
            else return fprintf(stderr, "cacao-raster: --depth-format %s: use d32 or d24s8\n", value), -1;
        } else if (!strcmp(flag, "--dump")) {
            o->dump_dir = value;
        } else {
            const unsigned long n = strtoul(value, &end, 10);
            if (*end || value[0] == '-' || n >= FRAME_COUNT)
                return fprintf(stderr, "cacao-raster: --dump-frame %s: must be 0 to %d\n", value, FRAME_COUNT - 1), -1;
            o->dump_frame = (uint32_t)n;
            frame_given = true;
        }
    }
    if (frame_given && !o->dump_dir) return fprintf(stderr, "cacao-raster: --dump-frame: needs --dump DIR\n"), -1;
    struct stat st; /* the folder, made here when absent: the only output before the frames */
    if (o->dump_dir && stat(o->dump_dir, &st) != 0 && mkdir(o->dump_dir, 0777) != 0)
        return fprintf(stderr, "cacao-raster: --dump %s: cannot create it: %s\n", o->dump_dir, strerror(errno)), -1;
    if (o->dump_dir && stat(o->dump_dir, &st) == 0 && !S_ISDIR(st.st_mode))
        return fprintf(stderr, "cacao-raster: --dump %s: not a directory\n", o->dump_dir), -1;
    return 1;
}

/* ---- Device ----------------------------------------------------------------------------- */

static bool has_extension(VkPhysicalDevice pd, const char *name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL);
    VkExtensionProperties *list = calloc(n ? n : 1, sizeof *list);
    bool found = false;
    if (list && vkEnumerateDeviceExtensionProperties(pd, NULL, &n, list) == VK_SUCCESS)
        for (uint32_t i = 0; i < n && !found; ++i) found = !strcmp(list[i].extensionName, name);
    free(list);
    return found;
}

/* A queue family that draws and computes, or UINT32_MAX. */
static uint32_t graphics_family(VkPhysicalDevice pd) {
    VkQueueFamilyProperties families[16];
    uint32_t n = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families);
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < n; ++i)
        if ((families[i].queueFlags & need) == need) return i;
    return UINT32_MAX;
}

/* Instance and device: a Vulkan 1.1 device with push descriptors and a graphics queue; a CPU
 * device (lavapipe) first, as the `cacao` command picks, so that the tests compare like with like
 * (an engine would pick its GPU). */
static bool create_device(app *a) {
    const VkApplicationInfo info = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "cacao-raster",
                                    .apiVersion = VK_API_VERSION_1_1};
    const VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &info};
    if (!vk_ok(vkCreateInstance(&ici, NULL, &a->instance), "vkCreateInstance (is a Vulkan driver installed?)"))
        return false;
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    vkEnumeratePhysicalDevices(a->instance, &count, devices);
    for (int cpu_only = 1; cpu_only >= 0 && !a->physical_device; --cpu_only)
        for (uint32_t i = 0; i < count && !a->physical_device; ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            if (p.apiVersion >= VK_API_VERSION_1_1 && (!cpu_only || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) &&
                has_extension(devices[i], VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) &&
                graphics_family(devices[i]) != UINT32_MAX)
                a->physical_device = devices[i];
        }
    if (!a->physical_device) return fail("no Vulkan 1.1 device with VK_KHR_push_descriptor and a graphics queue");
    a->queue_family = graphics_family(a->physical_device);
    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                           .queueFamilyIndex = a->queue_family, .queueCount = 1,
                                           .pQueuePriorities = &priority};
    const VkPhysicalDeviceFeatures features = {.shaderStorageImageWriteWithoutFormat = VK_TRUE,
                                               .shaderStorageImageExtendedFormats = VK_TRUE};
    const char *extension = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    const VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1,
                                    .pQueueCreateInfos = &queue, .enabledExtensionCount = 1,
                                    .ppEnabledExtensionNames = &extension, .pEnabledFeatures = &features};
    if (!vk_ok(vkCreateDevice(a->physical_device, &dci, NULL, &a->device), "vkCreateDevice")) return false;
    vkGetDeviceQueue(a->device, a->queue_family, 0, &a->queue);
    a->push_descriptor_set =
        (PFN_vkCmdPushDescriptorSetKHR)vkGetDeviceProcAddr(a->device, "vkCmdPushDescriptorSetKHR");
    const VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                          .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                          .queueFamilyIndex = a->queue_family};
    const VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (!vk_ok(vkCreateCommandPool(a->device, &pool, NULL, &a->pool), "vkCreateCommandPool") ||
        !vk_ok(vkCreateFence(a->device, &fence, NULL, &a->fence), "vkCreateFence"))
        return false;
    const VkCommandBufferAllocateInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                             .commandPool = a->pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                             .commandBufferCount = 1};
    return vk_ok(vkAllocateCommandBuffers(a->device, &cbi, &a->cmd), "vkAllocateCommandBuffers");
}

/* Whether the depth format can be a depth attachment, sampled (by cacao and the composite) and
 * copied out (--dump). */
static bool depth_format_supported(const app *a) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(a->physical_device, a->opt.depth_format, &p);
    const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    return (p.optimalTilingFeatures & need) == need;
}

static uint32_t memory_type(const app *a, uint32_t bits, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(a->physical_device, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (p.memoryTypes[i].propertyFlags & flags) == flags) return i;
    return UINT32_MAX;
}

static bool allocate(const app *a, VkMemoryRequirements req, VkMemoryPropertyFlags flags, VkDeviceMemory *memory) {
    const uint32_t type = memory_type(a, req.memoryTypeBits, flags);
    const VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                                     .memoryTypeIndex = type};
    return type != UINT32_MAX && vk_ok(vkAllocateMemory(a->device, &ai, NULL, memory), "vkAllocateMemory");
}

static bool view_create(const app *a, VkImage image, VkFormat format, VkImageAspectFlags aspect, VkImageView *out) {
    const VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = image,
                                      .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                      .subresourceRange = {aspect, 0, 1, 0, 1}};
    return vk_ok(vkCreateImageView(a->device, &vi, NULL, out), "vkCreateImageView");
}

static bool image_create(const app *a, VkFormat format, VkImageAspectFlags aspect, VkImageUsageFlags usage,
                         image *out) {
    const VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                                  .format = format, .extent = {a->t.width, a->t.height, 1}, .mipLevels = 1,
                                  .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT, .usage = usage};
    if (!vk_ok(vkCreateImage(a->device, &ii, NULL, &out->image), "vkCreateImage")) return false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(a->device, out->image, &req);
    if (!allocate(a, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &out->memory) ||
        !vk_ok(vkBindImageMemory(a->device, out->image, out->memory, 0), "vkBindImageMemory"))
        return false;
    return view_create(a, out->image, format, aspect, &out->view);
}

static void image_destroy(const app *a, image *img) {
    vkDestroyImageView(a->device, img->view, NULL);
    vkDestroyImage(a->device, img->image, NULL);
    vkFreeMemory(a->device, img->memory, NULL);
    *img = (image){0};
}

static bool buffer_create(const app *a, VkDeviceSize size, VkBufferUsageFlags usage, buffer *out) {
    const VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    if (!vk_ok(vkCreateBuffer(a->device, &bi, NULL, &out->buffer), "vkCreateBuffer")) return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(a->device, out->buffer, &req);
    return allocate(a, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &out->memory) &&
           vk_ok(vkBindBufferMemory(a->device, out->buffer, out->memory, 0), "vkBindBufferMemory") &&
           vk_ok(vkMapMemory(a->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped), "vkMapMemory");
}

static void buffer_destroy(const app *a, buffer *b) {
    vkDestroyBuffer(a->device, b->buffer, NULL);
    vkFreeMemory(a->device, b->memory, NULL);
    *b = (buffer){0};
}

static VkImageAspectFlags depth_aspects(const app *a) { /* every aspect: for transitions and the framebuffer */
    return a->opt.depth_format == VK_FORMAT_D24_UNORM_S8_UINT ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT
                                                              : VK_IMAGE_ASPECT_DEPTH_BIT;
}

static void targets_destroy(app *a) {
    vkDestroyFramebuffer(a->device, a->t.gbuffer, NULL);
    vkDestroyFramebuffer(a->device, a->t.composite, NULL);
    vkDestroyImageView(a->device, a->t.depth_attachment, NULL);
    image_destroy(a, &a->t.depth);
    image_destroy(a, &a->t.normals);
    image_destroy(a, &a->t.ao);
    image_destroy(a, &a->t.colour);
    buffer_destroy(a, &a->t.readback);
    a->t = (targets){0};
}

static bool framebuffer_create(const app *a, VkRenderPass pass, uint32_t count, const VkImageView *views,
                               VkFramebuffer *out) {
    const VkFramebufferCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO, .renderPass = pass,
                                        .attachmentCount = count, .pAttachments = views, .width = a->t.width,
                                        .height = a->t.height, .layers = 1};
    return vk_ok(vkCreateFramebuffer(a->device, &fi, NULL, out), "vkCreateFramebuffer");
}

/* The app's images and framebuffers at this size (cacao's are cacao_context_resize's business). */
static bool targets_create(app *a, uint32_t width, uint32_t height) {
    targets_destroy(a);
    a->t.width = width;
    a->t.height = height;
    const VkImageUsageFlags read = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    return image_create(a, a->opt.depth_format, VK_IMAGE_ASPECT_DEPTH_BIT,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | read, &a->t.depth) &&
           view_create(a, a->t.depth.image, a->opt.depth_format, depth_aspects(a), &a->t.depth_attachment) &&
           image_create(a, VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_IMAGE_ASPECT_COLOR_BIT,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | read, &a->t.normals) &&
           image_create(a, VK_FORMAT_R32_SFLOAT, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_USAGE_STORAGE_BIT | read,
                        &a->t.ao) &&
           image_create(a, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_ASPECT_COLOR_BIT,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &a->t.colour) &&
           buffer_create(a, 16ull * width * height, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &a->t.readback) &&
           framebuffer_create(a, a->gbuffer_pass, 2, (VkImageView[2]){a->t.normals.view, a->t.depth_attachment},
                              &a->t.gbuffer) &&
           framebuffer_create(a, a->composite_pass, 1, &a->t.colour.view, &a->t.composite);
}

/* ---- Render passes and pipelines (size-independent: viewport and scissor are dynamic) ------- */

/* One subpass writing a colour attachment and, when depth_format is not UNDEFINED, a depth
 * attachment, each cleared (colour: load_colour) and stored. Every attachment starts and ends in
 * its attachment layout: the frame records the transitions in and out as barriers. */
static bool render_pass_create(const app *a, VkFormat colour_format, VkAttachmentLoadOp load_colour,
                               VkFormat depth_format, VkRenderPass *out) {
    const VkImageLayout colour_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkImageLayout depth_layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    const VkAttachmentDescription attachments[2] = {
        {0, colour_format, VK_SAMPLE_COUNT_1_BIT, load_colour, VK_ATTACHMENT_STORE_OP_STORE,
         VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, colour_layout, colour_layout},
        {0, depth_format, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
         VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, depth_layout, depth_layout}};
    const VkAttachmentReference colour = {0, colour_layout}, depth = {1, depth_layout};
    const bool has_depth = depth_format != VK_FORMAT_UNDEFINED;
    const VkSubpassDescription subpass = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                                          .colorAttachmentCount = 1, .pColorAttachments = &colour,
                                          .pDepthStencilAttachment = has_depth ? &depth : NULL};
    const VkRenderPassCreateInfo ri = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                       .attachmentCount = has_depth ? 2 : 1, .pAttachments = attachments,
                                       .subpassCount = 1, .pSubpasses = &subpass};
    return vk_ok(vkCreateRenderPass(a->device, &ri, NULL, out), "vkCreateRenderPass");
}

static VkShaderModule shader(const app *a, const uint32_t *code, size_t bytes) {
    const VkShaderModuleCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes,
                                         .pCode = code};
    VkShaderModule module = VK_NULL_HANDLE;
    vkCreateShaderModule(a->device, &si, NULL, &module);
    return module;
}

typedef struct pipeline_desc {
    const uint32_t *vert, *frag;
    size_t vert_bytes, frag_bytes;
    bool depth_test;
    bool vertices; /* raster_vertex input; else none */
    VkPipelineLayout layout;
    VkRenderPass pass;
} pipeline_desc;

static bool pipeline_create(const app *a, const pipeline_desc *d, VkPipeline *out) {
    const VkShaderModule vert = shader(a, d->vert, d->vert_bytes), frag = shader(a, d->frag, d->frag_bytes);
    const VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = frag, .pName = "main"}};
    const VkVertexInputBindingDescription binding = {0, sizeof(raster_vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(raster_vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(raster_vertex, normal)},
        {2, 0, VK_FORMAT_R32_UINT, offsetof(raster_vertex, material)}};
    const VkPipelineVertexInputStateCreateInfo input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = d->vertices, .pVertexBindingDescriptions = &binding,
        .vertexAttributeDescriptionCount = d->vertices ? 3 : 0, .pVertexAttributeDescriptions = attributes};
    const VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    const VkPipelineViewportStateCreateInfo viewport = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                                        .viewportCount = 1, .scissorCount = 1};
    const VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO, .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = VK_CULL_MODE_NONE, .lineWidth = 1.0f};
    const VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    const VkPipelineDepthStencilStateCreateInfo depth_state = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO, .depthTestEnable = d->depth_test,
        .depthWriteEnable = d->depth_test, .depthCompareOp = VK_COMPARE_OP_LESS};
    const VkPipelineColorBlendAttachmentState blend_attachment = {.colorWriteMask = 0xf};
    const VkPipelineColorBlendStateCreateInfo blend = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                                       .attachmentCount = 1, .pAttachments = &blend_attachment};
    const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    const VkPipelineDynamicStateCreateInfo dynamic = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                                      .dynamicStateCount = 2, .pDynamicStates = dynamic_states};
    const VkGraphicsPipelineCreateInfo gi = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, .stageCount = 2,
        .pStages = stages, .pVertexInputState = &input, .pInputAssemblyState = &assembly,
        .pViewportState = &viewport, .pRasterizationState = &raster, .pMultisampleState = &multisample,
        .pDepthStencilState = &depth_state, .pColorBlendState = &blend, .pDynamicState = &dynamic,
        .layout = d->layout, .renderPass = d->pass};
    const bool ok = vert && frag && vk_ok(vkCreateGraphicsPipelines(a->device, VK_NULL_HANDLE, 1, &gi, NULL, out),
                                          "vkCreateGraphicsPipelines");
    vkDestroyShaderModule(a->device, vert, NULL);
    vkDestroyShaderModule(a->device, frag, NULL);
    return ok;
}

/* Push constants of the two passes (std430 layout of the shaders' blocks; matrices column-major). */
typedef struct gbuffer_constants {
    float clip_from_world[16], view_from_world[16];
} gbuffer_constants;
typedef struct composite_constants {
    float light_view[4], size[2];
} composite_constants;

static bool pipelines_create(app *a) {
    const VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, .magFilter = VK_FILTER_NEAREST,
                                    .minFilter = VK_FILTER_NEAREST};
    VkDescriptorSetLayoutBinding bindings[3];
    for (uint32_t i = 0; i < 3; ++i)
        bindings[i] = (VkDescriptorSetLayoutBinding){i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                     VK_SHADER_STAGE_FRAGMENT_BIT, NULL};
    const VkDescriptorSetLayoutCreateInfo dsl = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                                 .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
                                                 .bindingCount = 3, .pBindings = bindings};
    const VkPushConstantRange gbuffer_range = {VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(gbuffer_constants)};
    const VkPushConstantRange composite_range = {VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(composite_constants)};
    const VkPipelineLayoutCreateInfo gbuffer_layout = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                                       .pushConstantRangeCount = 1,
                                                       .pPushConstantRanges = &gbuffer_range};
    if (!render_pass_create(a, VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_ATTACHMENT_LOAD_OP_CLEAR, a->opt.depth_format,
                            &a->gbuffer_pass) ||
        !render_pass_create(a, VK_FORMAT_R8G8B8A8_UNORM, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_FORMAT_UNDEFINED,
                            &a->composite_pass) ||
        !vk_ok(vkCreateSampler(a->device, &si, NULL, &a->sampler), "vkCreateSampler") ||
        !vk_ok(vkCreateDescriptorSetLayout(a->device, &dsl, NULL, &a->composite_inputs), "vkCreateDescriptorSetLayout") ||
        !vk_ok(vkCreatePipelineLayout(a->device, &gbuffer_layout, NULL, &a->gbuffer_layout), "vkCreatePipelineLayout"))
        return false;
    const VkPipelineLayoutCreateInfo composite_layout = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
        .pSetLayouts = &a->composite_inputs, .pushConstantRangeCount = 1, .pPushConstantRanges = &composite_range};
    if (!vk_ok(vkCreatePipelineLayout(a->device, &composite_layout, NULL, &a->composite_layout),
               "vkCreatePipelineLayout"))
        return false;
    const pipeline_desc gbuffer = {gbuffer_vert, gbuffer_frag, sizeof gbuffer_vert, sizeof gbuffer_frag,
                                   true, true, a->gbuffer_layout, a->gbuffer_pass};
    const pipeline_desc composite = {composite_vert, composite_frag, sizeof composite_vert, sizeof composite_frag,
                                     false, false, a->composite_layout, a->composite_pass};
    return pipeline_create(a, &gbuffer, &a->gbuffer) && pipeline_create(a, &composite, &a->composite);
}

/* The scene's triangles, in a host-visible vertex buffer (written once). */
static bool vertices_create(app *a) {
    raster_vertex *scene = malloc(RASTER_SCENE_MAX_VERTICES * sizeof *scene);
    if (!scene) return fail("out of memory");
    a->vertex_count = raster_scene_build(scene);
    const bool ok = buffer_create(a, a->vertex_count * sizeof *scene, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &a->vertices);
    if (ok) memcpy(a->vertices.mapped, scene, a->vertex_count * sizeof *scene);
    free(scene);
    return ok;
}

/* ---- One frame -------------------------------------------------------------------------- */

static void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                       VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                       VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    const VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src_access,
                                    .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to,
                                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                                    .subresourceRange = {aspect, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

/* Row-major (clip = P * v, as cacao takes it) to GLSL's column-major. */
static void transpose(const float in[16], float out[16]) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[4 * c + r] = in[4 * r + c];
}

static void multiply(const float x[16], const float y[16], float out[16]) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            float sum = 0.0f;
            for (int k = 0; k < 4; ++k) sum += x[4 * r + k] * y[4 * k + c];
            out[4 * r + c] = sum;
        }
}

/* The G-buffer pass: depth and normals attachments, cleared, then the room. */
static void record_gbuffer(const app *a, const raster_camera *cam) {
    const VkCommandBuffer cmd = a->cmd;
    const VkPipelineStageFlags readers = /* of the previous frame: cacao, the composite, --dump's copies */
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    const VkPipelineStageFlags tests =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    transition(cmd, a->t.depth.image, depth_aspects(a), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, readers, 0, tests,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    transition(cmd, a->t.normals.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, readers, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    const VkClearValue clear[2] = {{.color = {{0.5f, 0.5f, 0.5f, 0.0f}}}, /* normal 0 where nothing is drawn */
                                   {.depthStencil = {1.0f, 0}}};
    const VkRect2D area = {{0, 0}, {a->t.width, a->t.height}};
    const VkRenderPassBeginInfo rendering = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                             .renderPass = a->gbuffer_pass, .framebuffer = a->t.gbuffer,
                                             .renderArea = area, .clearValueCount = 2, .pClearValues = clear};
    vkCmdBeginRenderPass(cmd, &rendering, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport = {0, 0, (float)a->t.width, (float)a->t.height, 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, a->gbuffer);
    /* cacao takes the projection with clip y up; Vulkan's framebuffer y points down (row 0 is
     * NDC y = -1), so the rasterizer gets it with its y row negated and the image comes out upright. */
    float flipped[16], clip_from_world[16];
    memcpy(flipped, cam->projection, sizeof flipped);
    for (int c = 0; c < 4; ++c) flipped[4 + c] = -flipped[4 + c];
    multiply(flipped, cam->view_from_world, clip_from_world);
    gbuffer_constants constants;
    transpose(clip_from_world, constants.clip_from_world);
    transpose(cam->view_from_world, constants.view_from_world);
    vkCmdPushConstants(cmd, a->gbuffer_layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof constants, &constants);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &a->vertices.buffer, &offset);
    vkCmdDraw(cmd, a->vertex_count, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    /* Out of the attachment layouts, into the layouts cacao is told about, for cacao's compute
     * and the composite's fragment shader. */
    transition(cmd, a->t.depth.image, depth_aspects(a), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, tests, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    transition(cmd, a->t.normals.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

/* The composite: depth, normals and AO sampled by one fullscreen triangle into the colour image. */
static void record_composite(const app *a, const raster_camera *cam) {
    const VkCommandBuffer cmd = a->cmd;
    transition(cmd, a->t.colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    const VkRect2D area = {{0, 0}, {a->t.width, a->t.height}};
    const VkRenderPassBeginInfo rendering = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                             .renderPass = a->composite_pass, .framebuffer = a->t.composite,
                                             .renderArea = area};
    vkCmdBeginRenderPass(cmd, &rendering, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport = {0, 0, (float)a->t.width, (float)a->t.height, 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, a->composite);
    const VkDescriptorImageInfo inputs[3] = {
        {a->sampler, a->t.depth.view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
        {a->sampler, a->t.normals.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {a->sampler, a->t.ao.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkWriteDescriptorSet writes[3];
    for (uint32_t i = 0; i < 3; ++i)
        writes[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstBinding = i,
                                           .descriptorCount = 1,
                                           .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                           .pImageInfo = &inputs[i]};
    a->push_descriptor_set(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, a->composite_layout, 0, 3, writes);
    composite_constants constants = {.light_view = {cam->light_view[0], cam->light_view[1], cam->light_view[2], 0},
                                     .size = {(float)a->t.width, (float)a->t.height}};
    vkCmdPushConstants(cmd, a->composite_layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof constants, &constants);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
}

/* Copies an image (4 bytes a texel) into the readback buffer at slot (of 4), leaving it in
 * TRANSFER_SRC_OPTIMAL. */
static void record_copy(const app *a, VkImage image, VkImageAspectFlags transition_aspects, VkImageAspectFlags aspect,
                        VkImageLayout from, VkPipelineStageFlags src_stage, VkAccessFlags src_access, uint32_t slot) {
    transition(a->cmd, image, transition_aspects, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, src_stage, src_access,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferImageCopy region = {.bufferOffset = 4ull * a->t.width * a->t.height * slot,
                                      .imageSubresource = {aspect, 0, 0, 1},
                                      .imageExtent = {a->t.width, a->t.height, 1}};
    vkCmdCopyImageToBuffer(a->cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, a->t.readback.buffer, 1, &region);
}

static bool record_frame(app *a, uint32_t frame, const raster_camera *cam, bool png, bool dump) {
    const VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                            .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    if (!vk_ok(vkBeginCommandBuffer(a->cmd, &begin), "vkBeginCommandBuffer")) return false;
    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    if (!a->t.ao_layout_set) { /* a new AO image: into the layout it keeps between frames */
        transition(a->cmd, a->t.ao.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, shaders,
                   VK_ACCESS_SHADER_READ_BIT);
        a->t.ao_layout_set = true;
    }
    record_gbuffer(a, cam);

    /* cacao, between the two graphics passes. No barrier of ours around it: it orders itself
     * after the transitions above and before the composite's reads of the AO, and returns the
     * AO image to SHADER_READ_ONLY_OPTIMAL, the layout we give. */
    cacao_inputs in = {
        .depth = {a->t.depth.image, a->t.depth.view, a->opt.depth_format, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
        .normals = {a->t.normals.image, a->t.normals.view, VK_FORMAT_A2B10G10R10_UNORM_PACK32,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .output = {a->t.ao.image, a->t.ao.view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        /* Right-handed view-space normals (camera-facing +z) to cacao's view space (z forward);
         * unpack: both 0, cacao's default 2 and -1 for UNORM-packed normals. */
        .normals_to_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1},
        .matrices_row_major = true,
        .frame_index = frame,
    };
    memcpy(in.projection, cam->projection, sizeof in.projection);
    if (cacao_record(a->cacao, a->cmd, &in) != CACAO_SUCCESS) {
        vkEndCommandBuffer(a->cmd);
        fprintf(stderr, "cacao-raster: cacao_record: %s\n", cacao_context_last_error(a->cacao));
        return false;
    }

    record_composite(a, cam);
    if (png)
        record_copy(a, a->t.colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0);
    if (dump) { /* what cacao read, and what it wrote; the AO image then returns to its layout */
        record_copy(a, a->t.depth.image, depth_aspects(a), VK_IMAGE_ASPECT_DEPTH_BIT,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, shaders, 0, 1);
        record_copy(a, a->t.normals.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, shaders, 0, 2);
        record_copy(a, a->t.ao.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 3);
        transition(a->cmd, a->t.ao.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, shaders,
                   VK_ACCESS_SHADER_READ_BIT);
    }
    if (png || dump) {
        const VkMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                         .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                         .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(a->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                             NULL, 0, NULL);
    }
    return vk_ok(vkEndCommandBuffer(a->cmd), "vkEndCommandBuffer");
}

static bool submit_and_wait(app *a) {
    const VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                             .pCommandBuffers = &a->cmd};
    return vk_ok(vkQueueSubmit(a->queue, 1, &si, a->fence), "vkQueueSubmit") &&
           vk_ok(vkWaitForFences(a->device, 1, &a->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences") &&
           vk_ok(vkResetFences(a->device, 1, &a->fence), "vkResetFences");
}

/* ---- Resize and settings ---------------------------------------------------------------- */

/* Called between frames, after the previous frame's fence: the GPU uses none of what changes. */
static bool apply_change(app *a, const frame_change *c) {
    const bool resized = c->width != a->t.width || c->height != a->t.height;
    if (resized && !targets_create(a, c->width, c->height)) return false;
    if (c->quality != a->settings.quality) {
        a->settings.quality = c->quality;
        if (cacao_context_set_settings(a->cacao, &a->settings) != CACAO_SUCCESS)
            return fail(cacao_context_last_error(a->cacao));
    }
    cacao_memory_info memory;
    if (cacao_context_resize(a->cacao, c->width, c->height, &memory) != CACAO_SUCCESS)
        return fail(cacao_context_last_error(a->cacao));
    printf("frame %2u: %ux%u, %s quality: cacao holds %.1f MB in %u images, %u pipelines\n", c->frame, c->width,
           c->height, cacao_quality_name(c->quality), memory.total_bytes / 1e6, memory.image_count,
           memory.pipeline_count);
    return true;
}

/* ---- Output ----------------------------------------------------------------------------- */

static const uint32_t *readback_slot(const app *a, uint32_t slot) {
    return (const uint32_t *)a->t.readback.mapped + (size_t)a->t.width * a->t.height * slot;
}

static bool write_png(const app *a) {
    const size_t pixels = (size_t)a->t.width * a->t.height;
    cacao_img img = {a->t.width, a->t.height, 3, malloc(pixels * 3 * sizeof(float))};
    if (!img.data) return fail("out of memory");
    const uint8_t *rgba = (const uint8_t *)readback_slot(a, 0);
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) img.data[3 * i + c] = rgba[4 * i + c] / 255.0f;
    char err[512];
    const bool ok = cacao_png_write(a->opt.png_path, &img, 8, err, sizeof err);
    cacao_img_free(&img);
    return ok || fail(err);
}

/* A text file written whole or not at all. */
static bool write_text(const char *path, const char *text) {
    char *temp = cacao_temp_path_for(path), err[512];
    FILE *f = temp ? fopen(temp, "w") : NULL;
    bool ok = f && fputs(text, f) >= 0;
    if (f) ok = fclose(f) == 0 && ok;
    if (!temp) return fail("out of memory");
    return cacao_commit_temp(temp, path, ok, err, sizeof err) || fail(err);
}

/* A D24 texel as copied out (depth in the low 24 bits) to the float a sampler gives cacao. Vulkan
 * leaves the last bit of that conversion to the driver: lavapipe multiplies by the float nearest
 * 1/(2^24-1), as here. (The correctly rounded quotient differs in about 1% of this scene's texels,
 * and the AO computed from it by up to 0.006.) */
static float d24_to_float(uint32_t texel) { return (float)(texel & 0xffffffu) * (float)(1.0 / 16777215.0); }

/* The inputs as the `cacao` command reads a scene folder (shared/scenes/README.md): raw depth as
 * float, unit right-handed view-space normals as float, the projection in camera.json. */
static bool write_dump(const app *a, const raster_camera *cam) {
    const uint32_t w = a->t.width, h = a->t.height;
    const size_t pixels = (size_t)w * h;
    cacao_img depth = {w, h, 1, malloc(pixels * sizeof(float))}, normals = {w, h, 3, malloc(pixels * 3 * sizeof(float))};
    cacao_img ao = {w, h, 1, malloc(pixels * sizeof(float))};
    char path[4096], err[512], text[2048];
    bool ok = (depth.data && normals.data && ao.data) || fail("out of memory");
    const uint32_t *d = readback_slot(a, 1), *n = readback_slot(a, 2);
    for (size_t i = 0; ok && i < pixels; ++i) {
        if (a->opt.depth_format == VK_FORMAT_D32_SFLOAT) memcpy(&depth.data[i], &d[i], sizeof(float));
        else depth.data[i] = d24_to_float(d[i]);
        for (int c = 0; c < 3; ++c) normals.data[3 * i + c] = (float)(n[i] >> (10 * c) & 1023u) / 1023.0f * 2.0f - 1.0f;
    }
    if (ok) memcpy(ao.data, readback_slot(a, 3), pixels * sizeof(float));
    const char *files[3] = {"depth.pfm", "normals.pfm", "ao.pfm"};
    const cacao_img *images[3] = {&depth, &normals, &ao};
    for (int i = 0; ok && i < 3; ++i) {
        snprintf(path, sizeof path, "%s/%s", a->opt.dump_dir, files[i]);
        ok = cacao_pfm_write(path, images[i], err, sizeof err) || fail(err);
    }
    int len = snprintf(text, sizeof text, "{\"width\": %u, \"height\": %u, \"fov_y_deg\": %g, \"near\": %g, "
                       "\"far\": %g, \"ao_radius_world\": %g,\n \"projection\": [", w, h, RASTER_FOV_Y_DEG, RASTER_NEAR,
                       RASTER_FAR, RASTER_AO_RADIUS);
    for (int i = 0; i < 16; ++i)
        len += snprintf(text + len, sizeof text - (size_t)len, "%.9g%s", (double)cam->projection[i], i < 15 ? ", " : "]}\n");
    snprintf(path, sizeof path, "%s/camera.json", a->opt.dump_dir);
    ok = ok && write_text(path, text);
    snprintf(text, sizeof text, "{\"quality\": \"%s\", \"radius\": %.9g}\n", cacao_quality_name(a->settings.quality),
             (double)a->settings.radius);
    snprintf(path, sizeof path, "%s/settings.json", a->opt.dump_dir);
    ok = ok && write_text(path, text);
    cacao_img_free(&depth);
    cacao_img_free(&normals);
    cacao_img_free(&ao);
    return ok;
}

/* ---- Main ------------------------------------------------------------------------------- */

static double now_ms(void) {
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static bool run(app *a) {
    double start = now_ms();
    uint32_t first = 0;
    for (uint32_t frame = 0, next = 0; frame < FRAME_COUNT; ++frame) {
        if (next < SCHEDULE_LENGTH && schedule[next].frame == frame) {
            if (frame > 0) printf("frames %u-%u: %.0f ms a frame\n", first, frame - 1, (now_ms() - start) / (frame - first));
            if (!apply_change(a, &schedule[next++])) return false;
            first = frame;
            start = now_ms();
        }
        raster_camera cam;
        raster_camera_at(frame, FRAME_COUNT, (double)a->t.width / a->t.height, &cam);
        const bool png = frame == FRAME_COUNT - 1, dump = a->opt.dump_dir && frame == a->opt.dump_frame;
        if (!record_frame(a, frame, &cam, png, dump) || !submit_and_wait(a)) return false;
        if (dump && !write_dump(a, &cam)) return false;
        if (png && !write_png(a)) return false;
    }
    printf("frames %u-%u: %.0f ms a frame\n", first, FRAME_COUNT - 1, (now_ms() - start) / (FRAME_COUNT - first));
    printf("cacao-raster: wrote %s (%ux%u)%s%s\n", a->opt.png_path, a->t.width, a->t.height,
           a->opt.dump_dir ? ", and frame inputs and AO into " : "", a->opt.dump_dir ? a->opt.dump_dir : "");
    return true;
}

static void destroy(app *a) {
    if (a->device) vkDeviceWaitIdle(a->device);
    cacao_context_destroy(a->cacao);
    if (a->device) {
        targets_destroy(a);
        buffer_destroy(a, &a->vertices);
        vkDestroyPipeline(a->device, a->gbuffer, NULL);
        vkDestroyPipeline(a->device, a->composite, NULL);
        vkDestroyPipelineLayout(a->device, a->gbuffer_layout, NULL);
        vkDestroyPipelineLayout(a->device, a->composite_layout, NULL);
        vkDestroyDescriptorSetLayout(a->device, a->composite_inputs, NULL);
        vkDestroyRenderPass(a->device, a->gbuffer_pass, NULL);
        vkDestroyRenderPass(a->device, a->composite_pass, NULL);
        vkDestroySampler(a->device, a->sampler, NULL);
        vkDestroyFence(a->device, a->fence, NULL);
        vkDestroyCommandPool(a->device, a->pool, NULL);
        vkDestroyDevice(a->device, NULL);
    }
    if (a->instance) vkDestroyInstance(a->instance, NULL);
}

int main(int argc, char **argv) {
    static app a; /* zero: every handle VK_NULL_HANDLE until created */
    const int parsed = parse_flags(argc, argv, &a.opt);
    if (parsed <= 0) return parsed < 0;
    int rc = 1;
    if (!create_device(&a)) goto done;
    if (!depth_format_supported(&a)) {
        fprintf(stderr, "cacao-raster: --depth-format: this device cannot use %s as a sampled depth attachment\n",
                a.opt.depth_format == VK_FORMAT_D32_SFLOAT ? "D32_SFLOAT" : "D24_UNORM_S8_UINT");
        rc = EXIT_UNSUPPORTED;
        goto done;
    }
    a.settings = (cacao_settings){.quality = schedule[0].quality, .radius = (float)RASTER_AO_RADIUS};
    if (cacao_context_create(&(cacao_context_desc){.physical_device = a.physical_device, .device = a.device},
                             &a.cacao) != CACAO_SUCCESS ||
        cacao_context_set_settings(a.cacao, &a.settings) != CACAO_SUCCESS) {
        fail("cannot create the cacao context");
        goto done;
    }
    if (vertices_create(&a) && pipelines_create(&a) && run(&a)) rc = 0;
done:
    destroy(&a);
    return rc;
}
