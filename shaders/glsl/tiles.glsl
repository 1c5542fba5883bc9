/* tiles.glsl - tile classification (docs/tiles.md; the buffer's layout in cacao_shared.h): the
 * lists a pass dispatches from, and the classify, compact and fill passes. */

/* Word i of the tile buffer, written by an earlier pass: through its texel view where the pass
 * binds it (a list step, compact), which lavapipe loads at a fraction of a storage buffer's cost
 * (docs/tiles.md "What a list costs"); else from the storage buffer. */
#ifdef CACAO_BIND_TILE_ENTRIES
uint tile_read(uint i) { return imageLoad(tile_entries, int(i)).x; }
#elif defined(CACAO_BIND_TILES)
uint tile_read(uint i) { return tiles[i]; }
#endif

#if CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_LIST != CACAO_LIST_NONE
/* First uint of a list's entries (cacao_shared.h). */
uint list_base(int list) { return uint(CACAO_TILE_LIST_BASE(list, CB.tiles_x * CB.tiles_y)); }

/* A list's grid width: the host writes it as the command's x (record.c); the blocks in rows as
 * wide as their passes' direct grids (in rows tiles_x wide lavapipe ran the Q3 base pass 8% slower). */
uint list_width(int list)
{
    return uint(list == CACAO_LIST_BLUR ? CB.blur_groups_x : list == CACAO_LIST_BLOCKS ? (CB.tiles_x + 1) / 2 : CB.tiles_x);
}
#endif

/* The group this workgroup computes, false for none. Over a list: the entry at y width + x,
 * where width is the grid's (cb); past the last entry the host's fill left
 * CACAO_TILE_NO_ENTRY, and the group returns at once (uniformly, so also before a barrier).
 * One load per invocation, through the tile buffer's texel view: lavapipe loads a storage
 * buffer lane by lane with a bounds check, which cost a list step's invocation about 4 ns, 30%
 * of the half apply's (docs/tiles.md "What a list costs"). */
bool group_of(out ivec2 g)
{
#if CACAO_LIST != CACAO_LIST_NONE
    uint e = tile_read(list_base(CACAO_LIST) + gl_WorkGroupID.y * list_width(CACAO_LIST) + gl_WorkGroupID.x);
    g = ivec2(int(e & 0xffffu), int(e >> 16));
    return e != CACAO_TILE_NO_ENTRY;
#else
    g = ivec2(gl_WorkGroupID.xy);
    return true;
#endif
}

/* The passes that classify tiles: classify, the GPU form of the fused prepare (native the texels
 * it stores, downsampled in groups of its own), classify_gpu, and the GPU form of the horizon
 * estimators' prepare. */
#define CACAO_CLASSIFIES (CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU || \
                          CACAO_PASS == CACAO_PASS_PREPARE_GPU || CACAO_PASS == CACAO_PASS_CLASSIFY_GPU)
/* The classes of the horizon estimators' pixels, from the caller's depth */
#define CACAO_CLASSIFIES_DEPTH ((CACAO_PASS == CACAO_PASS_CLASSIFY && CACAO_VARIANT == CACAO_CLASSIFY_HORIZON) || \
                                CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU)

#if (CACAO_CLASSIFIES || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_PASS == CACAO_PASS_FILL || \
     CACAO_PASS == CACAO_PASS_REUSE || CACAO_SKIPS_BY_CLASS || CACAO_READS_CLASSES) && defined(CACAO_BIND_TILES)
/* Tile t's index in the per-tile regions of the tile buffer (cacao_shared.h), and where its class is. */
uint tile_index(ivec2 t) { return uint(t.y * CB.tiles_x + t.x); }
uint class_index(ivec2 t) { return uint(CACAO_TILE_CLASSES) + tile_index(t); }

/* Block b of 2x2 tiles (tiles 2b .. 2b + 1 inside the grid) holds an active tile: compact's test
 * for the blocks list, and the GPU form of the downsampled horizon estimator's, per group. */
bool block_has_active(ivec2 b)
{
    bool any_active = false;
    for (int k = 0; k < 4; ++k) {
        ivec2 t = 2 * b + ivec2(k & 1, k >> 1);
        any_active = any_active || (in_rect(t, ivec2(CB.tiles_x, CB.tiles_y)) && tile_read(class_index(t)) == CACAO_TILE_CLASS_ACTIVE);
    }
    return any_active;
}
#endif

/* The invocation's texel in group g: a macro, since gl_WorkGroupSize is only known after each
 * pass declares its local size (glslang takes 1 x 1 x 1 before). */
#define texel_of(g) ((g) * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy))

#if (CACAO_PASS == CACAO_PASS_COMPACT || CACAO_PASS == CACAO_PASS_CLASSIFY) && defined(CACAO_BIND_OUTPUT)
/* AO 1 into the output's n x n pixels from p0 (those inside the image). */
void store_output_one(ivec2 p0, int n)
{
    ivec2 size = imageSize(output_image);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            if (in_rect(p0 + ivec2(x, y), size)) imageStore(output_image, p0 + ivec2(x, y), vec4(1.0, 0.0, 0.0, 0.0));
}
#endif

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
            if (tile_read(class_index(ivec2(x, y))) == CACAO_TILE_CLASS_ACTIVE) return true;
    return false;
}
#endif

#if CACAO_SKIPS_BY_CLASS || CACAO_CLASSIFIES || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_PASS == CACAO_PASS_REUSE
#define TILE_REGION(name) uint(name(CB.tiles_x * CB.tiles_y, CB.blur_groups_x * CB.blur_groups_y))
uint needed_base() { return TILE_REGION(CACAO_TILE_NEEDED); }
uint blur_needed_base() { return TILE_REGION(CACAO_TILE_BLUR_NEEDED); }
uint recompute_base() { return TILE_REGION(CACAO_TILE_RECOMPUTE); }
uint blur_recompute_base() { return TILE_REGION(CACAO_TILE_BLUR_RECOMPUTE); }

/* Reuse (docs/tiles.md "Reusing the previous frame"): tile t, or blur group g, is recomputed this
 * frame (the reach pass's flags); without reuse, and on a full frame (which runs no reach pass),
 * every one is. */
bool tile_recomputed(ivec2 t) { return CB.reuse != 1 || tile_read(recompute_base() + tile_index(t)) == 0u; }
bool blur_group_recomputed(ivec2 g)
{
    return CB.reuse != 1 || tile_read(blur_recompute_base() + uint(g.y * CB.blur_groups_x + g.x)) == 0u;
}
#endif

#if CACAO_CLASSIFIES || CACAO_PASS == CACAO_PASS_REUSE
/* Every mark stores the same 0 (flags the host reset to CACAO_TILE_NO_ENTRY), an atomic whose
 * result nothing waits for: counting here (the mark that found the flag unset) made each active
 * tile wait on a chain of atomics, 3 microseconds of an H200's frame (docs/gpu.md). */
void mark(uint flag) { atomicAnd(tiles[flag], 0u); }

/* Marks, in the flags from tile_base and blur_base, the tiles within one tile of tile a and the
 * blur groups whose output touches one of those (a group g, output texels g out .. g out + out -
 * 1, touches tiles a - 1 .. a + 1 when g out < (a + 2) TILE and g out + out > (a - 1) TILE). */
void mark_around(ivec2 a, uint tile_base, uint blur_base)
{
    /* unrolled: a GPU compiler then knows the trip count (ACO weighs a loop it cannot count as 8
     * iterations, a nested one as 64) */
    [[unroll]] for (int dy = -1; dy <= 1; ++dy)
        [[unroll]] for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = a + ivec2(dx, dy);
            if (in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) mark(tile_base + tile_index(t));
        }
    if (CB.blur_groups_x == 0) return; /* no blur */
    ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
    ivec2 g0 = max(a - 1, ivec2(0)) * CACAO_TILE / out_size;
    ivec2 g1 = min(((a + 2) * CACAO_TILE - 1) / out_size, ivec2(CB.blur_groups_x, CB.blur_groups_y) - 1);
    for (int y = g0.y; y <= g1.y; ++y)
        for (int x = g0.x; x <= g1.x; ++x) mark(blur_base + uint(y * CB.blur_groups_x + x));
}
#endif

#if CACAO_SKIPS_BY_CLASS
/* What group g of generate (a tile), of the blur or of a horizon estimator's pass does: GROUP_COMPUTE where the lists would hold
 * it (classify's flags: compact's test, made from each active tile) and reuse recomputes it;
 * GROUP_FILL (store AO 1, the CPU forms' fill) where reuse recomputes it but no active tile is
 * near; GROUP_KEEP where reuse keeps the previous frame's. One or two loads per invocation, the
 * same for the group. */
#define GROUP_KEEP 0
#define GROUP_FILL 1
#define GROUP_COMPUTE 2
int group_work(ivec2 g)
{
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
    if (!blur_group_recomputed(g)) return GROUP_KEEP;
    bool needed = tiles[blur_needed_base() + g.y * CB.blur_groups_x + g.x] == 0u;
    const uint count = CACAO_TILE_COUNT_BLUR_NEEDED;
#else
#if CACAO_PASS != CACAO_PASS_HORIZON_MAIN_GPU && CACAO_PASS != CACAO_PASS_HORIZON_DENOISE_GPU
    /* (the horizon estimators reuse all or nothing: a pass of theirs that runs computes its groups,
     * the last one also on a frame with nothing changed, when the output is not held and no reach
     * pass marked anything) */
    if (!tile_recomputed(g)) return GROUP_KEEP;
#endif
    bool needed = tiles[needed_base() + tile_index(g)] == 0u;
    const uint count = CACAO_TILE_COUNT_NEEDED;
#endif
    /* counted once per group of the first layer (cacao_tile_counts), by the first of the horizon
     * estimators' passes over the tiles (the later denoise passes run the same groups) */
#if CACAO_PASS == CACAO_PASS_HORIZON_DENOISE_GPU && CACAO_VARIANT != CACAO_DENOISE_UPSAMPLE && \
    CACAO_VARIANT != CACAO_DENOISE_UPSAMPLE_FINAL
    const bool counts = false;
#else
    const bool counts = true;
#endif
    if (counts && needed && gl_WorkGroupID.z == 0u && gl_LocalInvocationIndex == 0u) atomicAdd(tiles[count], 1u);
    return needed ? GROUP_COMPUTE : GROUP_FILL;
}
#endif

/* ---- classify ---- */
#if CACAO_CLASSIFIES
/* Flags of a tile: not quiet, not background. */
#define FLAG_NOT_QUIET 1u
#define FLAG_NOT_BACKGROUND 2u
#define FLAGS_ALL (FLAG_NOT_QUIET | FLAG_NOT_BACKGROUND)

#if CACAO_PASS == CACAO_PASS_PREPARE_GPU || CACAO_PASS == CACAO_PASS_CLASSIFY_GPU || \
    (CACAO_PASS == CACAO_PASS_CLASSIFY && CACAO_VARIANT == CACAO_CLASSIFY_SLICES)
/* CACAO's stored view z (deinterleaved, R16F): background at or past background_z; quiet by fade
 * with the margin of CB.quiet_margin, so that generate finds it faded too. */
uint slice_z_flags(float z)
{
    bool background = z >= CB.background_z;
    bool faded = (z * CB.depth_precision_offset_mod) * CB.effect_fade_out_mul + CB.effect_fade_out_add < -CB.quiet_margin;
    return (background ? 0u : FLAG_NOT_BACKGROUND) | (background || faded ? 0u : FLAG_NOT_QUIET);
}

/* The GPU forms classify the view z they compute, before the R16F store: a z the store keeps,
 * whichever way it rounds, is at least z less 2^-10 of it (a half's step; 1% more for the ulps by
 * which two passes' arithmetic may differ), and being quiet is monotonic in z (background at or
 * past background_z; faded where the fade argument is below -margin, mul negative), so the flags
 * of that floor are a superset of the stored texel's. An infinite z is its own floor. */
float quiet_floor(float z) { return isinf(z) ? z : z - abs(z) * (1.01 / 1024.0); }
#endif

#if CACAO_CLASSIFIES_DEPTH
/* The horizon estimators' pixels, from the caller's depth, before their prepare: background where
 * the depth is the far plane's or NaN (their prepare stores view z -1 there by the same exact
 * tests, and the estimator and the denoise write 1); quiet by fade where the view z the prepare
 * computes is positive and the fade factor of horizon_visibility is 0 with the margin (the margin
 * covers the ulps by which two passes may evaluate z differently). A depth whose z is invalid in
 * another way is neither: the passes compute it (and write 1). In the CPU forms a background tile
 * is left to the clear, which stores what the prepare would. */
uint depth_flags(float d)
{
    bool background = d == CB.horizon_far_depth || isnan(d);
    float z = background ? -1.0 : horizon_view_z(d);
    bool faded = z > 0.0 && z * CB.effect_fade_out_mul + CB.effect_fade_out_add < -CB.quiet_margin;
    return (background ? 0u : FLAG_NOT_BACKGROUND) | (background || faded ? 0u : FLAG_NOT_QUIET);
}
#endif

/* Stores tile t's class from its flags, counts it and marks the needed tiles and blur groups
 * around it. */
void store_tile_class(ivec2 t, uint flags)
{
    uint cls = (flags & FLAG_NOT_QUIET) != 0u ? CACAO_TILE_CLASS_ACTIVE
             : (flags & FLAG_NOT_BACKGROUND) != 0u ? CACAO_TILE_CLASS_FADED : CACAO_TILE_CLASS_BACKGROUND;
    tiles[class_index(t)] = cls;
    atomicAdd(tiles[CACAO_TILE_COUNT_ACTIVE + cls], 1u);
#if !(CACAO_PASS == CACAO_PASS_CLASSIFY && CACAO_VARIANT == CACAO_CLASSIFY_HORIZON)
    /* Active tile t makes needed the tiles within one tile of it, and the blur groups whose output
     * touches one of those (none for the horizon estimators): compact's tests, turned around, in the
     * GPU forms' flags (the CPU forms run from compact's lists; classify.horizon serves only them).
     * The GPU forms' passes that skip by them count the needed groups they run (group_work). */
    if (cls == CACAO_TILE_CLASS_ACTIVE) mark_around(t, needed_base(), blur_needed_base());
#endif
}

#if CACAO_PASS != CACAO_PASS_CLASSIFY
/* The GPU forms' prepare passes classify what they store: a workgroup covers side x side tiles
 * from tile0. Every invocation of the group calls classify_group_begin, then gives the flags of its
 * texels to the group's tile own that holds them (classify_group_flag, any invocation, any number
 * of times), then calls classify_group_end (barriers). */
shared uint s_group_flags[4];

void classify_group_begin(int side)
{
    if (gl_LocalInvocationIndex < uint(side * side))
        s_group_flags[gl_LocalInvocationIndex] = CB.tiles_all != 0 ? FLAG_NOT_QUIET : 0u;
    barrier();
}

void classify_group_flag(int side, ivec2 own, uint flags)
{
    if (flags != 0u) atomicOr(s_group_flags[own.y * side + own.x], flags);
}

void classify_group_end(ivec2 tile0, int side)
{
    barrier();
    int l = int(gl_LocalInvocationIndex);
    if (side == 1) { /* a group per tile of the tiles' grid: always inside */
        if (l == 0) store_tile_class(tile0, s_group_flags[0]);
    } else if (l < side * side) {
        ivec2 t = tile0 + ivec2(l % side, l / side);
        if (in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) store_tile_class(t, s_group_flags[l]);
    }
}
#endif
#endif

#if CACAO_PASS == CACAO_PASS_CLASSIFY
/* docs/tiles.md: one invocation per tile, no barriers; a tile's scan stops at its first texel that
 * is not quiet. Gathers read 2x2 texels; past the slice's edge they clamp to texels of the same
 * tile. (CACAO's GPU forms classify in the fused prepare where normals come from depth, native:
 * prepare.glsl.) */
layout(local_size_x = CACAO_WG_CLASSIFY, local_size_y = CACAO_WG_CLASSIFY) in;

#if CACAO_VARIANT == CACAO_CLASSIFY_HORIZON
uint tile_flags(ivec2 t)
{
    ivec2 size = textureSize(src_depth, 0);
    vec2 inv_size = 1.0 / vec2(size);
    uint flags = CB.tiles_all != 0 ? FLAGS_ALL : 0u;
    /* 2x2 pixels a gather (a quarter of the fetches: lavapipe pays per fetch); past the image's
     * edge the sampler clamps to pixels of the same tile, which changes no class */
    for (int y = 0; y < CACAO_TILE && flags != FLAGS_ALL; y += 2) {
        for (int x = 0; x < CACAO_TILE; x += 2) {
            ivec2 p = t * CACAO_TILE + ivec2(x, y);
            if (!in_rect(p, size)) continue;
            vec4 d = textureGather(src_depth, vec2(p + 1) * inv_size, 0);
            for (int i = 0; i < 4; ++i) flags |= depth_flags(d[i]);
        }
    }
    return flags;
}
#elif CACAO_VARIANT == CACAO_CLASSIFY_QUIET
/* docs/tiles.md "A quiet frame": whether raw depth d can give a texel that is not quiet, by the
 * rules of slice_z_flags, which classify applies to the R16F view z the prepare stores. The
 * prepare's z is view_z(d) rounded to half: within 2^-11 of it, relative (an absolute 2^-25 below
 * half's normal range), and this pass's view_z may differ from the prepare's by ulps; so z is
 * widened by 2^-10 both ways (and 1e-7), and a texel is called quiet only if every z in that range
 * is background, or faded by twice the margin (the fade argument is linear in z: its ends decide).
 * A NaN or infinite z, or one well past CACAO_MAX_VIEW_Z, is that value in the prepare (view_z),
 * background; a negative z too, but the ulps of a z near 0 could give the prepare a small positive
 * one: called active (only depths outside the projection's range have it). */
bool may_be_active(float d)
{
    float z = view_z_unclamped(d);
    if (isnan(z) || isinf(z) || z >= CACAO_MAX_VIEW_Z * (1.0 + 1.0 / 1024.0)) return false;
    if (z < 0.0) return true;
    float lo = z * (1.0 - 1.0 / 1024.0) - 1.0e-7, hi = z * (1.0 + 1.0 / 1024.0) + 1.0e-7;
    if (lo >= CB.background_z) return false;
    float m = CB.depth_precision_offset_mod * CB.effect_fade_out_mul;
    return !(lo * m + CB.effect_fade_out_add < -2.0 * CB.quiet_margin &&
             hi * m + CB.effect_fade_out_add < -2.0 * CB.quiet_margin);
}

/* The host wrote every gate with x 0. The first invocation to find a pixel that may be active
 * (compute_all_tiles: every one) opens the gates (each one's grid from CACAO_TILE_GATE_GRIDS). */
void open_gates()
{
    if (atomicExchange(tiles[CACAO_TILE_NOT_QUIET], 1u) != 0u) return;
    uint gates = TILE_REGION(CACAO_TILE_GATES), grids = TILE_REGION(CACAO_TILE_GATE_GRIDS);
    for (int g = 0; g < CB.gate_count; ++g) tiles[gates + uint(3 * g)] = tiles[grids + uint(g)];
}

/* Scans tile t's output pixels (CB.tile_pixels each way) for one that may make a texel active,
 * with gathers of 2x2 pixels (past the image's edge the sampler clamps to pixels of the image,
 * which the prepare reads there too, or depth 0: quiet_zero_depth), and opens the gates at the
 * first. Every row it stops when another invocation has found one: on most frames one soon does,
 * and a scan of a quiet tile would otherwise keep its whole SIMD row looping (lavapipe). A tile
 * scanned whole stores the AO 1 of its output pixels: on a quiet frame every tile does, and this
 * is the frame's output; on another frame the passes the gates open write every output pixel
 * again (apply or the upsample, and compact over the tiles they skip). */
void scan_tile(ivec2 t)
{
    ivec2 size = textureSize(src_depth, 0);
    vec2 inv_size = 1.0 / vec2(size);
    ivec2 p0 = t * CB.tile_pixels;
    for (int y = 0; y < CB.tile_pixels; y += 2) {
        if (tiles[CACAO_TILE_NOT_QUIET] != 0u) return;
        for (int x = 0; x < CB.tile_pixels; x += 2) {
            ivec2 p = min(p0 + ivec2(x, y), size - 1);
            vec4 d = textureGather(src_depth, vec2(p + 1) * inv_size, 0);
            if (may_be_active(d.x) || may_be_active(d.y) || may_be_active(d.z) || may_be_active(d.w)) {
                open_gates();
                return;
            }
        }
    }
    store_output_one(p0, CB.tile_pixels);
}
#else
/* A tile is quiet only where every layer is: each layer is scanned until a texel that is not
 * quiet (a scan that stopped at the first layer with a texel that is not background called a tile
 * faded whose other layers were active: test_tiles, test_faded_layer). */
uint tile_flags(ivec2 t)
{
    ivec2 size = slice_size();
    ivec2 image_size = textureSize(depths, 0).xy;
    vec2 inv_d = 1.0 / vec2(image_size);
    /* The largest gather corner: the slice's edge, where the sampler clamps; or where the atlas
     * continues past the slice (cacao_shared.h), one texel inside it (the gather then also reads
     * texel n - 2, of this tile or its neighbour: at most a tile more is computed). */
    ivec2 corner_max = size - ivec2(greaterThan(image_size, size));
    uint flags = CB.tiles_all != 0 ? FLAG_NOT_QUIET : 0u;
    for (int layer = 0; layer < CB.slice_count && (flags & FLAG_NOT_QUIET) == 0u; ++layer) {
        for (int y = 0; y < CACAO_TILE && (flags & FLAG_NOT_QUIET) == 0u; y += 2) {
            for (int x = 0; x < CACAO_TILE; x += 2) {
                ivec2 corner = min(t * CACAO_TILE + ivec2(x, y) + 1, corner_max);
                vec4 z = textureGather(depths, vec3(vec2(corner) * inv_d, float(layer)), 0);
                for (int i = 0; i < 4; ++i) flags |= slice_z_flags(z[i]);
            }
        }
    }
    return flags;
}
#endif

#if CACAO_VARIANT == CACAO_CLASSIFY_QUIET
/* A frame where no invocation finds a pixel that may be active runs this pass alone. The
 * groups take the tiles bottom row first: lavapipe runs groups in order, every group before the
 * first finder scans its tiles whole, and an upright camera sees the nearest surfaces (the ground)
 * at the bottom and the sky and the distance, which the fade-out takes, at the top (on
 * street_track three quarters faded: 0.31 ms top first, 0.09 ms bottom first). */
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.x, CB.tiles_y - 1 - int(gl_GlobalInvocationID.y));
    /* once one found a pixel (on most frames in the first group), the others need not look: a
     * load costs lavapipe less than the scan's first gather */
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y)) || tiles[CACAO_TILE_NOT_QUIET] != 0u) return;
    if (CB.tiles_all != 0 || (t == ivec2(0) && CB.quiet_zero_depth != 0 && may_be_active(0.0))) open_gates();
    else scan_tile(t);
}
#else
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) return;
    store_tile_class(t, tile_flags(t));
}
#endif
#endif /* CLASSIFY */

/* ---- classify_gpu, and prepare_gpu's classification groups downsampled ---- */
#if CACAO_PASS == CACAO_PASS_CLASSIFY_GPU || (CACAO_PASS == CACAO_PASS_PREPARE_GPU && CACAO_DOWNSAMPLED == 1)
#if CACAO_TILE != 8 || CACAO_WG_CLASSIFY != 8 || CACAO_WG_PREPARE_X != 8 || CACAO_WG_PREPARE_Y != 8
#error "classify_from_depth classifies the 2x2 tiles of an 8x8 group of 2x2 texels: rewrite it for other sizes"
#endif
/* The GPU forms where the prepare's own texels are not classified (downsampled: extra groups of
 * prepare_gpu's dispatch; the caller's normals: classify_gpu): the tile classes from the caller's
 * depth, an invocation per 2x2 slice texels, a workgroup per 2x2 tiles. Each texel's view z is the
 * one the prepare computes from the caller's depth (the same pixel, clamp and view_z; LOWEST's
 * integer loads give raw 0 past the image); its flags are those of quiet_floor of it, a superset
 * of the flags of the R16F value the prepare stores: a tile may be called active that classify
 * would call quiet (a texel within 2^-10 of a threshold), never the other way. It reads nothing
 * the prepare writes. Every invocation of the group calls it (barriers). */
void classify_from_depth(ivec2 group)
{
    ivec2 u = group * 8 + ivec2(gl_LocalInvocationID.xy); /* the quad of slice texels 2u .. 2u + 1 */
    ivec2 s = slice_size(), src_size = textureSize(src_depth, 0);
    int step = CB.slice_count == 2 ? 3 : 1; /* LOWEST keeps slices 0 and 3 */
    uint flags = 0u;
    /* unrolled: a GPU compiler then knows the trip counts (ACO weighs a loop it cannot count as 8) */
    [[unroll]] for (int q = 0; q < 4; ++q) {
        ivec2 t = quad_texel(u, q);
        if (!in_rect(t, s)) continue;
        [[unroll]] for (int layer = 0; layer < 4; ++layer) {
            if (layer >= CB.slice_count) break;
            ivec2 p = full_res_pixel(t, layer * step);
            float z = CB.slice_count == 2 && !in_rect(p, src_size) ? view_z(0.0) : view_z(load_src_depth_clamped(p));
            flags |= slice_z_flags(quiet_floor(z));
        }
    }
    classify_group_begin(2);
    classify_group_flag(2, ivec2(gl_LocalInvocationID.xy) / 4, flags);
    classify_group_end(2 * group, 2);
}
#endif

#if CACAO_PASS == CACAO_PASS_CLASSIFY_GPU
layout(local_size_x = CACAO_WG_CLASSIFY, local_size_y = CACAO_WG_CLASSIFY) in;
void main() { classify_from_depth(ivec2(gl_WorkGroupID.xy)); }
#endif

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

#if CACAO_VARIANT != CACAO_COMPACT_HORIZON
/* AO 1 and edges 1 into tile g of every layer of generate's output, where a later pass reads the
 * AO generate skips (the fill list): what the full computation gives every texel of a tile that
 * is not needed (nothing reads the edges there). Generate writes only the needed tiles' texels;
 * the barrier after this pass orders both. The blur's output gets its 1s from the fill step over
 * the same list, beside generate (HIGHEST's Q3 base pass writes that image before generate). On
 * lavapipe a tile's texels per invocation cost less than a dispatch of an invocation per texel
 * (docs/tiles.md "A quiet frame"). */
void store_slices_one(ivec2 g)
{
    ivec2 p0 = g * CACAO_TILE, size = imageSize(ssao_image).xy;
    for (int layer = 0; layer < CB.slice_count; ++layer)
        for (int y = 0; y < CACAO_TILE; ++y)
            for (int x = 0; x < CACAO_TILE; ++x)
                if (in_rect(p0 + ivec2(x, y), size)) imageStore(ssao_image, ivec3(p0 + ivec2(x, y), layer), vec4(1.0, 1.0, 0.0, 0.0));
}

/* Whether a listed step writes the output's needed tiles, compact the others' 1s: the upsample's
 * and smart apply's lists always (needed_list 1, 2); the non-smart and half applies' (3) where at
 * most CACAO_APPLY_LIST_ACTIVE_NUM/_DEN of the tiles are active (classify's count, the same for
 * every invocation); else their direct step runs over every group. */
bool lists_output()
{
    if (CB.needed_list != 3) return CB.needed_list != 0;
    return CACAO_APPLY_LISTS(tile_read(CACAO_TILE_COUNT_ACTIVE), uint(CB.tiles_x * CB.tiles_y));
}

/* Whether a later pass can read the AO of tile g, which generate skips: the fills' list. Where
 * apply runs over every group, every skipped tile (no listed output: also every frame with reuse,
 * where a tile keeps its AO for later frames; cacao_policy lists apply and the upsample only
 * without reuse). Else (the CPU forms' listed apply or upsample, no reuse: the intermediates carry
 * nothing from frame to frame) the tiles within reach of a needed one: the upsample's tiles
 * (needed) read two slice texels around them: the tiles within one of a needed tile; the
 * non-smart and half applies' tile g (a needed tile in [g - shift, g]: the odd output's shift)
 * reads the texels of tiles g - 1 and g: within one of that needed tile; smart apply's blocks of
 * 2x2 tiles (holding a needed one) two around the block: the tiles within two. The blur's output
 * there is made of its input at most 8 texels away (8 passes), one tile more. What lies farther
 * may be read by a blur group but reaches no texel that is read. */
bool fill_read(ivec2 g, bool listed)
{
    if (!listed) return true;
    int reach = (CB.needed_list == 2 ? 2 : 1) + (CB.blur_groups_x != 0 ? 1 : 0);
    if (CB.blur_groups_x != 0) {
        /* first the blur groups over those tiles (a few loads): a needed tile there lies in one,
         * which classify marked (its output touches the tile); none marked, none needed */
        ivec2 t0 = max(g - reach, ivec2(0)), t1 = min(g + reach, ivec2(CB.tiles_x, CB.tiles_y) - 1);
        ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
        ivec2 b0 = t0 * CACAO_TILE / out_size, b1 = min(((t1 + 1) * CACAO_TILE - 1) / out_size,
                                                        ivec2(CB.blur_groups_x, CB.blur_groups_y) - 1);
        bool marked = false;
        for (int y = b0.y; y <= b1.y; ++y)
            for (int x = b0.x; x <= b1.x; ++x)
                marked = marked || tile_read(blur_needed_base() + uint(y * CB.blur_groups_x + x)) == 0u;
        if (!marked) return false;
    }
    return touches_needed(g - reach, g + reach);
}
#endif

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    int t = CB.tiles_x * CB.tiles_y, b = CB.blur_groups_x * CB.blur_groups_y;
    if (i < t) {
        ivec2 g = ivec2(i % CB.tiles_x, i / CB.tiles_x);
        /* reuse: a tile it does not recompute keeps the previous frame's values, in no list. The
         * output of an unneeded tile, where list steps write the others' (the horizon estimators'
         * last pass; CACAO's upsample or smart apply over their lists, needed_list), gets its AO 1
         * here, a tile's tile_pixels x tile_pixels pixels per invocation: on lavapipe about a third
         * of what a fill dispatch over the same tiles, an invocation per pixel or four, cost
         * (docs/tiles.md "What runs"). */
#if CACAO_VARIANT != CACAO_COMPACT_HORIZON
        bool listed = lists_output();
        /* the non-smart and half applies listed: their direct step's gate closed (one invocation;
         * classify.quiet opened it, the barrier after this pass orders both before the dispatch) */
        if (i == 0 && CB.needed_list == 3 && listed) tiles[TILE_REGION(CACAO_TILE_GATES) + uint(3 * (CB.apply_gate - 1))] = 0u;
#endif
        if (tile_recomputed(g)) {
            bool needed = touches_needed(g, g);
#if CACAO_VARIANT == CACAO_COMPACT_HORIZON
            if (needed) append(CACAO_LIST_GENERATE, g);
            else store_output_one(g * CB.tile_pixels, CB.tile_pixels);
#else
            if (needed) append(CACAO_LIST_GENERATE, g);
            else if (fill_read(g, listed)) {
                append(CACAO_LIST_FILL_SLICES, g);
                store_slices_one(g);
            }
            if (!needed && listed) store_output_one(g * CB.tile_pixels, CB.tile_pixels);
#endif
        }
        /* The blocks of 2x2 tiles holding an active tile, for CACAO's Q3 base pass at HIGHEST or the
         * horizon estimators' downsampled estimator (the CPU forms): the first tile of each block
         * appends it; every such block whatever reuse recomputes (the load counter sums the whole
         * frame's importance). */
        if (CB.active_blocks != 0 && (g.x & 1) == 0 && (g.y & 1) == 0 && block_has_active(g / 2))
            append(CACAO_LIST_BLOCKS, g / 2);
#if CACAO_VARIANT == CACAO_COMPACT_HORIZON
        /* the background tiles keep the clear's view z and normal (what the prepare would store);
         * the estimator reads the normals of the needed tiles, the denoise passes those of one
         * pixel around them (the upsample three): the tiles within two of an active one. The view
         * z: of the others (the caller's normals: their prepare stores both), or of every one
         * (normals from depth: computed from the stored z, normals_list 2). The border tiles'
         * normals too: a sample past the image's edge reads its edge pixel's (horizon.glsl,
         * side_plane). */
        if (tile_read(CACAO_TILE_CLASSES + i) != CACAO_TILE_CLASS_BACKGROUND) {
            bool border = g.x == 0 || g.y == 0 || g.x == CB.tiles_x - 1 || g.y == CB.tiles_y - 1;
            bool normals = border || touches_needed(g - 1, g + 1);
            if (normals) append(CACAO_LIST_NORMALS, g);
            if (!normals || CB.normals_list == 2) append(CACAO_LIST_PREPARE, g);
        }
#else
        /* the CPU forms without reuse: the groups of the upsample (downsampled: the needed tiles)
         * or of smart apply (native: the blocks of 2x2 tiles holding a needed one, appended by
         * their first tile) */
        if (CB.needed_list == 1 && touches_needed(g, g)) append(CACAO_LIST_PREPARE, g);
        if (CB.needed_list == 2 && (g.x & 1) == 0 && (g.y & 1) == 0 && touches_needed(g, g + 1))
            append(CACAO_LIST_PREPARE, g / 2);
        /* the non-smart and half applies where listed: the tiles whose quads' pixels, a pixel
         * left (up) where the output's width (height) is odd, touch a needed tile: this one, or
         * that one and the one before */
        if (CB.needed_list == 3 && listed &&
            touches_needed(max(g - ivec2(CB.needed_shift & 1, CB.needed_shift >> 1), ivec2(0)), g))
            append(CACAO_LIST_PREPARE, g);
        /* the caller's normals, the CPU forms without reuse: generate reads the normals of the
         * needed tiles and of one texel around them, the Q3 base pass those of its blocks and one
         * texel around: the tiles within two of an active tile */
        if (CB.normals_list != 0 && touches_needed(g - 1, g + 1)) append(CACAO_LIST_NORMALS, g);
#endif
    } else if (i < t + b) {
        i -= t;
        ivec2 g = ivec2(i % CB.blur_groups_x, i / CB.blur_groups_x);
        ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
        ivec2 lo = g * out_size, hi = lo + out_size - 1; /* its output texels */
        if (blur_group_recomputed(g) && touches_needed(lo / CACAO_TILE, hi / CACAO_TILE)) append(CACAO_LIST_BLUR, g);
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
    if (in_rect(p, imageSize(ssao_image).xy))
        for (int layer = 0; layer < CB.slice_count; ++layer) imageStore(ssao_image, ivec3(p, layer), vec4(1.0, 1.0, 0.0, 0.0));
}
#endif /* FILL */

/* ---- reuse (docs/tiles.md "Reusing the previous frame") ---- */
#if CACAO_PASS == CACAO_PASS_REUSE
layout(local_size_x = CACAO_WG_CLASSIFY, local_size_y = CACAO_WG_CLASSIFY) in;

#if CACAO_VARIANT != CACAO_REUSE_PREFIX && CACAO_VARIANT != CACAO_REUSE_REACH
#define REUSE_NORMALS (CACAO_VARIANT == CACAO_REUSE_DIFF_NORMALS || CACAO_VARIANT == CACAO_REUSE_DIFF_NORMALS_GPU)
/* The least view z of raw depths in [dmin, dmax] (no NaN), as prepare's view_z gives them: z is a
 * ratio of two linear functions of the depth, monotonic between two depths with no pole between,
 * so its least value is at an end (the 1% the reach allows covers a rounding that is not). 0, the
 * nearest (the tile always recomputes), where a pole lies between or an end is behind the camera. */
float least_view_z(float dmin, float dmax)
{
    if (dmin > dmax) return uintBitsToFloat(0x7f800000u); /* no depth that is not NaN: +inf */
    vec2 d = vec2(dmin, dmax);
    vec2 num = CB.depth_unpack.x + CB.depth_unpack_d.x * d, den = CB.depth_unpack.y + CB.depth_unpack_d.y * d;
    vec2 z = num / den;
    return den.x * den.y > 0.0 && all(greaterThanEqual(z, vec2(0.0))) ? min(z.x, z.y) : 0.0;
}

/* The 2x2 pixels whose gather corner is (x + 1, y + 1) (pixels x..x+1, y..y+1) against the copies
 * the previous frame kept, bit for bit (a NaN that stays NaN is unchanged): true where any differs
 * (always on a full frame, CB.reuse 2), after updating the copies. The copies hold each block as
 * one texel per channel, in the order of the gather that reads the block (past the image's edge
 * the gather clamps, the same way every frame): the depth, and the input normals' r, g, b (what
 * prepare reads). Widens [dmin, dmax] by the block's depths that are not NaN. */
bool block_differs(int x, int y, vec2 inv_size, inout vec4 dmin, inout vec4 dmax)
{
    const float inf = uintBitsToFloat(0x7f800000u);
    bool full = CB.reuse == 2, changed = full;
    vec2 uv = vec2(x + 1, y + 1) * inv_size;
    vec4 d4 = textureGather(src_depth, uv, 0);
    ivec2 q = ivec2(x, y) / 2;
    if (full || any(notEqual(floatBitsToUint(d4), floatBitsToUint(imageLoad(depth_history, q))))) {
        imageStore(depth_history, q, d4);
        changed = true;
    }
    bvec4 number = not(isnan(d4));
    dmin = min(dmin, mix(vec4(inf), d4, number));
    dmax = max(dmax, mix(vec4(-inf), d4, number));
#if REUSE_NORMALS
    vec4 nc[3] = vec4[3](textureGather(src_normals, uv, 0), textureGather(src_normals, uv, 1),
                         textureGather(src_normals, uv, 2));
    for (int c = 0; c < 3; ++c) {
        ivec2 h = ivec2(3 * q.x + c, q.y);
        if (full || any(notEqual(floatBitsToUint(nc[c]), floatBitsToUint(imageLoad(normals_history, h))))) {
            imageStore(normals_history, h, nc[c]);
            changed = true;
        }
    }
#endif
    return changed;
}

/* The least and greatest of the depths block_differs gathered into dmin and dmax (lo > hi: none). */
vec2 depth_range(vec4 dmin, vec4 dmax)
{
    return vec2(min(min(dmin.x, dmin.y), min(dmin.z, dmin.w)), max(max(dmax.x, dmax.y), max(dmax.z, dmax.w)));
}

#if CACAO_VARIANT == CACAO_REUSE_DIFF || CACAO_VARIANT == CACAO_REUSE_DIFF_NORMALS
/* The CPU forms: one invocation per tile (lavapipe runs long loops over few invocations well), its
 * blocks in turn. Writes the tile's changed flag (0: changed) and least view z, which the reach
 * pass bounds the taps' radius by. */
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) return;
    ivec2 size = textureSize(src_depth, 0);
    int n = CB.tile_pixels;
    ivec2 p0 = t * n, p1 = min(p0 + n, size);
    vec2 inv_size = 1.0 / vec2(size);
    bool changed = false;
    vec4 dmin = vec4(uintBitsToFloat(0x7f800000u)), dmax = -dmin;
    for (int y = p0.y; y < p1.y; y += 2)
        for (int x = p0.x; x < p1.x; x += 2) changed = block_differs(x, y, inv_size, dmin, dmax) || changed;
    tiles[TILE_REGION(CACAO_TILE_CHANGED) + tile_index(t)] = changed ? 0u : CACAO_TILE_NO_ENTRY;
    vec2 range = depth_range(dmin, dmax);
    tiles[TILE_REGION(CACAO_TILE_ZMIN) + tile_index(t)] = floatBitsToUint(least_view_z(range.x, range.y));
    if (changed) atomicAdd(tiles[CACAO_TILE_COUNT_CHANGED], 1u);
}
#else
/* The GPU forms: one invocation per block, a group of 16x16 pixels (a CACAO tile native, a quarter
 * of one downsampled; 2x2 tiles of the horizon estimators). The group reduces in shared memory (depths as order-preserving keys), then marks
 * its tile (flags the host reset: 0 marks changed, the first mark counts) and lowers its least z
 * (uint order is float order for z >= 0 and +inf). */
shared uint group_changed, group_dmin, group_dmax;

uint order_key(float v) { uint b = floatBitsToUint(v); return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u; }
float key_value(uint k) { return uintBitsToFloat((k & 0x80000000u) != 0u ? k & 0x7fffffffu : ~k); }

void main()
{
    if (gl_LocalInvocationIndex == 0u) {
        group_changed = 0u;
        group_dmin = order_key(uintBitsToFloat(0x7f800000u));
        group_dmax = order_key(-uintBitsToFloat(0x7f800000u));
    }
    barrier();
    ivec2 size = textureSize(src_depth, 0);
    ivec2 p = 2 * ivec2(gl_GlobalInvocationID.xy);
    if (in_rect(p, size)) {
        vec4 dmin = vec4(uintBitsToFloat(0x7f800000u)), dmax = -dmin;
        if (block_differs(p.x, p.y, 1.0 / vec2(size), dmin, dmax)) atomicOr(group_changed, 1u);
        vec2 range = depth_range(dmin, dmax);
        if (range.x <= range.y) {
            atomicMin(group_dmin, order_key(range.x));
            atomicMax(group_dmax, order_key(range.y));
        }
    }
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    /* the tiles of the group's pixels: one (CACAO: 16 or 32 pixels a side), or 2x2 (the horizon
     * estimators' tiles of 8) */
    ivec2 first = ivec2(gl_WorkGroupID.xy) * 16;
    ivec2 t0 = first / CB.tile_pixels, t1 = min((first + 15) / CB.tile_pixels, ivec2(CB.tiles_x, CB.tiles_y) - 1);
    float zmin = least_view_z(key_value(group_dmin), key_value(group_dmax));
    /* unrolled (at most 2x2 tiles: tile_pixels is 8 or more): a GPU compiler knows the count */
    [[unroll]] for (int dy = 0; dy < 2; ++dy)
        [[unroll]] for (int dx = 0; dx < 2; ++dx) {
            if (t0.x + dx > t1.x || t0.y + dy > t1.y) continue;
            uint t = tile_index(t0 + ivec2(dx, dy));
            if (group_changed != 0u && atomicAnd(tiles[TILE_REGION(CACAO_TILE_CHANGED) + t], 0u) != 0u)
                atomicAdd(tiles[CACAO_TILE_COUNT_CHANGED], 1u);
            atomicMin(tiles[TILE_REGION(CACAO_TILE_ZMIN) + t], floatBitsToUint(zmin));
        }
}
#endif
#elif CACAO_VARIANT == CACAO_REUSE_PREFIX
/* One invocation per row of tiles: the changed tiles of the row up to each tile, so that the
 * reach pass counts those of a span of a row with two loads. */
void main()
{
    int row = int(gl_WorkGroupID.x * gl_WorkGroupSize.x * gl_WorkGroupSize.y + gl_LocalInvocationIndex);
    if (row >= CB.tiles_y) return;
    uint changed = TILE_REGION(CACAO_TILE_CHANGED) + uint(row * CB.tiles_x), sums = TILE_REGION(CACAO_TILE_ROW_SUM) +
                   uint(row * CB.tiles_x), sum = 0u;
    /* eight flags loaded before their sums are stored: the loads need not wait on the stores */
    for (int x0 = 0; x0 < CB.tiles_x; x0 += 8) {
        uint flag[8];
        [[unroll]] for (int i = 0; i < 8; ++i) flag[i] = x0 + i < CB.tiles_x ? tiles[changed + uint(x0 + i)] : 1u;
        [[unroll]] for (int i = 0; i < 8; ++i) {
            sum += flag[i] == 0u ? 1u : 0u; /* 0 marks a changed tile */
            if (x0 + i < CB.tiles_x) tiles[sums + uint(x0 + i)] = sum;
        }
    }
}
#else /* CACAO_REUSE_REACH */
/* One invocation per tile. A changed texel reaches the output of tile t through the taps of the
 * texels the blur and apply of t read (those within 2 tiles), at most reuse_tap_reach times
 * their lookup radius, which is largest at their least view z (the near limit only shrinks it),
 * plus reuse_margin texels (mips, edges, normals, blur, apply). t is recomputed when a changed
 * tile lies within that reach (a count over the rows' prefix sums, at most the image's tiles),
 * and where reuse is all or nothing (HIGHEST, whose adaptive pass depends on the whole frame's
 * importance, and the horizon estimators) every tile and blur group when anything changed;
 * full frames record no reach pass (tile_recomputed). A recomputed tile marks the tiles
 * within one tile of it, and the blur groups touching those, for generate, the fills and the
 * blur (group_work, compact). With nothing changed, the gated steps' commands are zeroed: they
 * dispatch nothing. */
void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, ivec2(CB.tiles_x, CB.tiles_y))) return;
    uint changed_tiles = tiles[CACAO_TILE_COUNT_CHANGED]; /* the host's count on a frame without a diff */
    if (changed_tiles == 0u) {
        if (t == ivec2(0))
            for (int g = 0; g < CB.gate_count; ++g) tiles[TILE_REGION(CACAO_TILE_GATES) + uint(3 * g)] = 0u;
        return;
    }
    if (CB.reuse_all_or_nothing != 0) {
        /* every tile and blur group (there are no more groups than tiles): plain stores, where
         * marking around each tile took nine atomics and more per tile */
        uint i = tile_index(t);
        tiles[recompute_base() + i] = 0u;
        if (i < uint(CB.blur_groups_x * CB.blur_groups_y)) tiles[blur_recompute_base() + i] = 0u;
        if (t == ivec2(0)) tiles[CACAO_TILE_COUNT_RECOMPUTE] = uint(CB.tiles_x * CB.tiles_y);
        return;
    }
    ivec2 last = ivec2(CB.tiles_x, CB.tiles_y) - 1;
    float zmin = uintBitsToFloat(0x7f800000u);
    for (int y = max(t.y - 2, 0); y <= min(t.y + 2, last.y); ++y)
        for (int x = max(t.x - 2, 0); x <= min(t.x + 2, last.x); ++x)
            zmin = min(zmin, uintBitsToFloat(tiles[TILE_REGION(CACAO_TILE_ZMIN) + tile_index(ivec2(x, y))]));
    /* generate's radius in texels, lookup factor r near_mod / texel size, is largest at the
     * least z: near_mod = sat(|p| near_limit_rec) 0.8 + 0.2 with |p| <= z near_k */
    float texel = view_xy_scale(zmin) * abs(CB.ndc_to_view_mul.x) * CB.ssao_buffer_inverse_dimensions.x;
    float near_mod = sat(zmin * CB.reuse_near_k * CB.effect_sampling_radius_near_limit_rec) * CACAO_NEAR_LIMIT_SCALE +
                     CACAO_NEAR_LIMIT_BIAS;
    float reach = CB.reuse_tap_reach * (CACAO_LOOKUP_RADIUS_FACTOR * CB.effect_radius * near_mod / texel) +
                  float(CB.reuse_margin);
    /* tiles t and c, d tiles apart (Chebyshev), are (d - 1) TILE + 1 texels apart at least */
    float r = floor((reach - 1.0) / float(CACAO_TILE)) + 1.0;
    /* a reach past the image's tiles counts them all (also inf and NaN: z 0) */
    int k = r <= float(max(CB.tiles_x, CB.tiles_y)) ? int(r) : max(CB.tiles_x, CB.tiles_y);
    uint sums = TILE_REGION(CACAO_TILE_ROW_SUM), count = 0u;
    int x1 = min(t.x + k, last.x), x0 = t.x - k - 1;
    for (int y = max(t.y - k, 0); y <= min(t.y + k, last.y); ++y) {
        uint row = uint(y * CB.tiles_x);
        count += tiles[sums + row + uint(x1)] - (x0 >= 0 ? tiles[sums + row + uint(x0)] : 0u);
    }
    if (count == 0u) return;
    atomicAdd(tiles[CACAO_TILE_COUNT_RECOMPUTE], 1u);
    mark_around(t, recompute_base(), blur_recompute_base());
}
#endif
#endif /* REUSE */
