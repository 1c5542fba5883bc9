/* plan.c - the pass plan: which permutations a frame dispatches, with what sizes, reading and
 * writing which resources, and where barriers go (spec: README "Pass graph"). Pure: no Vulkan
 * calls. The runtime records it, allocates from it and creates pipelines from it; the tools print
 * it. */
#include <string.h>

#include "internal.h"

static const char *const resource_names[CACAO_RES_COUNT] = {
    "depth_input", "normals_input", "output",    "constants",  "load_counter",   "depths",
    "normals",     "ssao_ping",     "ssao_pong", "importance", "importance_pong", "view_depth",
    "view_normals", "ao_raw",       "ao_pong",
};

const char *cacao_resource_name(cacao_resource resource) {
    return (unsigned)resource < CACAO_RES_COUNT ? resource_names[resource] : "unknown";
}

static uint32_t div_up(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

_Static_assert(CACAO_DEPTH_MIP_COUNT == 4 && CACAO_DEPTH_MIP_LEVELS(8) == 4 && CACAO_DEPTH_MIP_LEVELS(7) == 3,
               "CACAO_DEPTH_MIP_LEVELS is written for a chain of 4 levels");

cacao_key cacaoi_plan_step_key(const cacao_plan_step *step) {
    return (cacao_key){step->key[0], step->key[1], step->key[2], step->key[3], step->key[4]};
}

/* Builder state: accesses since the last barrier, to place barriers where hazards are. */
typedef struct plan_builder {
    cacao_plan *plan;
    uint32_t read_since_barrier, written_since_barrier;
} plan_builder;

static cacao_plan_step *add_step(plan_builder *b, const cacao_key *key, uint32_t gx, uint32_t gy, uint32_t gz) {
    cacao_plan_step *s = &b->plan->steps[b->plan->step_count++];
    memset(s, 0, sizeof *s);
    cacaoi_key_name(key, s->key_name, sizeof s->key_name);
    s->key[0] = key->pass;
    s->key[1] = key->variant;
    s->key[2] = key->downsampled;
    s->key[3] = key->blur_passes;
    s->key[4] = key->fp16;
    s->dispatch[0] = gx;
    s->dispatch[1] = gy;
    s->dispatch[2] = gz;
    s->bindings[s->binding_count++] = (cacao_plan_binding){CACAO_BINDING_CONSTANTS, CACAO_RES_CONSTANTS, 0, 0};
    return s;
}

static void bind(cacao_plan_step *s, unsigned binding, cacao_resource res, unsigned mip, bool write) {
    s->bindings[s->binding_count++] = (cacao_plan_binding){(uint8_t)binding, (uint8_t)res, (uint8_t)mip, write};
}

/* Decides whether the step needs a barrier before it (read-after-write, write-after-read or
 * write-after-write on any intermediate since the last barrier), then records its accesses. */
static void finish_step(plan_builder *b, cacao_plan_step *s) {
    uint32_t reads = 0, writes = 0;
    for (uint32_t i = 0; i < s->binding_count; ++i) {
        uint32_t bit = 1u << s->bindings[i].resource;
        if (s->bindings[i].write)
            writes |= bit;
        else
            reads |= bit;
    }
    uint32_t hazards =
        (reads & b->written_since_barrier) | (writes & (b->read_since_barrier | b->written_since_barrier));
    hazards &= ~(1u << CACAO_RES_CONSTANTS);
    if (hazards) {
        s->barrier_before = true;
        s->barrier_resources = hazards;
        b->read_since_barrier = b->written_since_barrier = 0;
    }
    b->read_since_barrier |= reads;
    b->written_since_barrier |= writes;
}

/* One row per intermediate image: its format, the format's name and bytes per texel. */
#define INTERMEDIATE(res, fmt, bytes) [res] = {VK_FORMAT_##fmt, #fmt, bytes}
static const struct {
    VkFormat format;
    const char *format_name;
    uint32_t texel_bytes;
} intermediates[CACAO_RES_COUNT] = {
    INTERMEDIATE(CACAO_RES_DEPTHS, R16_SFLOAT, 2),    INTERMEDIATE(CACAO_RES_NORMALS, R8G8B8A8_SNORM, 4),
    INTERMEDIATE(CACAO_RES_SSAO_PING, R8G8_UNORM, 2), INTERMEDIATE(CACAO_RES_SSAO_PONG, R8G8_UNORM, 2),
    INTERMEDIATE(CACAO_RES_IMPORTANCE, R8_UNORM, 1),  INTERMEDIATE(CACAO_RES_IMPORTANCE_PONG, R8_UNORM, 1),
    INTERMEDIATE(CACAO_RES_VIEW_DEPTH, R32_SFLOAT, 4),  INTERMEDIATE(CACAO_RES_VIEW_NORMALS, R8G8B8A8_SNORM, 4),
    INTERMEDIATE(CACAO_RES_AO_RAW, R16_SFLOAT, 2),    INTERMEDIATE(CACAO_RES_AO_PONG, R16_SFLOAT, 2),
};
#undef INTERMEDIATE

static void add_image(cacao_plan *p, cacao_resource res, uint32_t w, uint32_t h, uint32_t layers, uint32_t mips) {
    const VkFormat format = intermediates[res].format;
    const uint32_t texel_bytes = intermediates[res].texel_bytes;
    uint64_t bytes = 0;
    for (uint32_t m = 0; m < mips; ++m) {
        uint64_t mw = w >> m ? w >> m : 1, mh = h >> m ? h >> m : 1;
        bytes += mw * mh * layers * texel_bytes;
    }
    p->images[p->image_count++] = (cacao_plan_image){res, format, w, h, layers, mips, bytes};
    p->total_bytes += bytes;
}

/* The horizon-slice estimators (spec: estimators.md): prepare view z and normals at full
 * resolution, run the estimator per pixel, then the denoise passes (the last one writes the
 * output; with no denoise the estimator writes it). */
static void build_slice_plan(cacao_plan *plan, unsigned blur) {
    const cacao_settings *s = &plan->settings;
    const uint32_t w = plan->width, h = plan->height;
    plan->slice_width = w;
    plan->slice_height = h;
    plan->slice_count = 1;
    add_image(plan, CACAO_RES_VIEW_DEPTH, w, h, 1, 1);
    add_image(plan, CACAO_RES_VIEW_NORMALS, w, h, 1, 1);
    if (blur > 0) add_image(plan, CACAO_RES_AO_RAW, w, h, 1, 1);
    if (blur > 1) add_image(plan, CACAO_RES_AO_PONG, w, h, 1, 1);
    plan->total_bytes += sizeof(cacao_constants);

    plan_builder b = {plan, 0, 0};
    const uint32_t gx = div_up(w, CACAO_WG_SLICE_X), gy = div_up(h, CACAO_WG_SLICE_Y);
    cacao_key key = {CACAO_PASS_SLICE_PREPARE,
                     s->generate_normals ? CACAO_SLICE_NORMALS_DEPTH : CACAO_SLICE_NORMALS_INPUT, 0, 0, 0};
    cacao_plan_step *st = add_step(&b, &key, gx, gy, 1);
    bind(st, CACAO_BINDING_SRC_DEPTH, CACAO_RES_DEPTH_INPUT, 0, false);
    if (!s->generate_normals) bind(st, CACAO_BINDING_SRC_NORMALS, CACAO_RES_NORMALS_INPUT, 0, false);
    bind(st, CACAO_BINDING_DEPTHS_OUT0, CACAO_RES_VIEW_DEPTH, 0, true);
    bind(st, CACAO_BINDING_NORMALS_OUT, CACAO_RES_VIEW_NORMALS, 0, true);
    finish_step(&b, st);

    const bool gtao = s->estimator == CACAO_ESTIMATOR_GTAO;
    key = (cacao_key){CACAO_PASS_SLICE_MAIN,
                      (uint8_t)((gtao ? CACAO_SLICE_GTAO : CACAO_SLICE_BITMASK) + (blur == 0 ? CACAO_SLICE_GTAO_DIRECT : 0)),
                      0, 0, 0};
    st = add_step(&b, &key, gx, gy, 1);
    bind(st, CACAO_BINDING_DEPTHS_OUT0, CACAO_RES_VIEW_DEPTH, 0, false);
    bind(st, CACAO_BINDING_NORMALS_OUT, CACAO_RES_VIEW_NORMALS, 0, false);
    if (blur == 0) bind(st, CACAO_BINDING_OUTPUT, CACAO_RES_OUTPUT, 0, true);
    else bind(st, CACAO_BINDING_SSAO_OUT, CACAO_RES_AO_RAW, 0, true);
    finish_step(&b, st);

    cacao_resource ao = CACAO_RES_AO_RAW;
    for (unsigned pass = 1; pass <= blur; ++pass) {
        const bool last = pass == blur;
        key = (cacao_key){CACAO_PASS_SLICE_DENOISE, last ? CACAO_DENOISE_FINAL : CACAO_DENOISE_INTERMEDIATE, 0, 0, 0};
        st = add_step(&b, &key, gx, gy, 1);
        bind(st, CACAO_BINDING_DEPTHS_OUT1, ao, 0, false);
        bind(st, CACAO_BINDING_DEPTHS_OUT0, CACAO_RES_VIEW_DEPTH, 0, false);
        bind(st, CACAO_BINDING_NORMALS_OUT, CACAO_RES_VIEW_NORMALS, 0, false);
        const cacao_resource next = ao == CACAO_RES_AO_RAW ? CACAO_RES_AO_PONG : CACAO_RES_AO_RAW;
        if (last) bind(st, CACAO_BINDING_OUTPUT, CACAO_RES_OUTPUT, 0, true);
        else bind(st, CACAO_BINDING_SSAO_OUT, next, 0, true);
        finish_step(&b, st);
        ao = next;
    }
}

cacao_result cacao_plan_build(const cacao_settings *settings, uint32_t width, uint32_t height,
                              cacao_plan *plan, char *error, size_t error_size) {
    if (!plan) {
        cacaoi_set_error(error, error_size, "plan: NULL pointer");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    cacao_settings s;
    cacao_result r = cacao_settings_resolve(settings, &s, error, error_size);
    if (r != CACAO_SUCCESS) return r;
    if (width < 1 || height < 1 || width > CACAO_MAX_SIZE || height > CACAO_MAX_SIZE) {
        cacaoi_set_error(error, error_size, "size %ux%u: width and height must be in 1..%d", width, height,
                         CACAO_MAX_SIZE);
        return CACAO_ERROR_INVALID_SIZE;
    }
    memset(plan, 0, sizeof *plan);
    plan->settings = s;
    plan->width = width;
    plan->height = height;
    const unsigned quality = cacaoi_key_quality(s.quality);
    const bool ds = s.downsample, highest = quality == CACAO_KEY_QUALITY_HIGHEST;
    const uint8_t fp16 = s.precision == CACAO_PRECISION_FP16;
    const uint32_t sw = ds ? div_up(div_up(width, 2), 2) : div_up(width, 2);
    const uint32_t sh = ds ? div_up(div_up(height, 2), 2) : div_up(height, 2);
    const uint32_t iw = div_up(sw, 2), ih = div_up(sh, 2);
    const uint32_t slices = cacaoi_slice_count_for_quality(quality);
    const unsigned depths_variant = cacaoi_depths_variant_for_quality(quality);
    const uint32_t mips = depths_variant == CACAO_DEPTHS_MIPS ? CACAO_DEPTH_MIP_LEVELS(sw > sh ? sw : sh) : 1;
    const unsigned blur = s.blur_pass_count == CACAO_BLUR_NONE ? 0 : (unsigned)s.blur_pass_count;
    if (s.estimator != CACAO_ESTIMATOR_CACAO) {
        build_slice_plan(plan, blur);
        return CACAO_SUCCESS;
    }
    plan->slice_width = sw;
    plan->slice_height = sh;
    plan->importance_width = iw;
    plan->importance_height = ih;
    plan->slice_count = slices;
    plan->uses_load_counter = highest;

    /* Intermediates: only what the steps below touch. */
    add_image(plan, CACAO_RES_DEPTHS, sw, sh, slices, mips);
    add_image(plan, CACAO_RES_NORMALS, sw, sh, slices, 1);
    add_image(plan, CACAO_RES_SSAO_PING, sw, sh, slices, 1);
    if (blur > 0 || highest) add_image(plan, CACAO_RES_SSAO_PONG, sw, sh, slices, 1);
    if (highest) {
        add_image(plan, CACAO_RES_IMPORTANCE, iw, ih, 1, 1);
        add_image(plan, CACAO_RES_IMPORTANCE_PONG, iw, ih, 1, 1);
        plan->total_bytes += sizeof(uint32_t); /* load counter */
    }
    plan->total_bytes += sizeof(cacao_constants);

    plan_builder b = {plan, 0, 0};
    const uint32_t pgx = div_up(sw, CACAO_WG_PREPARE_X), pgy = div_up(sh, CACAO_WG_PREPARE_Y);
    cacao_key key = {CACAO_PASS_PREPARE_DEPTHS, (uint8_t)depths_variant, ds, 0, 0};
    cacao_plan_step *st = add_step(&b, &key, pgx, pgy, 1);
    bind(st, CACAO_BINDING_SRC_DEPTH, CACAO_RES_DEPTH_INPUT, 0, false);
    /* The MIPS variant writes every level's binding; a small slice's missing levels alias its last
     * level, which the shader leaves alone there (CACAO_DEPTH_MIP_LEVELS). */
    const uint32_t outputs = depths_variant == CACAO_DEPTHS_MIPS ? CACAO_DEPTH_MIP_COUNT : 1;
    for (uint32_t m = 0; m < outputs; ++m)
        bind(st, CACAO_BINDING_DEPTHS_OUT0 + m, CACAO_RES_DEPTHS, m < mips ? m : mips - 1, true);
    finish_step(&b, st);

    key = (cacao_key){CACAO_PASS_PREPARE_NORMALS, s.generate_normals ? 0 : 1, ds, 0, 0};
    st = add_step(&b, &key, pgx, pgy, 1);
    if (s.generate_normals)
        bind(st, CACAO_BINDING_SRC_DEPTH, CACAO_RES_DEPTH_INPUT, 0, false);
    else
        bind(st, CACAO_BINDING_SRC_NORMALS, CACAO_RES_NORMALS_INPUT, 0, false);
    bind(st, CACAO_BINDING_NORMALS_OUT, CACAO_RES_NORMALS, 0, true);
    finish_step(&b, st);

    const uint32_t ggx = div_up(sw, CACAO_WG_GENERATE_X), ggy = div_up(sh, CACAO_WG_GENERATE_Y);
    if (highest) {
        key = (cacao_key){CACAO_PASS_GENERATE, CACAO_GENERATE_Q3_BASE, 0, 0, 0};
        st = add_step(&b, &key, ggx, ggy, slices);
        bind(st, CACAO_BINDING_DEPTHS, CACAO_RES_DEPTHS, 0, false);
        bind(st, CACAO_BINDING_NORMALS, CACAO_RES_NORMALS, 0, false);
        bind(st, CACAO_BINDING_SSAO_OUT, CACAO_RES_SSAO_PONG, 0, true);
        finish_step(&b, st);

        const uint32_t igx = div_up(iw, CACAO_WG_IMPORTANCE_X), igy = div_up(ih, CACAO_WG_IMPORTANCE_Y);
        key = (cacao_key){CACAO_PASS_IMPORTANCE, 0, 0, 0, 0};
        st = add_step(&b, &key, igx, igy, 1);
        bind(st, CACAO_BINDING_SSAO_IN, CACAO_RES_SSAO_PONG, 0, false);
        bind(st, CACAO_BINDING_IMPORTANCE_OUT, CACAO_RES_IMPORTANCE, 0, true);
        finish_step(&b, st);

        key = (cacao_key){CACAO_PASS_IMPORTANCE_A, 0, 0, 0, 0};
        st = add_step(&b, &key, igx, igy, 1);
        bind(st, CACAO_BINDING_IMPORTANCE_IN, CACAO_RES_IMPORTANCE, 0, false);
        bind(st, CACAO_BINDING_IMPORTANCE_OUT, CACAO_RES_IMPORTANCE_PONG, 0, true);
        finish_step(&b, st);

        key = (cacao_key){CACAO_PASS_IMPORTANCE_B, 0, 0, 0, 0};
        st = add_step(&b, &key, igx, igy, 1);
        bind(st, CACAO_BINDING_IMPORTANCE_IN, CACAO_RES_IMPORTANCE_PONG, 0, false);
        bind(st, CACAO_BINDING_IMPORTANCE_OUT, CACAO_RES_IMPORTANCE, 0, true);
        bind(st, CACAO_BINDING_LOAD_COUNTER, CACAO_RES_LOAD_COUNTER, 0, true);
        finish_step(&b, st);
    }

    key = (cacao_key){CACAO_PASS_GENERATE, (uint8_t)cacaoi_generate_variant_for_quality(quality), 0, 0, 0};
    st = add_step(&b, &key, ggx, ggy, slices);
    bind(st, CACAO_BINDING_DEPTHS, CACAO_RES_DEPTHS, 0, false);
    bind(st, CACAO_BINDING_NORMALS, CACAO_RES_NORMALS, 0, false);
    if (highest) {
        bind(st, CACAO_BINDING_IMPORTANCE_IN, CACAO_RES_IMPORTANCE, 0, false);
        bind(st, CACAO_BINDING_LOAD_COUNTER, CACAO_RES_LOAD_COUNTER, 0, false);
        bind(st, CACAO_BINDING_SSAO_BASE, CACAO_RES_SSAO_PONG, 0, false);
    }
    bind(st, CACAO_BINDING_SSAO_OUT, CACAO_RES_SSAO_PING, 0, true);
    finish_step(&b, st);

    cacao_resource ao = CACAO_RES_SSAO_PING;
    if (blur > 0) {
        key = (cacao_key){CACAO_PASS_BLUR, 0, 0, (uint8_t)blur, fp16};
        st = add_step(&b, &key, div_up(sw, CACAO_BLUR_OUT_X(blur)), div_up(sh, CACAO_BLUR_OUT_Y(blur)), slices);
        bind(st, CACAO_BINDING_SSAO_IN, CACAO_RES_SSAO_PING, 0, false);
        bind(st, CACAO_BINDING_SSAO_OUT, CACAO_RES_SSAO_PONG, 0, true);
        finish_step(&b, st);
        ao = CACAO_RES_SSAO_PONG;
    }

    const uint8_t out_variant = (uint8_t)cacaoi_output_variant_for_quality(quality, ds);
    if (ds) {
        key = (cacao_key){CACAO_PASS_UPSAMPLE, out_variant, 0, 0, fp16};
        st = add_step(&b, &key, div_up(width, 2 * CACAO_UPSAMPLE_SPAN_X), div_up(height, 2 * CACAO_UPSAMPLE_SPAN_Y), 1);
        bind(st, CACAO_BINDING_SSAO_IN, ao, 0, false);
        bind(st, CACAO_BINDING_DEPTHS, CACAO_RES_DEPTHS, 0, false);
        bind(st, CACAO_BINDING_SRC_DEPTH, CACAO_RES_DEPTH_INPUT, 0, false);
    } else {
        key = (cacao_key){CACAO_PASS_APPLY, out_variant, 0, 0, fp16};
        st = add_step(&b, &key, div_up(width, CACAO_WG_APPLY_X), div_up(height, CACAO_WG_APPLY_Y), 1);
        bind(st, CACAO_BINDING_SSAO_IN, ao, 0, false);
    }
    bind(st, CACAO_BINDING_OUTPUT, CACAO_RES_OUTPUT, 0, true);
    finish_step(&b, st);
    return CACAO_SUCCESS;
}

void cacao_plan_print(const cacao_plan *p, FILE *out) {
    const int blur = p->settings.blur_pass_count == CACAO_BLUR_NONE ? 0 : p->settings.blur_pass_count;
    static const char *const estimator_names[] = {"default", "cacao", "gtao", "bitmask"};
    fprintf(out, "plan: %ux%u, estimator %s, quality %s, %s, blur %d, %s, normals %s\n", p->width, p->height,
            estimator_names[p->settings.estimator], cacaoi_quality_names[cacaoi_key_quality(p->settings.quality)],
            p->settings.downsample ? "downsampled" : "native", blur,
            p->settings.precision == CACAO_PRECISION_FP16 ? "fp16" : "fp32",
            p->settings.generate_normals ? "from depth" : "from input");
    if (p->settings.estimator != CACAO_ESTIMATOR_CACAO) {
        fprintf(out, "horizon slices: %d x %d steps per side = %d depth reads per pixel, %s visibility\n",
                p->settings.horizon_slices, p->settings.horizon_steps,
                2 * p->settings.horizon_slices * p->settings.horizon_steps,
                p->settings.visibility == CACAO_VISIBILITY_BINARY ? "binary" : "falloff");
    } else {
        fprintf(out, "slices: %u of %ux%u", p->slice_count, p->slice_width, p->slice_height);
        if (p->uses_load_counter) fprintf(out, "; importance map %ux%u", p->importance_width, p->importance_height);
        fprintf(out, "\n");
    }
    for (uint32_t i = 0; i < p->step_count; ++i) {
        const cacao_plan_step *s = &p->steps[i];
        if (s->barrier_before) {
            fprintf(out, "  barrier (compute -> compute) for");
            for (unsigned r = 0; r < CACAO_RES_COUNT; ++r)
                if (s->barrier_resources & (1u << r)) fprintf(out, " %s", resource_names[r]);
            fprintf(out, "\n");
        }
        fprintf(out, "  %2u %-34s dispatch %4u x %4u x %u  reads", i, s->key_name, s->dispatch[0], s->dispatch[1],
                s->dispatch[2]);
        for (uint32_t j = 0; j < s->binding_count; ++j)
            if (!s->bindings[j].write && s->bindings[j].resource != CACAO_RES_CONSTANTS)
                fprintf(out, " %s", resource_names[s->bindings[j].resource]);
        fprintf(out, "  writes");
        for (uint32_t j = 0; j < s->binding_count; ++j)
            if (s->bindings[j].write) {
                if (s->bindings[j].resource == CACAO_RES_DEPTHS)
                    fprintf(out, " depths[mip %u]", s->bindings[j].mip);
                else
                    fprintf(out, " %s", resource_names[s->bindings[j].resource]);
            }
        fprintf(out, "\n");
    }
    fprintf(out, "intermediates:\n");
    for (uint32_t i = 0; i < p->image_count; ++i) {
        const cacao_plan_image *im = &p->images[i];
        fprintf(out, "  %-16s %4ux%-4u x%u layers, %u mips, %-14s %llu bytes\n", resource_names[im->resource],
                im->width, im->height, im->layers, im->mips, intermediates[im->resource].format_name,
                (unsigned long long)im->bytes);
    }
    fprintf(out, "total intermediate memory: %llu bytes\n", (unsigned long long)p->total_bytes);
}
