/* vulkan_internal.h - the context struct and helpers shared by context.c and record.c. */
#ifndef CACAO_VULKAN_INTERNAL_H
#define CACAO_VULKAN_INTERNAL_H

#include <stdarg.h>
#include <stdio.h>

#include "internal.h"

/* Every Vulkan entry point the runtime calls, loaded per context through the caller's
 * vkGetInstanceProcAddr / vkGetDeviceProcAddr or the system loader (cacao_context_desc). The
 * runtime is built with VK_NO_PROTOTYPES: it names no vk* symbol. */
#define CACAOI_VK_INSTANCE_FUNCTIONS(X)                                                              \
    X(GetDeviceProcAddr) X(GetPhysicalDeviceProperties) X(GetPhysicalDeviceProperties2)             \
    X(GetPhysicalDeviceFeatures2) X(GetPhysicalDeviceMemoryProperties)                              \
    X(GetPhysicalDeviceFormatProperties) X(EnumerateDeviceExtensionProperties)
#define CACAOI_VK_DEVICE_FUNCTIONS(X)                                                                \
    X(AllocateMemory) X(FreeMemory) X(BindBufferMemory) X(BindImageMemory) X(CreateBuffer)          \
    X(DestroyBuffer) X(CreateImage) X(DestroyImage) X(CreateImageView) X(DestroyImageView)          \
    X(GetBufferMemoryRequirements) X(GetImageMemoryRequirements) X(CreateSampler) X(DestroySampler) \
    X(CreateDescriptorSetLayout) X(DestroyDescriptorSetLayout) X(CreatePipelineLayout)              \
    X(DestroyPipelineLayout) X(CreateShaderModule) X(DestroyShaderModule)                           \
    X(CreateComputePipelines) X(DestroyPipeline) X(CmdBindPipeline) X(CmdDispatch)                 \
    X(CmdDispatchIndirect) X(CmdPipelineBarrier) X(CmdUpdateBuffer) X(CmdFillBuffer)                \
    X(CmdCopyBuffer) X(CmdWriteTimestamp) X(CmdPushDescriptorSetKHR) X(CmdClearColorImage)         \
    X(CreateBufferView) X(DestroyBufferView)

#define CACAOI_VK_MEMBER(name) PFN_vk##name name;
typedef struct cacaoi_vk {
    CACAOI_VK_INSTANCE_FUNCTIONS(CACAOI_VK_MEMBER)
    CACAOI_VK_DEVICE_FUNCTIONS(CACAOI_VK_MEMBER)
} cacaoi_vk;
#undef CACAOI_VK_MEMBER

typedef struct cacao_intermediate {
    VkImage image;
    VkImageView view; /* all layers of level 0, for storage (and sampling where that is the only level) */
    /* An image with mip levels (the GPU forms' depth chain): all levels for sampling, and levels
     * 1..3 one per view for storage (a storage view holds one level); VK_NULL_HANDLE otherwise. */
    VkImageView sampled_view;
    VkImageView level_views[CACAO_DEPTH_MIP_COUNT];
} cacao_intermediate;


struct cacao_context {
    cacaoi_vk vk;
    void *loader; /* the system loader cacao opened (no get_instance_proc_addr given), or NULL */
    VkPhysicalDevice physical_device;
    VkDevice device;
    const VkAllocationCallbacks *alloc; /* &alloc_copy, or NULL */
    VkAllocationCallbacks alloc_copy;   /* the caller's callbacks, kept for the context's life */
    VkDeviceSize buffer_image_granularity;
    uint32_t max_texel_buffer_elements; /* the device's limit on the tile buffer's texel view */
    VkPipelineCache pipeline_cache;
    uint32_t required_subgroup_size; /* 0: the driver's choice */
    VkPipelineCreateFlags pipeline_create_flags; /* the caller's, on every pipeline */
    cacao_shader_forms forms;        /* CPU or GPU: for settings that leave shader_forms DEFAULT */
    bool fp16_available;
    bool separate_depth_layouts; /* DEPTH_READ_ONLY_OPTIMAL may be used (the caller enabled the feature) */

    cacao_settings settings; /* as given (zero = default) */
    bool ready;              /* plan, intermediates and pipelines exist */
    bool pipelines_only;     /* the pipelines of the settings exist (cacao_context_create_pipelines),
                                no intermediates: plan holds the steps at a nominal size */
    cacao_plan plan;
    /* reuse_unchanged (record.c reuse_frame): a frame was recorded since the last resize, and its
     * constants (less the per-frame reuse fields) */
    bool reuse_primed;
    bool reuse_copies_stale; /* the last frame skipped the diff (its constants changed): the next
                                one refreshes the copies of the inputs */
    cacao_constants reuse_constants;
    /* temporal_frames (record.c): a frame was recorded since the last resize, so the history
     * image holds its accumulation */
    bool temporal_primed;
    bool temporal_odd; /* this frame reads AO_HISTORY_NEXT and writes AO_HISTORY (record.c describe) */

    VkSampler nearest_sampler, linear_sampler;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout pipeline_layout;
    VkPipeline pipelines[CACAO_PLAN_MAX_STEPS]; /* one per plan step (VK_NULL_HANDLE for a clear) */
    cacao_intermediate images[CACAO_RES_COUNT];
    VkBuffer buffers[CACAO_RES_COUNT];             /* the plan's buffers, by resource */
    VkBufferView tile_entries_view; /* the tile buffer as R32_UINT texels, where a list step reads
                                       it (CACAO_BINDING_TILE_ENTRIES); else VK_NULL_HANDLE */
    VkDeviceMemory memory_blocks[VK_MAX_MEMORY_TYPES]; /* every intermediate and buffer lives in
                                                          these: one allocation per memory type used */
    cacao_memory_info memory;
    char last_error[256];
};

/* Sets the context's last error and returns result. */
cacao_result cacaoi_fail(cacao_context *ctx, cacao_result result, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

VkDescriptorType cacaoi_binding_type(unsigned binding);

#endif
