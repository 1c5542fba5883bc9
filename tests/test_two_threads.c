/* test_two_threads - two contexts on one device, each driven by a thread of its own (issue 32,
 * "Faults and load"). cacao.h promises that distinct contexts are independent: an engine may
 * record AO for two views on two threads at once. Each thread here creates its context, then for
 * 100 frames sets settings, resizes and records into a command buffer of its own command pool,
 * submits (the one queue is shared: Vulkan makes the caller serialise its use, done through one
 * mutex, vkdev_lane_create) and waits on its own fence; the threads use different sizes and
 * settings and change both along the way. So:
 *   - every frame succeeds and gives AO in [0,1] everywhere, and the validation layer (with its
 *     thread-safety and synchronization checks) reports nothing (the threads' loads are balanced
 *     so that they overlap throughout: with a mutex per lane instead of one, the layer reported
 *     the queue used by both threads at once in 5 runs of 5);
 *   - each thread's last frame equals, byte for byte, the frame a single thread computed first
 *     with a fresh context at the same size and settings: running beside another context must
 *     not change a result (nothing shared, nothing raced).
 * In a ThreadSanitizer build (CACAO_SANITIZE_THREAD, run by tools/run-tests.sh) the same run
 * fails on any data race the sanitizer sees in cacao's code or the test's. */
#define _POSIX_C_SOURCE 200809L

#include <pthread.h>
#include <time.h>

#include "gpu_scene.h"

#define FRAMES_PER_THREAD 100
#define SIZES_PER_THREAD 3

typedef struct worker {
    const char *name;
    vkdev lane;                             /* its command pool, command buffer and fence */
    cacao_settings settings[2];             /* for the first half of the frames, then the second */
    scene_buffers scenes[SIZES_PER_THREAD]; /* the sizes it cycles through, one per frame */
    pthread_barrier_t *start;
    float *ao, *reference; /* the last frame, and the single-threaded one */
    uint32_t frames, resizes;
    double begin_s, end_s; /* its frames' wall-clock span */
    char error[600];       /* the first failure */
} worker;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Frame i's settings and inputs. */
static const cacao_settings *frame_settings(const worker *w, uint32_t i) {
    return &w->settings[i < FRAMES_PER_THREAD / 2 ? 0 : 1];
}
static const scene_buffers *frame_scene(const worker *w, uint32_t i) { return &w->scenes[i % SIZES_PER_THREAD]; }

static void *run_worker(void *arg) {
    worker *w = arg;
    cacao_context *ctx = NULL;
    cacao_result r = vkdev_context_create(&w->lane, &ctx);
    if (r != CACAO_SUCCESS) snprintf(w->error, sizeof w->error, "cacao_context_create: %s", cacao_result_string(r));
    pthread_barrier_wait(w->start);
    w->begin_s = now_s();
    const cacao_settings *settings = NULL;
    const scene_buffers *scene = NULL;
    for (uint32_t i = 0; r == CACAO_SUCCESS && i < FRAMES_PER_THREAD; ++i) {
        const cacao_settings *s = frame_settings(w, i);
        const scene_buffers *b = frame_scene(w, i);
        if (s != settings) r = cacao_context_set_settings(ctx, s);
        if (r == CACAO_SUCCESS && (s != settings || b != scene)) {
            r = cacao_context_resize(ctx, b->width, b->height, NULL);
            w->resizes++;
        }
        if (r != CACAO_SUCCESS) {
            snprintf(w->error, sizeof w->error, "frame %u: settings or resize: %s", i, cacao_context_last_error(ctx));
            break;
        }
        settings = s, scene = b;
        const vkdev_frame f = scene_frame(b, false, !s->generate_normals);
        char err[512];
        r = vkdev_run_context(&w->lane, ctx, &f, 1, w->ao, NULL, err, sizeof err);
        if (r != CACAO_SUCCESS) {
            snprintf(w->error, sizeof w->error, "frame %u: %s", i, err);
            break;
        }
        if (!all_finite_unit(w->ao, (size_t)b->width * b->height)) {
            snprintf(w->error, sizeof w->error, "frame %u: AO outside [0,1]", i);
            break;
        }
        w->frames++;
    }
    w->end_s = now_s();
    cacao_context_destroy(ctx);
    return NULL;
}

/* The worker's last frame on a fresh context, one thread only (before the workers start). */
static bool reference_frame(vkdev *dev, worker *w) {
    const uint32_t last = FRAMES_PER_THREAD - 1;
    const cacao_settings *s = frame_settings(w, last);
    const vkdev_frame f = scene_frame(frame_scene(w, last), false, !s->generate_normals);
    return run(dev, s, &f, w->reference);
}

static void worker_init(worker *w, const char *name, const uint32_t sizes[SIZES_PER_THREAD][2], cacao_settings first,
                        cacao_settings second, pthread_barrier_t *start) {
    memset(w, 0, sizeof *w);
    w->name = name;
    w->start = start;
    float radius = 0;
    uint32_t most = 0;
    for (int k = 0; k < SIZES_PER_THREAD; ++k) {
        radius = scene_buffers_default(sizes[k][0], sizes[k][1], &w->scenes[k]);
        if (sizes[k][0] * sizes[k][1] > most) most = sizes[k][0] * sizes[k][1];
    }
    first.radius = second.radius = radius;
    w->settings[0] = first;
    w->settings[1] = second;
    w->ao = malloc(sizeof(float) * most);
    w->reference = malloc(sizeof(float) * most);
}

static void worker_free(worker *w) {
    for (int k = 0; k < SIZES_PER_THREAD; ++k) scene_buffers_free(&w->scenes[k]);
    free(w->ao);
    free(w->reference);
}

int main(void) {
    vkdev dev;
    open_device(&dev);
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, 2);
    pthread_mutex_t queue_lock = PTHREAD_MUTEX_INITIALIZER;

    /* Different sizes, estimators and settings per thread, changed halfway. */
    static const uint32_t sizes_a[SIZES_PER_THREAD][2] = {{96, 64}, {128, 72}, {80, 80}};
    static const uint32_t sizes_b[SIZES_PER_THREAD][2] = {{128, 128}, {240, 180}, {200, 104}};
    worker workers[2];
    worker_init(
        &workers[0], "A", sizes_a,
        (cacao_settings){.quality = CACAO_QUALITY_HIGHEST, .precision = CACAO_PRECISION_FP16},
        (cacao_settings){
            .quality = CACAO_QUALITY_MEDIUM, .downsample = true, .blur_pass_count = 3, .generate_normals = true},
        &start);
    worker_init(&workers[1], "B", sizes_b,
                (cacao_settings){.estimator = CACAO_ESTIMATOR_GTAO, .quality = CACAO_QUALITY_HIGH},
                (cacao_settings){.estimator = CACAO_ESTIMATOR_BITMASK,
                                 .quality = CACAO_QUALITY_MEDIUM,
                                 .generate_normals = true,
                                 .blur_pass_count = CACAO_BLUR_NONE},
                &start);
    for (int t = 0; t < 2; ++t) CHECK(reference_frame(&dev, &workers[t]));

    pthread_t threads[2];
    bool started[2] = {false, false};
    for (int t = 0; t < 2; ++t) {
        char err[512];
        if (!vkdev_lane_create(&dev, &queue_lock, &workers[t].lane, err, sizeof err)) {
            fprintf(stderr, "thread %s: %s\n", workers[t].name, err);
            return 1;
        }
    }
    for (int t = 0; t < 2; ++t) started[t] = pthread_create(&threads[t], NULL, run_worker, &workers[t]) == 0;
    CHECK(started[0] && started[1]);
    if (!started[0] || !started[1]) return test_report("test_two_threads"); /* the barrier would wait forever */
    for (int t = 0; t < 2; ++t) pthread_join(threads[t], NULL);

    for (int t = 0; t < 2; ++t) {
        worker *w = &workers[t];
        if (w->error[0]) {
            fprintf(stderr, "thread %s: %s\n", w->name, w->error);
            ++test_failures;
        }
        CHECK(w->frames == FRAMES_PER_THREAD);
        const scene_buffers *last = frame_scene(w, FRAMES_PER_THREAD - 1);
        if (memcmp(w->ao, w->reference, sizeof(float) * last->width * last->height) != 0) {
            fprintf(stderr, "thread %s: its last frame (%ux%u) differs from the single-threaded one\n", w->name,
                    last->width, last->height);
            ++test_failures;
        }
        vkdev_destroy(&w->lane);
    }
    const double overlap_s = fmin(workers[0].end_s, workers[1].end_s) - fmax(workers[0].begin_s, workers[1].begin_s);
    for (int t = 0; t < 2; ++t)
        printf("thread %s: %u frames, %u resizes in %.2f s\n", workers[t].name, workers[t].frames, workers[t].resizes,
               workers[t].end_s - workers[t].begin_s);
    printf("the threads ran side by side for %.2f s\n", overlap_s > 0 ? overlap_s : 0.0);
    CHECK(overlap_s > 0);
    vkdev_destroy(&dev);
    CHECK(dev.validation_messages == 0);
    printf("validation messages: %u\n", dev.validation_messages);
    for (int t = 0; t < 2; ++t) worker_free(&workers[t]);
    pthread_barrier_destroy(&start);
    pthread_mutex_destroy(&queue_lock);
    return test_report("test_two_threads");
}
