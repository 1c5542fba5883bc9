/* gpu.c - the plain Vulkan of the raster example (see gpu.h). */
#include "gpu.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool gpu_check(VkResult result, const char *what) {
    if (result == VK_SUCCESS) return true;
    fprintf(stderr, "cacao-raster: %s failed (VkResult %d)\n", what, (int)result);
    return false;
}

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

static VkPhysicalDevice pick_device(VkInstance instance) {
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    vkEnumeratePhysicalDevices(instance, &count, devices);
    for (int cpu_only = 1; cpu_only >= 0; --cpu_only)
        for (uint32_t i = 0; i < count; ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            if (p.apiVersion >= VK_API_VERSION_1_1 && (!cpu_only || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) &&
                has_extension(devices[i], VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) &&
                graphics_family(devices[i]) != UINT32_MAX)
                return devices[i];
        }
    return VK_NULL_HANDLE;
}

bool gpu_create(gpu *g) {
    const VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "cacao-raster",
                                   .apiVersion = VK_API_VERSION_1_1};
    const VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    if (!gpu_check(vkCreateInstance(&ici, NULL, &g->instance), "vkCreateInstance (is a Vulkan driver installed?)"))
        return false;
    g->physical_device = pick_device(g->instance);
    if (!g->physical_device) {
        fprintf(stderr, "cacao-raster: no Vulkan 1.1 device with VK_KHR_push_descriptor and a graphics queue\n");
        return false;
    }
    g->queue_family = graphics_family(g->physical_device);
    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                           .queueFamilyIndex = g->queue_family, .queueCount = 1,
                                           .pQueuePriorities = &priority};
    const VkPhysicalDeviceFeatures features = {.shaderStorageImageWriteWithoutFormat = VK_TRUE,
                                               .shaderStorageImageExtendedFormats = VK_TRUE};
    const char *extension = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    const VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1,
                                    .pQueueCreateInfos = &queue, .enabledExtensionCount = 1,
                                    .ppEnabledExtensionNames = &extension, .pEnabledFeatures = &features};
    if (!gpu_check(vkCreateDevice(g->physical_device, &dci, NULL, &g->device), "vkCreateDevice")) return false;
    vkGetDeviceQueue(g->device, g->queue_family, 0, &g->queue);
    g->push_descriptor_set = (PFN_vkCmdPushDescriptorSetKHR)vkGetDeviceProcAddr(g->device, "vkCmdPushDescriptorSetKHR");
    const VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                          .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                          .queueFamilyIndex = g->queue_family};
    const VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (!gpu_check(vkCreateCommandPool(g->device, &pool, NULL, &g->pool), "vkCreateCommandPool") ||
        !gpu_check(vkCreateFence(g->device, &fence, NULL, &g->fence), "vkCreateFence"))
        return false;
    const VkCommandBufferAllocateInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                             .commandPool = g->pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                             .commandBufferCount = 1};
    return gpu_check(vkAllocateCommandBuffers(g->device, &cbi, &g->cmd), "vkAllocateCommandBuffers");
}

void gpu_destroy(gpu *g) {
    if (g->device) {
        vkDeviceWaitIdle(g->device);
        vkDestroyFence(g->device, g->fence, NULL);
        vkDestroyCommandPool(g->device, g->pool, NULL);
        vkDestroyDevice(g->device, NULL);
    }
    if (g->instance) vkDestroyInstance(g->instance, NULL);
    *g = (gpu){0};
}

static bool allocate(const gpu *g, VkMemoryRequirements req, VkMemoryPropertyFlags flags, VkDeviceMemory *memory) {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(g->physical_device, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (p.memoryTypes[i].propertyFlags & flags) == flags) {
            const VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                             .allocationSize = req.size, .memoryTypeIndex = i};
            return gpu_check(vkAllocateMemory(g->device, &ai, NULL, memory), "vkAllocateMemory");
        }
    fprintf(stderr, "cacao-raster: no memory type with properties 0x%x\n", (unsigned)flags);
    return false;
}

bool gpu_view_create(const gpu *g, VkImage image, VkFormat format, VkImageAspectFlags aspect, VkImageView *out) {
    const VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = image,
                                      .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                      .subresourceRange = {aspect, 0, 1, 0, 1}};
    return gpu_check(vkCreateImageView(g->device, &vi, NULL, out), "vkCreateImageView");
}

bool gpu_image_create(const gpu *g, VkFormat format, VkImageAspectFlags view_aspect, VkImageUsageFlags usage,
                      uint32_t width, uint32_t height, gpu_image *out) {
    const VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                                  .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                                  .samples = VK_SAMPLE_COUNT_1_BIT, .usage = usage};
    if (!gpu_check(vkCreateImage(g->device, &ii, NULL, &out->image), "vkCreateImage")) return false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(g->device, out->image, &req);
    return allocate(g, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &out->memory) &&
           gpu_check(vkBindImageMemory(g->device, out->image, out->memory, 0), "vkBindImageMemory") &&
           gpu_view_create(g, out->image, format, view_aspect, &out->view);
}

void gpu_image_destroy(const gpu *g, gpu_image *image) {
    vkDestroyImageView(g->device, image->view, NULL);
    vkDestroyImage(g->device, image->image, NULL);
    vkFreeMemory(g->device, image->memory, NULL);
    *image = (gpu_image){0};
}

bool gpu_buffer_create(const gpu *g, VkDeviceSize size, VkBufferUsageFlags usage, gpu_buffer *out) {
    const VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    if (!gpu_check(vkCreateBuffer(g->device, &bi, NULL, &out->buffer), "vkCreateBuffer")) return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(g->device, out->buffer, &req);
    return allocate(g, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &out->memory) &&
           gpu_check(vkBindBufferMemory(g->device, out->buffer, out->memory, 0), "vkBindBufferMemory") &&
           gpu_check(vkMapMemory(g->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped), "vkMapMemory");
}

void gpu_buffer_destroy(const gpu *g, gpu_buffer *buffer) {
    vkDestroyBuffer(g->device, buffer->buffer, NULL);
    vkFreeMemory(g->device, buffer->memory, NULL);
    *buffer = (gpu_buffer){0};
}

bool gpu_render_pass_create(const gpu *g, VkFormat colour_format, VkAttachmentLoadOp load_colour,
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
    return gpu_check(vkCreateRenderPass(g->device, &ri, NULL, out), "vkCreateRenderPass");
}

bool gpu_framebuffer_create(const gpu *g, VkRenderPass pass, uint32_t count, const VkImageView *views, uint32_t width,
                            uint32_t height, VkFramebuffer *out) {
    const VkFramebufferCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO, .renderPass = pass,
                                        .attachmentCount = count, .pAttachments = views, .width = width,
                                        .height = height, .layers = 1};
    return gpu_check(vkCreateFramebuffer(g->device, &fi, NULL, out), "vkCreateFramebuffer");
}

static VkShaderModule shader_module(const gpu *g, const uint32_t *code, size_t bytes) {
    const VkShaderModuleCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes,
                                         .pCode = code};
    VkShaderModule module = VK_NULL_HANDLE;
    gpu_check(vkCreateShaderModule(g->device, &si, NULL, &module), "vkCreateShaderModule");
    return module;
}

bool gpu_pipeline_create(const gpu *g, const gpu_pipeline_desc *d, VkPipeline *out) {
    const VkShaderModule vert = shader_module(g, d->vert, d->vert_bytes);
    const VkShaderModule frag = shader_module(g, d->frag, d->frag_bytes);
    const VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = frag, .pName = "main"}};
    const VkPipelineVertexInputStateCreateInfo no_vertices = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
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
    const VkPipelineDepthStencilStateCreateInfo depth = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO, .depthTestEnable = d->depth_test,
        .depthWriteEnable = d->depth_test, .depthCompareOp = VK_COMPARE_OP_LESS};
    const VkPipelineColorBlendAttachmentState blend_attachment = {.colorWriteMask = 0xf};
    const VkPipelineColorBlendStateCreateInfo blend = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                                       .attachmentCount = 1, .pAttachments = &blend_attachment};
    const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    const VkPipelineDynamicStateCreateInfo dynamic = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                                      .dynamicStateCount = 2, .pDynamicStates = dynamic_states};
    const VkGraphicsPipelineCreateInfo gi = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, .stageCount = 2, .pStages = stages,
        .pVertexInputState = d->vertex_input ? d->vertex_input : &no_vertices, .pInputAssemblyState = &assembly,
        .pViewportState = &viewport, .pRasterizationState = &raster, .pMultisampleState = &multisample,
        .pDepthStencilState = &depth, .pColorBlendState = &blend, .pDynamicState = &dynamic, .layout = d->layout,
        .renderPass = d->pass};
    const bool ok = vert && frag &&
                    gpu_check(vkCreateGraphicsPipelines(g->device, VK_NULL_HANDLE, 1, &gi, NULL, out),
                              "vkCreateGraphicsPipelines");
    vkDestroyShaderModule(g->device, vert, NULL);
    vkDestroyShaderModule(g->device, frag, NULL);
    return ok;
}

void gpu_transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                    VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    const VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src_access,
                                    .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to,
                                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                                    .subresourceRange = {aspect, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

bool gpu_submit_and_wait(gpu *g) {
    const VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                             .pCommandBuffers = &g->cmd};
    return gpu_check(vkQueueSubmit(g->queue, 1, &si, g->fence), "vkQueueSubmit") &&
           gpu_check(vkWaitForFences(g->device, 1, &g->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences") &&
           gpu_check(vkResetFences(g->device, 1, &g->fence), "vkResetFences");
}
