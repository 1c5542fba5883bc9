/* prepare.glsl - the prepare passes: the deinterleaved depths (and mips) and normals. */

/* ============================== PREPARE_DEPTHS, PREPARE, PREPARE_GPU ============================== */
#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS || CACAO_PASS == CACAO_PASS_PREPARE || CACAO_PASS == CACAO_PASS_PREPARE_GPU
/* spec: prepare.md "Which full-resolution pixels each slice keeps", "Depth mips". PREPARE, the
 * fused pass, writes the depths (and mips) of its variant and the normals from depth. */
layout(local_size_x = CACAO_WG_PREPARE_X, local_size_y = CACAO_WG_PREPARE_Y) in;

/* HALF and FULL: one slice texel per invocation. MIPS: a 2x2 quad of slice texels per invocation
 * (2u .. 2u + 1, all slices; the pass row halves its grid), so a group covers 2T x 2T texels: the
 * first mip level comes from registers, and only levels 2 and 3 go through shared memory and
 * barriers, which lavapipe runs slowly (shared loads lane by lane, barriers by switching between
 * the group's invocations; docs/speed-notes.md has the measurement). */
/* The mips in the atlas (the CPU forms) or as the image's mip levels (PREP_MIP_CHAIN: the GPU
 * forms, prepare_depths.mips_chain and prepare_gpu.mips). */
#if CACAO_VARIANT == CACAO_DEPTHS_MIPS_CHAIN || (CACAO_PASS == CACAO_PASS_PREPARE_GPU && CACAO_VARIANT == CACAO_DEPTHS_MIPS)
#define PREP_MIP_CHAIN 1
#else
#define PREP_MIP_CHAIN 0
#endif
#if CACAO_VARIANT == CACAO_DEPTHS_MIPS || CACAO_VARIANT == CACAO_DEPTHS_MIPS_CHAIN
#define PREP_MIPS 1
#else
#define PREP_MIPS 0
#endif
#if PREP_MIPS
/* Per-slice tiles of levels 1 and 2 of this group, fp32 (AMD does not re-quantise between levels).
 * Levels 1..3 of the group's tile are T, T/2 and T/4 texels wide, and the reduction below gives
 * each step's texels to the first threads: written for T = 8. */
#define PREP_T CACAO_WG_PREPARE_X
#if CACAO_WG_PREPARE_X != 8 || CACAO_WG_PREPARE_Y != 8
#error "prepare_depths.mips reduces a 16x16 tile of an 8x8 workgroup to mips 1..3 (2x2 texels at mip 3): rewrite its reduction for another CACAO_WG_PREPARE size"
#endif
shared float lds_mip1[4][PREP_T * PREP_T];
shared float lds_mip2[4][(PREP_T / 2) * (PREP_T / 2)];

/* Depth-aware average; F = -1 ([quirk] MIP-WEIGHT-PRECEDENCE kept). */
float smart_average(float d0, float d1, float d2, float d3)
{
    float m = min(min(d0, d1), min(d2, d3));
    vec4 d = vec4(d0, d1, d2, d3);
    vec4 dm = d - m;
    vec4 w = sat(1.0 + (CACAO_MIP_WEIGHT_FALLOFF) * dm * dm);
    return dot(w, d) / dot(w, vec4(1.0));
}

/* Texel p of level 1..3 into its place in the atlas (cacao_shared.h), or into its level of the
 * chain (PREP_MIP_CHAIN); levels beyond the slice's
 * chain (CACAO_DEPTH_MIP_LEVELS) are not stored. */
void store_mip(int level, ivec2 p, int layer, float z)
{
    ivec2 s0 = slice_size();
    if (level >= CACAO_DEPTH_MIP_LEVELS(max(s0.x, s0.y))) return;
    ivec4 lv = depth_atlas_level(s0, level);
#if PREP_MIP_CHAIN
    /* level l's own view (a chain shorter than 3 levels binds its last level's view to the slots
     * past it, which the test above never reaches) */
    if (!in_rect(p, lv.xy)) return;
    if (level == 1) imageStore(depths_mip1, ivec3(p, layer), vec4(z));
    else if (level == 2) imageStore(depths_mip2, ivec3(p, layer), vec4(z));
    else imageStore(depths_mip3, ivec3(p, layer), vec4(z));
#else
    if (in_rect(p, lv.xy)) imageStore(depths_image, ivec3(lv.zw + p, layer), vec4(z));
#endif
}

/* The 2x2 level-l texels 2q .. 2q + 1 of tile[k] (row-major, w wide) reduced to one texel of
 * level l + 1; the argument order is the one every level uses: (0,0), (0,1), (1,0), (1,1). */
#define REDUCE_QUAD(tile, k, q, w)                                                                 \
    smart_average(tile[k][(2 * (q).y) * (w) + 2 * (q).x], tile[k][(2 * (q).y + 1) * (w) + 2 * (q).x], \
                  tile[k][(2 * (q).y) * (w) + 2 * (q).x + 1], tile[k][(2 * (q).y + 1) * (w) + 2 * (q).x + 1])

/* Levels 1..3 of the group's tile from every invocation's quad: z[q][k] is level 0 at texel
 * 2u + (q & 1, q >> 1) of slice k, also past the slice's edge (clamped values), since the levels
 * above average them. Every invocation of the group calls it (barriers). */
void reduce_mips(ivec2 u, vec4 z[4])
{
    int li = int(gl_LocalInvocationIndex);
    ivec2 g = ivec2(gl_WorkGroupID.xy);
    /* level 1: texel u of each slice, from this thread's quad */
    [[unroll]] for (int k = 0; k < 4; ++k) {
        float m = smart_average(z[0][k], z[2][k], z[1][k], z[3][k]);
        lds_mip1[k][li] = m;
        store_mip(1, u, k, m);
    }
    barrier();

    { /* level 2: 4 slices x 4x4 texels = 64 work items, one per thread */
        int k = li / 16;
        ivec2 q = ivec2(li % 4, (li % 16) / 4);
        float m = REDUCE_QUAD(lds_mip1, k, q, PREP_T);
        lds_mip2[k][q.y * (PREP_T / 2) + q.x] = m;
        store_mip(2, g * (PREP_T / 2) + q, k, m);
    }
    barrier();

    if (li < 16) { /* level 3: 4 slices x 2x2 texels */
        int k = li / 4;
        ivec2 q = ivec2(li % 2, (li % 4) / 2);
        store_mip(3, g * (PREP_T / 4) + q, k, REDUCE_QUAD(lds_mip2, k, q, PREP_T / 2));
    }
}
#endif

/* View z of slice texel t in the four slices, from clamp-to-edge reads (the footprint AMD's
 * gather / point samples intend). */
vec4 slice_depths(ivec2 t)
{
#if CACAO_DOWNSAMPLED == 0
    /* Native: slice k holds pixel 2t + (k & 1, k >> 1), so the four are one 2x2 gather, taken at
     * the texels' shared corner (see prepare_normals). Gather order: x = (0,1), y = (1,1),
     * z = (1,0), w = (0,0). */
    vec4 raw = textureGather(src_depth, vec2(2 * t + 1) * CB.depth_buffer_inverse_dimensions, 0).wzxy;
    return vec4(view_z(raw.x), view_z(raw.y), view_z(raw.z), view_z(raw.w));
#else
    return vec4(view_z(load_src_depth_clamped(full_res_pixel(t, 0))), view_z(load_src_depth_clamped(full_res_pixel(t, 1))),
                view_z(load_src_depth_clamped(full_res_pixel(t, 2))), view_z(load_src_depth_clamped(full_res_pixel(t, 3))));
#endif
}

void store_slices(ivec2 t, vec4 z)
{
    [[unroll]] for (int k = 0; k < 4; ++k) imageStore(depths_image, ivec3(t, k), vec4(z[k]));
}

#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS
void main()
{
#if CACAO_HOISTS_CONSTANTS
    hoist_constants();
#endif
    ivec2 s = slice_size();
#if CACAO_VARIANT == CACAO_DEPTHS_HALF
    /* LOWEST: slices 0 and 3 in layers 0 and 1; integer loads, OOB -> raw 0 (z = M/A). */
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, s)) return;
    imageStore(depths_image, ivec3(t, 0), vec4(view_z(load_src_depth_or_zero(full_res_pixel(t, 0)))));
    imageStore(depths_image, ivec3(t, 1), vec4(view_z(load_src_depth_or_zero(full_res_pixel(t, 3)))));
#elif CACAO_VARIANT == CACAO_DEPTHS_FULL
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, s)) return;
    store_slices(t, slice_depths(t));
#else
    /* The quad 2u .. 2u + 1; every texel of it is computed, also past the slice's edge (clamped
     * values), since the levels above average them. z[q][k]: texel 2u + (q & 1, q >> 1), slice k. */
    ivec2 u = ivec2(gl_GlobalInvocationID.xy);
    vec4 z[4];
    [[unroll]] for (int q = 0; q < 4; ++q) {
        ivec2 t = quad_texel(u, q);
        z[q] = slice_depths(t);
        if (in_rect(t, s)) store_slices(t, z[q]);
    }
    reduce_mips(u, z);
#endif
}
#endif /* PREPARE_DEPTHS main */

#if CACAO_PASS == CACAO_PASS_PREPARE || CACAO_PASS == CACAO_PASS_PREPARE_GPU
/* Slices the variant keeps: all four, or (HALF, LOWEST) slices 0 and 3 in layers 0 and 1. */
#if CACAO_VARIANT == CACAO_DEPTHS_HALF
#define PREP_SLICE_STEP 3
#else
#define PREP_SLICE_STEP 1
#endif

/* The GPU form's own path (PREPARE_GPU): FULL and MIPS native, FULL downsampled. HALF's two slices
 * (0 and 3) have no neighbours in common, and MIPS downsampled held more registers than gfx11
 * gives it without spilling: those take the shared form's code (the same module as PREPARE's). */
#if CACAO_PASS == CACAO_PASS_PREPARE_GPU && CACAO_VARIANT != CACAO_DEPTHS_HALF && \
    !(CACAO_VARIANT == CACAO_DEPTHS_MIPS && CACAO_DOWNSAMPLED == 1)
#define PREP_GPU_PATH 1
#else
#define PREP_GPU_PATH 0
#endif
/* The normals' loop that normalises each direction between neighbouring entries once (main): the
 * GPU form's path, and the CPU form's keys but HALF's, whose two slices share no neighbour. HALF
 * (either form) and the GPU form's MIPS downsampled take the loop with a normalisation a
 * neighbour. */
#define PREP_SHARED_DIRECTIONS (PREP_GPU_PATH || (CACAO_PASS == CACAO_PASS_PREPARE && CACAO_VARIANT != CACAO_DEPTHS_HALF))

/* Entry (i, j) = o + 1 of the block: its view z (read with clamp to edge) and view position. d:
 * its raw depth, gathered (native); downsampled, the entry loads its own (d unused). */
void prep_entry(ivec2 u, ivec2 o, float d, vec2 inv, ivec2 src_size, float z0, out float zc, out vec3 pos)
{
#if CACAO_DOWNSAMPLED == 1
    /* the normals' loads are integer loads: OOB -> raw 0 ([quirk] DOWNSAMPLED-NORMAL-OOB kept); the
     * depths' are clamped */
    ivec2 px = 8 * u + 2 * o;
    zc = view_z(load_src_depth_clamped(px));
    vec2 uv = (vec2(8 * u) + 0.5 + 2.0 * vec2(o)) * inv;
    pos = view_pos(uv, in_rect(px, src_size) ? zc : z0);
#else
    zc = view_z(d);
    vec2 uv = (vec2(4 * u) + 0.5 + vec2(o)) * inv;
    pos = view_pos(uv, zc);
#endif
}

#if CACAO_DOWNSAMPLED == 1
#define PREP_DEPTH(dz, row, col) 0.0 /* prep_entry loads it */
#else
#define PREP_DEPTH(dz, row, col) dz[row][col]
#endif

#if PREP_GPU_PATH
/* The GPU form's entries, two rows at a time (rows 2 gj and 2 gj + 1 of main's block), so that a
 * row is computed when the raster order first needs it and few rows are live at once (a GPU keeps
 * them in registers: gfx11 spilled with all 32 live). The same reads and arithmetic as main's
 * loops below. */
void prep_rows(ivec2 u, int gj, vec2 inv, ivec2 src_size, float z0, inout vec3 pos[6][6], inout float zc[6][6])
{
#if CACAO_DOWNSAMPLED == 0
    float dz[2][6];
    [[unroll]] for (int gi = 0; gi < 3; ++gi) {
        vec4 g4 = textureGather(src_depth, vec2(4 * u + 2 * ivec2(gi, gj)) * inv, 0);
        dz[0][2 * gi] = g4.w;
        dz[0][2 * gi + 1] = g4.z;
        dz[1][2 * gi] = g4.x;
        dz[1][2 * gi + 1] = g4.y;
    }
#endif
    [[unroll]] for (int r = 0; r < 2; ++r) {
        int j = 2 * gj + r;
        [[unroll]] for (int i = 0; i < 6; ++i) {
            pos[j][i] = vec3(0.0);
            zc[j][i] = 0.0;
            if ((i == 0 || i == 5) && (j == 0 || j == 5)) continue;
            prep_entry(u, ivec2(i - 1, j - 1), PREP_DEPTH(dz, r, i), inv, src_size, z0, zc[j][i], pos[j][i]);
        }
    }
}
#endif

/* The GPU form's native keys classify the tiles of the texels they store (tiles.glsl, the
 * classify pass's rules), which spares the frame the classify pass's dispatch and barrier (an H200
 * ran CACAO HIGH at 960x540 in 74 instead of 80 microseconds: docs/gpu.md). A group's 8x8
 * invocations of 2x2 texels cover 2x2 tiles; an invocation's quad lies in one of them. The
 * downsampled keys classify in groups of their own (main): with the classification in the
 * prepare's code, gfx11 spilled two registers of their unrolled block, however it was placed. */
#define PREP_CLASSIFIES (CACAO_PASS == CACAO_PASS_PREPARE_GPU && CACAO_DOWNSAMPLED == 0)
#if PREP_CLASSIFIES
#if CACAO_TILE != 8 || CACAO_WG_PREPARE_X != 8 || CACAO_WG_PREPARE_Y != 8
#error "prepare_gpu classifies the 2x2 tiles of an 8x8 group of 2x2 texels: rewrite it for other sizes"
#endif
/* The least view z this invocation stores: +inf for none, -inf where one is NaN (NaN, like -inf,
 * is neither quiet nor background). */
float g_zmin = uintBitsToFloat(0x7f800000u);

void classify_texel(float z) { g_zmin = min(g_zmin, isnan(z) ? uintBitsToFloat(0xff800000u) : z); }

/* Every invocation of the group calls it, after main's stores (barriers). Being quiet is
 * monotonic in z (background at or past background_z; faded where (z mod) mul + add is below
 * -margin, and mul is negative), so some texel is not quiet, or not background, where the least is.
 * The least as the R16F store keeps it, whichever way the store rounds, is at least the least less
 * 2^-10 of it (a half's step; 1% more for the ulps of the arithmetic): its flags are a superset of
 * the stored texels', which can call a tile active that the classify pass would not (a texel
 * within 2^-10 of a threshold), never the other way. */
void classify_group()
{
    uint flags = g_zmin > 0.0 && isinf(g_zmin) ? 0u : slice_z_flags(quiet_floor(g_zmin)); /* +inf: no texel */
    classify_group_begin(2);
    classify_group_flag(2, ivec2(gl_LocalInvocationID.xy) / 4, flags);
    classify_group_end(2 * ivec2(gl_WorkGroupID.xy), 2);
}
#define CLASSIFY_TEXEL(z) classify_texel(z)
#else
#define CLASSIFY_TEXEL(z)
#endif

/* The fused prepare, for normals from depth: the 2x2 quad of slice texels 2u .. 2u + 1 (the pass
 * row halves the grid), all kept slices, its depths (and with MIPS the levels above) and its
 * normals from one block of full-res depths. Each texel's normals need a 4x4 block of full-res
 * depths without its corners, whose inner 2x2 are the texel's four slice depths; the quad's blocks
 * overlap in one 6x6 block (without its corners): 32 reads instead of 4 x 12, and the depths
 * come with it (docs/speed-notes.md). No early return: the mips reduction has barriers (but the
 * GPU form's classification groups downsampled, a whole group each). */
void main()
{
#if CACAO_HOISTS_CONSTANTS
    hoist_constants();
#endif
#if CACAO_PASS == CACAO_PASS_PREPARE_GPU && CACAO_DOWNSAMPLED == 1
    /* groups z 0 classify the tiles from the caller's depth (tiles.glsl), groups z 1 prepare: one
     * dispatch (a pass of its own cost an H200 its dispatch, docs/gpu.md), and the prepare's code
     * holds no classification (in it, gfx11 spilled) */
    if (gl_WorkGroupID.z == 0u) {
        classify_from_depth(ivec2(gl_WorkGroupID.xy));
        return;
    }
#endif
    ivec2 u = ivec2(gl_GlobalInvocationID.xy);
    ivec2 s = slice_size();
    ivec2 src_size = textureSize(src_depth, 0);
    vec2 inv = CB.depth_buffer_inverse_dimensions;
    float z0 = view_z(0.0); /* raw depth 0: an out-of-bounds integer load (D3D rule) */
    /* pos[j][i] = column i, row j; the full-res pixel of entry (i, j) is 4u - 1 + (i, j) native,
     * 8u + 2 (i - 1, j - 1) downsampled. zc: view z of the entry read with clamp to edge. */
    vec3 pos[6][6];
    float zc[6][6];
#if PREP_GPU_PATH
    prep_rows(u, 0, inv, src_size, z0, pos, zc); /* rows 2 .. 5 as the loop below reaches them */
#else
#if CACAO_DOWNSAMPLED == 0
    /* Native: in nine gathers (one sampler operation per 2x2, clamp-to-edge like
     * load_src_depth_clamped), not 32 loads. Each gather is taken at the shared corner of its 2x2
     * texels, exactly representable, so the texels are the intended ones. Gather order: x = (0,1),
     * y = (1,1), z = (1,0), w = (0,0). */
    float dz[6][6];
    [[unroll]] for (int gj = 0; gj < 3; ++gj) {
        [[unroll]] for (int gi = 0; gi < 3; ++gi) {
            vec4 g4 = textureGather(src_depth, vec2(4 * u + 2 * ivec2(gi, gj)) * inv, 0);
            dz[2 * gj][2 * gi] = g4.w;
            dz[2 * gj][2 * gi + 1] = g4.z;
            dz[2 * gj + 1][2 * gi] = g4.x;
            dz[2 * gj + 1][2 * gi + 1] = g4.y;
        }
    }
#endif
    /* fully unrolled: with constant indices the arrays live in registers (a dynamically indexed
     * local array is copied to memory on lavapipe) */
    [[unroll]] for (int j = 0; j < 6; ++j) {
        [[unroll]] for (int i = 0; i < 6; ++i) {
            pos[j][i] = vec3(0.0);
            zc[j][i] = 0.0;
            if ((i == 0 || i == 5) && (j == 0 || j == 5)) continue;
            prep_entry(u, ivec2(i - 1, j - 1), PREP_DEPTH(dz, j, i), inv, src_size, z0, zc[j][i], pos[j][i]);
        }
    }
#endif

    vec4 z[4]; /* z[q][k]: level 0 at quad texel q, slice k (the mips' input) */
#if PREP_SHARED_DIRECTIONS
    /* The unit direction between two neighbouring entries is normalised once, for both normals
     * that use it (40 normalisations instead of 64); the other normal takes its negation, which is
     * exactly the direction the other way (a - b = -(b - a), and normalize(-v) = -normalize(v)):
     * the same output. The centres go row by row, so that only the directions of two rows are
     * live (a GPU keeps them in registers: fewer of them, more waves). The CPU form has computed
     * every entry before. Never HALF (PREP_SHARED_DIRECTIONS). */
    [[unroll]] for (int q = 0; q < 4; ++q) z[q] = vec4(0.0);
    vec3 up[5]; /* up[i]: from entry (i, cj - 1) down to (i, cj) */
    [[unroll]] for (int i = 1; i < 5; ++i) up[i] = normalize(pos[1][i] - pos[0][i]);
    [[unroll]] for (int cj = 1; cj < 5; ++cj) {
#if PREP_GPU_PATH
        if (cj == 1 || cj == 3) prep_rows(u, (cj + 1) / 2, inv, src_size, z0, pos, zc); /* rows cj + 1 .. cj + 2 */
#endif
        vec3 right[5], down[5]; /* from entry (i, cj) to (i + 1, cj), and to (i, cj + 1) */
        [[unroll]] for (int i = 0; i < 5; ++i) right[i] = normalize(pos[cj][i + 1] - pos[cj][i]);
        [[unroll]] for (int i = 1; i < 5; ++i) down[i] = normalize(pos[cj + 1][i] - pos[cj][i]);
        [[unroll]] for (int ci = 1; ci < 5; ++ci) {
            int k = ((ci - 1) & 1) + 2 * ((cj - 1) & 1); /* the slice, and the quad texel: */
            int q = ((ci - 1) >> 1) + 2 * ((cj - 1) >> 1);
            int layer = k / PREP_SLICE_STEP;
            ivec2 t = quad_texel(u, q);
            z[q][k] = zc[cj][ci];
            vec3 pc = pos[cj][ci];
            vec4 e = depth_edges(pc.z, pos[cj][ci - 1].z, pos[cj][ci + 1].z, pos[cj - 1][ci].z, pos[cj + 1][ci].z);
            vec3 n = normal_from_neighbours(-right[ci - 1], right[ci], -up[ci], down[ci], e);
            if (in_rect(t, s)) {
                imageStore(depths_image, ivec3(t, layer), vec4(z[q][k]));
                imageStore(normals_image, ivec3(t, layer), vec4(n, 1.0));
                CLASSIFY_TEXEL(z[q][k]);
            }
        }
        [[unroll]] for (int i = 1; i < 5; ++i) up[i] = down[i];
    }
#else
    [[unroll]] for (int q = 0; q < 4; ++q) {
        ivec2 t = quad_texel(u, q);
        ivec2 qo = t - 2 * u;
        bool inside = in_rect(t, s);
        z[q] = vec4(0.0);
        [[unroll]] for (int k = 0; k < 4; k += PREP_SLICE_STEP) {
            int layer = k / PREP_SLICE_STEP;
            /* centre: (1,1) for slice 0 ... (2,2) for slice 3, of the texel's 4x4 block */
            int ci = 1 + (k & 1) + 2 * qo.x, cj = 1 + (k >> 1) + 2 * qo.y;
            z[q][k] = zc[cj][ci];
#if CACAO_VARIANT == CACAO_DEPTHS_HALF
            /* LOWEST's depths: integer loads, OOB -> raw 0 (z = M/A) */
            if (!in_rect(full_res_pixel(t, k), src_size)) z[q][k] = z0;
#endif
            vec3 pc = pos[cj][ci];
            vec3 pl = pos[cj][ci - 1], pr = pos[cj][ci + 1];
            vec3 pt = pos[cj - 1][ci], pb = pos[cj + 1][ci];
            vec4 e = depth_edges(pc.z, pl.z, pr.z, pt.z, pb.z);
            vec3 n = normal_from_neighbours(normalize(pl - pc), normalize(pr - pc), normalize(pt - pc),
                                            normalize(pb - pc), e);
            if (inside) {
                imageStore(depths_image, ivec3(t, layer), vec4(z[q][k]));
                imageStore(normals_image, ivec3(t, layer), vec4(n, 1.0));
                CLASSIFY_TEXEL(z[q][k]);
            }
        }
    }
#endif
#if PREP_MIPS
    reduce_mips(u, z);
#endif
#if PREP_CLASSIFIES
    classify_group();
#endif
}
#endif /* PREPARE, PREPARE_GPU main */
#endif /* PREPARE_DEPTHS, PREPARE, PREPARE_GPU */

/* ============================== PREPARE_NORMALS ============================== */
#if CACAO_PASS == CACAO_PASS_PREPARE_NORMALS
/* spec: prepare.md "Normals from input normals" (normals from depth: the fused PREPARE above) */
layout(local_size_x = CACAO_WG_PREPARE_X, local_size_y = CACAO_WG_PREPARE_Y) in;

void main()
{
#if CACAO_HOISTS_CONSTANTS
    hoist_constants();
#endif
    ivec2 g; /* listed: a tile (the group's 8x8 texels) */
    if (!group_of(g)) return;
    ivec2 t = texel_of(g);
    if (!in_rect(t, imageSize(normals_image).xy)) return; /* no side effects: no LDS, no atomics */
    ivec2 size = textureSize(src_normals, 0);
    [[unroll]] for (int layer = 0; layer < 4; ++layer) {
        if (layer >= CB.slice_count) break;
        imageStore(normals_image, ivec3(t, layer), vec4(input_normal(t, layer, size), 1.0));
    }
}
#endif /* PREPARE_NORMALS */
