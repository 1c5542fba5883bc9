/* vkdev.h - a small headless Vulkan device for the cacao command and the tests: instance (with
 * the Khronos validation layer and synchronization validation when asked), device selection
 * (lavapipe by default), and one-shot "upload depth, run cacao, read back AO" frames.
 * This is application code built on the public API (cacao.h), as an engine would write it. */
#ifndef CACAO_VKDEV_H
#define CACAO_VKDEV_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "cacao.h"
#include "timing.h"

typedef struct vkdev {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    VkQueryPool timestamps;
    double timestamp_period_ns;
    bool fp16;                    /* shaderFloat16 enabled */
    bool validation;              /* validation layer on */
    uint32_t validation_messages; /* warnings and errors reported by the layer */
    bool expect_out_of_memory;    /* set by a test that makes allocations fail: the layer's report of
                                     a call returning VK_ERROR_OUT_OF_*_MEMORY is counted here ... */
    uint32_t out_of_memory_reports; /* ... and not as a validation message */
    char device_name[256];
    uint32_t subgroup_size_min, subgroup_size_max; /* compute, VK_EXT_subgroup_size_control enabled; 0: not */
    uint32_t required_subgroup_size; /* passed to cacao_context_desc by vkdev_context_create; 0: default */
    cacao_shader_forms shader_forms; /* passed to cacao_context_desc likewise; 0: the device's choice */
    char context_error[256];         /* the message of vkdev_context_create's last failure */
    const VkAllocationCallbacks *allocation_callbacks; /* passed to cacao_context_desc likewise; NULL: none */
    bool statistics_only;            /* vkdev_options.pipeline_statistics: no pool, fence, queries or command buffer */
    bool lane;                       /* made by vkdev_lane_create: the device belongs to another vkdev */
    pthread_mutex_t *queue_lock;     /* a lane's: held around every use of the shared queue */
} vkdev;

typedef struct vkdev_options {
    bool validation;    /* Khronos validation + synchronization validation; messages are counted and printed */
    const char *device; /* NULL: lavapipe (CPU) if present, else the first device; or an index or a name substring */
    bool quiet;         /* do not print validation messages */
    bool subgroup_size_control; /* enable VK_EXT_subgroup_size_control where offered (tests) */
    /* A device for reading a compiler's pipeline statistics: VK_KHR_pipeline_executable_properties
     * and its pipelineExecutableInfo feature enabled, and nothing that records or submits work (a
     * compiler's null device, such as RADV's with RADV_FORCE_FAMILY, can create pipelines and no
     * more). device NULL picks the first device offering the extension instead of lavapipe. */
    bool pipeline_statistics;
} vkdev_options;

/* Creates everything; on failure writes a message into err and returns false. The validation
 * layer reports into *dev, so dev must not move while it is alive. */
bool vkdev_create(const vkdev_options *options, vkdev *dev, char *err, size_t err_size);
void vkdev_destroy(vkdev *dev);

/* A lane: the device, queue and validation of dev, with a command pool, command buffer, fence and
 * query pool of its own, for one more thread. Every vkdev function works on it as on dev; its
 * submissions and queue waits hold queue_lock (Vulkan makes the caller synchronise a queue's
 * use), which every lane on the device shares (dev itself then may not submit while lanes run).
 * Validation messages count in dev. vkdev_destroy(lane) frees the lane's own objects only, after
 * its work is done, and must precede vkdev_destroy(dev). */
bool vkdev_lane_create(vkdev *dev, pthread_mutex_t *queue_lock, vkdev *lane, char *err, size_t err_size);

/* The device's driver in words: its name and version, and the Vulkan version it offers. */
void vkdev_driver(const vkdev *dev, char *out, size_t out_size);

/* Lists the physical devices (index, name, type) to out. Returns false if Vulkan is unusable. */
bool vkdev_list(FILE *out, char *err, size_t err_size);

/* One frame's inputs as host data. */
typedef struct vkdev_frame {
    uint32_t width, height;
    const float *depth;        /* width*height raw depth, row 0 = top */
    const float *normals;      /* width*height*3 or NULL */
    float projection[16];      /* row-major, column vectors (scenes' camera.json convention) */
    bool depth_reversed;       /* cacao_inputs.depth_reversed (orthographic projections) */
    float normals_to_view[16]; /* row-major; zero = identity */
    float normals_unpack_mul, normals_unpack_add;
    VkFormat output_format;    /* 0 = R32_SFLOAT */
    uint32_t frame_index;      /* cacao_inputs.frame_index (GTAO/BITMASK sample pattern) */
    /* temporal_frames: the run's frames r = 0, 1, ... use frame_index + r (each a new sample
     * pattern for the accumulation); view_to_previous_view (row-major, zero = identity) and
     * temporal_reset are the inputs' */
    bool advance_frame_index;
    float view_to_previous_view[16];
    bool temporal_reset;
    /* reuse_unchanged (docs/tiles.md): alternate_depth, when set, is the depth of every other frame
     * of a run (frames 1, 3, ...: a change between every two frames); output_holds_previous sets
     * that input on every frame after a run's first (the run keeps one output image);
     * force_full_frame sets that input on every frame. */
    const float *alternate_depth;
    bool alternate_camera; /* every other frame, P(0,0) one part in a million larger: a moving camera */
    bool output_holds_previous;
    bool force_full_frame;
    /* Optional: called after the last cacao_record, before submission, to record extra commands
     * (e.g. copies of intermediates), and after the wait, to read them. */
    void (*after_record)(struct vkdev *dev, cacao_context *ctx, VkCommandBuffer cmd, void *user);
    void (*after_wait)(struct vkdev *dev, cacao_context *ctx, void *user);
    void *user;
    /* Optional: receives the plan the context ran (after the runtime's fallbacks, e.g. fp16 to
     * fp32 on a device without shaderFloat16). Filled by vkdev_run_timed and vkdev_run. */
    cacao_plan *plan_out;
} vkdev_frame;

/* Gives the frame float normals in the scenes' convention (right-handed view space, camera-facing
 * +z, unit length, as shared/scenes' normals.pfm): normals_to_view = diag(1, 1, -1), unpack 1, 0. */
void vkdev_frame_set_view_normals(vkdev_frame *frame, const float *normals);

/* Host-visible buffer helpers for after_record callbacks. */
typedef struct vkdev_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} vkdev_buffer;
bool vkdev_buffer_create(vkdev *dev, VkDeviceSize size, vkdev_buffer *out);
void vkdev_buffer_destroy(vkdev *dev, vkdev_buffer *b);

/* Creates a context with these settings, uploads the frame, records cacao warmup + repeat times
 * (each in its own submission, timestamped), reads the last frame's AO back into ao
 * (width*height floats) and summarises the timed frames (timing.h) with the context's memory,
 * pipeline count and set-up time. timings may be NULL. On a cacao error returns it with the
 * message in err; Vulkan failures return CACAO_ERROR_VULKAN. */
cacao_result vkdev_run_timed(vkdev *dev, const cacao_settings *settings, const vkdev_frame *frame, uint32_t warmup,
                             uint32_t repeat, float *ao, cacao_timings *timings, char *err, size_t err_size);

/* A cacao context on this device (its fp16 support as the device reports it). */
cacao_result vkdev_context_create(vkdev *dev, cacao_context **ctx);
/* The same, creating its pipelines through the caller's cache (VK_NULL_HANDLE: none). */
cacao_result vkdev_context_create_on_cache(vkdev *dev, VkPipelineCache cache, cacao_context **ctx);

/* Pipeline creation with and without the caller's VkPipelineCache (issue 15, docs/tiles.md):
 * per trial, in this order, a context resized to w x h with these settings and
 *   - no cache,
 *   - an empty cache of its own (cold),
 *   - a cache created from the data the first trial's cold cache held afterwards (warm),
 * each timed as the wall time of cacao_context_resize, which creates the plan's pipelines. */
typedef struct vkdev_cache_timing {
    uint32_t pipeline_count;
    uint32_t trials;
    cacao_time_stats no_cache, cold_cache, warm_cache; /* ms over the trials */
    size_t cache_bytes; /* vkGetPipelineCacheData of the first cold cache after the resize */
    bool header_valid;  /* its header names this device (version ONE, vendor, device, UUID) */
} vkdev_cache_timing;
cacao_result vkdev_time_pipeline_cache(vkdev *dev, const cacao_settings *settings, uint32_t width, uint32_t height,
                                       uint32_t trials, vkdev_cache_timing *out, char *err, size_t err_size);

/* The size of the header every VkPipelineCache's data starts with (VK_PIPELINE_CACHE_HEADER_VERSION_ONE):
 * data of this size holds no pipeline. */
#define VKDEV_PIPELINE_CACHE_HEADER_BYTES 32u

/* vkdev_run_timed without warm-up frames. */
cacao_result vkdev_run(vkdev *dev, const cacao_settings *settings, const vkdev_frame *frame, uint32_t repeat, float *ao,
                       cacao_timings *timings, char *err, size_t err_size);

/* The same frame on a context the caller created on this device and resized to the frame's size
 * (settings as it set them); the context stays the caller's, as an engine keeps its own. */
cacao_result vkdev_run_context(vkdev *dev, cacao_context *ctx, const vkdev_frame *frame, uint32_t repeat, float *ao,
                               cacao_timings *timings, char *err, size_t err_size);
/* vkdev_run_context with warmup untimed frames first (memory, pipelines and set-up left 0). */
cacao_result vkdev_run_context_timed(vkdev *dev, cacao_context *ctx, const vkdev_frame *frame, uint32_t warmup,
                                     uint32_t repeat, float *ao, cacao_timings *timings, char *err, size_t err_size);

#endif
