/* context.c - context lifetime, intermediates and pipelines, all driven by the plan. */
#include <assert.h>
#include <dlfcn.h>
#include <stdalign.h>
#include <stdlib.h>
#include <string.h>

#include "vulkan_internal.h"

uint32_t cacao_embedded_permutation_count(void) { return cacaoi_embedded_table.permutation_count; }

const char *cacao_context_last_error(const cacao_context *ctx) { return ctx ? ctx->last_error : ""; }

const cacao_plan *cacao_context_plan(const cacao_context *ctx) { return ctx && ctx->ready ? &ctx->plan : NULL; }

cacao_shader_forms cacao_context_shader_forms(const cacao_context *ctx) {
    return ctx ? ctx->forms : CACAO_SHADER_FORMS_DEFAULT;
}
cacao_precision cacao_context_precision(const cacao_context *ctx) {
    return ctx && ctx->ready ? ctx->plan.settings.precision : CACAO_PRECISION_DEFAULT;
}

cacao_result cacaoi_fail(cacao_context *ctx, cacao_result result, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    cacaoi_set_error_v(ctx->last_error, sizeof ctx->last_error, fmt, ap);
    va_end(ap);
    return result;
}

/* A failed Vulkan call: CACAO_ERROR_OUT_OF_MEMORY for either out-of-memory result, else
 * CACAO_ERROR_VULKAN; the message names the call (printf-style `what`) and the result. */
static cacao_result vk_fail(cacao_context *ctx, VkResult vr, const char *what, ...)
    __attribute__((format(printf, 3, 4)));
static cacao_result vk_fail(cacao_context *ctx, VkResult vr, const char *what, ...) {
    char call[160];
    va_list ap;
    va_start(ap, what);
    cacaoi_set_error_v(call, sizeof call, what, ap);
    va_end(ap);
    const char *meaning = vr == VK_ERROR_OUT_OF_HOST_MEMORY     ? "out of host memory"
                          : vr == VK_ERROR_OUT_OF_DEVICE_MEMORY ? "out of device memory"
                                                                : "error";
    const cacao_result r = vr == VK_ERROR_OUT_OF_HOST_MEMORY || vr == VK_ERROR_OUT_OF_DEVICE_MEMORY
                               ? CACAO_ERROR_OUT_OF_MEMORY
                               : CACAO_ERROR_VULKAN;
    return cacaoi_fail(ctx, r, "%s failed: %s (VkResult %d)", call, meaning, (int)vr);
}

/* Descriptor type of each binding of the one set layout (its slot row). */
VkDescriptorType cacaoi_binding_type(unsigned binding) {
    switch (cacaoi_slots[binding].descriptor) {
    case CACAOI_DESCRIPTOR_UNIFORM_BUFFER: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case CACAOI_DESCRIPTOR_STORAGE_BUFFER: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case CACAOI_DESCRIPTOR_SAMPLED_IMAGE: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case CACAOI_DESCRIPTOR_STORAGE_TEXEL_BUFFER: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    default: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
}

/* ---- Host memory: the caller's callbacks when given, else the C library --------------------- */

static void *host_alloc(const VkAllocationCallbacks *alloc, size_t bytes, VkSystemAllocationScope scope) {
    void *p = alloc ? alloc->pfnAllocation(alloc->pUserData, bytes, alignof(max_align_t), scope) : malloc(bytes);
    if (p) memset(p, 0, bytes);
    return p;
}

static void host_free(const VkAllocationCallbacks *alloc, void *p) {
    if (!p) return;
    if (alloc)
        alloc->pfnFree(alloc->pUserData, p);
    else
        free(p);
}

/* ---- Entry points ----------------------------------------------------------------------------- */

/* An instance-level function: through the caller's get_instance_proc_addr and instance, or the
 * system loader's (its exported function where no instance was given). */
static PFN_vkVoidFunction instance_function(const cacao_context *ctx, PFN_vkGetInstanceProcAddr get_instance_proc_addr,
                                            VkInstance instance, const char *name) {
    if (instance) return get_instance_proc_addr(instance, name);
    PFN_vkVoidFunction f = NULL;
    void *symbol = dlsym(ctx->loader, name);
    memcpy(&f, &symbol, sizeof f); /* POSIX: a data pointer from dlsym holds a function's address */
    return f;
}

static cacao_result load_functions(cacao_context *ctx, const cacao_context_desc *desc) {
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = desc->get_instance_proc_addr;
    if (get_instance_proc_addr && !desc->instance)
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT,
                           "context_desc.get_instance_proc_addr needs context_desc.instance");
    if (!get_instance_proc_addr) {
        ctx->loader = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        void *symbol = ctx->loader ? dlsym(ctx->loader, "vkGetInstanceProcAddr") : NULL;
        if (!symbol)
            return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                               "context_desc.get_instance_proc_addr is not given and the Vulkan loader "
                               "libvulkan.so.1 cannot be used (%s)",
                               dlerror());
        memcpy(&get_instance_proc_addr, &symbol, sizeof get_instance_proc_addr);
    }
    const char *missing = NULL;
#define CACAOI_LOAD_INSTANCE(name)                                                                  \
    ctx->vk.name = (PFN_vk##name)instance_function(ctx, get_instance_proc_addr, desc->instance, "vk" #name); \
    if (!ctx->vk.name && !missing) missing = "vk" #name;
    CACAOI_VK_INSTANCE_FUNCTIONS(CACAOI_LOAD_INSTANCE)
#undef CACAOI_LOAD_INSTANCE
    if (missing)
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE, "context_desc: the instance gives no %s", missing);
    PFN_vkGetDeviceProcAddr get_device_proc_addr =
        desc->get_device_proc_addr ? desc->get_device_proc_addr : ctx->vk.GetDeviceProcAddr;
#define CACAOI_LOAD_DEVICE(name)                                                                    \
    ctx->vk.name = (PFN_vk##name)get_device_proc_addr(ctx->device, "vk" #name);                     \
    if (!ctx->vk.name && !missing) missing = "vk" #name;
    CACAOI_VK_DEVICE_FUNCTIONS(CACAOI_LOAD_DEVICE)
#undef CACAOI_LOAD_DEVICE
    if (!ctx->vk.CmdPushDescriptorSetKHR)
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                           "context_desc.device: VK_KHR_push_descriptor is not enabled on this device");
    if (missing)
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE, "context_desc.device gives no %s", missing);
    return CACAO_SUCCESS;
}

/* ---- Layouts ------------------------------------------------------------------------------------ */

static cacao_result create_layouts(cacao_context *ctx) {
    const VkSamplerCreateInfo nearest_info = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_NEAREST,
        .minFilter = VK_FILTER_NEAREST,
        .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .maxLod = VK_LOD_CLAMP_NONE,
    };
    VkSamplerCreateInfo linear_info = nearest_info;
    linear_info.magFilter = linear_info.minFilter = VK_FILTER_LINEAR;
    VkResult vr = ctx->vk.CreateSampler(ctx->device, &nearest_info, ctx->alloc, &ctx->nearest_sampler);
    if (vr == VK_SUCCESS) vr = ctx->vk.CreateSampler(ctx->device, &linear_info, ctx->alloc, &ctx->linear_sampler);
    if (vr != VK_SUCCESS) return vk_fail(ctx, vr, "vkCreateSampler");

    /* one push-descriptor set of every slot: its descriptors may not exceed maxPushDescriptors, which
     * every device offering push descriptors sets to at least 32 */
    _Static_assert(CACAO_BINDING_COUNT <= 32, "more slots than a push-descriptor set is sure to hold");
    VkDescriptorSetLayoutBinding bindings[CACAO_BINDING_COUNT];
    for (unsigned b = 0; b < CACAO_BINDING_COUNT; ++b) {
        VkDescriptorType type = cacaoi_binding_type(b);
        bindings[b] = (VkDescriptorSetLayoutBinding){
            .binding = b,
            .descriptorType = type,
            .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
            .pImmutableSamplers = type != VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER ? NULL
                                  : cacaoi_slots[b].sampler == CACAOI_SAMPLER_LINEAR ? &ctx->linear_sampler
                                                                                    : &ctx->nearest_sampler,
        };
    }
    const VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
        .bindingCount = CACAO_BINDING_COUNT,
        .pBindings = bindings,
    };
    vr = ctx->vk.CreateDescriptorSetLayout(ctx->device, &set_info, ctx->alloc, &ctx->set_layout);
    if (vr != VK_SUCCESS) return vk_fail(ctx, vr, "vkCreateDescriptorSetLayout");
    const VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &ctx->set_layout,
    };
    vr = ctx->vk.CreatePipelineLayout(ctx->device, &layout_info, ctx->alloc, &ctx->pipeline_layout);
    return vr == VK_SUCCESS ? CACAO_SUCCESS : vk_fail(ctx, vr, "vkCreatePipelineLayout");
}

/* Whether the physical device offers an extension; *out_of_memory tells a failed list apart. */
static bool has_extension(const cacao_context *ctx, const char *name, bool *out_of_memory) {
    uint32_t n = 0;
    VkResult vr = ctx->vk.EnumerateDeviceExtensionProperties(ctx->physical_device, NULL, &n, NULL);
    if (vr != VK_SUCCESS || n == 0) return false;
    VkExtensionProperties *ext = host_alloc(ctx->alloc, n * sizeof *ext, VK_SYSTEM_ALLOCATION_SCOPE_COMMAND);
    *out_of_memory = !ext;
    bool found = false;
    if (ext && ctx->vk.EnumerateDeviceExtensionProperties(ctx->physical_device, NULL, &n, ext) == VK_SUCCESS)
        for (uint32_t i = 0; i < n && !found; ++i) found = strcmp(ext[i].extensionName, name) == 0;
    host_free(ctx->alloc, ext);
    return found;
}

/* context_desc.required_subgroup_size must be a size the device can run compute pipelines with. */
static cacao_result check_subgroup_size(cacao_context *ctx) {
    const uint32_t size = ctx->required_subgroup_size;
    VkPhysicalDeviceSubgroupSizeControlPropertiesEXT range = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES_EXT};
    bool out_of_memory = false;
    if (has_extension(ctx, VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME, &out_of_memory)) {
        VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &range};
        ctx->vk.GetPhysicalDeviceProperties2(ctx->physical_device, &props);
    }
    if (out_of_memory)
        return cacaoi_fail(ctx, CACAO_ERROR_OUT_OF_MEMORY, "host memory for the device's extension list");
    if ((size & (size - 1)) != 0 || size < range.minSubgroupSize || size > range.maxSubgroupSize ||
        !(range.requiredSubgroupSizeStages & VK_SHADER_STAGE_COMPUTE_BIT))
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                           "context_desc.required_subgroup_size %u: the device's compute range is %u..%u "
                           "(VK_EXT_subgroup_size_control; 0..0: not offered)",
                           size, range.minSubgroupSize, range.maxSubgroupSize);
    return CACAO_SUCCESS;
}

/* cacao_context_create's failure before a context exists: the message into desc->error. */
static cacao_result create_fail(const cacao_context_desc *desc, cacao_result r, const char *message) {
    if (desc) cacaoi_set_error(desc->error, desc->error_size, "%s", message);
    return r;
}

/* The context as far as it got: its message into desc->error, then everything freed. */
static cacao_result create_abandon(const cacao_context_desc *desc, cacao_context *ctx, cacao_result r) {
    cacaoi_set_error(desc->error, desc->error_size, "%s", ctx->last_error);
    cacao_context_destroy(ctx);
    return r;
}

cacao_result cacao_context_create(const cacao_context_desc *desc, cacao_context **out) {
    if (!out) return create_fail(desc, CACAO_ERROR_INVALID_ARGUMENT, "out_context is NULL");
    *out = NULL;
    if (!desc) return CACAO_ERROR_INVALID_ARGUMENT;
    if (!desc->physical_device || !desc->device)
        return create_fail(desc, CACAO_ERROR_INVALID_ARGUMENT,
                           desc->device ? "context_desc.physical_device is required" : "context_desc.device is required");
    const VkAllocationCallbacks *alloc = desc->allocation_callbacks;
    if (alloc && (!alloc->pfnAllocation || !alloc->pfnReallocation || !alloc->pfnFree))
        return create_fail(desc, CACAO_ERROR_INVALID_ARGUMENT,
                           "context_desc.allocation_callbacks: pfnAllocation, pfnReallocation and pfnFree are "
                           "required");
    cacao_context *ctx = host_alloc(alloc, sizeof *ctx, VK_SYSTEM_ALLOCATION_SCOPE_OBJECT);
    if (!ctx)
        return create_fail(desc, CACAO_ERROR_OUT_OF_MEMORY, "host memory for the context (allocation_callbacks)");
    if (alloc) {
        ctx->alloc_copy = *alloc;
        ctx->alloc = &ctx->alloc_copy;
    }
    ctx->physical_device = desc->physical_device;
    ctx->device = desc->device;
    ctx->pipeline_cache = desc->pipeline_cache;
    ctx->required_subgroup_size = desc->required_subgroup_size;
    ctx->pipeline_create_flags = desc->pipeline_create_flags;
    cacao_result r = load_functions(ctx, desc);
    if (r != CACAO_SUCCESS) return create_abandon(desc, ctx, r);
    VkPhysicalDeviceProperties props;
    ctx->vk.GetPhysicalDeviceProperties(ctx->physical_device, &props);
    ctx->buffer_image_granularity = props.limits.bufferImageGranularity;
    ctx->max_texel_buffer_elements = props.limits.maxTexelBufferElements;
    ctx->forms = desc->shader_forms != CACAO_SHADER_FORMS_DEFAULT ? desc->shader_forms
                 : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? CACAO_SHADER_FORMS_CPU
                                                                   : CACAO_SHADER_FORMS_GPU;
    if ((int)desc->shader_forms < CACAO_SHADER_FORMS_DEFAULT || (int)desc->shader_forms > CACAO_SHADER_FORMS_GPU)
        r = cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "context_desc.shader_forms = %d is not a cacao_shader_forms",
                        (int)desc->shader_forms);
    VkPhysicalDeviceShaderFloat16Int8Features f16 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES};
    VkPhysicalDeviceFeatures2 features = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f16};
    ctx->vk.GetPhysicalDeviceFeatures2(ctx->physical_device, &features);
    ctx->fp16_available = desc->shader_float16_enabled && f16.shaderFloat16;
    ctx->separate_depth_layouts = desc->separate_depth_stencil_layouts_enabled;
    if (r == CACAO_SUCCESS && !features.features.shaderStorageImageWriteWithoutFormat)
        r = cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                        "context_desc.physical_device lacks shaderStorageImageWriteWithoutFormat");
    if (r == CACAO_SUCCESS && ctx->required_subgroup_size) r = check_subgroup_size(ctx);
    if (r == CACAO_SUCCESS) r = create_layouts(ctx);
    if (r != CACAO_SUCCESS) return create_abandon(desc, ctx, r);
    *out = ctx;
    return CACAO_SUCCESS;
}

/* The earlier step of the plan with the same permutation key as step index (it owns the pipeline
 * both use), or index itself. The tile fill runs twice with one key, for example. */
static uint32_t pipeline_owner(const cacao_plan *plan, uint32_t index) {
    for (uint32_t j = 0; j < index; ++j)
        if (memcmp(plan->steps[j].key, plan->steps[index].key, sizeof plan->steps[index].key) == 0) return j;
    return index;
}

static void release_pipelines(cacao_context *ctx) {
    ctx->pipelines_only = false;
    ctx->memory.pipeline_count = 0;
    for (uint32_t i = 0; i < CACAO_PLAN_MAX_STEPS; ++i) {
        bool shared = false;
        for (uint32_t j = 0; j < i && !shared; ++j) shared = ctx->pipelines[j] == ctx->pipelines[i];
        if (ctx->pipelines[i] && !shared) ctx->vk.DestroyPipeline(ctx->device, ctx->pipelines[i], ctx->alloc);
    }
    memset(ctx->pipelines, 0, sizeof ctx->pipelines);
}

/* Frees the intermediates and buffers resize created, not the pipelines or the layouts. */
static void release_images_and_buffers(cacao_context *ctx) {
    VkDevice d = ctx->device;
    if (ctx->tile_entries_view) ctx->vk.DestroyBufferView(d, ctx->tile_entries_view, ctx->alloc);
    ctx->tile_entries_view = VK_NULL_HANDLE;
    for (unsigned r = 0; r < CACAO_RES_COUNT; ++r) {
        cacao_intermediate *im = &ctx->images[r];
        if (im->view) ctx->vk.DestroyImageView(d, im->view, ctx->alloc);
        if (im->sampled_view) ctx->vk.DestroyImageView(d, im->sampled_view, ctx->alloc);
        for (unsigned l = 0; l < CACAO_DEPTH_MIP_COUNT; ++l)
            if (im->level_views[l]) ctx->vk.DestroyImageView(d, im->level_views[l], ctx->alloc);
        if (im->image) ctx->vk.DestroyImage(d, im->image, ctx->alloc);
        memset(im, 0, sizeof *im);
        if (ctx->buffers[r]) ctx->vk.DestroyBuffer(d, ctx->buffers[r], ctx->alloc);
        ctx->buffers[r] = VK_NULL_HANDLE;
    }
    for (unsigned t = 0; t < VK_MAX_MEMORY_TYPES; ++t) {
        if (ctx->memory_blocks[t]) ctx->vk.FreeMemory(d, ctx->memory_blocks[t], ctx->alloc);
        ctx->memory_blocks[t] = VK_NULL_HANDLE;
    }
    ctx->ready = false;
    ctx->memory.total_bytes = 0;
    ctx->memory.image_count = 0;
    ctx->memory.allocation_count = 0;
}

/* Frees everything resize created (not the layouts). */
static void release_frame_resources(cacao_context *ctx) {
    release_pipelines(ctx);
    release_images_and_buffers(ctx);
}

/* A pipeline depends on its step's key only, never on the size: a resize whose plan has the same
 * keys in the same order (same settings, new size: dynamic resolution) keeps the pipelines. */
static bool pipelines_fit(const cacao_context *ctx, const cacao_plan *plan) {
    bool created = false; /* a clear step has none */
    for (uint32_t i = 0; i < ctx->plan.step_count; ++i) created = created || ctx->pipelines[i];
    if (!created || ctx->plan.step_count != plan->step_count) return false;
    for (uint32_t i = 0; i < plan->step_count; ++i)
        if (memcmp(ctx->plan.steps[i].key, plan->steps[i].key, sizeof plan->steps[i].key) != 0) return false;
    return true;
}

void cacao_context_destroy(cacao_context *ctx) {
    if (!ctx) return;
    release_frame_resources(ctx); /* each release calls Vulkan only for a handle it created */
    VkDevice d = ctx->device;
    if (ctx->pipeline_layout) ctx->vk.DestroyPipelineLayout(d, ctx->pipeline_layout, ctx->alloc);
    if (ctx->set_layout) ctx->vk.DestroyDescriptorSetLayout(d, ctx->set_layout, ctx->alloc);
    if (ctx->nearest_sampler) ctx->vk.DestroySampler(d, ctx->nearest_sampler, ctx->alloc);
    if (ctx->linear_sampler) ctx->vk.DestroySampler(d, ctx->linear_sampler, ctx->alloc);
    if (ctx->loader) dlclose(ctx->loader);
    const VkAllocationCallbacks alloc = ctx->alloc_copy;
    host_free(ctx->alloc ? &alloc : NULL, ctx);
}

cacao_result cacao_context_set_settings(cacao_context *ctx, const cacao_settings *settings) {
    if (!ctx) return CACAO_ERROR_INVALID_ARGUMENT;
    cacao_settings resolved;
    cacao_result r = cacao_settings_resolve(settings, &resolved, ctx->last_error, sizeof ctx->last_error);
    if (r != CACAO_SUCCESS) return r;
    ctx->settings = *settings;
    ctx->ready = false; /* takes effect at the next resize */
    ctx->pipelines_only = false; /* the pipelines (kept for a resize that can use them) are no longer
                                    the settings' own: cacao_context_pipeline says none */
    return CACAO_SUCCESS;
}

static cacao_result check_format(cacao_context *ctx, VkFormat format, bool linear, const char *what) {
    VkFormatProperties props;
    ctx->vk.GetPhysicalDeviceFormatProperties(ctx->physical_device, format, &props);
    VkFormatFeatureFlags need = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if (linear) need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if ((props.optimalTilingFeatures & need) != need)
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                           "the device cannot use format %d for %s as a storage and sampled image", (int)format, what);
    return CACAO_SUCCESS;
}

/* An intermediate image of the plan, without memory yet (place_in_memory binds it). */
static cacao_result create_image(cacao_context *ctx, const cacao_plan_image *pi) {
    cacao_intermediate *im = &ctx->images[pi->resource];
    const cacaoi_resource_row *row = &cacaoi_resources[pi->resource];
    cacao_result r = check_format(ctx, pi->format, row->filtered, row->name);
    if (r != CACAO_SUCCESS) return r;
    const VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = pi->format,
        .extent = {pi->width, pi->height, 1},
        .mipLevels = pi->image_levels > 1 ? pi->image_levels : 1, /* the GPU forms' depth chain; else an atlas */
        .arrayLayers = pi->layers,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT | /* copyable for inspection */
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT,  /* the plan's clear steps */
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    VkResult vr = ctx->vk.CreateImage(ctx->device, &info, ctx->alloc, &im->image);
    if (vr != VK_SUCCESS) {
        im->image = VK_NULL_HANDLE; /* not to be destroyed, whatever the driver left there */
        return vk_fail(ctx, vr, "vkCreateImage (%s)", row->name);
    }
    ctx->memory.image_count++;
    return CACAO_SUCCESS;
}

/* A view of levels first .. first + count - 1, all layers (CACAO's deinterleaved intermediates are
 * arrays of slices; the rest are plain 2D images). */
static cacao_result create_level_view(cacao_context *ctx, const cacao_plan_image *pi, uint32_t first, uint32_t count,
                                      VkImageView *out) {
    const cacaoi_resource_row *row = &cacaoi_resources[pi->resource];
    const VkImageViewCreateInfo view = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = ctx->images[pi->resource].image,
        .viewType = row->layered ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D,
        .format = pi->format,
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, first, count, 0, pi->layers},
    };
    VkResult vr = ctx->vk.CreateImageView(ctx->device, &view, ctx->alloc, out);
    if (vr == VK_SUCCESS) return CACAO_SUCCESS;
    *out = VK_NULL_HANDLE;
    return vk_fail(ctx, vr, "vkCreateImageView (%s)", row->name);
}

/* The views of an image once it has memory: level 0 for sampling and storage; with mip levels (the
 * GPU forms' depth chain) all levels for sampling and each level above 0 for storage (the slots of
 * levels the chain lacks get its last level, which the prepare never writes there). */
static cacao_result create_view(cacao_context *ctx, const cacao_plan_image *pi) {
    cacao_intermediate *im = &ctx->images[pi->resource];
    cacao_result r = create_level_view(ctx, pi, 0, 1, &im->view);
    const uint32_t levels = pi->image_levels > 1 ? pi->image_levels : 1;
    if (levels == 1) return r;
    if (r == CACAO_SUCCESS) r = create_level_view(ctx, pi, 0, levels, &im->sampled_view);
    for (uint32_t l = 1; r == CACAO_SUCCESS && l < levels; ++l) r = create_level_view(ctx, pi, l, 1, &im->level_views[l]);
    return r;
}

/* A buffer of the plan, with its resource row's usage (and transfers: the frame's updates and
 * resets, and copies for inspection), without memory yet. */
static cacao_result create_buffer(cacao_context *ctx, const cacao_plan_buffer *pb) {
    const unsigned index = pb->resource;
    const VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = pb->bytes,
        .usage = cacaoi_resources[index].buffer_usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VkResult vr = ctx->vk.CreateBuffer(ctx->device, &info, ctx->alloc, &ctx->buffers[index]);
    if (vr == VK_SUCCESS) return CACAO_SUCCESS;
    ctx->buffers[index] = VK_NULL_HANDLE;
    return vk_fail(ctx, vr, "vkCreateBuffer (%s)", cacaoi_resources[index].name);
}

/* ---- Device memory: one allocation per memory type for all of a plan's resources ------------ */

typedef struct placement {
    cacao_resource resource;
    bool buffer;
    VkMemoryRequirements requirements;
    uint32_t type;       /* memory type index */
    VkDeviceSize offset; /* in that type's allocation */
} placement;

/* The first device-local memory type among type_bits, or UINT32_MAX. */
static uint32_t device_local_type(const VkPhysicalDeviceMemoryProperties *props, uint32_t type_bits) {
    for (uint32_t i = 0; i < props->memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (props->memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            return i;
    return UINT32_MAX;
}

/* Pure: picks each resource's memory type (one for all where one suits all, else one for the
 * images and one for the buffers, else each its own first) and its offset in that type's block:
 * images first, then buffers, the first buffer after an image on a new bufferImageGranularity
 * page. Returns false where a resource has no device-local type (its index in *failed). */
static bool place_resources(const VkPhysicalDeviceMemoryProperties *props, VkDeviceSize granularity, placement *p,
                            uint32_t count, VkDeviceSize block_bytes[VK_MAX_MEMORY_TYPES], uint32_t *failed) {
    uint32_t all = ~0u, images = ~0u, buffers = ~0u;
    for (uint32_t i = 0; i < count; ++i) {
        all &= p[i].requirements.memoryTypeBits;
        *(p[i].buffer ? &buffers : &images) &= p[i].requirements.memoryTypeBits;
    }
    const uint32_t shared = device_local_type(props, all);
    const uint32_t image_type = device_local_type(props, images), buffer_type = device_local_type(props, buffers);
    bool last_was_image[VK_MAX_MEMORY_TYPES] = {false};
    memset(block_bytes, 0, VK_MAX_MEMORY_TYPES * sizeof block_bytes[0]);
    for (uint32_t i = 0; i < count; ++i) { /* the caller lists images before buffers */
        uint32_t type = shared;
        if (type == UINT32_MAX && image_type != UINT32_MAX && buffer_type != UINT32_MAX)
            type = p[i].buffer ? buffer_type : image_type;
        if (type == UINT32_MAX) type = device_local_type(props, p[i].requirements.memoryTypeBits);
        if (type == UINT32_MAX) {
            *failed = i;
            return false;
        }
        VkDeviceSize align = p[i].requirements.alignment ? p[i].requirements.alignment : 1;
        if (p[i].buffer && last_was_image[type] && granularity > align) align = granularity;
        p[i].type = type;
        p[i].offset = (block_bytes[type] + align - 1) / align * align;
        block_bytes[type] = p[i].offset + p[i].requirements.size;
        last_was_image[type] = !p[i].buffer;
    }
    return true;
}

/* Allocates the blocks for the plan's images and buffers (created, without memory) and binds
 * each at its place. */
static cacao_result allocate_and_bind(cacao_context *ctx, const cacao_plan *plan) {
    placement p[CACAO_RES_COUNT + CACAO_PLAN_MAX_BUFFERS];
    uint32_t count = 0;
    for (uint32_t i = 0; i < plan->image_count; ++i, ++count) {
        p[count] = (placement){.resource = plan->images[i].resource};
        ctx->vk.GetImageMemoryRequirements(ctx->device, ctx->images[p[count].resource].image, &p[count].requirements);
    }
    for (uint32_t i = 0; i < plan->buffer_count; ++i, ++count) {
        p[count] = (placement){.resource = plan->buffers[i].resource, .buffer = true};
        ctx->vk.GetBufferMemoryRequirements(ctx->device, ctx->buffers[p[count].resource], &p[count].requirements);
    }
    VkPhysicalDeviceMemoryProperties props;
    ctx->vk.GetPhysicalDeviceMemoryProperties(ctx->physical_device, &props);
    VkDeviceSize block_bytes[VK_MAX_MEMORY_TYPES];
    uint32_t failed = 0;
    if (!place_resources(&props, ctx->buffer_image_granularity, p, count, block_bytes, &failed))
        return cacaoi_fail(ctx, CACAO_ERROR_OUT_OF_MEMORY, "no device-local memory type can hold %s",
                           cacaoi_resources[p[failed].resource].name);
    for (uint32_t t = 0; t < VK_MAX_MEMORY_TYPES; ++t) {
        if (!block_bytes[t]) continue;
        const VkMemoryAllocateInfo info = {
            .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = block_bytes[t], .memoryTypeIndex = t};
        VkResult vr = ctx->vk.AllocateMemory(ctx->device, &info, ctx->alloc, &ctx->memory_blocks[t]);
        if (vr != VK_SUCCESS) {
            ctx->memory_blocks[t] = VK_NULL_HANDLE;
            return vk_fail(ctx, vr, "vkAllocateMemory (%llu bytes, memory type %u, for the intermediates)",
                           (unsigned long long)block_bytes[t], t);
        }
        ctx->memory.total_bytes += block_bytes[t];
        ctx->memory.allocation_count++;
    }
    for (uint32_t i = 0; i < count; ++i) {
        const VkDeviceMemory block = ctx->memory_blocks[p[i].type];
        const cacao_resource res = p[i].resource;
        VkResult vr = p[i].buffer ? ctx->vk.BindBufferMemory(ctx->device, ctx->buffers[res], block, p[i].offset)
                                  : ctx->vk.BindImageMemory(ctx->device, ctx->images[res].image, block, p[i].offset);
        if (vr != VK_SUCCESS)
            return vk_fail(ctx, vr, p[i].buffer ? "vkBindBufferMemory (%s)" : "vkBindImageMemory (%s)",
                           cacaoi_resources[p[i].resource].name);
    }
    return CACAO_SUCCESS;
}

/* The tile buffer's R32_UINT texel view, where a step of the plan reads its list through it (the
 * CPU forms' list steps), within the device's limit on a texel buffer's elements. */
static cacao_result create_tile_entries_view(cacao_context *ctx, const cacao_plan *plan) {
    bool read = false;
    for (uint32_t i = 0; i < plan->step_count && !read; ++i)
        for (uint32_t j = 0; j < plan->steps[i].binding_count; ++j)
            read = read || plan->steps[i].bindings[j].binding == CACAO_BINDING_TILE_ENTRIES;
    if (!read) return CACAO_SUCCESS;
    VkDeviceSize bytes = 0;
    for (uint32_t i = 0; i < plan->buffer_count; ++i)
        if (plan->buffers[i].resource == CACAO_RES_TILES) bytes = plan->buffers[i].bytes;
    if (bytes / sizeof(uint32_t) > ctx->max_texel_buffer_elements)
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_DEVICE,
                           "the tile buffer at %ux%u holds %llu entries, more than the device's "
                           "maxTexelBufferElements (%u) that its list steps read through; use the GPU shader forms "
                           "(shader_forms) or a smaller size",
                           plan->width, plan->height, (unsigned long long)(bytes / sizeof(uint32_t)),
                           ctx->max_texel_buffer_elements);
    const VkBufferViewCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
        .buffer = ctx->buffers[CACAO_RES_TILES],
        .format = VK_FORMAT_R32_UINT,
        .offset = 0,
        .range = bytes / sizeof(uint32_t) * sizeof(uint32_t),
    };
    VkResult vr = ctx->vk.CreateBufferView(ctx->device, &info, ctx->alloc, &ctx->tile_entries_view);
    if (vr == VK_SUCCESS) return CACAO_SUCCESS;
    ctx->tile_entries_view = VK_NULL_HANDLE;
    return vk_fail(ctx, vr, "vkCreateBufferView (tiles)");
}

/* Every intermediate and buffer of the plan, in memory, with its view. */
static cacao_result create_intermediates(cacao_context *ctx, const cacao_plan *plan) {
    cacao_result r = CACAO_SUCCESS;
    for (uint32_t i = 0; r == CACAO_SUCCESS && i < plan->image_count; ++i) r = create_image(ctx, &plan->images[i]);
    for (uint32_t i = 0; r == CACAO_SUCCESS && i < plan->buffer_count; ++i) r = create_buffer(ctx, &plan->buffers[i]);
    if (r == CACAO_SUCCESS) r = allocate_and_bind(ctx, plan);
    for (uint32_t i = 0; r == CACAO_SUCCESS && i < plan->image_count; ++i) r = create_view(ctx, &plan->images[i]);
    if (r == CACAO_SUCCESS) r = create_tile_entries_view(ctx, plan);
    return r;
}

/* The module's reflected bindings must be exactly what the plan step provides. */
static bool step_matches_module(const cacao_plan_step *step, const cacao_permutation *perm) {
    bool provided[CACAO_BINDING_COUNT] = {false};
    for (uint32_t i = 0; i < step->binding_count; ++i) provided[step->bindings[i].binding] = true;
    for (unsigned b = 0; b < CACAO_BINDING_COUNT; ++b)
        if ((perm->bindings[b] != CACAOI_DESCRIPTOR_NONE) != provided[b]) return false;
    return true;
}

static cacao_result create_pipeline(cacao_context *ctx, uint32_t index) {
    if (ctx->plan.steps[index].clear) return CACAO_SUCCESS; /* a transfer: no pipeline */
    const uint32_t owner = pipeline_owner(&ctx->plan, index);
    if (owner != index) { /* one pipeline per distinct permutation */
        ctx->pipelines[index] = ctx->pipelines[owner];
        return CACAO_SUCCESS;
    }
    const cacao_plan_step *step = &ctx->plan.steps[index];
    const cacao_key key = cacaoi_plan_step_key(step);
    const cacao_permutation *perm = cacaoi_table_find(&cacaoi_embedded_table, &key);
    if (!perm)
        return cacaoi_fail(ctx, CACAO_ERROR_PERMUTATION_MISSING,
                           "permutation '%s' is not embedded in this build (subset %s); rebuild with it in "
                           "CACAO_QUALITIES / CACAO_DOWNSAMPLE / CACAO_PRECISION",
                           step->key_name, cacaoi_embedded_table.subset);
    /* The plan and the generated table must agree (our invariant, not a user error). */
    assert(step_matches_module(step, perm));
    assert(step->dispatch[2] >= 1 && perm->workgroup_size[2] == 1);
    if (!step_matches_module(step, perm))
        return cacaoi_fail(ctx, CACAO_ERROR_VULKAN, "internal: plan step '%s' does not match its module's bindings",
                           step->key_name);
    const cacao_module *module = &cacaoi_embedded_table.modules[perm->module];
    const VkShaderModuleCreateInfo module_info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = module->word_count * sizeof(uint32_t),
        .pCode = module->words,
    };
    VkShaderModule shader;
    VkResult vr = ctx->vk.CreateShaderModule(ctx->device, &module_info, ctx->alloc, &shader);
    if (vr != VK_SUCCESS) return vk_fail(ctx, vr, "vkCreateShaderModule (%s)", step->key_name);
    const VkPipelineShaderStageRequiredSubgroupSizeCreateInfoEXT subgroup = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_REQUIRED_SUBGROUP_SIZE_CREATE_INFO_EXT,
        .requiredSubgroupSize = ctx->required_subgroup_size};
    const VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = ctx->pipeline_create_flags,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .pNext = ctx->required_subgroup_size ? &subgroup : NULL,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = shader,
                  .pName = cacaoi_embedded_table.entry_point},
        .layout = ctx->pipeline_layout,
    };
    vr = ctx->vk.CreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &info, ctx->alloc, &ctx->pipelines[index]);
    ctx->vk.DestroyShaderModule(ctx->device, shader, ctx->alloc);
    if (vr != VK_SUCCESS) {
        ctx->pipelines[index] = VK_NULL_HANDLE;
        return vk_fail(ctx, vr, "vkCreateComputePipelines (%s)", step->key_name);
    }
    ctx->memory.pipeline_count++;
    return CACAO_SUCCESS;
}

/* The plan of the context's settings at this size (fp16 falling back to fp32 where the device
 * lacks it), with every permutation it needs embedded: checked before anything is created, so a
 * missing one leaves nothing behind. */
static cacao_result plan_settings(cacao_context *ctx, uint32_t width, uint32_t height, cacao_plan *plan) {
    cacao_settings settings = ctx->settings;
    if (settings.shader_forms == CACAO_SHADER_FORMS_DEFAULT) settings.shader_forms = ctx->forms;
    cacao_settings resolved;
    cacao_result r = cacao_settings_resolve(&settings, &resolved, ctx->last_error, sizeof ctx->last_error);
    if (r != CACAO_SUCCESS) return r;
    if (resolved.precision == CACAO_PRECISION_FP16 && !ctx->fp16_available)
        settings.precision = CACAO_PRECISION_FP32; /* documented fallback; cacao_context_precision tells */
    r = cacao_plan_build(&settings, width, height, plan, ctx->last_error, sizeof ctx->last_error);
    if (r != CACAO_SUCCESS) return r;
    for (uint32_t i = 0; i < plan->step_count; ++i) {
        const cacao_key key = cacaoi_plan_step_key(&plan->steps[i]);
        if (!plan->steps[i].clear && !cacaoi_table_find(&cacaoi_embedded_table, &key))
            return cacaoi_fail(ctx, CACAO_ERROR_PERMUTATION_MISSING,
                               "permutation '%s' is not embedded in this build (subset %s)", plan->steps[i].key_name,
                               cacaoi_embedded_table.subset);
    }
    return CACAO_SUCCESS;
}

/* A pipeline depends on its step's key, never on the size: the plan at any size names the
 * pipelines of the settings. */
#define PIPELINE_PLAN_SIZE 64

cacao_result cacao_context_create_pipelines(cacao_context *ctx, cacao_memory_info *out_info) {
    if (!ctx) return CACAO_ERROR_INVALID_ARGUMENT;
    cacao_plan plan;
    cacao_result r = plan_settings(ctx, PIPELINE_PLAN_SIZE, PIPELINE_PLAN_SIZE, &plan);
    if (r != CACAO_SUCCESS) return r;
    if (pipelines_fit(ctx, &plan)) { /* the settings' pipelines exist already */
        ctx->pipelines_only = !ctx->ready;
        if (out_info) *out_info = ctx->memory;
        return CACAO_SUCCESS;
    }
    release_frame_resources(ctx); /* other settings: their pipelines, and the intermediates of a size */
    ctx->plan = plan;
    for (uint32_t i = 0; r == CACAO_SUCCESS && i < plan.step_count; ++i) r = create_pipeline(ctx, i);
    if (r != CACAO_SUCCESS) {
        release_frame_resources(ctx);
        return r;
    }
    ctx->pipelines_only = true;
    ctx->last_error[0] = '\0';
    if (out_info) *out_info = ctx->memory;
    return CACAO_SUCCESS;
}

VkPipeline cacao_context_pipeline(const cacao_context *ctx, uint32_t step) {
    if (!ctx || !(ctx->ready || ctx->pipelines_only) || step >= ctx->plan.step_count) return VK_NULL_HANDLE;
    return ctx->pipelines[step];
}

cacao_result cacao_context_resize(cacao_context *ctx, uint32_t width, uint32_t height, cacao_memory_info *out_info) {
    if (!ctx) return CACAO_ERROR_INVALID_ARGUMENT;
    cacao_plan plan;
    cacao_result r = plan_settings(ctx, width, height, &plan);
    if (r != CACAO_SUCCESS) return r;
    const bool keep_pipelines = pipelines_fit(ctx, &plan);
    if (!keep_pipelines) release_pipelines(ctx);
    release_images_and_buffers(ctx);
    ctx->plan = plan;
    r = create_intermediates(ctx, &plan);
    for (uint32_t i = 0; r == CACAO_SUCCESS && !keep_pipelines && i < plan.step_count; ++i) r = create_pipeline(ctx, i);
    if (r != CACAO_SUCCESS) {
        release_frame_resources(ctx);
        return r;
    }
    ctx->ready = true;
    ctx->reuse_primed = false; /* new intermediates: the next frame is a full one */
    ctx->temporal_primed = false; /* and the history starts again */
    ctx->temporal_odd = false;
    ctx->pipelines_only = false;
    ctx->last_error[0] = '\0';
    if (out_info) *out_info = ctx->memory;
    return CACAO_SUCCESS;
}

cacao_result cacao_context_intermediate(const cacao_context *ctx, cacao_resource resource, VkImage *image,
                                        VkBuffer *buffer) {
    if (!ctx || !ctx->ready || !image || !buffer) return CACAO_ERROR_INVALID_ARGUMENT;
    *image = VK_NULL_HANDLE;
    *buffer = VK_NULL_HANDLE;
    if ((unsigned)resource < CACAO_RES_COUNT) {
        *buffer = ctx->buffers[resource];
        *image = ctx->images[resource].image;
    }
    return (*image || *buffer) ? CACAO_SUCCESS : CACAO_ERROR_INVALID_ARGUMENT;
}
