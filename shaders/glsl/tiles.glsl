/* tiles.glsl - tile classification (docs/tiles.md; the buffer's layout in cacao_shared.h): the
 * lists a pass dispatches from, and the classify, compact and fill passes. */

#if CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_LIST != CACAO_LIST_NONE
/* First uint of a list's entries (cacao_shared.h). */
uint list_base(int list) { return uint(CACAO_TILE_LIST_BASE(list, CB.tiles_x * CB.tiles_y)); }

/* A list's grid width: the host writes it as the command's x (record.c). */
uint list_width(int list) { return uint(list == CACAO_LIST_BLUR ? CB.blur_groups_x : CB.tiles_x); }
#endif

/* The group this workgroup computes, false for none. Over a list: the entry at y width + x,
 * where width is the grid's (cb); past the last entry the host's fill left
 * CACAO_TILE_NO_ENTRY, and the group returns at once (uniformly, so also before a barrier).
 * One buffer load per invocation (lavapipe loads per lane). */
bool group_of(out ivec2 g)
{
#if CACAO_LIST != CACAO_LIST_NONE
    uint e = tiles[list_base(CACAO_LIST) + gl_WorkGroupID.y * list_width(CACAO_LIST) + gl_WorkGroupID.x];
    g = ivec2(int(e & 0xffffu), int(e >> 16));
    return e != CACAO_TILE_NO_ENTRY;
#else
    g = ivec2(gl_WorkGroupID.xy);
    return true;
#endif
}

#if CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_PASS == CACAO_PASS_FILL
/* Where tile t's class is (cacao_shared.h). */
uint class_index(ivec2 t) { return uint(CACAO_TILE_CLASSES + t.y * CB.tiles_x + t.x); }
#endif

/* The invocation's texel in group g: a macro, since gl_WorkGroupSize is only known after each
 * pass declares its local size (glslang takes 1 x 1 x 1 before). */
#define texel_of(g) ((g) * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy))

/* CACAO_SKIPS_BY_CLASS (the generator's define, cacaoi_skips_by_class): the GPU forms of
 * generate and the blur run every group of a direct grid and skip by classify's flags: a group
 * the lists would leave out stores the AO 1 the CPU forms' fill stores there and computes nothing
 * else, a workgroup-uniform branch a GPU skips (lavapipe runs both sides: the CPU forms keep the
 * lists). */

#if CACAO_PASS == CACAO_PASS_COMPACT
/* Some tile within one tile of the tiles [t0, t1] is active: a needed tile lies in [t0, t1]. */
bool touches_needed(ivec2 t0, ivec2 t1)
{
    ivec2 last = ivec2(CB.tiles_x, CB.tiles_y) - 1;
    t0 = clamp(t0 - 1, ivec2(0), last);
    t1 = clamp(t1 + 1, ivec2(0), last);
    for (int y = t0.y; y <= t1.y; ++y)
        for (int x = t0.x; x <= t1.x; ++x)
            if (tiles[class_index(ivec2(x, y))] == CACAO_TILE_CLASS_ACTIVE) return true;
    return false;
}
#endif

#if CACAO_SKIPS_BY_CLASS || CACAO_PASS == CACAO_PASS_CLASSIFY
uint needed_base() { return uint(CACAO_TILE_NEEDED(CB.tiles_x * CB.tiles_y, CB.blur_groups_x * CB.blur_groups_y)); }
uint blur_needed_base() { return uint(CACAO_TILE_BLUR_NEEDED(CB.tiles_x * CB.tiles_y, CB.blur_groups_x * CB.blur_groups_y)); }
#endif

#if CACAO_SKIPS_BY_CLASS
/* Group g of generate (a tile) or of the blur is one the lists would hold (classify's flags:
 * compact's test, made from each active tile, which counted them). One load per invocation, the
 * same for the group. */
bool group_needed(ivec2 g)
{
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
    bool needed = tiles[blur_needed_base() + g.y * CB.blur_groups_x + g.x] == 0u;
    const uint count = CACAO_TILE_COUNT_BLUR_NEEDED;
#else
    bool needed = tiles[needed_base() + g.y * CB.tiles_x + g.x] == 0u;
    const uint count = CACAO_TILE_COUNT_NEEDED;
#endif
    /* counted once per group of the first layer (cacao_tile_counts) */
    if (needed && gl_WorkGroupID.z == 0u && gl_LocalInvocationIndex == 0u) atomicAdd(tiles[count], 1u);
    return needed;
}
#endif

/* ---- classify ---- */
#if CACAO_PASS == CACAO_PASS_CLASSIFY
/* docs/tiles.md: one invocation per tile, no barriers. A texel is quiet where every layer's
 * stored view z is background or faded (with the margin of CB.quiet_margin, so that generate
 * finds it faded too); the tile is active when some texel is not quiet (the scan stops there),
 * else faded when some texel is not background, else background. Gathers read 2x2 texels; past
 * the slice's edge they clamp to texels of the same tile. */
layout(local_size_x = CACAO_WG_CLASSIFY, local_size_y = CACAO_WG_CLASSIFY) in;

#if CACAO_VARIANT == CACAO_CLASSIFY_SLICES
/* Active tile a makes needed the tiles within one tile of it, and the blur groups whose output
 * touches one of those: compact's tests, turned around (a group g, output texels g out .. g out +
 * out - 1, touches tiles a - 1 .. a + 1 when g out < (a + 2) TILE and g out + out > (a - 1) TILE).
 * Every mark stores the same 0 (the GPU forms' flags; the CPU forms run from compact's lists), an
 * atomic whose result nothing waits for: counting here (the mark that found the flag unset) made
 * each active tile wait on a chain of atomics, 3 microseconds of an H200's frame (docs/gpu.md).
 * The GPU forms' generate and blur count the needed groups they run instead (group_needed). */
void mark(uint flag) { atomicAnd(tiles[flag], 0u); }

void mark_needed(ivec2 a)
{
    ivec2 last = ivec2(CB.tiles_x, CB.tiles_y) - 1;
    for (int y = max(a.y - 1, 0); y <= min(a.y + 1, last.y); ++y)
        for (int x = max(a.x - 1, 0); x <= min(a.x + 1, last.x); ++x)
            mark(needed_base() + uint(y * CB.tiles_x + x));
    if (CB.blur_groups_x == 0) return; /* no blur */
    ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
    ivec2 g0 = max(a - 1, ivec2(0)) * CACAO_TILE / out_size;
    ivec2 g1 = min(((a + 2) * CACAO_TILE - 1) / out_size, ivec2(CB.blur_groups_x, CB.blur_groups_y) - 1);
    for (int y = g0.y; y <= g1.y; ++y)
        for (int x = g0.x; x <= g1.x; ++x) mark(blur_needed_base() + uint(y * CB.blur_groups_x + x));
}
#endif

#if CACAO_VARIANT == CACAO_CLASSIFY_HORIZON
/* The horizon estimators' pixels, from the caller's depth, before their prepare: background where
 * the depth is the far plane's or NaN (their prepare stores view z -1 there by the same exact
 * tests, and the estimator and the denoise write 1); quiet by fade where the view z the prepare
 * computes is positive and the fade factor of horizon_visibility is 0 with the margin (the margin
 * covers the ulps by which two passes may evaluate z differently). A depth whose z is invalid in
 * another way is neither: the passes compute it (and write 1). A background tile is left to the
 * fill of the background list, which stores what the prepare would. */
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) return;
    ivec2 size = textureSize(src_depth, 0);
    vec2 inv_size = 1.0 / vec2(size);
    uint flags = CB.tiles_all != 0 ? 3u : 0u; /* 1: not quiet, 2: not background */
    /* 2x2 pixels a gather (a quarter of the fetches: lavapipe pays per fetch); past the image's
     * edge the sampler clamps to pixels of the same tile, which changes no class */
    for (int y = 0; y < CACAO_TILE && flags != 3u; y += 2) {
        for (int x = 0; x < CACAO_TILE; x += 2) {
            ivec2 p = t * CACAO_TILE + ivec2(x, y);
            if (!in_rect(p, size)) continue;
            vec4 d = textureGather(src_depth, vec2(p + 1) * inv_size, 0);
            for (int i = 0; i < 4; ++i) {
                bool background = d[i] == CB.horizon_far_depth || isnan(d[i]);
                float z = background ? -1.0 : horizon_view_z(d[i]);
                bool faded = z > 0.0 && z * CB.effect_fade_out_mul + CB.effect_fade_out_add < -CB.quiet_margin;
                if (!background) flags |= 2u;
                if (!(background || faded)) flags |= 1u;
            }
        }
    }
#else
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) return;
    ivec2 size = slice_size();
    ivec2 image_size = textureSize(depths, 0).xy;
    vec2 inv_d = 1.0 / vec2(image_size);
    /* The largest gather corner: the slice's edge, where the sampler clamps; or where the atlas
     * continues past the slice (cacao_shared.h), one texel inside it (the gather then also reads
     * texel n - 2, of this tile or its neighbour: at most a tile more is computed). */
    ivec2 corner_max = size - ivec2(greaterThan(image_size, size));
    uint flags = CB.tiles_all != 0 ? 1u : 0u; /* 1: not quiet, 2: not background */
    for (int layer = 0; layer < CB.slice_count && flags < 1u; ++layer) {
        for (int y = 0; y < CACAO_TILE && (flags & 1u) == 0u; y += 2) {
            for (int x = 0; x < CACAO_TILE; x += 2) {
                ivec2 corner = min(t * CACAO_TILE + ivec2(x, y) + 1, corner_max);
                vec4 z = textureGather(depths, vec3(vec2(corner) * inv_d, float(layer)), 0);
                bvec4 background = greaterThanEqual(z, vec4(CB.background_z));
                bvec4 faded = lessThan((z * CB.depth_precision_offset_mod) * CB.effect_fade_out_mul +
                                           CB.effect_fade_out_add, vec4(-CB.quiet_margin));
                if (!all(background)) flags |= 2u;
                if (!all(bvec4(uvec4(background) | uvec4(faded)))) flags |= 1u;
            }
        }
    }
#endif
    uint cls = (flags & 1u) != 0u ? CACAO_TILE_CLASS_ACTIVE
             : (flags & 2u) != 0u ? CACAO_TILE_CLASS_FADED : CACAO_TILE_CLASS_BACKGROUND;
    tiles[class_index(t)] = cls;
    atomicAdd(tiles[CACAO_TILE_COUNT_ACTIVE + cls], 1u);
#if CACAO_VARIANT == CACAO_CLASSIFY_SLICES
    if (cls == CACAO_TILE_CLASS_ACTIVE) mark_needed(t);
#endif
}
#endif /* CLASSIFY */

/* ---- compact ---- */
#if CACAO_PASS == CACAO_PASS_COMPACT
/* docs/tiles.md: one invocation per tile, then one per blur group; each goes into the list that
 * computes it (or, a tile, into the one that fills it with 1). Order within a list is arbitrary:
 * every group writes only its own texels. */
layout(local_size_x = CACAO_WG_COMPACT) in;

/* Entry i goes to grid row i / width: the command's rows cover every entry. */
void append(int list, ivec2 g)
{
    uint i = atomicAdd(tiles[CACAO_TILE_LIST_ENTRIES(list)], 1u);
    tiles[list_base(list) + i] = uint(g.x) | (uint(g.y) << 16);
    atomicMax(tiles[CACAO_TILE_COMMAND(list) + 1], i / list_width(list) + 1u); /* the command's y */
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    int t = CB.tiles_x * CB.tiles_y, b = CB.blur_groups_x * CB.blur_groups_y;
    if (i < t) {
        ivec2 g = ivec2(i % CB.tiles_x, i / CB.tiles_x);
        append(touches_needed(g, g) ? CACAO_LIST_GENERATE : CACAO_LIST_FILL_SLICES, g);
#if CACAO_VARIANT == CACAO_COMPACT_HORIZON
        /* the background tiles keep the clear's view z and normal (what the prepare would store) */
        if (tiles[CACAO_TILE_CLASSES + i] != CACAO_TILE_CLASS_BACKGROUND) append(CACAO_LIST_PREPARE, g);
#endif
    } else if (i < t + b) {
        i -= t;
        ivec2 g = ivec2(i % CB.blur_groups_x, i / CB.blur_groups_x);
        ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
        ivec2 lo = g * out_size, hi = lo + out_size - 1; /* its output texels */
        if (touches_needed(lo / CACAO_TILE, hi / CACAO_TILE)) append(CACAO_LIST_BLUR, g);
    }
}
#endif /* COMPACT */

/* ---- fill ---- */
#if CACAO_PASS == CACAO_PASS_FILL
/* docs/tiles.md: AO 1, the value the full computation gives every texel of a tile that is not
 * needed (edges 1: nothing reads them there): the slices' AO (CACAO's CPU forms), or the caller's
 * output (a horizon estimator's last pass writes the needed tiles). The horizon estimators' own
 * images get theirs from a clear (cacao_plan_step.clear): no variant dispatches for them. */
layout(local_size_x = CACAO_TILE, local_size_y = CACAO_TILE) in;

void main()
{
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 p = texel_of(group);
#if CACAO_VARIANT == CACAO_FILL_OUTPUT
    if (in_rect(p, imageSize(output_image))) imageStore(output_image, p, vec4(1.0, 0.0, 0.0, 0.0));
#elif CACAO_VARIANT == CACAO_FILL_HORIZON_ALL || CACAO_VARIANT == CACAO_FILL_VIEW_ALL
    /* The GPU forms' fills of the horizon estimators' images (a group is a tile of the direct grid),
     * with the values cacaoi_clear_value gives the CPU forms' clears, where a later pass does not
     * write them: prepare writes every pixel of the tiles that are not all background (its list),
     * the estimator and the denoise passes every pixel of the needed tiles, which hold every
     * active tile. The test is the same for the whole group. */
    uint cls = tiles[class_index(group)];
#if CACAO_VARIANT == CACAO_FILL_HORIZON_ALL
    if (cls != CACAO_TILE_CLASS_ACTIVE && in_rect(p, imageSize(horizon_ao_out)))
        imageStore(horizon_ao_out, p, vec4(1.0, 0.0, 0.0, 0.0));
#else
    if (cls == CACAO_TILE_CLASS_BACKGROUND && in_rect(p, imageSize(view_depth))) {
        imageStore(view_depth, p, vec4(-1.0, 0.0, 0.0, 0.0));
        imageStore(view_normals, p, vec4(0.0, 0.0, -1.0, 0.0));
    }
#endif
#else
    if (in_rect(p, imageSize(ssao_image).xy))
        for (int layer = 0; layer < CB.slice_count; ++layer) imageStore(ssao_image, ivec3(p, layer), vec4(1.0, 1.0, 0.0, 0.0));
#endif
}
#endif /* FILL */
