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
 * the AO this program got (ao.pfm): `cacao --scene DIR --settings DIR/settings.json` gives the
 * same AO (ctest raster_ao_equality).
 *
 * The plain Vulkan (device, images, render passes, pipelines) is in raster/gpu.c, the scene in
 * raster/scene.c, the GLSL shaders beside them; the PNG and PFM writers come from
 * tools/common (image_io.h). Exit 77: the device cannot sample the depth format. */
#include <cacao.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "image_io.h"
#include "raster/gpu.h"
#include "raster/scene.h"
/* SPIR-V of the shaders in raster/, compiled at build time by glslangValidator */
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
    const char *png_path;  /* the last frame, composited */
    VkFormat depth_format; /* D32_SFLOAT or D24_UNORM_S8_UINT */
    const char *dump_dir;  /* NULL: no dump */
    uint32_t dump_frame;
} options;

/* The app's images at one size: recreated on resize. */
typedef struct targets {
    uint32_t width, height;
    gpu_image depth;              /* depth attachment, then cacao's depth input (view: the depth aspect) */
    VkImageView depth_attachment; /* every aspect of the depth format, for the framebuffer */
    gpu_image normals;            /* A2B10G10R10 attachment, then cacao's normals input */
    gpu_image ao;                 /* cacao's output, R32_SFLOAT; SHADER_READ_ONLY_OPTIMAL between uses */
    gpu_image colour;             /* the composite, RGBA8 */
    gpu_buffer readback;          /* colour, depth, normals and AO, 4 bytes a texel each, in that order */
    VkFramebuffer gbuffer, composite;
    bool ao_layout_set;           /* the AO image has left UNDEFINED */
} targets;

typedef struct app {
    options opt;
    gpu g;
    gpu_buffer vertices;
    uint32_t vertex_count;
    VkRenderPass gbuffer_pass, composite_pass;
    VkSampler sampler;
    VkDescriptorSetLayout composite_inputs; /* push descriptors: depth, normals, AO */
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

/* ---- Flags ------------------------------------------------------------------------------ */

static void usage(void) {
    printf("usage: cacao-raster [-o FILE.png] [--depth-format d32|d24s8] [--dump DIR [--dump-frame N]]\n"
           "Renders %d frames of a rasterized room with cacao's AO; writes the last one to FILE.png\n"
           "(default cacao-raster.png). --dump DIR writes frame N's depth.pfm, normals.pfm, camera.json,\n"
           "settings.json and ao.pfm into DIR (default N = %d), for `cacao --scene DIR --settings ...`.\n",
           FRAME_COUNT, FRAME_COUNT - 1);
}

/* One line naming the flag; returns -1 (parse_flags' "bad flag"). */
static int bad_flag(const char *flag, const char *value, const char *why) {
    fprintf(stderr, "cacao-raster: %s%s%s: %s\n", cacao_shown(flag).text, value ? " " : "",
            value ? cacao_shown(value).text : "", why);
    return -1;
}

/* 1: run, 0: --help given, -1: a bad flag (one line said which). Nothing is written before 1. */
static int parse_flags(int argc, char **argv, options *o) {
    *o = (options){"cacao-raster.png", VK_FORMAT_D32_SFLOAT, NULL, FRAME_COUNT - 1};
    bool frame_given = false;
    for (int i = 1; i < argc; ++i) {
        const char *flag = argv[i];
        if (!strcmp(flag, "-h") || !strcmp(flag, "--help")) return usage(), 0;
        if (strcmp(flag, "-o") && strcmp(flag, "--depth-format") && strcmp(flag, "--dump") && strcmp(flag, "--dump-frame"))
            return bad_flag(flag, NULL, flag[0] == '-' ? "unknown flag (see --help)" : "unexpected argument (see --help)");
        const char *value = ++i < argc ? argv[i] : NULL;
        if (!value || !value[0]) return bad_flag(flag, NULL, "needs a value");
        if (!strcmp(flag, "-o")) {
            const char *dot = strrchr(value, '.');
            if (!dot || strcmp(dot, ".png")) return bad_flag(flag, value, "must name a .png file");
            o->png_path = value;
        } else if (!strcmp(flag, "--depth-format")) {
            if (!strcmp(value, "d32")) o->depth_format = VK_FORMAT_D32_SFLOAT;
            else if (!strcmp(value, "d24s8")) o->depth_format = VK_FORMAT_D24_UNORM_S8_UINT;
            else return bad_flag(flag, value, "use d32 or d24s8");
        } else if (!strcmp(flag, "--dump")) {
            o->dump_dir = value;
        } else {
            char *end = NULL;
            const unsigned long n = strtoul(value, &end, 10);
            char why[32];
            snprintf(why, sizeof why, "must be 0 to %d", FRAME_COUNT - 1);
            if (*end || value[0] == '-' || n >= FRAME_COUNT) return bad_flag(flag, value, why);
            o->dump_frame = (uint32_t)n;
            frame_given = true;
        }
    }
    if (frame_given && !o->dump_dir) return bad_flag("--dump-frame", NULL, "needs --dump DIR");
    struct stat st; /* the folder is made here when absent: the only output before the frames */
    if (o->dump_dir && stat(o->dump_dir, &st) != 0 && mkdir(o->dump_dir, 0777) != 0) {
        char why[256];
        snprintf(why, sizeof why, "cannot create it: %s", strerror(errno));
        return bad_flag("--dump", o->dump_dir, why);
    }
    if (o->dump_dir && stat(o->dump_dir, &st) == 0 && !S_ISDIR(st.st_mode))
        return bad_flag("--dump", o->dump_dir, "not a directory");
    return 1;
}

/* ---- The app's images, render passes and pipelines ---------------------------------------- */

/* Whether the depth format can be a depth attachment, sampled (by cacao and the composite) and
 * copied out (--dump). */
static bool depth_format_supported(const app *a) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(a->g.physical_device, a->opt.depth_format, &p);
    const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    return (p.optimalTilingFeatures & need) == need;
}

static VkImageAspectFlags depth_aspects(const app *a) { /* every aspect: for transitions and the framebuffer */
    return a->opt.depth_format == VK_FORMAT_D24_UNORM_S8_UINT ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT
                                                              : VK_IMAGE_ASPECT_DEPTH_BIT;
}

static void targets_destroy(app *a) {
    const gpu *g = &a->g;
    vkDestroyFramebuffer(g->device, a->t.gbuffer, NULL);
    vkDestroyFramebuffer(g->device, a->t.composite, NULL);
    vkDestroyImageView(g->device, a->t.depth_attachment, NULL);
    gpu_image_destroy(g, &a->t.depth);
    gpu_image_destroy(g, &a->t.normals);
    gpu_image_destroy(g, &a->t.ao);
    gpu_image_destroy(g, &a->t.colour);
    gpu_buffer_destroy(g, &a->t.readback);
    a->t = (targets){0};
}

/* The app's images and framebuffers at this size (cacao's own are cacao_context_resize's). */
static bool targets_create(app *a, uint32_t w, uint32_t h) {
    targets_destroy(a);
    a->t.width = w;
    a->t.height = h;
    const gpu *g = &a->g;
    const VkImageUsageFlags read = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const VkImageAspectFlags colour = VK_IMAGE_ASPECT_COLOR_BIT;
    return gpu_image_create(g, a->opt.depth_format, VK_IMAGE_ASPECT_DEPTH_BIT,
                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | read, w, h, &a->t.depth) &&
           gpu_view_create(g, a->t.depth.image, a->opt.depth_format, depth_aspects(a), &a->t.depth_attachment) &&
           gpu_image_create(g, VK_FORMAT_A2B10G10R10_UNORM_PACK32, colour, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | read,
                            w, h, &a->t.normals) &&
           gpu_image_create(g, VK_FORMAT_R32_SFLOAT, colour, VK_IMAGE_USAGE_STORAGE_BIT | read, w, h, &a->t.ao) &&
           gpu_image_create(g, VK_FORMAT_R8G8B8A8_UNORM, colour,
                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, w, h, &a->t.colour) &&
           gpu_buffer_create(g, 16ull * w * h, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &a->t.readback) &&
           gpu_framebuffer_create(g, a->gbuffer_pass, 2, (VkImageView[2]){a->t.normals.view, a->t.depth_attachment}, w,
                                  h, &a->t.gbuffer) &&
           gpu_framebuffer_create(g, a->composite_pass, 1, &a->t.colour.view, w, h, &a->t.composite);
}

/* Push constants of the two passes (std430 layout of the shaders' blocks; matrices column-major). */
typedef struct gbuffer_constants {
    float clip_from_world[16], view_from_world[16];
} gbuffer_constants;
typedef struct composite_constants {
    float light_view[4], size[2];
} composite_constants;

/* Render passes, pipelines and the scene's vertices: created once, whatever the size. */
static bool passes_create(app *a) {
    const gpu *g = &a->g;
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
    if (!gpu_render_pass_create(g, VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                a->opt.depth_format, &a->gbuffer_pass) ||
        !gpu_render_pass_create(g, VK_FORMAT_R8G8B8A8_UNORM, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_FORMAT_UNDEFINED,
                                &a->composite_pass) ||
        !gpu_check(vkCreateSampler(g->device, &si, NULL, &a->sampler), "vkCreateSampler") ||
        !gpu_check(vkCreateDescriptorSetLayout(g->device, &dsl, NULL, &a->composite_inputs),
                   "vkCreateDescriptorSetLayout") ||
        !gpu_check(vkCreatePipelineLayout(g->device, &gbuffer_layout, NULL, &a->gbuffer_layout),
                   "vkCreatePipelineLayout"))
        return false;
    const VkPipelineLayoutCreateInfo composite_layout = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
        .pSetLayouts = &a->composite_inputs, .pushConstantRangeCount = 1, .pPushConstantRanges = &composite_range};
    if (!gpu_check(vkCreatePipelineLayout(g->device, &composite_layout, NULL, &a->composite_layout),
                   "vkCreatePipelineLayout"))
        return false;
    const VkVertexInputBindingDescription binding = {0, sizeof(raster_vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(raster_vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(raster_vertex, normal)},
        {2, 0, VK_FORMAT_R32_UINT, offsetof(raster_vertex, material)}};
    const VkPipelineVertexInputStateCreateInfo vertices = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO, .vertexBindingDescriptionCount = 1,
        .pVertexBindingDescriptions = &binding, .vertexAttributeDescriptionCount = 3,
        .pVertexAttributeDescriptions = attributes};
    const gpu_pipeline_desc gbuffer = {gbuffer_vert, gbuffer_frag, sizeof gbuffer_vert, sizeof gbuffer_frag,
                                       &vertices, true, a->gbuffer_layout, a->gbuffer_pass};
    const gpu_pipeline_desc composite = {composite_vert, composite_frag, sizeof composite_vert, sizeof composite_frag,
                                         NULL, false, a->composite_layout, a->composite_pass};
    if (!gpu_pipeline_create(g, &gbuffer, &a->gbuffer) || !gpu_pipeline_create(g, &composite, &a->composite))
        return false;
    raster_vertex *scene = malloc(RASTER_SCENE_MAX_VERTICES * sizeof *scene);
    if (!scene) return fail("out of memory");
    a->vertex_count = raster_scene_build(scene);
    const bool ok = gpu_buffer_create(g, a->vertex_count * sizeof *scene, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                      &a->vertices);
    if (ok) memcpy(a->vertices.mapped, scene, a->vertex_count * sizeof *scene);
    free(scene);
    return ok;
}

/* ---- One frame -------------------------------------------------------------------------- */

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

static void begin_pass(const app *a, VkRenderPass pass, VkFramebuffer framebuffer, uint32_t clear_count,
                       const VkClearValue *clear) {
    const VkRect2D area = {{0, 0}, {a->t.width, a->t.height}};
    const VkRenderPassBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO, .renderPass = pass,
                                         .framebuffer = framebuffer, .renderArea = area,
                                         .clearValueCount = clear_count, .pClearValues = clear};
    vkCmdBeginRenderPass(a->g.cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport = {0, 0, (float)a->t.width, (float)a->t.height, 0, 1};
    vkCmdSetViewport(a->g.cmd, 0, 1, &viewport);
    vkCmdSetScissor(a->g.cmd, 0, 1, &area);
}

/* The G-buffer pass: depth and normals attachments, cleared, then the room. */
static void record_gbuffer(const app *a, const raster_camera *cam) {
    const VkCommandBuffer cmd = a->g.cmd;
    const VkPipelineStageFlags readers = /* of the previous frame: cacao, the composite, --dump's copies */
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    const VkPipelineStageFlags tests =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    gpu_transition(cmd, a->t.depth.image, depth_aspects(a), VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, readers, 0, tests,
                   VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    gpu_transition(cmd, a->t.normals.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, readers, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    const VkClearValue clear[2] = {{.color = {{0.5f, 0.5f, 0.5f, 0.0f}}}, /* normal 0 where nothing is drawn */
                                   {.depthStencil = {1.0f, 0}}};
    begin_pass(a, a->gbuffer_pass, a->t.gbuffer, 2, clear);
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
    /* Out of the attachment layouts into the layouts cacao is told about, for cacao's compute
     * and the composite's fragment shader. */
    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    gpu_transition(cmd, a->t.depth.image, depth_aspects(a), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, tests, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                   shaders, VK_ACCESS_SHADER_READ_BIT);
    gpu_transition(cmd, a->t.normals.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, shaders, VK_ACCESS_SHADER_READ_BIT);
}

/* The composite: depth, normals and AO sampled by one fullscreen triangle into the colour image. */
static void record_composite(const app *a, const raster_camera *cam) {
    const VkCommandBuffer cmd = a->g.cmd;
    gpu_transition(cmd, a->t.colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                   VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    begin_pass(a, a->composite_pass, a->t.composite, 0, NULL);
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
    a->g.push_descriptor_set(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, a->composite_layout, 0, 3, writes);
    const composite_constants constants = {{cam->light_view[0], cam->light_view[1], cam->light_view[2], 0},
                                           {(float)a->t.width, (float)a->t.height}};
    vkCmdPushConstants(cmd, a->composite_layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof constants, &constants);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
}

/* Copies an image (4 bytes a texel) into slot `slot` of the readback buffer, leaving it in
 * TRANSFER_SRC_OPTIMAL. */
static void record_copy(const app *a, VkImage image, VkImageAspectFlags aspects, VkImageAspectFlags copied,
                        VkImageLayout from, VkPipelineStageFlags src_stage, VkAccessFlags src_access, uint32_t slot) {
    gpu_transition(a->g.cmd, image, aspects, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, src_stage, src_access,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferImageCopy region = {.bufferOffset = 4ull * a->t.width * a->t.height * slot,
                                      .imageSubresource = {copied, 0, 0, 1},
                                      .imageExtent = {a->t.width, a->t.height, 1}};
    vkCmdCopyImageToBuffer(a->g.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, a->t.readback.buffer, 1, &region);
}

/* --dump's copies: what cacao read and what it wrote; the AO image then returns to its layout. */
static void record_dump_copies(const app *a) {
    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    const VkImageAspectFlags colour = VK_IMAGE_ASPECT_COLOR_BIT;
    record_copy(a, a->t.depth.image, depth_aspects(a), VK_IMAGE_ASPECT_DEPTH_BIT,
                VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, shaders, 0, 1);
    record_copy(a, a->t.normals.image, colour, colour, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, shaders, 0, 2);
    record_copy(a, a->t.ao.image, colour, colour, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 3);
    gpu_transition(a->g.cmd, a->t.ao.image, colour, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, shaders,
                   VK_ACCESS_SHADER_READ_BIT);
}

static bool record_frame(app *a, uint32_t frame, const raster_camera *cam, bool png, bool dump) {
    const VkCommandBuffer cmd = a->g.cmd;
    const VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                            .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    if (!gpu_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer")) return false;
    if (!a->t.ao_layout_set) { /* a new AO image: into the layout it keeps between frames */
        gpu_transition(cmd, a->t.ao.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0);
        a->t.ao_layout_set = true;
    }
    record_gbuffer(a, cam);

    /* cacao, between the two graphics passes. No barrier of ours around it: it orders itself
     * after the transitions above and before the composite's reads of the AO, and returns the
     * AO image to SHADER_READ_ONLY_OPTIMAL, the layout we give. */
    cacao_inputs in = {
        .depth = {a->t.depth.image, a->t.depth.view, a->opt.depth_format,
                  VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
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
    if (cacao_record(a->cacao, cmd, &in) != CACAO_SUCCESS) {
        vkEndCommandBuffer(cmd);
        fprintf(stderr, "cacao-raster: cacao_record: %s\n", cacao_context_last_error(a->cacao));
        return false;
    }

    record_composite(a, cam);
    if (png)
        record_copy(a, a->t.colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0);
    if (dump) record_dump_copies(a);
    if (png || dump) {
        const VkMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                         .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                         .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL,
                             0, NULL);
    }
    return gpu_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
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
    cacao_memory_info memory; /* after a size or settings change, before the next cacao_record */
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
    if (!temp) return fail("out of memory");
    FILE *f = fopen(temp, "w");
    bool ok = f && fputs(text, f) >= 0;
    if (f) ok = fclose(f) == 0 && ok;
    return cacao_commit_temp(temp, path, ok, err, sizeof err) || fail(err);
}

/* A D24 texel as copied out (depth in the low 24 bits) to the float a sampler gives cacao. Vulkan
 * leaves the last bit of that conversion to the driver: lavapipe multiplies by the float nearest
 * 1/(2^24-1), as here. (The correctly rounded quotient differs in the last bit for most texels of
 * this scene, and the AO computed from it in 0.8% of the pixels, by up to 0.015.) */
static float d24_to_float(uint32_t texel) { return (float)(texel & 0xffffffu) * (float)(1.0 / 16777215.0); }

/* The frame's camera.json and settings.json, as the `cacao` command reads them. */
static bool write_camera_and_settings(const app *a, const raster_camera *cam) {
    char path[4096], text[1024];
    int len = snprintf(text, sizeof text,
                       "{\"width\": %u, \"height\": %u, \"fov_y_deg\": %g, \"near\": %g, \"far\": %g,\n"
                       " \"projection\": [",
                       a->t.width, a->t.height, RASTER_FOV_Y_DEG, RASTER_NEAR, RASTER_FAR);
    for (int i = 0; i < 16; ++i) /* 9 digits: each float reads back as itself */
        len += snprintf(text + len, sizeof text - (size_t)len, "%.9g%s", (double)cam->projection[i],
                        i < 15 ? ", " : "]}\n");
    snprintf(path, sizeof path, "%s/camera.json", a->opt.dump_dir);
    if (!write_text(path, text)) return false;
    snprintf(text, sizeof text, "{\"quality\": \"%s\", \"radius\": %.9g}\n", cacao_quality_name(a->settings.quality),
             (double)a->settings.radius);
    snprintf(path, sizeof path, "%s/settings.json", a->opt.dump_dir);
    return write_text(path, text);
}

/* The inputs as the `cacao` command reads a scene folder (shared/scenes/README.md): raw depth as
 * float, unit right-handed view-space normals as float; and the AO cacao wrote. */
static bool write_dump(const app *a, const raster_camera *cam) {
    const uint32_t w = a->t.width, h = a->t.height;
    const size_t pixels = (size_t)w * h;
    cacao_img depth = {w, h, 1, malloc(pixels * sizeof(float))}, ao = {w, h, 1, malloc(pixels * sizeof(float))};
    cacao_img normals = {w, h, 3, malloc(pixels * 3 * sizeof(float))};
    bool ok = (depth.data && normals.data && ao.data) || fail("out of memory");
    const uint32_t *d = readback_slot(a, 1), *n = readback_slot(a, 2);
    for (size_t i = 0; ok && i < pixels; ++i) {
        if (a->opt.depth_format == VK_FORMAT_D32_SFLOAT) memcpy(&depth.data[i], &d[i], sizeof(float));
        else depth.data[i] = d24_to_float(d[i]);
        for (int c = 0; c < 3; ++c) /* 10-bit UNORM, unpacked as cacao does: * 2 - 1 */
            normals.data[3 * i + c] = (float)(n[i] >> (10 * c) & 1023u) / 1023.0f * 2.0f - 1.0f;
    }
    if (ok) memcpy(ao.data, readback_slot(a, 3), pixels * sizeof(float));
    const char *names[3] = {"depth.pfm", "normals.pfm", "ao.pfm"};
    const cacao_img *images[3] = {&depth, &normals, &ao};
    char path[4096], err[512];
    for (int i = 0; ok && i < 3; ++i) {
        snprintf(path, sizeof path, "%s/%s", a->opt.dump_dir, names[i]);
        ok = cacao_pfm_write(path, images[i], err, sizeof err) || fail(err);
    }
    cacao_img_free(&depth);
    cacao_img_free(&normals);
    cacao_img_free(&ao);
    return ok && write_camera_and_settings(a, cam);
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
        if (!record_frame(a, frame, &cam, png, dump) || !gpu_submit_and_wait(&a->g)) return false;
        if (dump && !write_dump(a, &cam)) return false;
        if (png && !write_png(a)) return false;
    }
    printf("frames %u-%u: %.0f ms a frame\n", first, FRAME_COUNT - 1, (now_ms() - start) / (FRAME_COUNT - first));
    printf("cacao-raster: wrote %s (%ux%u)%s%s\n", a->opt.png_path, a->t.width, a->t.height,
           a->opt.dump_dir ? " and frame inputs and AO into " : "", a->opt.dump_dir ? a->opt.dump_dir : "");
    return true;
}

static void destroy(app *a) {
    const VkDevice device = a->g.device;
    if (device) vkDeviceWaitIdle(device);
    cacao_context_destroy(a->cacao); /* cacao frees what it created; the app frees what it created */
    if (device) {
        targets_destroy(a);
        gpu_buffer_destroy(&a->g, &a->vertices);
        vkDestroyPipeline(device, a->gbuffer, NULL);
        vkDestroyPipeline(device, a->composite, NULL);
        vkDestroyPipelineLayout(device, a->gbuffer_layout, NULL);
        vkDestroyPipelineLayout(device, a->composite_layout, NULL);
        vkDestroyDescriptorSetLayout(device, a->composite_inputs, NULL);
        vkDestroySampler(device, a->sampler, NULL);
        vkDestroyRenderPass(device, a->gbuffer_pass, NULL);
        vkDestroyRenderPass(device, a->composite_pass, NULL);
    }
    gpu_destroy(&a->g);
}

int main(int argc, char **argv) {
    static app a; /* zero: every handle VK_NULL_HANDLE until created */
    const int parsed = parse_flags(argc, argv, &a.opt);
    if (parsed <= 0) return parsed < 0;
    int rc = 1;
    if (!gpu_create(&a.g)) goto done;
    if (!depth_format_supported(&a)) {
        fprintf(stderr, "cacao-raster: --depth-format: this device cannot use %s as a sampled depth attachment\n",
                a.opt.depth_format == VK_FORMAT_D32_SFLOAT ? "D32_SFLOAT" : "D24_UNORM_S8_UINT");
        rc = EXIT_UNSUPPORTED;
        goto done;
    }
    /* cacao on the app's device; settings before the first resize (in apply_change). */
    a.settings = (cacao_settings){.quality = schedule[0].quality, .radius = (float)RASTER_AO_RADIUS};
    if (cacao_context_create(&(cacao_context_desc){.physical_device = a.g.physical_device, .device = a.g.device},
                             &a.cacao) != CACAO_SUCCESS ||
        cacao_context_set_settings(a.cacao, &a.settings) != CACAO_SUCCESS) {
        fail("cannot create the cacao context");
        goto done;
    }
    if (passes_create(&a) && run(&a)) rc = 0;
done:
    destroy(&a);
    return rc;
}
