/* test_faults - what a trusted library promises when memory runs out: every failure of a host
 * allocation, of vkAllocateMemory and of vkCreateComputePipelines, at every point where one
 * happens in create + pipeline creation + resize + frame, makes the call that met it return
 * CACAO_ERROR_OUT_OF_MEMORY with a message naming what failed; nothing leaks (every allocation
 * made through the caller's callbacks, cacao's own and the driver's for cacao's objects, and every
 * VkDeviceMemory, is freed again); and once memory is back the same context goes on to compute
 * exactly the AO of a run that never failed.
 *
 * Why these are the right expectations: the host allocator and the entry points are the caller's
 * (cacao_context_desc.allocation_callbacks, .get_device_proc_addr), so the test can count and fail
 * each call independently of cacao; the reference AO comes from the same sequence with nothing
 * failing, on a fresh context. Under the sanitizer build LeakSanitizer checks the rest (memory
 * cacao might take from malloc behind the callbacks' back). */
#define _POSIX_C_SOURCE 200809L /* posix_memalign */
#include <dlfcn.h>
#include <string.h>

#include "counting_allocator.h"
#include "gpu_scene.h"

/* ---- The caller's host allocator: counting_allocator.h (counts, fails on request) ---- */

/* ---- The caller's entry points: vkAllocateMemory and vkCreateComputePipelines fail on request -- */

typedef struct device_faults {
    PFN_vkGetDeviceProcAddr real_get_device_proc_addr;
    PFN_vkAllocateMemory real_allocate;
    PFN_vkFreeMemory real_free;
    PFN_vkCreateComputePipelines real_create_pipelines;
    uint64_t allocate_calls, allocate_fail_at;
    uint64_t pipeline_calls, pipeline_fail_at;
    int64_t live_memory; /* VkDeviceMemory allocated and not freed */
} device_faults;

static device_faults faults; /* the entry points have no user pointer: one instance, this test's */
static PFN_vkGetInstanceProcAddr loader_get_instance_proc_addr;

static VkResult VKAPI_PTR faulty_allocate(VkDevice device, const VkMemoryAllocateInfo *info,
                                          const VkAllocationCallbacks *alloc, VkDeviceMemory *memory) {
    if (++faults.allocate_calls == faults.allocate_fail_at) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    VkResult vr = faults.real_allocate(device, info, alloc, memory);
    if (vr == VK_SUCCESS) faults.live_memory++;
    return vr;
}

static void VKAPI_PTR counted_free_memory(VkDevice device, VkDeviceMemory memory, const VkAllocationCallbacks *alloc) {
    if (memory) faults.live_memory--;
    faults.real_free(device, memory, alloc);
}

static VkResult VKAPI_PTR faulty_create_pipelines(VkDevice device, VkPipelineCache cache, uint32_t count,
                                                  const VkComputePipelineCreateInfo *infos,
                                                  const VkAllocationCallbacks *alloc, VkPipeline *pipelines) {
    if (++faults.pipeline_calls == faults.pipeline_fail_at) {
        for (uint32_t i = 0; i < count; ++i) pipelines[i] = VK_NULL_HANDLE;
        return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    return faults.real_create_pipelines(device, cache, count, infos, alloc, pipelines);
}

static PFN_vkVoidFunction VKAPI_PTR faulty_get_device_proc_addr(VkDevice device, const char *name) {
    if (strcmp(name, "vkAllocateMemory") == 0) return (PFN_vkVoidFunction)faulty_allocate;
    if (strcmp(name, "vkFreeMemory") == 0) return (PFN_vkVoidFunction)counted_free_memory;
    if (strcmp(name, "vkCreateComputePipelines") == 0) return (PFN_vkVoidFunction)faulty_create_pipelines;
    return faults.real_get_device_proc_addr(device, name);
}

/* ---- One sequence: create, pipelines, then per configuration a resize and a frame ----------- */

typedef struct configuration {
    cacao_settings settings;
    uint32_t width, height;
} configuration;

/* Settings that between them need every kind of intermediate (load counter and importance maps at
 * HIGHEST, the quarter-resolution path, the horizon estimator's images), at sizes small enough to
 * run a few hundred times. */
static const configuration configurations[] = {
    {{.quality = CACAO_QUALITY_HIGHEST, .generate_normals = true}, 40, 32},
    {{.quality = CACAO_QUALITY_LOW, .downsample = true, .generate_normals = true, .blur_pass_count = 1}, 48, 30},
    {{.estimator = CACAO_ESTIMATOR_GTAO, .quality = CACAO_QUALITY_LOWEST, .generate_normals = true}, 33, 27},
};
#define CONFIGURATIONS (sizeof configurations / sizeof configurations[0])

typedef struct sequence {
    vkdev *dev;
    host_counter *host;
    VkAllocationCallbacks callbacks;
    const scene_buffers *scenes; /* one per configuration */
    float *reference[CONFIGURATIONS]; /* AO of a run without failures */
    uint32_t configuration_count;
} sequence;

/* The steps of the sequence, in order; a failed step is retried once memory is back. */
enum { STEP_CREATE, STEP_SETTINGS, STEP_PIPELINES, STEP_RESIZE, STEP_FRAME };

typedef struct outcome {
    cacao_result first_failure;  /* CACAO_SUCCESS when nothing failed */
    char message[256];           /* its message */
    bool recovered;              /* the same context then computed every reference image */
} outcome;

static cacao_result run_step(sequence *s, cacao_context **ctx, int step, uint32_t c, float *ao, char *message,
                             size_t message_size) {
    const configuration *cfg = &configurations[c];
    cacao_result r = CACAO_SUCCESS;
    switch (step) {
    case STEP_CREATE: {
        const cacao_context_desc desc = {.physical_device = s->dev->physical_device,
                                         .device = s->dev->device,
                                         .allocation_callbacks = &s->callbacks,
                                         .instance = s->dev->instance,
                                         .get_instance_proc_addr = loader_get_instance_proc_addr,
                                         .get_device_proc_addr = faulty_get_device_proc_addr,
                                         .error = message,
                                         .error_size = message_size};
        return cacao_context_create(&desc, ctx);
    }
    case STEP_SETTINGS: r = cacao_context_set_settings(*ctx, &cfg->settings); break;
    case STEP_PIPELINES: r = cacao_context_create_pipelines(*ctx, NULL); break;
    case STEP_RESIZE: r = cacao_context_resize(*ctx, cfg->width, cfg->height, NULL); break;
    default: {
        vkdev_frame frame = scene_frame(&s->scenes[c], false, false);
        char err[256] = "";
        r = vkdev_run_context(s->dev, *ctx, &frame, 1, ao, NULL, err, sizeof err);
        if (r != CACAO_SUCCESS) snprintf(message, message_size, "%s", err);
        return r;
    }
    }
    if (r != CACAO_SUCCESS) snprintf(message, message_size, "%s", cacao_context_last_error(*ctx));
    return r;
}

/* Runs the whole sequence; the first failure is recorded, memory comes back (no more failures)
 * and the failed step is retried. out->recovered: every frame then equals its reference. */
static void run_sequence(sequence *s, outcome *out, float *ao) {
    *out = (outcome){.first_failure = CACAO_SUCCESS, .recovered = true};
    cacao_context *ctx = NULL;
    for (uint32_t c = 0; c < s->configuration_count; ++c) {
        for (int step = c == 0 ? STEP_CREATE : STEP_SETTINGS; step <= STEP_FRAME; ++step) {
            char message[256] = "";
            cacao_result r = run_step(s, &ctx, step, c, ao, message, sizeof message);
            if (r != CACAO_SUCCESS && out->first_failure == CACAO_SUCCESS) {
                out->first_failure = r;
                snprintf(out->message, sizeof out->message, "%s", message);
                s->host->fail_at = 0; /* memory is back */
                faults.allocate_fail_at = faults.pipeline_fail_at = 0;
                if (step == STEP_CREATE && ctx != NULL) out->recovered = false; /* no context on failure */
                r = run_step(s, &ctx, step, c, ao, message, sizeof message);
            }
            if (r != CACAO_SUCCESS) {
                fprintf(stderr, "configuration %u step %d failed after recovery: %s\n", c, step, message);
                out->recovered = false;
                cacao_context_destroy(ctx);
                return;
            }
        }
        const size_t n = (size_t)configurations[c].width * configurations[c].height;
        if (s->reference[c] && memcmp(ao, s->reference[c], n * sizeof *ao) != 0) out->recovered = false;
        if (!s->reference[c]) {
            s->reference[c] = malloc(n * sizeof *ao);
            memcpy(s->reference[c], ao, n * sizeof *ao);
        }
    }
    cacao_context_destroy(ctx);
}

/* One injected fault: the failing call's result and message, the recovery, and no leak. Returns
 * whether a failure happened at all (false: n is past the sequence's last call). */
static bool check_fault(sequence *s, const char *kind, uint64_t n, const char *expect_in_message, float *ao,
                        uint32_t *leaks) {
    outcome o;
    run_sequence(s, &o, ao);
    if (o.first_failure == CACAO_SUCCESS) return false;
    const bool named = strstr(o.message, expect_in_message) != NULL;
    const bool leaked = s->host->live_count != 0 || faults.live_memory != 0;
    if (o.first_failure != CACAO_ERROR_OUT_OF_MEMORY || !named || !o.recovered || leaked) {
        fprintf(stderr, "%s failure %llu: %s (%s), message \"%s\", recovered %d, live host blocks %lld, live device "
                        "allocations %lld\n",
                kind, (unsigned long long)n, cacao_result_string(o.first_failure),
                o.first_failure == CACAO_ERROR_OUT_OF_MEMORY ? "expected" : "expected out of memory", o.message,
                (int)o.recovered, (long long)s->host->live_count, (long long)faults.live_memory);
        ++test_failures;
    }
    *leaks += leaked;
    return true;
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    dev.expect_out_of_memory = true; /* the layer names each call the injected failures make fail */
    host_counter host = {0};
    sequence s = {.dev = &dev, .host = &host, .configuration_count = CONFIGURATIONS};
    s.callbacks = counting_callbacks(&host);
    /* The loader's own entry points, asked from the loader library itself: the sanitizer build
     * preloads the validation layer, whose exported vkGet*ProcAddr would otherwise answer. */
    void *loader = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    void *symbol = loader ? dlsym(loader, "vkGetInstanceProcAddr") : NULL;
    if (!symbol) return fprintf(stderr, "cannot open the Vulkan loader: %s\n", dlerror()), 1;
    memcpy(&loader_get_instance_proc_addr, &symbol, sizeof symbol);
    PFN_vkGetDeviceProcAddr get_device_proc_addr =
        (PFN_vkGetDeviceProcAddr)loader_get_instance_proc_addr(dev.instance, "vkGetDeviceProcAddr");
    faults.real_get_device_proc_addr = get_device_proc_addr;
    faults.real_allocate = (PFN_vkAllocateMemory)get_device_proc_addr(dev.device, "vkAllocateMemory");
    faults.real_free = (PFN_vkFreeMemory)get_device_proc_addr(dev.device, "vkFreeMemory");
    faults.real_create_pipelines =
        (PFN_vkCreateComputePipelines)get_device_proc_addr(dev.device, "vkCreateComputePipelines");
    scene_buffers scenes[CONFIGURATIONS];
    for (uint32_t c = 0; c < CONFIGURATIONS; ++c)
        scene_buffers_default(configurations[c].width, configurations[c].height, &scenes[c]);
    s.scenes = scenes;
    float *ao = malloc(64 * 64 * sizeof *ao);

    /* The run without failures: the reference images and the number of calls of each kind. */
    outcome clean;
    run_sequence(&s, &clean, ao);
    CHECK(clean.first_failure == CACAO_SUCCESS && host.live_count == 0 && faults.live_memory == 0);
    const uint64_t host_calls = host.calls, allocate_calls = faults.allocate_calls,
                   pipeline_calls = faults.pipeline_calls;
    CHECK(allocate_calls == CONFIGURATIONS); /* one block per resize: cacao_memory_info's promise */
    printf("one sequence (%zu configurations): %llu host allocations through the callbacks, %llu vkAllocateMemory, "
           "%llu vkCreateComputePipelines\n",
           CONFIGURATIONS, (unsigned long long)host_calls, (unsigned long long)allocate_calls,
           (unsigned long long)pipeline_calls);

    /* Host allocations: fail the n-th, for every n of the sequence. */
    uint32_t tried = 0, leaks = 0;
    for (uint64_t n = 1;; ++n) {
        host.calls = 0;
        host.fail_at = n;
        faults.allocate_calls = faults.pipeline_calls = 0;
        if (!check_fault(&s, "host allocation", n, "memory", ao, &leaks)) break;
        ++tried;
    }
    CHECK(tried == host_calls);
    printf("host allocation failures: %u tried, %u leaked\n", tried, leaks);

    /* vkAllocateMemory, then vkCreateComputePipelines: fail the n-th call of each. */
    uint32_t device_tried = 0, pipeline_tried = 0;
    for (uint64_t n = 1; n <= allocate_calls; ++n, ++device_tried) {
        host.fail_at = 0;
        faults.allocate_calls = faults.pipeline_calls = 0;
        faults.allocate_fail_at = n;
        CHECK(check_fault(&s, "vkAllocateMemory", n, "vkAllocateMemory", ao, &leaks));
    }
    for (uint64_t n = 1; n <= pipeline_calls; ++n, ++pipeline_tried) {
        faults.allocate_calls = faults.pipeline_calls = 0;
        faults.pipeline_fail_at = n;
        CHECK(check_fault(&s, "vkCreateComputePipelines", n, "vkCreateComputePipelines", ao, &leaks));
    }
    printf("vkAllocateMemory failures: %u tried; vkCreateComputePipelines failures: %u tried; %u leaked in all\n",
           device_tried, pipeline_tried, leaks);
    printf("validation: %u messages; %u reports of a call returning out of memory (at most one per injected "
           "host failure: %u)\n",
           dev.validation_messages, dev.out_of_memory_reports, tried);
    CHECK(dev.validation_messages == 0 && dev.out_of_memory_reports <= tried);

    for (uint32_t c = 0; c < CONFIGURATIONS; ++c) {
        free(s.reference[c]);
        scene_buffers_free(&scenes[c]);
    }
    free(ao);
    vkdev_destroy(&dev);
    dlclose(loader);
    return test_report("test_faults");
}
