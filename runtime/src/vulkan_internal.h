/* vulkan_internal.h - the context struct and helpers shared by context.c and record.c. */
#ifndef CACAO_VULKAN_INTERNAL_H
#define CACAO_VULKAN_INTERNAL_H

#include <stdarg.h>
#include <stdio.h>

#include "internal.h"

typedef struct cacao_intermediate {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view; /* all layers of its one level, for sampling and storage */
} cacao_intermediate;


struct cacao_context {
    VkPhysicalDevice physical_device;
    VkDevice device;
    const VkAllocationCallbacks *alloc;
    VkPipelineCache pipeline_cache;
    uint32_t required_subgroup_size; /* 0: the driver's choice */
    VkPipelineCreateFlags pipeline_create_flags; /* the caller's, on every pipeline */
    cacao_shader_forms forms;        /* CPU or GPU: for settings that leave shader_forms DEFAULT */
    PFN_vkCmdPushDescriptorSetKHR push_descriptor;
    bool fp16_available;
    bool separate_depth_layouts; /* DEPTH_READ_ONLY_OPTIMAL may be used (the caller enabled the feature) */

    cacao_settings settings; /* as given (zero = default) */
    bool ready;              /* plan, intermediates and pipelines exist */
    bool pipelines_only;     /* the pipelines of the settings exist (cacao_context_create_pipelines),
                                no intermediates: plan holds the steps at a nominal size */
    cacao_plan plan;

    VkSampler nearest_sampler, linear_sampler;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout pipeline_layout;
    VkPipeline pipelines[CACAO_PLAN_MAX_STEPS]; /* one per plan step */
    cacao_intermediate images[CACAO_RES_COUNT];
    VkBuffer buffers[CACAO_RES_COUNT];             /* the plan's buffers, by resource */
    VkDeviceMemory buffer_memory[CACAO_RES_COUNT];
    cacao_memory_info memory;
    char last_error[256];
};

/* Sets the context's last error and returns result. */
cacao_result cacaoi_fail(cacao_context *ctx, cacao_result result, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

VkDescriptorType cacaoi_binding_type(unsigned binding);

#endif
