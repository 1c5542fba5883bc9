/* gpu.h - the plain Vulkan of the raster example, none of it about cacao: a device with one
 * graphics and compute queue, images, host-visible buffers, render passes, graphics pipelines,
 * image barriers and a submission waited for. On failure a function prints one line naming the
 * call to stderr and returns false. Objects are destroyed with the NULL-tolerant vkDestroy*. */
#ifndef RASTER_GPU_H
#define RASTER_GPU_H

#include <stdbool.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

typedef struct gpu {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;                             /* draws and computes */
    VkCommandPool pool;
    VkCommandBuffer cmd;                               /* the frame's: recorded, submitted, waited for */
    VkFence fence;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_set; /* VK_KHR_push_descriptor, which cacao needs too */
} gpu;

/* A Vulkan 1.1 device with VK_KHR_push_descriptor, a graphics + compute queue and the features
 * cacao needs (cacao.h). A CPU device (lavapipe) is taken first, as the `cacao` command takes it,
 * so that the tests compare like with like; an engine would take its GPU. */
bool gpu_create(gpu *g);
/* Waits for the device, then destroys what gpu_create made (the caller's objects go first). */
void gpu_destroy(gpu *g);

/* Prints "cacao-raster: <what> failed (VkResult N)" unless result is VK_SUCCESS. */
bool gpu_check(VkResult result, const char *what);

typedef struct gpu_image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
} gpu_image;

/* A 2D image of one level and layer in device memory, with a view of view_aspect. */
bool gpu_image_create(const gpu *g, VkFormat format, VkImageAspectFlags view_aspect, VkImageUsageFlags usage,
                      uint32_t width, uint32_t height, gpu_image *out);
void gpu_image_destroy(const gpu *g, gpu_image *image);
bool gpu_view_create(const gpu *g, VkImage image, VkFormat format, VkImageAspectFlags aspect, VkImageView *out);

typedef struct gpu_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped; /* host-visible, coherent, mapped for its lifetime */
} gpu_buffer;

bool gpu_buffer_create(const gpu *g, VkDeviceSize size, VkBufferUsageFlags usage, gpu_buffer *out);
void gpu_buffer_destroy(const gpu *g, gpu_buffer *buffer);

/* One subpass writing a colour attachment (loaded with load_colour) and, unless depth_format is
 * UNDEFINED, a cleared depth attachment; both stored. Each attachment starts and ends in its
 * attachment layout: the caller records the transitions in and out as barriers. */
bool gpu_render_pass_create(const gpu *g, VkFormat colour_format, VkAttachmentLoadOp load_colour,
                            VkFormat depth_format, VkRenderPass *out);
bool gpu_framebuffer_create(const gpu *g, VkRenderPass pass, uint32_t count, const VkImageView *views, uint32_t width,
                            uint32_t height, VkFramebuffer *out);

typedef struct gpu_pipeline_desc {
    const uint32_t *vert, *frag; /* SPIR-V */
    size_t vert_bytes, frag_bytes;
    const VkPipelineVertexInputStateCreateInfo *vertex_input; /* NULL: no vertex buffer */
    bool depth_test;                                          /* test LESS and write */
    VkPipelineLayout layout;
    VkRenderPass pass;
} gpu_pipeline_desc;

/* Triangles, no culling, no blending; viewport and scissor dynamic (the pipeline outlives sizes). */
bool gpu_pipeline_create(const gpu *g, const gpu_pipeline_desc *desc, VkPipeline *out);

/* One image barrier with a layout transition, all of the image's one level and layer. */
void gpu_transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                    VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

/* Submits g->cmd and waits for it (one frame in flight: the next frame and any resize may then
 * replace whatever it used). */
bool gpu_submit_and_wait(gpu *g);

#endif
