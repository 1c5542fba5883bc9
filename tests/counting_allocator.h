/* counting_allocator.h - VkAllocationCallbacks that count what a context (and the driver, for the
 * objects cacao creates) holds, and can fail one chosen call: the tests of issue 32's allocator
 * promises (test_faults, test_resize_storm). Header-only, tests only. */
#ifndef CACAO_COUNTING_ALLOCATOR_H
#define CACAO_COUNTING_ALLOCATOR_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

typedef struct host_counter {
    int64_t live_count, live_bytes; /* updated atomically: drivers may call from any thread */
    int64_t total_count;            /* blocks handed out so far */
    uint64_t calls;                 /* allocations and reallocations asked for so far */
    uint64_t fail_at;               /* the call that fails (1-based); 0: none */
} host_counter;

/* Every block carries its size and its offset from the malloc'd start just before the pointer. */
typedef struct block_header {
    size_t size, offset;
} block_header;

static void *VKAPI_CALL counted_alloc(void *user, size_t size, size_t alignment, VkSystemAllocationScope scope) {
    (void)scope;
    host_counter *c = user;
    if (__atomic_add_fetch(&c->calls, 1, __ATOMIC_RELAXED) == c->fail_at) return NULL;
    if (alignment < sizeof(block_header)) alignment = sizeof(block_header); /* both powers of two */
    const size_t offset = (sizeof(block_header) + alignment - 1) / alignment * alignment;
    void *base = NULL;
    if (posix_memalign(&base, alignment, offset + size) != 0) return NULL;
    char *p = (char *)base + offset;
    ((block_header *)p)[-1] = (block_header){size, offset};
    __atomic_add_fetch(&c->live_count, 1, __ATOMIC_RELAXED);
    __atomic_add_fetch(&c->live_bytes, (int64_t)size, __ATOMIC_RELAXED);
    __atomic_add_fetch(&c->total_count, 1, __ATOMIC_RELAXED);
    return p;
}

static void VKAPI_CALL counted_free(void *user, void *p) {
    if (!p) return;
    host_counter *c = user;
    const block_header h = ((block_header *)p)[-1];
    __atomic_sub_fetch(&c->live_count, 1, __ATOMIC_RELAXED);
    __atomic_sub_fetch(&c->live_bytes, (int64_t)h.size, __ATOMIC_RELAXED);
    free((char *)p - h.offset);
}

static void *VKAPI_CALL counted_realloc(void *user, void *old, size_t size, size_t alignment,
                                        VkSystemAllocationScope scope) {
    if (!old) return counted_alloc(user, size, alignment, scope);
    if (size == 0) {
        counted_free(user, old);
        return NULL;
    }
    void *p = counted_alloc(user, size, alignment, scope);
    if (!p) return NULL; /* the old block stays valid, as the spec asks */
    const size_t old_size = ((block_header *)old)[-1].size;
    memcpy(p, old, old_size < size ? old_size : size);
    counted_free(user, old);
    return p;
}

/* The callbacks over counter c. */
static inline VkAllocationCallbacks counting_callbacks(host_counter *c) {
    return (VkAllocationCallbacks){
        .pUserData = c, .pfnAllocation = counted_alloc, .pfnReallocation = counted_realloc, .pfnFree = counted_free};
}

#endif
