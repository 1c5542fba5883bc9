/* vkdev.c - headless Vulkan device and one-shot cacao frames (see vkdev.h). */
#include "vkdev.h"
#include "text_file.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_TIMESTAMPS (CACAO_PLAN_MAX_STEPS + 1)

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user) {
    (void)type;
    vkdev *dev = user;
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    /* The layer reports a call that returned out of memory by the result's name alone. */
    if (dev->expect_out_of_memory && data->pMessage &&
        (strcmp(data->pMessage, "VK_ERROR_OUT_OF_HOST_MEMORY") == 0 ||
         strcmp(data->pMessage, "VK_ERROR_OUT_OF_DEVICE_MEMORY") == 0)) {
        dev->out_of_memory_reports++;
    } else {
        __atomic_fetch_add(&dev->validation_messages, 1, __ATOMIC_RELAXED); /* lanes' threads report too */
        fprintf(stderr, "validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

static bool has_layer(const char *name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, NULL);
    VkLayerProperties *layers = calloc(n ? n : 1, sizeof *layers);
    bool found = false;
    if (layers && vkEnumerateInstanceLayerProperties(&n, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < n; ++i) found |= strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static bool create_instance(vkdev *dev, bool validation, char *err, size_t n) {
    const char *layer = "VK_LAYER_KHRONOS_validation";
    if (validation && !has_layer(layer)) {
        cacao_set_err(err, n, "--validate: the Vulkan validation layer is not installed (Debian: vulkan-validationlayers)");
        return false;
    }
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    const VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    const VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .pNext = &features,
        .messageSeverity =
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = dev,
    };
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    const VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "cacao", .apiVersion = VK_API_VERSION_1_1};
    const VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? &messenger : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1 : 0,
        .ppEnabledLayerNames = &layer,
        .enabledExtensionCount = validation ? 1 : 0,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateInstance(&info, NULL, &dev->instance);
    if (vr != VK_SUCCESS) {
        cacao_set_err(err, n, "no usable Vulkan driver: vkCreateInstance failed (VkResult %d); install mesa-vulkan-drivers",
                (int)vr);
        return false;
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(dev->instance, "vkCreateDebugUtilsMessengerEXT");
        VkDebugUtilsMessengerCreateInfoEXT info = messenger;
        info.pNext = NULL; /* the validation features only go to vkCreateInstance */
        if (!create || create(dev->instance, &info, NULL, &dev->messenger) != VK_SUCCESS) {
            cacao_set_err(err, n, "cannot create the validation messenger");
            return false;
        }
    }
    return true;
}

static bool has_device_extension(VkPhysicalDevice pd, const char *name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL);
    VkExtensionProperties *ext = calloc(n ? n : 1, sizeof *ext);
    bool found = false;
    if (ext && vkEnumerateDeviceExtensionProperties(pd, NULL, &n, ext) == VK_SUCCESS)
        for (uint32_t i = 0; i < n; ++i) found |= strcmp(ext[i].extensionName, name) == 0;
    free(ext);
    return found;
}

/* The device `want` names by index or name substring; without a name, the first device offering
 * `required` (an extension) where one is given, else lavapipe (a CPU device), else the first. */
static bool pick_device(vkdev *dev, const char *want, const char *required, char *err, size_t n) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(dev->instance, &count, NULL);
    if (count == 0) {
        cacao_set_err(err, n, "no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
        return false;
    }
    VkPhysicalDevice devices[16];
    if (count > 16) count = 16;
    vkEnumeratePhysicalDevices(dev->instance, &count, devices);
    int chosen = -1;
    char *end = NULL;
    long index = want ? strtol(want, &end, 10) : -1;
    for (uint32_t i = 0; i < count && chosen < 0; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        if (!want) {
            if (required ? has_device_extension(devices[i], required) : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
                chosen = (int)i;
        } else if (end && *end == '\0' && end != want) {
            if ((long)i == index) chosen = (int)i;
        } else if (strstr(p.deviceName, want)) {
            chosen = (int)i;
        }
    }
    if (chosen < 0 && !want && !required) chosen = 0;
    if (chosen < 0 && !want)
        return cacao_set_err(err, n, "no Vulkan device offers %s (RADV's null device does: see docs/gpu.md)", required);
    if (chosen < 0) return cacao_set_err(err, n, "--device %s: no such Vulkan device (see cacao --list-devices)", want);
    dev->physical_device = devices[chosen];
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(dev->physical_device, &p);
    snprintf(dev->device_name, sizeof dev->device_name, "%s", p.deviceName);
    dev->timestamp_period_ns = p.limits.timestampPeriod;
    if (required && !has_device_extension(dev->physical_device, required))
        return cacao_set_err(err, n, "--device %s: '%s' does not offer %s", want, dev->device_name, required);
    return true;
}

/* The compute queue family: one with timestamps where frames are timed, any otherwise. */
static bool pick_queue_family(vkdev *dev, bool timestamps, char *err, size_t n) {
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(dev->physical_device, &families, NULL);
    VkQueueFamilyProperties props[16];
    if (families > 16) families = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(dev->physical_device, &families, props);
    dev->queue_family = UINT32_MAX;
    for (uint32_t i = 0; i < families && dev->queue_family == UINT32_MAX; ++i)
        if ((props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && (!timestamps || props[i].timestampValidBits > 0))
            dev->queue_family = i;
    if (dev->queue_family == UINT32_MAX)
        return cacao_set_err(err, n, "device '%s' has no compute queue%s", dev->device_name,
                             timestamps ? " with timestamps" : "");
    return true;
}

/* What frames need besides the device: command pool and buffer, fence, timestamp queries. */
static bool create_frame_objects(vkdev *dev, char *err, size_t n) {
    vkGetDeviceQueue(dev->device, dev->queue_family, 0, &dev->queue);
    const VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                          .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                          .queueFamilyIndex = dev->queue_family};
    const VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    const VkQueryPoolCreateInfo query = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                         .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                         .queryCount = MAX_TIMESTAMPS};
    if (vkCreateCommandPool(dev->device, &pool, NULL, &dev->pool) != VK_SUCCESS ||
        vkCreateFence(dev->device, &fence, NULL, &dev->fence) != VK_SUCCESS ||
        vkCreateQueryPool(dev->device, &query, NULL, &dev->timestamps) != VK_SUCCESS)
        return cacao_set_err(err, n, "cannot create command pool, fence or query pool");
    const VkCommandBufferAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                               .commandPool = dev->pool,
                                               .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                               .commandBufferCount = 1};
    if (vkAllocateCommandBuffers(dev->device, &alloc, &dev->cmd) != VK_SUCCESS)
        return cacao_set_err(err, n, "cannot allocate a command buffer");
    return true;
}

static bool create_device(vkdev *dev, const vkdev_options *options, char *err, size_t n) {
    if (!pick_queue_family(dev, !dev->statistics_only, err, n)) return false;
    if (!has_device_extension(dev->physical_device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) {
        cacao_set_err(err, n, "device '%s' lacks VK_KHR_push_descriptor, which cacao needs", dev->device_name);
        return false;
    }
    VkPhysicalDeviceShaderFloat16Int8Features f16 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES};
    VkPhysicalDeviceFeatures2 supported = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f16};
    vkGetPhysicalDeviceFeatures2(dev->physical_device, &supported);
    dev->fp16 = f16.shaderFloat16 && has_device_extension(dev->physical_device, "VK_KHR_shader_float16_int8");
    /* The features to enable, chained as they apply. */
    void *chain = NULL;
    VkPhysicalDeviceShaderFloat16Int8Features f16_on = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES, .shaderFloat16 = dev->fp16};
    if (dev->fp16) f16_on.pNext = chain, chain = &f16_on;
    /* Subgroup size control (asked for by the subgroup test): the feature, and the compute range. */
    VkPhysicalDeviceSubgroupSizeControlFeaturesEXT sizes_on = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES_EXT};
    const bool sizes = options->subgroup_size_control &&
                       has_device_extension(dev->physical_device, VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME);
    if (sizes) {
        VkPhysicalDeviceSubgroupSizeControlFeaturesEXT sizes_supported = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES_EXT};
        VkPhysicalDeviceFeatures2 features = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                              .pNext = &sizes_supported};
        vkGetPhysicalDeviceFeatures2(dev->physical_device, &features);
        VkPhysicalDeviceSubgroupSizeControlPropertiesEXT range = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES_EXT};
        VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &range};
        vkGetPhysicalDeviceProperties2(dev->physical_device, &props);
        sizes_on.subgroupSizeControl = sizes_supported.subgroupSizeControl;
        if (sizes_supported.subgroupSizeControl && (range.requiredSubgroupSizeStages & VK_SHADER_STAGE_COMPUTE_BIT)) {
            dev->subgroup_size_min = range.minSubgroupSize;
            dev->subgroup_size_max = range.maxSubgroupSize;
        }
        sizes_on.pNext = chain, chain = &sizes_on;
    }
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR statistics_on = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
        .pipelineExecutableInfo = VK_TRUE};
    if (dev->statistics_only) statistics_on.pNext = chain, chain = &statistics_on;
    VkPhysicalDeviceFeatures2 enabled = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = chain};
    enabled.features.shaderStorageImageWriteWithoutFormat = supported.features.shaderStorageImageWriteWithoutFormat;
    enabled.features.shaderStorageImageExtendedFormats = supported.features.shaderStorageImageExtendedFormats;
    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                           .queueFamilyIndex = dev->queue_family,
                                           .queueCount = 1,
                                           .pQueuePriorities = &priority};
    const char *extensions[4] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    uint32_t extension_count = 1;
    if (dev->fp16) extensions[extension_count++] = "VK_KHR_shader_float16_int8";
    if (sizes) extensions[extension_count++] = VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME;
    if (dev->statistics_only) extensions[extension_count++] = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
    const VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &enabled,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = extension_count,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateDevice(dev->physical_device, &info, NULL, &dev->device);
    if (vr != VK_SUCCESS) {
        cacao_set_err(err, n, "vkCreateDevice failed on '%s' (VkResult %d)", dev->device_name, (int)vr);
        return false;
    }
    return dev->statistics_only || create_frame_objects(dev, err, n);
}

bool vkdev_create(const vkdev_options *options, vkdev *dev, char *err, size_t n) {
    memset(dev, 0, sizeof *dev);
    dev->validation = options->validation;
    dev->statistics_only = options->pipeline_statistics;
    const char *required = options->pipeline_statistics ? VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME : NULL;
    if (!create_instance(dev, options->validation, err, n) || !pick_device(dev, options->device, required, err, n) ||
        !create_device(dev, options, err, n)) {
        vkdev_destroy(dev);
        return false;
    }
    return true;
}

bool vkdev_lane_create(vkdev *dev, pthread_mutex_t *queue_lock, vkdev *lane, char *err, size_t n) {
    *lane = *dev;
    lane->messenger = VK_NULL_HANDLE;
    lane->pool = VK_NULL_HANDLE;
    lane->cmd = VK_NULL_HANDLE;
    lane->fence = VK_NULL_HANDLE;
    lane->timestamps = VK_NULL_HANDLE;
    lane->validation_messages = 0;
    lane->lane = true;
    lane->queue_lock = queue_lock;
    if (dev->statistics_only) return cacao_set_err(err, n, "a pipeline-statistics device records nothing: no lanes");
    if (create_frame_objects(lane, err, n)) return true;
    vkdev_destroy(lane);
    return false;
}

/* A lane's own objects; the device's owner waits for the device and destroys it. */
static void destroy_lane(vkdev *lane) {
    if (lane->timestamps) vkDestroyQueryPool(lane->device, lane->timestamps, NULL);
    if (lane->fence) vkDestroyFence(lane->device, lane->fence, NULL);
    if (lane->pool) vkDestroyCommandPool(lane->device, lane->pool, NULL);
    memset(lane, 0, sizeof *lane);
}

void vkdev_destroy(vkdev *dev) {
    if (dev->lane) {
        destroy_lane(dev);
        return;
    }
    if (dev->device) {
        if (!dev->statistics_only) vkDeviceWaitIdle(dev->device); /* a compiler's null device runs nothing */
        if (dev->timestamps) vkDestroyQueryPool(dev->device, dev->timestamps, NULL);
        if (dev->fence) vkDestroyFence(dev->device, dev->fence, NULL);
        if (dev->pool) vkDestroyCommandPool(dev->device, dev->pool, NULL);
        vkDestroyDevice(dev->device, NULL);
    }
    if (dev->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
            dev->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(dev->instance, dev->messenger, NULL);
    }
    if (dev->instance) vkDestroyInstance(dev->instance, NULL);
    uint32_t messages = dev->validation_messages;
    memset(dev, 0, sizeof *dev);
    dev->validation_messages = messages;
}

void vkdev_driver(const vkdev *dev, char *out, size_t n) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(dev->physical_device, &p);
    snprintf(out, n, "driver version 0x%x, Vulkan %u.%u.%u", p.driverVersion, VK_API_VERSION_MAJOR(p.apiVersion),
             VK_API_VERSION_MINOR(p.apiVersion), VK_API_VERSION_PATCH(p.apiVersion));
    if (p.apiVersion < VK_API_VERSION_1_2) return;
    VkPhysicalDeviceDriverProperties driver = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
    vkGetPhysicalDeviceProperties2(dev->physical_device, &p2);
    snprintf(out, n, "%s %s (Vulkan %u.%u.%u)", driver.driverName, driver.driverInfo,
             VK_API_VERSION_MAJOR(p.apiVersion), VK_API_VERSION_MINOR(p.apiVersion),
             VK_API_VERSION_PATCH(p.apiVersion));
}

bool vkdev_list(FILE *out, char *err, size_t n) {
    vkdev dev;
    memset(&dev, 0, sizeof dev);
    if (!create_instance(&dev, false, err, n)) return false;
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(dev.instance, &count, NULL);
    VkPhysicalDevice devices[16];
    if (count > 16) count = 16;
    vkEnumeratePhysicalDevices(dev.instance, &count, devices);
    static const char *const types[] = {"other", "integrated GPU", "discrete GPU", "virtual GPU", "CPU"};
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        fprintf(out, "%u: %s (%s)%s\n", i, p.deviceName, p.deviceType <= 4 ? types[p.deviceType] : "?",
                p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? " [default]" : "");
    }
    vkDestroyInstance(dev.instance, NULL);
    return true;
}

void vkdev_frame_set_view_normals(vkdev_frame *frame, const float *normals) {
    frame->normals = normals;
    memset(frame->normals_to_view, 0, sizeof frame->normals_to_view);
    frame->normals_to_view[0] = 1.0f;
    frame->normals_to_view[5] = 1.0f;
    frame->normals_to_view[10] = -1.0f;
    frame->normals_to_view[15] = 1.0f;
    frame->normals_unpack_mul = 1.0f;
    frame->normals_unpack_add = 0.0f;
}

/* ---- Resources of one run ---- */

typedef struct gpu_image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
    VkFormat format;
} gpu_image;

typedef vkdev_buffer gpu_buffer;

static bool find_memory(vkdev *dev, uint32_t bits, VkMemoryPropertyFlags flags, uint32_t *index) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(dev->physical_device, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) {
            *index = i;
            return true;
        }
    return false;
}

static bool make_image(vkdev *dev, VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage, gpu_image *im) {
    im->format = format;
    const VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                                    .imageType = VK_IMAGE_TYPE_2D,
                                    .format = format,
                                    .extent = {w, h, 1},
                                    .mipLevels = 1,
                                    .arrayLayers = 1,
                                    .samples = VK_SAMPLE_COUNT_1_BIT,
                                    .tiling = VK_IMAGE_TILING_OPTIMAL,
                                    .usage = usage,
                                    .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    if (vkCreateImage(dev->device, &info, NULL, &im->image) != VK_SUCCESS) return false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev->device, im->image, &req);
    uint32_t type;
    if (!find_memory(dev, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &type)) return false;
    const VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = type};
    if (vkAllocateMemory(dev->device, &alloc, NULL, &im->memory) != VK_SUCCESS ||
        vkBindImageMemory(dev->device, im->image, im->memory, 0) != VK_SUCCESS)
        return false;
    const VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                        .image = im->image,
                                        .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                        .format = format,
                                        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    return vkCreateImageView(dev->device, &view, NULL, &im->view) == VK_SUCCESS;
}

static void free_image(vkdev *dev, gpu_image *im) {
    if (im->view) vkDestroyImageView(dev->device, im->view, NULL);
    if (im->image) vkDestroyImage(dev->device, im->image, NULL);
    if (im->memory) vkFreeMemory(dev->device, im->memory, NULL);
    memset(im, 0, sizeof *im);
}

static bool make_buffer(vkdev *dev, VkDeviceSize size, gpu_buffer *b) {
    const VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                     .size = size,
                                     .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    if (vkCreateBuffer(dev->device, &info, NULL, &b->buffer) != VK_SUCCESS) return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev->device, b->buffer, &req);
    uint32_t type;
    if (!find_memory(dev, req.memoryTypeBits,
                     VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &type))
        return false;
    const VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = type};
    return vkAllocateMemory(dev->device, &alloc, NULL, &b->memory) == VK_SUCCESS &&
           vkBindBufferMemory(dev->device, b->buffer, b->memory, 0) == VK_SUCCESS &&
           vkMapMemory(dev->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped) == VK_SUCCESS;
}

static void free_buffer(vkdev *dev, gpu_buffer *b) {
    if (b->buffer) vkDestroyBuffer(dev->device, b->buffer, NULL);
    if (b->memory) vkFreeMemory(dev->device, b->memory, NULL);
    memset(b, 0, sizeof *b);
}

bool vkdev_buffer_create(vkdev *dev, VkDeviceSize size, vkdev_buffer *out) {
    memset(out, 0, sizeof *out);
    if (make_buffer(dev, size, out)) return true;
    free_buffer(dev, out);
    return false;
}

void vkdev_buffer_destroy(vkdev *dev, vkdev_buffer *b) { free_buffer(dev, b); }

static void transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                       VkAccessFlags dst, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage) {
    const VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                                    .srcAccessMask = src,
                                    .dstAccessMask = dst,
                                    .oldLayout = from,
                                    .newLayout = to,
                                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .image = image,
                                    .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

/* vkQueueSubmit, holding a lane's queue lock. */
static VkResult queue_submit(vkdev *dev, const VkSubmitInfo *submit) {
    if (dev->queue_lock) pthread_mutex_lock(dev->queue_lock);
    const VkResult vr = vkQueueSubmit(dev->queue, 1, submit, dev->fence);
    if (dev->queue_lock) pthread_mutex_unlock(dev->queue_lock);
    return vr;
}

/* Waits until the device is idle; a lane waits for the queue it shares instead (vkDeviceWaitIdle
 * would touch the queue without the lock). */
static void wait_idle(vkdev *dev) {
    if (!dev->lane) {
        vkDeviceWaitIdle(dev->device);
        return;
    }
    pthread_mutex_lock(dev->queue_lock);
    vkQueueWaitIdle(dev->queue);
    pthread_mutex_unlock(dev->queue_lock);
}

static bool submit_and_wait(vkdev *dev) {
    const VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &dev->cmd};
    if (vkEndCommandBuffer(dev->cmd) != VK_SUCCESS || queue_submit(dev, &submit) != VK_SUCCESS ||
        vkWaitForFences(dev->device, 1, &dev->fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS)
        return false;
    vkResetFences(dev->device, 1, &dev->fence);
    return true;
}

static bool begin(vkdev *dev) {
    const VkCommandBufferBeginInfo info = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                           .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    return vkResetCommandBuffer(dev->cmd, 0) == VK_SUCCESS && vkBeginCommandBuffer(dev->cmd, &info) == VK_SUCCESS;
}

/* Copies host floats into an image and leaves it in SHADER_READ_ONLY_OPTIMAL. */
static void record_upload(vkdev *dev, gpu_buffer *staging, VkDeviceSize offset, gpu_image *im, uint32_t w, uint32_t h) {
    transition(dev->cmd, im->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    const VkBufferImageCopy region = {
        .bufferOffset = offset, .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {w, h, 1}};
    vkCmdCopyBufferToImage(dev->cmd, staging->buffer, im->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(dev->cmd, im->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               VK_ACCESS_TRANSFER_WRITE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
}

static cacao_result vk_error(char *err, size_t n, const char *what) {
    cacao_set_err(err, n, "%s failed", what);
    return CACAO_ERROR_VULKAN;
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

cacao_result vkdev_context_create_on_cache(vkdev *dev, VkPipelineCache cache, cacao_context **ctx) {
    const cacao_context_desc desc = {.error = dev->context_error,
                                     .error_size = sizeof dev->context_error,
                                     .physical_device = dev->physical_device,
                                     .device = dev->device,
                                     .shader_float16_enabled = dev->fp16,
                                     .required_subgroup_size = dev->required_subgroup_size,
                                     .shader_forms = dev->shader_forms,
                                     .allocation_callbacks = dev->allocation_callbacks,
                                     .pipeline_cache = cache};
    return cacao_context_create(&desc, ctx);
}

cacao_result vkdev_context_create(vkdev *dev, cacao_context **ctx) {
    return vkdev_context_create_on_cache(dev, VK_NULL_HANDLE, ctx);
}

/* A context on cache (VK_NULL_HANDLE: none) with these settings, resized to w x h; *ms is the wall
 * time of the resize (pipelines and intermediates). On failure the message is in err; *ctx is
 * the caller's to destroy either way (NULL when creation failed). */
static cacao_result context_resized(vkdev *dev, VkPipelineCache cache, const cacao_settings *settings, uint32_t w,
                                    uint32_t h, cacao_context **ctx, cacao_memory_info *memory, double *ms, char *err,
                                    size_t n) {
    *ctx = NULL;
    *memory = (cacao_memory_info){0};
    *ms = 0;
    cacao_result r = vkdev_context_create_on_cache(dev, cache, ctx);
    if (r != CACAO_SUCCESS) {
        cacao_set_err(err, n, "cacao_context_create: %s: %s", cacao_result_string(r), dev->context_error);
        return r;
    }
    r = cacao_context_set_settings(*ctx, settings);
    const double start = now_ms();
    if (r == CACAO_SUCCESS) r = cacao_context_resize(*ctx, w, h, memory);
    *ms = now_ms() - start;
    if (r != CACAO_SUCCESS) cacao_set_err(err, n, "%s", cacao_context_last_error(*ctx));
    return r;
}

/* Times the resize of a new context on cache; its pipeline count in *pipelines. */
static cacao_result timed_resize(vkdev *dev, VkPipelineCache cache, const cacao_settings *settings, uint32_t w,
                                 uint32_t h, double *ms, uint32_t *pipelines, char *err, size_t n) {
    cacao_context *ctx;
    cacao_memory_info memory;
    const cacao_result r = context_resized(dev, cache, settings, w, h, &ctx, &memory, ms, err, n);
    *pipelines = memory.pipeline_count;
    cacao_context_destroy(ctx);
    return r;
}

/* Whether data starts with a VK_PIPELINE_CACHE_HEADER_VERSION_ONE header naming this device. */
static bool cache_header_valid(const vkdev *dev, const uint8_t *data, size_t size) {
    if (size < VKDEV_PIPELINE_CACHE_HEADER_BYTES) return false;
    uint32_t words[4];
    memcpy(words, data, sizeof words);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(dev->physical_device, &props);
    return words[0] >= VKDEV_PIPELINE_CACHE_HEADER_BYTES && words[1] == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           words[2] == props.vendorID && words[3] == props.deviceID &&
           memcmp(data + 16, props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

cacao_result vkdev_time_pipeline_cache(vkdev *dev, const cacao_settings *settings, uint32_t w, uint32_t h,
                                       uint32_t trials, vkdev_cache_timing *out, char *err, size_t n) {
    memset(out, 0, sizeof *out);
    if (trials == 0) trials = 1;
    double *ms = calloc(3 * (size_t)trials, sizeof *ms);
    uint8_t *data = NULL;
    size_t size = 0;
    cacao_result r = ms ? CACAO_SUCCESS : CACAO_ERROR_OUT_OF_MEMORY;
    if (!ms) cacao_set_err(err, n, "out of memory");
    for (uint32_t t = 0; r == CACAO_SUCCESS && t < trials; ++t) {
        uint32_t counts[3] = {0};
        r = timed_resize(dev, VK_NULL_HANDLE, settings, w, h, &ms[t], &counts[0], err, n);
        for (int warm = 0; r == CACAO_SUCCESS && warm < 2; ++warm) {
            const VkPipelineCacheCreateInfo info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
                                                    .initialDataSize = warm ? size : 0,
                                                    .pInitialData = warm ? data : NULL};
            VkPipelineCache cache;
            if (vkCreatePipelineCache(dev->device, &info, NULL, &cache) != VK_SUCCESS) {
                r = vk_error(err, n, "vkCreatePipelineCache");
                break;
            }
            r = timed_resize(dev, cache, settings, w, h, &ms[(1 + warm) * (size_t)trials + t], &counts[1 + warm],
                             err, n);
            if (r == CACAO_SUCCESS && !warm && !data) {
                if (vkGetPipelineCacheData(dev->device, cache, &size, NULL) != VK_SUCCESS ||
                    !(data = malloc(size ? size : 1)) ||
                    vkGetPipelineCacheData(dev->device, cache, &size, data) != VK_SUCCESS)
                    r = vk_error(err, n, "vkGetPipelineCacheData");
            }
            vkDestroyPipelineCache(dev->device, cache, NULL);
        }
        if (r == CACAO_SUCCESS && (counts[1] != counts[0] || counts[2] != counts[0])) {
            cacao_set_err(err, n, "pipeline counts differ with a cache: %u, %u, %u", counts[0], counts[1], counts[2]);
            r = CACAO_ERROR_VULKAN;
        }
        out->pipeline_count = counts[0];
    }
    if (r == CACAO_SUCCESS) {
        out->trials = trials;
        out->no_cache = cacao_time_stats_of(ms, trials);
        out->cold_cache = cacao_time_stats_of(ms + trials, trials);
        out->warm_cache = cacao_time_stats_of(ms + 2 * (size_t)trials, trials);
        out->cache_bytes = size;
        out->header_valid = cache_header_valid(dev, data, size);
    }
    free(data);
    free(ms);
    return r;
}

cacao_result vkdev_run(vkdev *dev, const cacao_settings *settings, const vkdev_frame *frame, uint32_t repeat, float *ao,
                       cacao_timings *timings, char *err, size_t n) {
    return vkdev_run_timed(dev, settings, frame, 0, repeat, ao, timings, err, n);
}

cacao_result vkdev_run_timed(vkdev *dev, const cacao_settings *settings, const vkdev_frame *frame, uint32_t warmup,
                             uint32_t repeat, float *ao, cacao_timings *timings, char *err, size_t n) {
    cacao_context *ctx;
    cacao_memory_info memory;
    double setup_ms;
    cacao_result r =
        context_resized(dev, VK_NULL_HANDLE, settings, frame->width, frame->height, &ctx, &memory, &setup_ms, err, n);
    if (r == CACAO_SUCCESS) r = vkdev_run_context_timed(dev, ctx, frame, warmup, repeat, ao, timings, err, n);
    if (r == CACAO_SUCCESS && frame->plan_out) *frame->plan_out = *cacao_context_plan(ctx);
    if (r == CACAO_SUCCESS && timings) {
        timings->memory_bytes = memory.total_bytes;
        timings->memory_allocations = memory.allocation_count;
        timings->pipeline_count = memory.pipeline_count;
        timings->setup_ms = setup_ms;
    }
    cacao_context_destroy(ctx);
    return r;
}

cacao_result vkdev_run_context(vkdev *dev, cacao_context *ctx, const vkdev_frame *frame, uint32_t repeat, float *ao,
                               cacao_timings *timings, char *err, size_t n) {
    return vkdev_run_context_timed(dev, ctx, frame, 0, repeat, ao, timings, err, n);
}

cacao_result vkdev_run_context_timed(vkdev *dev, cacao_context *ctx, const vkdev_frame *frame, uint32_t warmup,
                                     uint32_t repeat, float *ao, cacao_timings *timings, char *err, size_t n) {
    const uint32_t w = frame->width, h = frame->height;
    const VkFormat out_format = frame->output_format ? frame->output_format : VK_FORMAT_R32_SFLOAT;
    if (out_format != VK_FORMAT_R32_SFLOAT) return vk_error(err, n, "vkdev: only R32_SFLOAT readback");
    const cacao_plan *plan = cacao_context_plan(ctx);
    if (!plan || plan->width != w || plan->height != h) {
        cacao_set_err(err, n, "vkdev: the context is not resized to the frame's %ux%u", w, h);
        return CACAO_ERROR_NOT_READY;
    }
    if (repeat == 0) repeat = 1;
    const uint32_t frames = warmup + repeat;
    gpu_image depth = {0}, normals = {0}, output = {0}, alternate = {0};
    gpu_buffer staging = {0};
    cacao_result r;
    const VkDeviceSize pixels = (VkDeviceSize)w * h;
    const VkDeviceSize normals_offset = (pixels * 4 + 15) / 16 * 16; /* RGBA32F copies need 16-byte offsets */
    /* depth R32 (+ normals RGBA32 when given); AO read back into the front. Only what is used is
     * staged: depth alone at 16384x16384 is 1 GiB, within the 4 GiB buffers lavapipe allows. */
    const VkDeviceSize depths_bytes = frame->alternate_depth ? normals_offset + pixels * 4 : pixels * 4;
    const VkDeviceSize alternate_offset = normals_offset; /* the alternate depth, then the normals */
    const VkDeviceSize normals_at = frame->alternate_depth ? (depths_bytes + 15) / 16 * 16 : normals_offset;
    const VkDeviceSize image_bytes = frame->normals ? normals_at + pixels * 16 : depths_bytes;
    const VkDeviceSize tiles_offset = (image_bytes + 15) / 16 * 16; /* then the tile counts */
    const VkDeviceSize bytes = tiles_offset + (plan->uses_tiles ? CACAO_TILE_COUNTS_BYTES : 0);
    r = CACAO_ERROR_VULKAN;
    if (!make_buffer(dev, bytes, &staging) ||
        !make_image(dev, VK_FORMAT_R32_SFLOAT, w, h, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                    &depth) ||
        (frame->alternate_depth &&
         !make_image(dev, VK_FORMAT_R32_SFLOAT, w, h, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                     &alternate)) ||
        (frame->normals && !make_image(dev, VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &normals)) ||
        !make_image(dev, out_format, w, h,
                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                    &output)) {
        cacao_set_err(err, n, "cannot create the frame's images (%ux%u)", w, h);
        goto done;
    }
    float *host = staging.mapped;
    memcpy(host, frame->depth, pixels * 4);
    if (frame->alternate_depth) memcpy(host + alternate_offset / 4, frame->alternate_depth, pixels * 4);
    if (frame->normals)
        for (VkDeviceSize i = 0; i < pixels; ++i) {
            float *dst = host + normals_at / 4 + 4 * i;
            dst[0] = frame->normals[3 * i];
            dst[1] = frame->normals[3 * i + 1];
            dst[2] = frame->normals[3 * i + 2];
            dst[3] = 0.0f;
        }
    if (!begin(dev)) goto vk_failed;
    record_upload(dev, &staging, 0, &depth, w, h);
    if (frame->alternate_depth) record_upload(dev, &staging, alternate_offset, &alternate, w, h);
    if (frame->normals) record_upload(dev, &staging, normals_at, &normals, w, h);
    transition(dev->cmd, output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    /* NaN in every output pixel: a pixel cacao does not write reads back as NaN, never as AO. */
    const VkClearColorValue nan_colour = {.float32 = {NAN, NAN, NAN, NAN}};
    const VkImageSubresourceRange whole = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(dev->cmd, output.image, VK_IMAGE_LAYOUT_GENERAL, &nan_colour, 1, &whole);
    if (!submit_and_wait(dev)) goto vk_failed;

    cacao_inputs in = {
        .depth = {depth.image, depth.view, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .normals = {normals.image, normals.view, VK_FORMAT_R32G32B32A32_SFLOAT,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        .output = {output.image, output.view, out_format, VK_IMAGE_LAYOUT_GENERAL},
        .matrices_row_major = true,
        .depth_reversed = frame->depth_reversed,
        .frame_index = frame->frame_index,
        .normals_unpack_mul = frame->normals_unpack_mul,
        .normals_unpack_add = frame->normals_unpack_add,
        .timestamp_query_pool = dev->timestamps,
        .timestamp_query_count = MAX_TIMESTAMPS,
    };
    memcpy(in.projection, frame->projection, sizeof in.projection);
    memcpy(in.normals_to_view, frame->normals_to_view, sizeof in.normals_to_view);
    memcpy(in.view_to_previous_view, frame->view_to_previous_view, sizeof in.view_to_previous_view);
    in.temporal_reset = frame->temporal_reset;
    const uint32_t steps = plan->step_count;
    double *samples = calloc((size_t)frames * (steps ? steps : 1), sizeof *samples);
    if (!samples) goto vk_failed;
    for (uint32_t rep = 0; rep < frames; ++rep) {
        if (!begin(dev)) {
            free(samples);
            goto vk_failed;
        }
        vkCmdResetQueryPool(dev->cmd, dev->timestamps, 0, steps + 1);
        in.depth.image = frame->alternate_depth && rep % 2 ? alternate.image : depth.image;
        in.depth.view = frame->alternate_depth && rep % 2 ? alternate.view : depth.view;
        in.output_holds_previous = frame->output_holds_previous && rep > 0;
        in.projection[0] = frame->alternate_camera && rep % 2 ? frame->projection[0] * (1.0f + 1.0e-6f) : frame->projection[0];
        in.force_full_frame = frame->force_full_frame;
        in.frame_index = frame->frame_index + (frame->advance_frame_index ? rep : 0u);
        r = cacao_record(ctx, dev->cmd, &in);
        if (r != CACAO_SUCCESS) {
            cacao_set_err(err, n, "%s", cacao_context_last_error(ctx));
            vkEndCommandBuffer(dev->cmd);
            free(samples);
            goto done;
        }
        if (rep + 1 == frames) { /* read the AO back after the last run */
            transition(dev->cmd, output.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT);
            const VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                              .imageExtent = {w, h, 1}};
            vkCmdCopyImageToBuffer(dev->cmd, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1,
                                   &region);
            const VkMemoryBarrier host_read = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                               .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                               .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
            vkCmdPipelineBarrier(dev->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host_read,
                                 0, NULL, 0, NULL);
            if (plan->uses_tiles) cacao_record_tile_counts(ctx, dev->cmd, staging.buffer, tiles_offset);
            if (frame->after_record) frame->after_record(dev, ctx, dev->cmd, frame->user);
        }
        if (!submit_and_wait(dev)) {
            free(samples);
            goto vk_failed;
        }
        uint64_t stamps[MAX_TIMESTAMPS];
        if (vkGetQueryPoolResults(dev->device, dev->timestamps, 0, steps + 1, sizeof stamps, stamps, sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS)
            for (uint32_t s = 0; s < steps; ++s)
                samples[(size_t)s * frames + rep] =
                    (double)(stamps[s + 1] - stamps[s]) * dev->timestamp_period_ns * 1e-6;
    }
    memcpy(ao, staging.mapped, pixels * 4);
    if (frame->after_wait) frame->after_wait(dev, ctx, frame->user);
    if (timings) {
        cacao_timings_summarise(samples, steps, warmup, repeat, timings);
        timings->has_tiles = plan->uses_tiles &&
                             cacao_tile_counts_decode(ctx, (const char *)staging.mapped + tiles_offset, &timings->tiles) ==
                                 CACAO_SUCCESS;
    }
    free(samples);
    r = CACAO_SUCCESS;
    goto done;
vk_failed:
    r = vk_error(err, n, "a Vulkan submission");
done:
    wait_idle(dev);
    free_image(dev, &depth);
    free_image(dev, &normals);
    free_image(dev, &alternate);
    free_image(dev, &output);
    free_buffer(dev, &staging);
    return r;
}
