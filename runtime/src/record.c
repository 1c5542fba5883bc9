/* record.c - cacao_record: walks the plan, recording barriers, pushed descriptors and dispatches
 * into the caller's command buffer. No submission, no waiting, no allocation. */
#include <string.h>

#include "vulkan_internal.h"

static bool format_in(VkFormat f, const VkFormat *list, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (list[i] == f) return true;
    return false;
}

static const VkFormat depth_formats[] = {
    VK_FORMAT_D32_SFLOAT,         VK_FORMAT_D16_UNORM,  VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D24_UNORM_S8_UINT,
    VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT,
};
static const VkFormat normal_formats[] = {CACAO_NORMALS_FORMATS};
static const VkFormat output_formats[] = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R8_UNORM,
                                          VK_FORMAT_R16_UNORM};
static const VkImageLayout read_layouts[] = {
    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
    VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL};

static bool layout_readable(VkImageLayout layout) {
    for (size_t i = 0; i < sizeof read_layouts / sizeof read_layouts[0]; ++i)
        if (read_layouts[i] == layout) return true;
    return false;
}

static VkImageAspectFlags aspect_of(VkFormat f) {
    switch (f) {
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32: return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default: return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

static cacao_result check_image(cacao_context *ctx, const cacao_image *im, const char *field, const VkFormat *formats,
                                size_t format_count, bool read) {
    if (!im->image || !im->view)
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "inputs.%s: image and view are required", field);
    if (!format_in(im->format, formats, format_count))
        return cacaoi_fail(ctx, CACAO_ERROR_UNSUPPORTED_FORMAT, "inputs.%s.format %d is not supported", field,
                          (int)im->format);
    if (read && !layout_readable(im->layout))
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT,
                          "inputs.%s.layout %d is not a shader-readable layout", field, (int)im->layout);
    if (!read && (im->layout == VK_IMAGE_LAYOUT_UNDEFINED || im->layout == VK_IMAGE_LAYOUT_PREINITIALIZED))
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "inputs.%s.layout must be a defined layout", field);
    return CACAO_SUCCESS;
}

static cacao_result check_inputs(cacao_context *ctx, const cacao_inputs *in) {
    cacao_result r = check_image(ctx, &in->depth, "depth", depth_formats,
                                 sizeof depth_formats / sizeof depth_formats[0], true);
    if (r == CACAO_SUCCESS && !ctx->plan.settings.generate_normals)
        r = check_image(ctx, &in->normals, "normals", normal_formats,
                        sizeof normal_formats / sizeof normal_formats[0], true);
    if (r == CACAO_SUCCESS)
        r = check_image(ctx, &in->output, "output", output_formats,
                        sizeof output_formats / sizeof output_formats[0], false);
    if (r == CACAO_SUCCESS && in->depth.layout == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL &&
        !ctx->separate_depth_layouts)
        r = cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT,
                       "inputs.depth.layout DEPTH_READ_ONLY_OPTIMAL needs separateDepthStencilLayouts enabled on the "
                       "device and cacao_context_desc.separate_depth_stencil_layouts_enabled; use "
                       "DEPTH_STENCIL_READ_ONLY_OPTIMAL");
    const uint64_t queries_needed = (uint64_t)in->timestamp_first_query + ctx->plan.step_count + 1;
    if (r == CACAO_SUCCESS && in->timestamp_query_pool && in->timestamp_query_count < queries_needed)
        r = cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT,
                       "inputs.timestamp_query_count %u is too small: from timestamp_first_query %u, %u timestamps "
                       "need %llu queries",
                       in->timestamp_query_count, in->timestamp_first_query, ctx->plan.step_count + 1,
                       (unsigned long long)queries_needed);
    if (r == CACAO_SUCCESS) r = cacaoi_check_projection(in, ctx->last_error, sizeof ctx->last_error);
    return r;
}

/* Image barrier on the whole first mip/layer range of an image. */
static VkImageMemoryBarrier image_barrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                                          VkImageLayout to, VkAccessFlags src, VkAccessFlags dst) {
    return (VkImageMemoryBarrier){
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = src,
        .dstAccessMask = dst,
        .oldLayout = from,
        .newLayout = to,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS},
    };
}

/* Frame start: previous frames' accesses to our intermediates end before this frame overwrites
 * them (their contents are discarded: UNDEFINED -> GENERAL, unless reuse keeps them), the caller's
 * earlier writes to its inputs become visible, and the output goes to GENERAL for storage writes. */
static void record_frame_start(cacao_context *ctx, VkCommandBuffer cmd, const cacao_inputs *in, bool keep,
                               bool keep_history) {
    VkImageMemoryBarrier barriers[CACAO_RES_COUNT + 3];
    uint32_t n = 0;
    /* `keep` (reuse: the frame may keep tiles of the previous one): contents stay, in GENERAL; so
     * do the temporal history's two images, from the second frame after a resize */
    for (uint32_t i = 0; i < ctx->plan.image_count; ++i) {
        const cacao_resource res = ctx->plan.images[i].resource;
        const bool kept = keep || (keep_history && (res == CACAO_RES_AO_HISTORY || res == CACAO_RES_AO_HISTORY_NEXT));
        barriers[n++] = image_barrier(ctx->images[res].image, VK_IMAGE_ASPECT_COLOR_BIT,
                                      kept ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
                                      VK_IMAGE_LAYOUT_GENERAL,
                                      VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                          VK_ACCESS_TRANSFER_WRITE_BIT);
    }
    barriers[n++] = image_barrier(in->depth.image, aspect_of(in->depth.format), in->depth.layout, in->depth.layout,
                                  VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    if (!ctx->plan.settings.generate_normals)
        barriers[n++] = image_barrier(in->normals.image, VK_IMAGE_ASPECT_COLOR_BIT, in->normals.layout,
                                      in->normals.layout, VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    barriers[n++] = image_barrier(in->output.image, VK_IMAGE_ASPECT_COLOR_BIT, in->output.layout,
                                  VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    /* Buffers: last frame's shader reads/writes end before this frame's transfer writes. */
    const VkMemoryBarrier memory = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                    .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                    .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT};
    ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &memory, 0, NULL,
                         n, barriers);
}

/* The plan's gate commands (cacao_plan_step.gate numbers them in step order) and their byte
 * offset in the tile buffer. */
static uint32_t gate_count(const cacao_plan *p) {
    uint32_t gates = 0;
    for (uint32_t i = 0; i < p->step_count; ++i)
        if (p->steps[i].gate > gates) gates = p->steps[i].gate;
    return gates;
}

/* The byte offset of a region of the plan's tile buffer: REGION one of cacao_shared.h's
 * CACAO_TILE_*(tiles, blur_groups) macros. */
#define TILE_REGION_OFFSET(p, REGION)                                                                  \
    (sizeof(uint32_t) * (VkDeviceSize)REGION((VkDeviceSize)(p)->tiles_x * (p)->tiles_y,                \
                                             (VkDeviceSize)(p)->blur_groups_x * (p)->blur_groups_y))

static VkDeviceSize gates_offset(const cacao_plan *p) { return TILE_REGION_OFFSET(p, CACAO_TILE_GATES); }

/* Reuse (docs/tiles.md "Reusing the previous frame"): how this frame uses the previous one, as
 * the per-frame constant reuse: 1 keep what did not change (the constants, so camera, settings
 * and size, are the last frame's, whose copies of the inputs are current, and the caller does not
 * force a full frame); 2 a full frame that refreshes the copies (the first after a resize, a
 * forced one, or the first with the same constants after a 3); 3 a full frame with other
 * constants than the last (a moving camera): the diff is not recorded and the copies go stale.
 * 0 without reuse. Also the gates a frame with nothing changed zeroes. Remembers this frame's
 * constants. */
static int reuse_frame(cacao_context *ctx, const cacao_inputs *in, cacao_constants *c) {
    const cacao_plan *p = &ctx->plan;
    if (!p->settings.reuse_unchanged) return 0;
    const bool same = ctx->reuse_primed && memcmp(&ctx->reuse_constants, c, sizeof *c) == 0;
    /* The last step writes the output. Where it is gated (apply, the upsample, the GPU forms' last
     * horizon pass), a frame with nothing changed runs it alone unless the output holds the last
     * frame's. Where it is not (the CPU forms of the horizon estimators: a pass over compact's list,
     * after clears of its inputs), such a frame could not rewrite the output: without the output
     * held, every frame is a full one, with no diff (as when the camera moves: the copies go
     * stale, and the first frame with the output held refreshes them). */
    const bool output_gated = p->step_count && p->steps[p->step_count - 1].gate;
    const bool can_keep = output_gated || in->output_holds_previous;
    const int mode = !ctx->reuse_primed || in->force_full_frame ? 2
                     : !same || !can_keep                       ? 3
                     : ctx->reuse_copies_stale                  ? 2
                                                                : 1;
    ctx->reuse_constants = *c;
    ctx->reuse_primed = true;
    ctx->reuse_copies_stale = mode == 3;
    c->reuse = mode;
    /* the last gate is apply's (or the upsample's, or the last horizon pass's): kept only where the
     * output holds the last frame's */
    c->gate_count = (int)gate_count(p) - (output_gated && !in->output_holds_previous ? 1 : 0);
    return mode;
}

static void record_constants(cacao_context *ctx, VkCommandBuffer cmd, const cacao_constants *constants) {
    const cacao_plan *p = &ctx->plan;
    ctx->vk.CmdUpdateBuffer(cmd, ctx->buffers[CACAO_RES_CONSTANTS], 0, sizeof *constants, constants);
    if (ctx->plan.uses_load_counter)
        ctx->vk.CmdFillBuffer(cmd, ctx->buffers[CACAO_RES_LOAD_COUNTER], 0, sizeof(uint32_t), 0);
    if (ctx->plan.uses_tiles) { /* empty lists; the compact pass appends (docs/tiles.md) */
        uint32_t header[CACAO_TILE_HEADER] = {0};
        /* full frames run no reach pass (and 3 no diff): every tile changed and is recomputed */
        if (constants->reuse == 3) header[CACAO_TILE_COUNT_CHANGED] = p->tiles_x * p->tiles_y;
        if (constants->reuse >= 2) header[CACAO_TILE_COUNT_RECOMPUTE] = p->tiles_x * p->tiles_y;
        for (unsigned list = 1; list <= CACAO_LIST_COUNT; ++list) { /* x: the grid's width; rows 0 */
            const uint32_t width = list == CACAO_LIST_BLUR     ? p->blur_groups_x
                                   : list == CACAO_LIST_BLOCKS ? (p->tiles_x + 1) / 2
                                                               : p->tiles_x;
            header[CACAO_TILE_COMMAND(list)] = width ? width : 1;
            header[CACAO_TILE_COMMAND(list) + 2] = 1;
        }
        /* z: the layers of the grid of the steps that dispatch over the list (their pass row's
         * grid: generate and the blur cover the layers with z, a fill group loops over them) */
        for (uint32_t i = 0; i < p->step_count; ++i)
            if (p->steps[i].list) header[CACAO_TILE_COMMAND(p->steps[i].list) + 2] = p->steps[i].dispatch[2];
        ctx->vk.CmdUpdateBuffer(cmd, ctx->buffers[CACAO_RES_TILES], 0, sizeof header, header);
        const VkDeviceSize lists =
            sizeof(uint32_t) * (VkDeviceSize)CACAO_TILE_LIST_BASE(CACAO_LIST_GENERATE, (VkDeviceSize)p->tiles_x * p->tiles_y);
        const VkDeviceSize gates = gates_offset(p);
        if (constants->reuse == 1 && p->settings.estimator != CACAO_ESTIMATOR_CACAO) {
            /* The horizon estimators reusing: the needed flags stay as the last frame left them.
             * Where nothing changed, the GPU forms' last pass (run when the output is not held)
             * reads them, and no classification runs to remake them; where anything changed, the
             * classification marks this frame's needed tiles on top, and a tile needed only by the
             * last frame's is computed as well: quiet within a tile, it computes the 1 it would
             * have stored (the equality test_tiles checks against compute_all_tiles). */
            const VkDeviceSize needed = TILE_REGION_OFFSET(p, CACAO_TILE_NEEDED),
                               reuse = TILE_REGION_OFFSET(p, CACAO_TILE_CHANGED);
            ctx->vk.CmdFillBuffer(cmd, ctx->buffers[CACAO_RES_TILES], lists, needed - lists, CACAO_TILE_NO_ENTRY);
            ctx->vk.CmdFillBuffer(cmd, ctx->buffers[CACAO_RES_TILES], reuse, gates - reuse, CACAO_TILE_NO_ENTRY);
        } else {
            ctx->vk.CmdFillBuffer(cmd, ctx->buffers[CACAO_RES_TILES], lists, gates - lists, CACAO_TILE_NO_ENTRY);
        }
        /* reuse: each gated step's full grid (the reach pass zeroes x when nothing changed). A plan
         * that can find its frame quiet: every one with x 0 and their x among the grids, which
         * classify.quiet copies in on a frame that is not quiet (docs/tiles.md "A quiet frame") */
        _Static_assert(CACAO_TILE_GATE_GRIDS(0, 0) == CACAO_TILE_GATES(0, 0) + 3 * CACAO_TILE_GATE_MAX,
                       "the grids follow the gate commands");
        uint32_t words[4 * CACAO_TILE_GATE_MAX] = {0}; /* the commands, then the grids */
        uint32_t *commands = words, *grids = words + 3 * CACAO_TILE_GATE_MAX;
        for (uint32_t i = 0; i < p->step_count; ++i) {
            const cacao_plan_step *st = &p->steps[i];
            if (!st->gate) continue;
            memcpy(&commands[3 * (st->gate - 1)], st->dispatch, sizeof st->dispatch);
            grids[st->gate - 1] = st->dispatch[0];
            if (constants->quiet_test) commands[3 * (st->gate - 1)] = 0;
        }
        /* the grids only where classify.quiet reads them: one update either way */
        const uint32_t count = gate_count(p);
        if (count)
            ctx->vk.CmdUpdateBuffer(cmd, ctx->buffers[CACAO_RES_TILES], gates,
                                    constants->quiet_test ? sizeof words : sizeof(uint32_t) * 3 * count, words);
    }
    const VkMemoryBarrier memory = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &memory, 0,
                         NULL, 0, NULL);
}

/* Descriptor content of one plan binding. */
typedef union descriptor_info {
    VkDescriptorBufferInfo buffer;
    VkDescriptorImageInfo image;
    VkBufferView texel_view;
} descriptor_info;

static void describe(const cacao_context *ctx, const cacao_inputs *in, const cacao_plan_binding *b,
                     descriptor_info *info) {
    const uint8_t size = cacaoi_resources[b->resource].size;
    if (b->binding == CACAO_BINDING_TILE_ENTRIES) { /* the tile buffer's texel view */
        info->texel_view = ctx->tile_entries_view;
        return;
    }
    if (size == CACAOI_SIZE_BUFFER || size == CACAOI_SIZE_TILES) { /* the plan's buffers */
        info->buffer = (VkDescriptorBufferInfo){ctx->buffers[b->resource], 0, VK_WHOLE_SIZE};
        return;
    }
    switch (b->resource) {
    case CACAO_RES_DEPTH_INPUT: info->image = (VkDescriptorImageInfo){0, in->depth.view, in->depth.layout}; return;
    case CACAO_RES_NORMALS_INPUT:
        info->image = (VkDescriptorImageInfo){0, in->normals.view, in->normals.layout};
        return;
    case CACAO_RES_OUTPUT: info->image = (VkDescriptorImageInfo){0, in->output.view, VK_IMAGE_LAYOUT_GENERAL}; return;
    default: {
        /* a mip chain: its sampled view holds every level, the storage slots of levels 1..3 their
         * own level (the last the chain has, for a slot past it). The temporal history's two images
         * trade roles every frame: the one written last frame is read (temporal_odd). */
        cacao_resource res = (cacao_resource)b->resource;
        if (ctx->temporal_odd && (res == CACAO_RES_AO_HISTORY || res == CACAO_RES_AO_HISTORY_NEXT))
            res = res == CACAO_RES_AO_HISTORY ? CACAO_RES_AO_HISTORY_NEXT : CACAO_RES_AO_HISTORY;
        const cacao_intermediate *im = &ctx->images[res];
        VkImageView view = im->view;
        unsigned level = cacaoi_depth_mip_slot_level(b->binding);
        while (level > 0 && !im->level_views[level]) --level;
        if (level > 0) view = im->level_views[level];
        else if (im->sampled_view && cacaoi_slots[b->binding].descriptor == CACAOI_DESCRIPTOR_SAMPLED_IMAGE)
            view = im->sampled_view;
        info->image = (VkDescriptorImageInfo){0, view, VK_IMAGE_LAYOUT_GENERAL};
        return;
    }
    }
}

/* A clear step (cacao_plan_step.clear): every image it writes, whole, to the value the passes
 * would give the tiles they skip. */
static void record_clear(cacao_context *ctx, VkCommandBuffer cmd, const cacao_plan_step *step) {
    for (uint32_t i = 0; i < step->binding_count; ++i) {
        VkClearColorValue color;
        if (!cacaoi_clear_value(step->bindings[i].resource, color.float32)) continue;
        const VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0,
                                               VK_REMAINING_ARRAY_LAYERS};
        ctx->vk.CmdClearColorImage(cmd, ctx->images[step->bindings[i].resource].image, VK_IMAGE_LAYOUT_GENERAL, &color, 1,
                                   &range);
    }
}

static bool plan_has_clears(const cacao_plan *plan) {
    for (uint32_t i = 0; i < plan->step_count; ++i)
        if (plan->steps[i].clear) return true;
    return false;
}

/* The stage of a step: a clear's is the transfer stage. */
static VkPipelineStageFlags step_stage(const cacao_plan_step *step) {
    return step->clear ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
}

/* `clears`: the plan has clear steps (plan_has_clears). */
static void record_step(cacao_context *ctx, VkCommandBuffer cmd, const cacao_inputs *in, uint32_t index, bool clears) {
    const cacao_plan_step *step = &ctx->plan.steps[index];
    if (step->barrier_before) {
        /* With tiles, every barrier also makes the compact pass's commands visible to the
         * indirect dispatches after it. Clears are transfers: a barrier orders them too where the
         * plan has any (before a clear: the passes that read the image; after: its writes). */
        const bool tiles = ctx->plan.uses_tiles;
        const VkMemoryBarrier memory = {
            .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT |
                             (clears ? VK_ACCESS_TRANSFER_WRITE_BIT : 0),
            .dstAccessMask = step->clear ? VK_ACCESS_TRANSFER_WRITE_BIT
                                         : VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                               (tiles ? VK_ACCESS_INDIRECT_COMMAND_READ_BIT : 0)};
        ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | (clears ? VK_PIPELINE_STAGE_TRANSFER_BIT : 0),
                             step->clear ? VK_PIPELINE_STAGE_TRANSFER_BIT
                                         : VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | (tiles ? VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT : 0),
                             0, 1, &memory, 0, NULL, 0, NULL);
    }
    if (step->clear) {
        record_clear(ctx, cmd, step);
        return;
    }
    descriptor_info infos[CACAO_PLAN_MAX_BINDINGS];
    VkWriteDescriptorSet writes[CACAO_PLAN_MAX_BINDINGS];
    for (uint32_t i = 0; i < step->binding_count; ++i) {
        const cacao_plan_binding *b = &step->bindings[i];
        const VkDescriptorType type = cacaoi_binding_type(b->binding);
        describe(ctx, in, b, &infos[i]);
        const bool buffer = type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        const bool texel = type == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstBinding = b->binding,
            .descriptorCount = 1,
            .descriptorType = type,
            .pImageInfo = buffer || texel ? NULL : &infos[i].image,
            .pBufferInfo = buffer ? &infos[i].buffer : NULL,
            .pTexelBufferView = texel ? &infos[i].texel_view : NULL,
        };
    }
    ctx->vk.CmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->pipelines[index]);
    ctx->vk.CmdPushDescriptorSetKHR(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ctx->pipeline_layout, 0, step->binding_count, writes);
    if (step->list)
        ctx->vk.CmdDispatchIndirect(cmd, ctx->buffers[CACAO_RES_TILES], sizeof(uint32_t) * CACAO_TILE_COMMAND(step->list));
    else if (step->gate)
        ctx->vk.CmdDispatchIndirect(cmd, ctx->buffers[CACAO_RES_TILES],
                                    gates_offset(&ctx->plan) + sizeof(uint32_t) * 3u * (step->gate - 1u));
    else
        ctx->vk.CmdDispatch(cmd, step->dispatch[0], step->dispatch[1], step->dispatch[2]);
}

cacao_result cacao_record(cacao_context *ctx, VkCommandBuffer cmd, const cacao_inputs *in) {
    if (!ctx) return CACAO_ERROR_INVALID_ARGUMENT;
    if (!cmd || !in)
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "%s is NULL", !cmd ? "command_buffer" : "inputs");
    if (!ctx->ready)
        return cacaoi_fail(ctx, CACAO_ERROR_NOT_READY, "cacao_context_resize must succeed before cacao_record");
    cacao_result r = check_inputs(ctx, in);
    if (r != CACAO_SUCCESS) return r;

    /* the constants first: whether the frame keeps the intermediates' contents depends on them */
    cacao_constants constants;
    cacaoi_fill_constants(&ctx->plan, in, &constants);
    const int reuse = reuse_frame(ctx, in, &constants);
    /* temporal accumulation: the history of the last frame recorded, unless the caller drops it */
    const bool primed = ctx->plan.settings.temporal_frames && ctx->temporal_primed;
    constants.temporal_history = primed && !in->temporal_reset ? 1 : 0;
    record_frame_start(ctx, cmd, in, reuse == 1, primed);
    ctx->temporal_odd = primed && !ctx->temporal_odd; /* the history this frame reads: the last one's output */
    ctx->temporal_primed = ctx->plan.settings.temporal_frames != 0;
    record_constants(ctx, cmd, &constants);
    const VkQueryPool timer = in->timestamp_query_pool;
    if (timer)
        ctx->vk.CmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timer, in->timestamp_first_query);
    const bool clears = plan_has_clears(&ctx->plan);
    for (uint32_t i = 0; i < ctx->plan.step_count; ++i) {
        /* a full frame records no prefix and reach (every tile is recomputed), and one whose
         * constants changed no diff either (the copies go stale) */
        const uint8_t *key = ctx->plan.steps[i].key;
        const bool reach =
            key[0] == CACAO_PASS_REUSE && (key[1] == CACAO_REUSE_PREFIX || key[1] == CACAO_REUSE_REACH);
        const bool diff = key[0] == CACAO_PASS_REUSE && !reach;
        if (!((reach && reuse >= 2) || (diff && reuse == 3))) record_step(ctx, cmd, in, i, clears);
        if (timer)
            ctx->vk.CmdWriteTimestamp(cmd, step_stage(&ctx->plan.steps[i]), timer, in->timestamp_first_query + i + 1);
    }

    /* Output back to the caller's layout; its later accesses are ordered after our writes. */
    const VkImageMemoryBarrier done =
        image_barrier(in->output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, in->output.layout,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, NULL, 0,
                         NULL, 1, &done);
    ctx->last_error[0] = '\0';
    return CACAO_SUCCESS;
}

cacao_result cacao_record_tile_counts(cacao_context *ctx, VkCommandBuffer cmd, VkBuffer dst, VkDeviceSize offset) {
    if (!ctx) return CACAO_ERROR_INVALID_ARGUMENT;
    if (!ctx->ready) return cacaoi_fail(ctx, CACAO_ERROR_NOT_READY, "cacao_context_resize must succeed first");
    if (!ctx->plan.uses_tiles)
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "tile counts: the plan has no tiles");
    if (!cmd || !dst)
        return cacaoi_fail(ctx, CACAO_ERROR_INVALID_ARGUMENT, "tile counts: %s is NULL",
                           !cmd ? "command_buffer" : "dst");
    const VkMemoryBarrier before = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                    .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                    .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT};
    ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0,
                         NULL, 0, NULL);
    const VkBufferCopy region = {0, offset, CACAO_TILE_COUNTS_BYTES};
    ctx->vk.CmdCopyBuffer(cmd, ctx->buffers[CACAO_RES_TILES], dst, 1, &region);
    /* The next frame's header reset (a transfer write) waits for this read. */
    const VkMemoryBarrier after = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                   .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                   .dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT};
    ctx->vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 1, &after, 0, NULL, 0, NULL);
    return CACAO_SUCCESS;
}

cacao_result cacao_tile_counts_decode(const cacao_context *ctx, const void *bytes, cacao_tile_counts *out) {
    if (!ctx || !bytes || !out || !ctx->ready || !ctx->plan.uses_tiles) return CACAO_ERROR_INVALID_ARGUMENT;
    uint32_t h[CACAO_TILE_COUNTS_BYTES / sizeof(uint32_t)];
    memcpy(h, bytes, sizeof h);
    const cacao_plan *p = &ctx->plan;
#define LIST_X(list) h[CACAO_TILE_LIST_ENTRIES(list)]
    bool skip_in_shader = false; /* the plan's generate skips by classify's flags, not a list */
    for (uint32_t i = 0; i < p->step_count; ++i)
        skip_in_shader = skip_in_shader || cacaoi_skips_by_class(p->steps[i].key[0], p->steps[i].key[1]);
    *out = (cacao_tile_counts){
        .tiles = p->tiles_x * p->tiles_y,
        .active = h[CACAO_TILE_COUNT_ACTIVE],
        .faded = h[CACAO_TILE_COUNT_FADED],
        .background = h[CACAO_TILE_COUNT_BACKGROUND],
        /* the lists' entries; the GPU forms of CACAO have no lists: classify counted the tiles and
         * blur groups it marked needed, the same sets (docs/tiles.md) */
        .generate_run = skip_in_shader ? h[CACAO_TILE_COUNT_NEEDED] : LIST_X(CACAO_LIST_GENERATE),
        .generate_total = p->tiles_x * p->tiles_y,
        .blur_run = skip_in_shader ? h[CACAO_TILE_COUNT_BLUR_NEEDED] : LIST_X(CACAO_LIST_BLUR),
        .blur_total = p->blur_groups_x * p->blur_groups_y,
        .changed = h[CACAO_TILE_COUNT_CHANGED],
        .recomputed = h[CACAO_TILE_COUNT_RECOMPUTE],
    };
    for (uint32_t i = 0; i < p->step_count; ++i) /* a plan that can find its frame quiet (docs/tiles.md) */
        if (p->steps[i].key[0] == CACAO_PASS_CLASSIFY && p->steps[i].key[1] == CACAO_CLASSIFY_QUIET)
            out->quiet = h[CACAO_TILE_NOT_QUIET] == 0;
    for (uint32_t i = 0; i < p->step_count; ++i) { /* a step over compact's blocks, or the GPU form's base pass */
        const cacao_plan_step *st = &p->steps[i];
        if (st->list == CACAO_LIST_FILL_SLICES || (st->key[0] == CACAO_PASS_COMPACT && st->key[1] == CACAO_COMPACT_SLICES))
            out->fill_run = LIST_X(CACAO_LIST_FILL_SLICES); /* compact fills generate's output */
        if (st->list == CACAO_LIST_BLOCKS) {
            out->blocks_run = LIST_X(CACAO_LIST_BLOCKS);
            out->blocks_total = st->dispatch[0] * st->dispatch[1];
        } else if (st->key[0] == CACAO_PASS_GENERATE_GPU && st->key[1] == CACAO_GENERATE_Q3_BASE) {
            out->blocks_run = out->active;
            out->blocks_total = out->tiles;
        }
    }
#undef LIST_X
    return CACAO_SUCCESS;
}
