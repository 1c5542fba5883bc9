/* plan.c - the pass plan: which permutations a frame dispatches, with what sizes, reading and
 * writing which resources, and where barriers go (spec: README "Pass graph"). Pure: no Vulkan
 * calls. The runtime records it, allocates from it and creates pipelines from it; the tools print
 * it. */
#include <stdio.h>
#include <string.h>

#include "cacao_passes.h"
#include "internal.h"

const char *cacao_resource_name(cacao_resource resource) {
    return (unsigned)resource < CACAO_RES_COUNT ? cacaoi_resources[resource].name : "unknown";
}

static uint32_t div_up(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

_Static_assert(CACAO_TILE_COMMAND(CACAO_LIST_COUNT) + 3 <= CACAO_TILE_COUNT_ACTIVE &&
                   CACAO_TILE_LIST_ENTRIES(CACAO_LIST_COUNT) < CACAO_TILE_COUNT_NEEDED &&
                   CACAO_TILE_COUNT_BLUR_NEEDED < CACAO_TILE_HEADER,
               "the tile header holds the lists' commands, the class counts and the entry counts");
_Static_assert(CACAO_TILE_COUNTS_BYTES == CACAO_TILE_HEADER * sizeof(uint32_t), "the tile counts are the header");
_Static_assert(CACAO_DEPTH_MIP_COUNT == 4 && CACAO_DEPTH_MIP_LEVELS(8) == 4 && CACAO_DEPTH_MIP_LEVELS(7) == 3,
               "CACAO_DEPTH_MIP_LEVELS is written for a chain of 4 levels");

/* Builder state: accesses since the last barrier, to place barriers where hazards are. */
typedef struct plan_builder {
    cacao_plan *plan;
    uint32_t read_since_barrier, written_since_barrier;
} plan_builder;

/* Decides whether the step needs a barrier before it (read-after-write, write-after-read or
 * write-after-write on any intermediate since the last barrier), then records its accesses. */
static void finish_step(plan_builder *b, cacao_plan_step *s) {
    uint32_t reads = s->gate ? 1u << CACAO_RES_TILES : 0u; /* a gated step's command is in the tile buffer */
    uint32_t writes = 0;
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

cacao_key_config cacaoi_key_config_of(const cacao_settings *s) {
    return (cacao_key_config){
        .quality = cacaoi_key_quality(s->quality),
        .downsampled = s->downsample,
        .fp16 = s->precision == CACAO_PRECISION_FP16,
        .normals_from_input = !s->generate_normals,
        .blur_passes = s->blur_pass_count == CACAO_BLUR_NONE ? 0 : (unsigned)s->blur_pass_count,
        .estimator = (unsigned)s->estimator - 1u,
        .gpu_forms = s->shader_forms == CACAO_SHADER_FORMS_GPU,
        .reuse = s->reuse_unchanged, /* CACAO only (cacao_settings_resolve) */
        .temporal = s->temporal_frames != 0, /* GTAO/BITMASK only, without reuse (cacao_settings_resolve) */
    };
}

/* The dispatch grid of a step (the pass row's grid rule). */
static void dispatch_size(const cacao_plan *p, const cacao_key *key, uint32_t out[3]) {
    const cacaoi_pass_row *row = &cacaoi_passes[key->pass];
    const uint32_t quad = row->quad[key->variant] ? row->quad[key->variant] : 1u; /* texels per invocation, x and y */
    const uint32_t wx = quad * row->workgroup[0], wy = quad * row->workgroup[1];
    out[2] = 1;
    const uint8_t grid = row->grids[key->variant] != CACAOI_GRID_ROW ? row->grids[key->variant] : row->grid;
    switch (grid) {
    case CACAOI_GRID_SLICE_LAYERS:
    case CACAOI_GRID_SLICE_CLASSIFY:
    case CACAOI_GRID_SLICE:
        out[0] = div_up(p->slice_width, wx);
        out[1] = div_up(p->slice_height, wy);
        if (grid == CACAOI_GRID_SLICE_LAYERS) out[2] = p->slice_count;
        if (grid == CACAOI_GRID_SLICE_CLASSIFY && key->downsampled) out[2] = 2; /* z 0: the classification's groups */
        return;
    case CACAOI_GRID_IMPORTANCE:
        out[0] = div_up(p->importance_width, wx);
        out[1] = div_up(p->importance_height, wy);
        return;
    case CACAOI_GRID_BLUR: {
        uint32_t blur_out[2];
        cacaoi_blur_out(key->pass, key->blur_passes, blur_out);
        out[0] = div_up(p->slice_width, blur_out[0]);
        out[1] = div_up(p->slice_height, blur_out[1]);
        out[2] = p->slice_count;
        return;
    }
    case CACAOI_GRID_UPSAMPLE:
        out[0] = div_up(p->width, 2 * CACAO_UPSAMPLE_SPAN_X);
        out[1] = div_up(p->height, 2 * CACAO_UPSAMPLE_SPAN_Y);
        return;
    case CACAOI_GRID_COMPACT:
        out[0] = div_up(p->tiles_x * p->tiles_y + p->blur_groups_x * p->blur_groups_y, wx);
        out[1] = 1;
        return;
    case CACAOI_GRID_TILES:
        out[0] = div_up(p->tiles_x, wx);
        out[1] = div_up(p->tiles_y, wy);
        return;
    case CACAOI_GRID_TILE_ROWS:
        out[0] = div_up(p->tiles_y, wx * wy);
        out[1] = 1;
        return;
    case CACAOI_GRID_HALF:
        out[0] = div_up(div_up(p->width, 2), wx);
        out[1] = div_up(div_up(p->height, 2), wy);
        return;

    default: /* CACAOI_GRID_OUTPUT */
        out[0] = div_up(p->width, wx);
        out[1] = div_up(p->height, wy);
        return;
    }
}

/* An intermediate sized by its row's rule. With more than one mip level bound (the depths at
 * HIGH+), the levels of the chain the slice has (CACAO_DEPTH_MIP_LEVELS): in one atlas image, level
 * 0 with levels 1.. stacked to its right (cacao_shared.h), or with `chain` (the GPU forms, whose
 * passes bind the levels' own slots) as the image's mip levels. */
static void add_image(cacao_plan *p, cacao_resource res, uint32_t levels_bound, bool chain) {
    const cacaoi_resource_row *row = &cacaoi_resources[res];
    uint32_t w = p->width, h = p->height, layers = 1;
    if (row->size == CACAOI_SIZE_SLICE) w = p->slice_width, h = p->slice_height;
    if (row->size == CACAOI_SIZE_IMPORTANCE) w = p->importance_width, h = p->importance_height;
    if (row->size == CACAOI_SIZE_HALF) w = div_up(p->width, 2), h = div_up(p->height, 2);
    if (row->size == CACAOI_SIZE_HALF_X3) w = 3 * div_up(p->width, 2), h = div_up(p->height, 2);
    if (row->layered) layers = p->slice_count;
    const uint32_t levels = CACAO_DEPTH_MIP_LEVELS(w > h ? w : h);
    const uint32_t mips = levels_bound < levels ? levels_bound : levels;
    uint64_t texels = (uint64_t)w * h;
    if (mips > 1 && chain) {
        for (uint32_t l = 1; l < mips; ++l)
            texels += (uint64_t)CACAO_DEPTH_LEVEL_EXTENT(w, l) * CACAO_DEPTH_LEVEL_EXTENT(h, l);
    } else if (mips > 1) {
        const uint32_t chain_h = CACAO_DEPTH_ATLAS_Y(h, mips);
        w += CACAO_DEPTH_LEVEL_EXTENT(w, 1);
        h = h > chain_h ? h : chain_h;
        texels = (uint64_t)w * h;
    }
    const uint64_t bytes = texels * layers * row->texel_bytes;
    p->images[p->image_count++] =
        (cacao_plan_image){res, row->format, w, h, layers, mips, bytes, mips > 1 && chain ? mips : 1};
    p->total_bytes += bytes;
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
    const cacao_key_config config = cacaoi_key_config_of(&s);
    if (s.estimator != CACAO_ESTIMATOR_CACAO) { /* one full-resolution "slice" */
        plan->slice_width = width;
        plan->slice_height = height;
        plan->slice_count = 1;
    } else {
        plan->slice_width = s.downsample ? div_up(div_up(width, 2), 2) : div_up(width, 2);
        plan->slice_height = s.downsample ? div_up(div_up(height, 2), 2) : div_up(height, 2);
        plan->importance_width = div_up(plan->slice_width, 2);
        plan->importance_height = div_up(plan->slice_height, 2);
        plan->slice_count = cacaoi_qualities[config.quality].slice_count;
    }

    cacaoi_step steps[CACAOI_SEQUENCE_MAX];
    const size_t count = cacaoi_sequence(&config, steps);
    { /* tile grids (docs/tiles.md); a horizon estimator's slice is the image, its denoise groups the tiles */
        const unsigned blur = config.blur_passes;
        plan->uses_tiles = true;
        plan->tiles_x = div_up(plan->slice_width, CACAO_TILE);
        plan->tiles_y = div_up(plan->slice_height, CACAO_TILE);
        if (blur > 0 && s.estimator == CACAO_ESTIMATOR_CACAO) {
            uint32_t blur_out[2];
            cacaoi_blur_out(cacaoi_form_pass(CACAO_PASS_BLUR, config.gpu_forms), blur, blur_out);
            plan->blur_groups_x = div_up(plan->slice_width, blur_out[0]);
            plan->blur_groups_y = div_up(plan->slice_height, blur_out[1]);
        }
        const uint64_t tiles = (uint64_t)plan->tiles_x * plan->tiles_y;
        const uint64_t groups = (uint64_t)plan->blur_groups_x * plan->blur_groups_y;
        plan->tile_buffer_bytes = sizeof(uint32_t) * CACAO_TILE_BUFFER_UINTS(tiles, groups);
    }
    cacaoi_pass_binding bindings[CACAOI_SEQUENCE_MAX][CACAO_PLAN_MAX_BINDINGS];
    size_t binding_count[CACAOI_SEQUENCE_MAX];
    uint32_t mips[CACAO_RES_COUNT] = {0}; /* levels bound per resource, 0 = untouched */
    bool chain[CACAO_RES_COUNT] = {false}; /* its levels bound through their own slots: a mip chain */
    for (size_t i = 0; i < count; ++i) {
        binding_count[i] = cacaoi_step_bindings(&steps[i], bindings[i]);
        if (binding_count[i] > CACAO_PLAN_MAX_BINDINGS) { /* a wrong pass table, not a user error */
            cacaoi_set_error(error, error_size, "internal: pass %s binds %zu slots, more than CACAO_PLAN_MAX_BINDINGS %d",
                             cacaoi_pass_name(steps[i].key.pass), binding_count[i], CACAO_PLAN_MAX_BINDINGS);
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        for (size_t j = 0; j < binding_count[i]; ++j) {
            const cacaoi_pass_binding *b = &bindings[i][j];
            const uint32_t levels = b->levels > 1 ? b->levels : 1;
            if (mips[b->resource] < levels) mips[b->resource] = levels;
            if (cacaoi_depth_mip_slot_level(b->slot)) chain[b->resource] = true;
        }
    }

    /* Intermediates and buffers: only those the steps touch, in resource order. */
    for (unsigned res = 0; res < CACAO_RES_COUNT; ++res) {
        const uint8_t size = cacaoi_resources[res].size;
        if (!mips[res] || size == CACAOI_SIZE_CALLER) continue;
        if (size == CACAOI_SIZE_BUFFER || size == CACAOI_SIZE_TILES) {
            if (plan->buffer_count == CACAO_PLAN_MAX_BUFFERS) { /* a wrong resource table, not a user error */
                cacaoi_set_error(error, error_size, "internal: more buffers than CACAO_PLAN_MAX_BUFFERS %d",
                                 CACAO_PLAN_MAX_BUFFERS);
                return CACAO_ERROR_INVALID_ARGUMENT;
            }
            const uint64_t bytes = size == CACAOI_SIZE_TILES ? plan->tile_buffer_bytes : cacaoi_resources[res].buffer_bytes;
            plan->buffers[plan->buffer_count++] = (cacao_plan_buffer){res, bytes};
            plan->total_bytes += bytes;
        } else {
            add_image(plan, res, mips[res], chain[res]);
        }
    }
    plan->uses_load_counter = mips[CACAO_RES_LOAD_COUNTER] != 0;

    plan_builder b = {plan, 0, 0};
    unsigned gates = 0;
    bool quiet = false;
    for (size_t i = 0; i < count; ++i) {
        cacao_plan_step *st = &plan->steps[plan->step_count++];
        const cacao_key *key = &steps[i].key;
        cacaoi_key_name(key, st->key_name, sizeof st->key_name);
        st->key[0] = key->pass;
        st->key[1] = key->variant;
        st->key[2] = key->downsampled;
        st->key[3] = key->blur_passes;
        st->key[4] = key->fp16;
        st->clear = cacaoi_fill_is_clear(key->pass, key->variant);
        if (!st->clear) {
            dispatch_size(plan, key, st->dispatch);
            st->list = cacaoi_passes[key->pass].lists[key->variant];
            /* reuse: every direct step after the reuse passes runs from a gate command (the
             * frame with nothing changed zeroes it); gates are numbered in step order, so
             * apply's, the last step's, is the last */
            if (config.reuse && !st->list && key->pass != CACAO_PASS_REUSE) st->gate = (uint8_t)++gates;
            /* a plan that can find its frame quiet: every direct step after classify.quiet, closed
             * until it opens them (docs/tiles.md "A quiet frame") */
            if (quiet && !st->list) st->gate = (uint8_t)++gates;
            if (key->pass == CACAO_PASS_CLASSIFY && key->variant == CACAO_CLASSIFY_QUIET) quiet = true;
        }
        for (size_t j = 0; j < binding_count[i]; ++j) {
            const cacaoi_pass_binding *b = &bindings[i][j];
            if (st->clear && !b->write) continue; /* a clear only writes its images */
            st->bindings[st->binding_count++] = (cacao_plan_binding){b->slot, b->resource, b->write};
        }
        if (st->clear && st->binding_count) /* named by what it clears: "clear.ssao_ping" */
            snprintf(st->key_name, sizeof st->key_name, "clear.%s", cacaoi_resources[st->bindings[0].resource].name);
        finish_step(&b, st);
    }
    return CACAO_SUCCESS;
}

/* The resources a step reads (or writes), each once (a pass can bind one through two slots). */
static void print_resources(FILE *out, const cacao_plan_step *s, bool write) {
    uint32_t printed = 1u << CACAO_RES_CONSTANTS;
    for (uint32_t j = 0; j < s->binding_count; ++j) {
        const uint32_t bit = 1u << s->bindings[j].resource;
        if (s->bindings[j].write != write || (printed & bit)) continue;
        printed |= bit;
        fprintf(out, " %s", cacaoi_resources[s->bindings[j].resource].name);
    }
}

void cacao_plan_print(const cacao_plan *p, FILE *out) {
    const int blur = p->settings.blur_pass_count == CACAO_BLUR_NONE ? 0 : p->settings.blur_pass_count;
    fprintf(out, "plan: %ux%u, estimator %s, quality %s, %s, blur %d, %s, normals %s\n", p->width, p->height,
            cacao_estimator_name(p->settings.estimator), cacao_quality_name(p->settings.quality),
            p->settings.downsample ? "downsampled" : "native", blur, cacao_precision_name(p->settings.precision),
            p->settings.generate_normals ? "from depth" : "from input");
    if (p->settings.estimator != CACAO_ESTIMATOR_CACAO) {
        fprintf(out, "horizon slices: %d x %d steps per side = %d depth reads per pixel, %s visibility\n",
                p->settings.horizon_slices, p->settings.horizon_steps,
                2 * p->settings.horizon_slices * p->settings.horizon_steps,
                cacao_visibility_name(p->settings.visibility));
    } else {
        fprintf(out, "slices: %u of %ux%u", p->slice_count, p->slice_width, p->slice_height);
        if (p->uses_load_counter) fprintf(out, "; importance map %ux%u", p->importance_width, p->importance_height);
        fprintf(out, "\ntiles: %ux%u of %dx%d slice texels (tile buffer %llu bytes)\n", p->tiles_x, p->tiles_y,
                CACAO_TILE, CACAO_TILE, (unsigned long long)p->tile_buffer_bytes);
    }
    uint32_t cleared = 0; /* resources a clear wrote last */
    for (uint32_t i = 0; i < p->step_count; ++i) {
        const cacao_plan_step *s = &p->steps[i];
        const uint32_t cleared_before = cleared;
        for (uint32_t j = 0; j < s->binding_count; ++j)
            if (s->bindings[j].write) cleared = s->clear ? cleared | (1u << s->bindings[j].resource)
                                                         : cleared & ~(1u << s->bindings[j].resource);
        if (s->barrier_before) {
            const bool after_clear = (s->barrier_resources & cleared_before) != 0,
                       after_compute = (s->barrier_resources & ~cleared_before) != 0;
            fprintf(out, "  barrier (%s -> %s) for",
                    after_clear ? (after_compute ? "compute, transfer" : "transfer") : "compute",
                    s->clear ? "transfer" : "compute");
            for (unsigned r = 0; r < CACAO_RES_COUNT; ++r)
                if (s->barrier_resources & (1u << r)) fprintf(out, " %s", cacaoi_resources[r].name);
            fprintf(out, "\n");
        }
        static const char *const list_names[] = {"",
                                                 "needed tiles",
                                                 "unneeded tiles",
                                                 "view z tiles (horizon estimators), or output groups at needed tiles",
                                                 "blur groups at needed tiles",
                                                 "blocks of 2x2 tiles with an active tile",
                                                 "tiles within two of an active tile"};
        _Static_assert(sizeof list_names / sizeof list_names[0] == CACAO_LIST_COUNT + 1, "a name per list");
        if (s->clear) {
            fprintf(out, "  %2u %-34s clear (no dispatch)            writes", i, s->key_name);
            print_resources(out, s, true);
            fprintf(out, "\n");
            continue;
        }
        fprintf(out, "  %2u %-34s dispatch %4u x %4u x %u%s%s  reads", i, s->key_name, s->dispatch[0], s->dispatch[1],
                s->dispatch[2], s->list ? " at most, indirect over " : "", list_names[s->list]);
        print_resources(out, s, false);
        fprintf(out, "  writes");
        print_resources(out, s, true);
        fprintf(out, "\n");
    }
    fprintf(out, "intermediates:\n");
    for (uint32_t i = 0; i < p->image_count; ++i) {
        const cacao_plan_image *im = &p->images[i];
        fprintf(out, "  %-16s %4ux%-4u x%u layers, %u mips%s, %-14s %llu bytes\n", cacaoi_resources[im->resource].name,
                im->width, im->height, im->layers, im->mips,
                im->image_levels > 1 ? " (mip chain)" : im->mips > 1 ? " (atlas)" : "",
                cacaoi_resources[im->resource].format_name, (unsigned long long)im->bytes);
    }
    fprintf(out, "total intermediate memory: %llu bytes\n", (unsigned long long)p->total_bytes);
}
