/* headless.c - the smallest complete cacao integration, as a guide.
 *
 * An "engine" that owns its Vulkan device, uploads a depth buffer, and records cacao into its own
 * command buffer next to its own work (a clear of the AO image), submits once, and reads the AO
 * back. Works on any Vulkan 1.1 device with VK_KHR_push_descriptor (lavapipe included).
 * Prints the mean AO of the floor and of a crease; exits non-zero on any failure. With an argument,
 * writes the AO there too (W x H little-endian floats, row by row).
 *
 * Built with -DCACAO_EXAMPLE_VOLK (and volk.c), it is an engine on volk: no loader linked, every
 * vk* call through volk's pointers, and cacao handed the same entry points (cacao_context_desc
 * .instance / .get_instance_proc_addr / .get_device_proc_addr). Without it, cacao finds the loader
 * on its own. The consumer_volk test checks that both write the same bytes. */
#ifdef CACAO_EXAMPLE_VOLK
#include <volk.h> /* before cacao.h: it defines VK_NO_PROTOTYPES */
#endif
#include <cacao.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define W 128
#define H 96
#define CHECK_VK(x) do { if ((x) != VK_SUCCESS) { fprintf(stderr, "failed: %s\n", #x); return 1; } } while (0)

static VkDevice dev;
static VkPhysicalDevice gpu;

static uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(gpu, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (p.memoryTypes[i].propertyFlags & flags) == flags) return i;
    return 0;
}

/* A 2D image with its memory and view (the engine's own resources). */
static void make_image(VkFormat format, VkImageUsageFlags usage, VkImage *image, VkImageView *view,
                       VkDeviceMemory *mem) {
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D, .format = format,
                            .extent = {W, H, 1}, .mipLevels = 1, .arrayLayers = 1, .samples = VK_SAMPLE_COUNT_1_BIT,
                            .usage = usage};
    vkCreateImage(dev, &ii, NULL, image);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, *image, &req);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = memory_type(req.memoryTypeBits, 0)};
    vkAllocateMemory(dev, &ai, NULL, mem);
    vkBindImageMemory(dev, *image, *mem, 0);
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = *image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCreateImageView(dev, &vi, NULL, view);
}

static void barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                    VkAccessFlags dst, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
    VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, .srcAccessMask = src, .dstAccessMask = dst,
                              .oldLayout = from, .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                              .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                              .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

int main(int argc, char **argv) {
    /* 1. Instance and device: Vulkan 1.1 plus VK_KHR_push_descriptor; any device will do. */
#ifdef CACAO_EXAMPLE_VOLK
    CHECK_VK(volkInitialize());
#endif
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .apiVersion = VK_API_VERSION_1_1};
    VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VkInstance instance;
    CHECK_VK(vkCreateInstance(&ici, NULL, &instance));
#ifdef CACAO_EXAMPLE_VOLK
    volkLoadInstance(instance);
#endif
    uint32_t count = 1;
    vkEnumeratePhysicalDevices(instance, &count, &gpu);
    if (count == 0) return fprintf(stderr, "no Vulkan device\n"), 1;
    const char *ext = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = 0,
                                  .queueCount = 1, .pQueuePriorities = &priority}; /* family 0 has compute */
    VkPhysicalDeviceFeatures features = {.shaderStorageImageWriteWithoutFormat = VK_TRUE,
                                         .shaderStorageImageExtendedFormats = VK_TRUE};
    VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1, .pQueueCreateInfos = &qi,
                              .enabledExtensionCount = 1, .ppEnabledExtensionNames = &ext, .pEnabledFeatures = &features};
    CHECK_VK(vkCreateDevice(gpu, &dci, NULL, &dev));
#ifdef CACAO_EXAMPLE_VOLK
    volkLoadDevice(dev);
#endif
    VkQueue queue;
    vkGetDeviceQueue(dev, 0, 0, &queue);

    /* 2. The engine's images: a depth buffer (R32_SFLOAT here; D32 works too) and the AO target. */
    VkImage depth, ao;
    VkImageView depth_view, ao_view;
    VkDeviceMemory depth_memory, ao_memory;
    make_image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &depth, &depth_view,
               &depth_memory);
    make_image(VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT, &ao, &ao_view, &ao_memory);

    /* A host-visible buffer: depth goes up through it, AO comes back through it. Scene: a floor
     * (y = -1) meeting a wall (z = -4), camera at the origin looking down -z, fov 60, near 0.1, far 100. */
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = W * H * 4,
                             .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    VkBuffer staging;
    vkCreateBuffer(dev, &bi, NULL, &staging);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, staging, &req);
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
        .memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                           VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
    VkDeviceMemory staging_memory;
    float *host;
    vkAllocateMemory(dev, &ai, NULL, &staging_memory);
    vkBindBufferMemory(dev, staging, staging_memory, 0);
    vkMapMemory(dev, staging_memory, 0, VK_WHOLE_SIZE, 0, (void **)&host);
    const double n = 0.1, f = 100.0, t = tan(3.14159265358979 / 6), aspect = (double)W / H;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double dy = (1 - 2 * (y + 0.5) / H) * t; /* ray (dx, dy, -1) hits floor or wall first */
            double z = dy < -0.25 ? fmin(1.0 / -dy, 4.0) : 4.0;
            host[y * W + x] = (float)(f * (z - n) / (z * (f - n)));
        }

    /* 3. cacao: a context on the engine's device, settings, and the intermediates for this size. */
    cacao_context_desc desc = {.physical_device = gpu, .device = dev};
#ifdef CACAO_EXAMPLE_VOLK
    desc.instance = instance; /* cacao loads its entry points the way the engine does */
    desc.get_instance_proc_addr = vkGetInstanceProcAddr;
    desc.get_device_proc_addr = vkGetDeviceProcAddr;
#endif
    cacao_context *ctx;
    cacao_memory_info mem;
    if (cacao_context_create(&desc, &ctx) ||
        cacao_context_set_settings(ctx, &(cacao_settings){.quality = CACAO_QUALITY_HIGH, .radius = 0.5f,
                                                          .generate_normals = true}) ||
        cacao_context_resize(ctx, W, H, &mem))
        return fprintf(stderr, "cacao: %s\n", cacao_context_last_error(ctx)), 1;
    printf("cacao holds %llu bytes (%u device allocation) in %u images and %u pipelines\n",
           (unsigned long long)mem.total_bytes, mem.allocation_count, mem.image_count, mem.pipeline_count);

    /* 4. One command buffer: upload, the engine's own clear, cacao, readback. */
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .queueFamilyIndex = 0};
    VkCommandPool pool;
    vkCreateCommandPool(dev, &pi, NULL, &pool);
    VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer cmd;
    vkAllocateCommandBuffers(dev, &cai, &cmd);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
    barrier(cmd, depth, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    vkCmdCopyBufferToImage(cmd, staging, depth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    barrier(cmd, depth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
            VK_ACCESS_TRANSFER_WRITE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    /* The engine's own work on the AO image; cacao orders itself after it (it begins with a barrier
     * from ALL_COMMANDS), so no barrier of ours goes between this clear and cacao_record. */
    barrier(cmd, ao, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkClearColorValue zero = {{0}};
    VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, ao, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);

    cacao_inputs in = {
        .depth = {depth, depth_view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .output = {ao, ao_view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_GENERAL},
        .projection = {(float)(1 / (aspect * t)), 0, 0, 0, 0, (float)(1 / t), 0, 0,
                       0, 0, (float)(-f / (f - n)), (float)(-f * n / (f - n)), 0, 0, -1, 0},
        .matrices_row_major = true, /* math convention clip = P * v, written row by row */
    };
    if (cacao_record(ctx, cmd, &in) != CACAO_SUCCESS) return fprintf(stderr, "%s\n", cacao_context_last_error(ctx)), 1;

    /* cacao ends with a barrier from its compute writes to ALL_COMMANDS and leaves the AO in the
     * layout we gave (GENERAL), so the readback needs no barrier of ours (the example_headless
     * test runs this under synchronization validation, which checks exactly that). */
    vkCmdCopyImageToBuffer(cmd, ao, VK_IMAGE_LAYOUT_GENERAL, staging, 1, &region);
    VkMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                               .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL, 0,
                         NULL);
    CHECK_VK(vkEndCommandBuffer(cmd));
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    CHECK_VK(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE));
    CHECK_VK(vkQueueWaitIdle(queue));

    /* 5. Read back: open floor near the camera is unoccluded, the floor-wall crease is darker. */
    double floor_ao = host[(H - 2) * W + W / 2], crease_ao = 0;
    for (int y = 0; y < H; ++y) { /* the crease row: the first floor row below the wall */
        double dy = (1 - 2 * (y + 0.5) / H) * t;
        if (dy < -0.25) { crease_ao = host[(y + 1) * W + W / 2]; break; }
    }
    printf("AO: open floor %.3f, floor-wall crease %.3f\n", floor_ao, crease_ao);
    if (argc > 1) {
        FILE *out = fopen(argv[1], "wb");
        if (!out || fwrite(host, sizeof *host, W * H, out) != W * H || fclose(out) != 0)
            return fprintf(stderr, "%s: cannot write the AO\n", argv[1]), 1;
    }

    /* 6. Teardown: cacao frees what it created; the engine frees what it created. */
    cacao_context_destroy(ctx);
    vkDestroyCommandPool(dev, pool, NULL);
    vkDestroyBuffer(dev, staging, NULL);
    vkFreeMemory(dev, staging_memory, NULL);
    vkDestroyImageView(dev, depth_view, NULL);
    vkDestroyImageView(dev, ao_view, NULL);
    vkDestroyImage(dev, depth, NULL);
    vkDestroyImage(dev, ao, NULL);
    vkFreeMemory(dev, depth_memory, NULL);
    vkFreeMemory(dev, ao_memory, NULL);
    vkDestroyDevice(dev, NULL);
    vkDestroyInstance(instance, NULL);
    return (floor_ao > 0.95 && crease_ao < floor_ao - 0.05) ? 0 : 1;
}
