#version 450
#extension GL_GOOGLE_include_directive : enable
#extension GL_EXT_control_flow_attributes : enable
#if defined(CACAO_FP16) && CACAO_FP16 == 1
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : enable
#endif
#include "cacao_shared.h"

/* cacao.comp - every CACAO compute pass in one templated source (spec: README.md "Pass graph").
 *
 * The generator defines CACAO_GLSL, CACAO_PASS, CACAO_VARIANT, CACAO_DOWNSAMPLED,
 * CACAO_BLUR_PASSES and CACAO_FP16 (all integers). Each pass below has its own main() and
 * declares only the bindings it uses, so reflection of a module shows exactly its resources.
 *
 * Out-of-bounds behaviour: AMD relies on D3D rules (an out-of-range integer load returns 0, an
 * out-of-range store is dropped). Every load and store below that can leave its image is
 * bounds-checked explicitly, so nothing depends on robustImageAccess.
 *
 * ---- fp16 variant (CACAO_FP16 == 1; blur, apply and upsample only) ----
 * All texture coordinates, texel indices and view-space depths stay fp32 in every pass: UVs need
 * more than 11 bits of mantissa at 1080p and view depth reaches thousands of units.
 *  - blur: AO values (in [0,1]) are stored in shared memory as float16_t and blurred in half;
 *    the unpacked edge weights (in [0,1] after the saturate) are stored as f16vec4. The kernel
 *    sum of weights is at most 0.5 + 4 = 4.5 and the weighted sum at most 4.5, far inside the
 *    half range; the spacing of half near 1 (2^-11) is 8x finer than the 8-bit output step.
 *    (AMD keeps these values as half between iterations in both of its variants.)
 *  - apply: the fetched AO values, unpacked edges (in [0,1]), the edge-derived sample shifts
 *    (in [-1,1]) and the blend weights (each <= 1, sum <= 4) are half; the shifts are widened
 *    to fp32 before they enter the UV arithmetic.
 *  - upsample: table values (AO in [0,1]) and the weight accumulators are half: each weight is
 *    wS*wZ <= 1 and the sum over 25 taps plus the 1e-3 epsilon is <= 25.001, the weighted AO
 *    sum is <= the weight sum. The exponentials and the depth differences are computed in fp32
 *    (AMD's 16-bit variant does the depth difference in half; fp32 is safer because view depths
 *    above ~2000 would lose all bilateral discrimination in half, and depths above 65504 would
 *    overflow). The table depths come from the R16F deinterleaved-depth texture, so storing
 *    them as fp32 loses nothing.
 * The fp32 variant does everything in fp32; values that AMD keeps in half-precision shared
 * memory (blur values, upsample table values) are rounded through half there too so that the
 * two variants and AMD see the same stored values.
 */

#if !defined(CACAO_PASS) || !defined(CACAO_VARIANT) || !defined(CACAO_DOWNSAMPLED) || \
    !defined(CACAO_BLUR_PASSES) || !defined(CACAO_FP16)
#error "cacao.comp needs CACAO_PASS, CACAO_VARIANT, CACAO_DOWNSAMPLED, CACAO_BLUR_PASSES, CACAO_FP16"
#endif

/* ---- Precision of the "real" values (fp16 variant: half) ---- */
#if CACAO_FP16 == 1
#define rfloat float16_t
#define rvec2 f16vec2
#define rvec4 f16vec4
#else
#define rfloat float
#define rvec2 vec2
#define rvec4 vec4
#endif

/* ============================== shared helpers ============================== */

float sat(float x) { return clamp(x, 0.0, 1.0); }
vec4 sat(vec4 x) { return clamp(x, vec4(0.0), vec4(1.0)); }

/* D3D's max(0, x): a NaN operand yields the other operand, i.e. 0. */
float max0(float x) { return x > 0.0 ? x : 0.0; }

/* Layer of a 2D-array resource -> slice index k (spec: README "Notation"). */
int slice_of_layer(int layer) { return CB.slice_count == 2 ? layer * 3 : layer; }

/* Round a value to half precision and back: mirrors AMD's half-precision shared memory. */
float round_to_half(float x) { return unpackHalf2x16(packHalf2x16(vec2(x, 0.0))).x; }

/* Raw hardware depth -> positive view-space z (spec: prepare.md "Depth linearisation").
 * A depth that gives no finite positive z (NaN in the depth buffer, d == A on an infinite far
 * plane, d beyond the far plane) becomes CACAO_MAX_VIEW_Z: far background, which the fade-out
 * removes. AMD divides blindly there ([quirk] INF-DEPTH); finite depths are unchanged. */
float view_z(float d)
{
    float z = (CB.depth_unpack.x + CB.depth_unpack_d.x * d) / (CB.depth_unpack.y + CB.depth_unpack_d.y * d);
    return (z >= 0.0 && z < CACAO_MAX_VIEW_Z) ? z : CACAO_MAX_VIEW_Z;
}

/* View xy per unit of (ndc_to_view_mul * uv + add): z for a perspective projection, 1 for an
 * orthographic one. */
float view_xy_scale(float z) { return CB.view_xy_z.x * z + CB.view_xy_z.y; }

/* Screen UV + view z -> view-space position (spec: README "P(uv, z)"). */
vec3 view_pos(vec2 uv, float z) { return vec3((CB.ndc_to_view_mul * uv + CB.ndc_to_view_add) * view_xy_scale(z), z); }

/* Edge weights toward L, R, T, B (spec: prepare.md "Edges"); 1 = no edge. */
vec4 depth_edges(float c, float l, float r, float t, float b)
{
    vec4 d = vec4(l, r, t, b) - c;
    vec4 ds = d + d.yxwz; /* each difference plus its opposite: slope compensation */
    vec4 e = min(abs(d), abs(ds));
    return sat(CACAO_EDGE_SLOPE - e / (CACAO_EDGE_DEPTH_FRACTION * (CB.edge_depth.x * c + CB.edge_depth.y)));
}

/* Normal from the unit directions towards the left, right, top and bottom neighbours, each
 * cross product weighted by the edges of its two directions (spec: prepare.md "Normals
 * reconstructed from depth"); camera-facing (negative z) in cacao's view space. */
vec3 normal_from_neighbours(vec3 l, vec3 r, vec3 u, vec3 b, vec4 e)
{
    vec4 a = vec4(e.x * e.z, e.z * e.y, e.y * e.w, e.w * e.x);
    vec3 n = vec3(0.0, 0.0, CACAO_NORMAL_BIAS_Z) + a.x * cross(l, u) + a.y * cross(u, r) + a.z * cross(r, b) +
             a.w * cross(b, l);
    return normalize(n);
}

/* Per-sample obscurance (spec: generate.md "Obs"). max0 keeps D3D's NaN rule for a zero delta. */
float obscurance(vec3 n, vec3 delta, float falloff, float horizon)
{
    float len2 = dot(delta, delta);
    float cos_a = dot(n, delta) / sqrt(len2);
    return max0(cos_a - horizon) * max0(1.0 + len2 * falloff);
}

/* 2 bits per direction, LRTB -> one UNORM8 value (spec: generate.md step 10b). */
float pack_edges(vec4 e)
{
    e = roundEven(sat(e) * CACAO_EDGE_PACK_SCALE);
    return dot(e, vec4(64.0, 16.0, 4.0, 1.0)) / 255.0;
}

/* Packed UNORM8 edges -> the 8-bit integer (exact for k/255 inputs). */
uint edges_bits(float packed_value) { return uint(packed_value * 255.5); }

/* Integer edge bits -> LRTB weights plus InvSharpness (spec: generate.md "UnpackEdges"). */
rvec4 unpack_edge_bits(uint v)
{
    rvec4 e = rvec4(uvec4(v >> 6u, v >> 4u, v >> 2u, v) & uvec4(3u)) / rfloat(3.0);
    return clamp(e + rfloat(CB.inv_sharpness), rvec4(0.0), rvec4(1.0));
}
rvec4 unpack_edges(float packed_value) { return unpack_edge_bits(edges_bits(packed_value)); }

bool in_rect(ivec2 p, ivec2 size) { return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, size)); }

/* The slice (deinterleaved depths at level 0, normals, AO) in texels. The depth image can be
 * larger: at HIGH and HIGHEST it is the atlas of the mip chain (cacao_shared.h). */
ivec2 slice_size() { return ivec2(CB.slice_width, CB.slice_height); }

/* Level l of the depth atlas of a slice of size s0 (cacao_shared.h): (width, height, x, y). */
ivec4 depth_atlas_level(ivec2 s0, int l)
{
    return ivec4(CACAO_DEPTH_LEVEL_EXTENT(s0.x, l), CACAO_DEPTH_LEVEL_EXTENT(s0.y, l), l == 0 ? 0 : s0.x,
                 CACAO_DEPTH_ATLAS_Y(s0.y, l));
}

/* Texel q = 0..3 of the 2x2 quad 2u .. 2u + 1 that one invocation of a quad pass computes. */
ivec2 quad_texel(ivec2 u, int q) { return 2 * u + ivec2(q & 1, q >> 1); }

/* Mirror addressing (-1 -> 0, -2 -> 1, n -> n-1, ...), clamped for padding wider than n. */
int mirror_coord(int c, int n)
{
    if (c < 0) c = -c - 1;
    if (c >= n) c = 2 * n - c - 1;
    return clamp(c, 0, n - 1);
}
ivec2 mirror_coord(ivec2 c, ivec2 n) { return ivec2(mirror_coord(c.x, n.x), mirror_coord(c.y, n.y)); }

/* ============================== resources ============================== */

#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS || CACAO_PASS == CACAO_PASS_PREPARE || CACAO_PASS == CACAO_PASS_UPSAMPLE
layout(set = 0, binding = CACAO_BINDING_SRC_DEPTH) uniform sampler2D src_depth;

/* The caller's depth at pixel p with clamp-to-edge (what AMD's gathers/samples read): the
 * nearest clamp-to-edge sampler at the pixel centre, LOD 0 (the view's base level, as a fetch).
 * On lavapipe a sample costs less than a texelFetch. */
float load_src_depth_clamped(ivec2 p)
{
    return textureLod(src_depth, (vec2(p) + 0.5) * CB.depth_buffer_inverse_dimensions, 0.0).r;
}

/* The caller's depth, out of bounds -> raw 0 (D3D load rule). */
float load_src_depth_or_zero(ivec2 p)
{
    float d = load_src_depth_clamped(p);
    return in_rect(p, textureSize(src_depth, 0)) ? d : 0.0;
}
#endif

#if CACAO_PASS == CACAO_PASS_PREPARE_NORMALS
layout(set = 0, binding = CACAO_BINDING_SRC_NORMALS) uniform sampler2D src_normals;
#endif

#if CACAO_PASS == CACAO_PASS_GENERATE || CACAO_PASS == CACAO_PASS_UPSAMPLE || CACAO_PASS == CACAO_PASS_CLASSIFY
layout(set = 0, binding = CACAO_BINDING_DEPTHS) uniform sampler2DArray depths;
#endif

#if CACAO_PASS == CACAO_PASS_GENERATE
/* The taps and normals read single texels of the depths and normals through their storage-image
 * slots: on lavapipe an imageLoad costs less than the sampling function a nearest textureLod
 * calls (docs/speed-notes.md). The centre's depths are gathered through the sampler. */
layout(set = 0, binding = CACAO_BINDING_DEPTHS_OUT0, CACAO_FORMAT_DEPTHS_OUT0) uniform readonly image2DArray depth_texels;
layout(set = 0, binding = CACAO_BINDING_NORMALS_OUT, CACAO_FORMAT_NORMALS_OUT) uniform readonly image2DArray normal_texels;
#endif

#if CACAO_PASS == CACAO_PASS_BLUR || CACAO_PASS == CACAO_PASS_APPLY || CACAO_PASS == CACAO_PASS_UPSAMPLE
layout(set = 0, binding = CACAO_BINDING_SSAO_IN) uniform sampler2DArray ssao_in;
#endif

#if (CACAO_PASS == CACAO_PASS_GENERATE && CACAO_VARIANT == CACAO_GENERATE_Q3)
layout(set = 0, binding = CACAO_BINDING_SSAO_BASE) uniform sampler2DArray ssao_base;
#endif

#if (CACAO_PASS == CACAO_PASS_GENERATE && CACAO_VARIANT == CACAO_GENERATE_Q3) || \
    CACAO_PASS == CACAO_PASS_IMPORTANCE_A || CACAO_PASS == CACAO_PASS_IMPORTANCE_B
layout(set = 0, binding = CACAO_BINDING_IMPORTANCE_IN) uniform sampler2D importance_in;
#endif

#if (CACAO_PASS == CACAO_PASS_GENERATE && CACAO_VARIANT == CACAO_GENERATE_Q3) || \
    CACAO_PASS == CACAO_PASS_IMPORTANCE_B
layout(std430, set = 0, binding = CACAO_BINDING_LOAD_COUNTER) buffer cacao_load_counter { uint load_counter; };
#endif

#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS || CACAO_PASS == CACAO_PASS_PREPARE
/* The slice's depths; with mips (CACAO_DEPTHS_MIPS) the atlas of levels 0..3 (cacao_shared.h). */
layout(set = 0, binding = CACAO_BINDING_DEPTHS_OUT0, CACAO_FORMAT_DEPTHS_OUT0) uniform writeonly image2DArray depths_out0;
#endif

#if CACAO_PASS == CACAO_PASS_PREPARE_NORMALS || CACAO_PASS == CACAO_PASS_PREPARE
layout(set = 0, binding = CACAO_BINDING_NORMALS_OUT, CACAO_FORMAT_NORMALS_OUT) uniform writeonly image2DArray normals_out;
#endif

#if CACAO_PASS == CACAO_PASS_GENERATE || CACAO_PASS == CACAO_PASS_BLUR || CACAO_PASS == CACAO_PASS_FILL
layout(set = 0, binding = CACAO_BINDING_SSAO_OUT, CACAO_FORMAT_SSAO_OUT) uniform writeonly image2DArray ssao_out;
#endif

#if (CACAO_PASS == CACAO_PASS_GENERATE && CACAO_VARIANT == CACAO_GENERATE_Q3_BASE) || \
    CACAO_PASS == CACAO_PASS_IMPORTANCE_A || CACAO_PASS == CACAO_PASS_IMPORTANCE_B
layout(set = 0, binding = CACAO_BINDING_IMPORTANCE_OUT, CACAO_FORMAT_IMPORTANCE_OUT) uniform writeonly image2D importance_out;
#endif

#if CACAO_PASS == CACAO_PASS_APPLY || CACAO_PASS == CACAO_PASS_UPSAMPLE
/* No format qualifier: the caller's image format (shaderStorageImageWriteWithoutFormat). */
layout(set = 0, binding = CACAO_BINDING_OUTPUT) uniform writeonly image2D output_image;
#endif

/* ---- Tiles (docs/tiles.md; layout in cacao_shared.h) ---- */
#if CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_COMPACT
layout(std430, set = 0, binding = CACAO_BINDING_TILES) buffer cacao_tiles { uint tiles[]; };
#elif CACAO_LIST != CACAO_LIST_NONE
layout(std430, set = 0, binding = CACAO_BINDING_TILES) readonly buffer cacao_tiles { uint tiles[]; };
#endif

#if CACAO_PASS == CACAO_PASS_CLASSIFY || CACAO_PASS == CACAO_PASS_COMPACT || CACAO_LIST != CACAO_LIST_NONE
/* First uint of a list's entries: after the header, the classes, and the lists before it. */
uint list_base(int list)
{
    uint t = uint(CB.tiles_x * CB.tiles_y);
    uint base = uint(CACAO_TILE_HEADER) + t; /* the generate list */
    if (list >= CACAO_LIST_FILL_SLICES) base += t;
    if (list >= CACAO_LIST_BLUR) base += t;
    return base;
}

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

/* The invocation's texel in group g: a macro, since gl_WorkGroupSize is only known after each
 * pass declares its local size (glslang takes 1 x 1 x 1 before). */
#define texel_of(g) ((g) * ivec2(gl_WorkGroupSize.xy) + ivec2(gl_LocalInvocationID.xy))

/* Full-resolution pixel that slice texel t of slice k holds (spec: prepare.md table). */
ivec2 full_res_pixel(ivec2 t, int slice)
{
    ivec2 d = ivec2(slice & 1, slice >> 1);
#if CACAO_DOWNSAMPLED == 1
    return 4 * t + 2 * d;
#else
    return 2 * t + d;
#endif
}

/* ============================== PREPARE_DEPTHS, PREPARE ============================== */
#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS || CACAO_PASS == CACAO_PASS_PREPARE
/* spec: prepare.md "Which full-resolution pixels each slice keeps", "Depth mips". PREPARE, the
 * fused pass, writes the depths (and mips) of its variant and the normals from depth. */
layout(local_size_x = CACAO_WG_PREPARE_X, local_size_y = CACAO_WG_PREPARE_Y) in;

/* HALF and FULL: one slice texel per invocation. MIPS: a 2x2 quad of slice texels per invocation
 * (2u .. 2u + 1, all slices; the pass row halves its grid), so a group covers 2T x 2T texels: the
 * first mip level comes from registers, and only levels 2 and 3 go through shared memory and
 * barriers, which lavapipe runs slowly (shared loads lane by lane, barriers by switching between
 * the group's invocations): 47% faster than one texel per invocation with all three levels in
 * shared memory (docs/speed-notes.md). */
#if CACAO_VARIANT == CACAO_DEPTHS_MIPS
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

/* Texel p of level 1..3 into its place in the atlas (cacao_shared.h); levels beyond the slice's
 * chain (CACAO_DEPTH_MIP_LEVELS) are not stored. */
void store_mip(int level, ivec2 p, int layer, float z)
{
    ivec2 s0 = slice_size();
    if (level >= CACAO_DEPTH_MIP_LEVELS(max(s0.x, s0.y))) return;
    ivec4 lv = depth_atlas_level(s0, level);
    if (in_rect(p, lv.xy)) imageStore(depths_out0, ivec3(lv.zw + p, layer), vec4(z));
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
    [[unroll]] for (int k = 0; k < 4; ++k) imageStore(depths_out0, ivec3(t, k), vec4(z[k]));
}

#if CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS
void main()
{
    ivec2 s = slice_size();
#if CACAO_VARIANT == CACAO_DEPTHS_HALF
    /* LOWEST: slices 0 and 3 in layers 0 and 1; integer loads, OOB -> raw 0 (z = M/A). */
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, s)) return;
    imageStore(depths_out0, ivec3(t, 0), vec4(view_z(load_src_depth_or_zero(full_res_pixel(t, 0)))));
    imageStore(depths_out0, ivec3(t, 1), vec4(view_z(load_src_depth_or_zero(full_res_pixel(t, 3)))));
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

#if CACAO_PASS == CACAO_PASS_PREPARE
/* Slices the variant keeps: all four, or (HALF, LOWEST) slices 0 and 3 in layers 0 and 1. */
#if CACAO_VARIANT == CACAO_DEPTHS_HALF
#define PREP_SLICE_STEP 3
#else
#define PREP_SLICE_STEP 1
#endif

/* The fused prepare, for normals from depth: the 2x2 quad of slice texels 2u .. 2u + 1 (the pass
 * row halves the grid), all kept slices, its depths (and with MIPS the levels above) and its
 * normals from one block of full-res depths. Each texel's normals need a 4x4 block of full-res
 * depths without its corners, whose inner 2x2 are the texel's four slice depths; the quad's blocks
 * overlap in one 6x6 block (without its corners): 32 reads instead of 4 x 12, and the depths
 * come with it (docs/speed-notes.md). No early return: the mips reduction has barriers. */
void main()
{
    ivec2 u = ivec2(gl_GlobalInvocationID.xy);
    ivec2 s = slice_size();
    ivec2 src_size = textureSize(src_depth, 0);
    vec2 inv = CB.depth_buffer_inverse_dimensions;
    float z0 = view_z(0.0); /* raw depth 0: an out-of-bounds integer load (D3D rule) */
    /* pos[j][i] = column i, row j; the full-res pixel of entry (i, j) is 4u - 1 + (i, j) native,
     * 8u + 2 (i - 1, j - 1) downsampled. zc: view z of the entry read with clamp to edge. */
    vec3 pos[6][6];
    float zc[6][6];
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
            ivec2 o = ivec2(i - 1, j - 1);
#if CACAO_DOWNSAMPLED == 1
            /* the normals' loads are integer loads: OOB -> raw 0 ([quirk] DOWNSAMPLED-NORMAL-OOB
             * kept); the depths' are clamped */
            ivec2 px = 8 * u + 2 * o;
            zc[j][i] = view_z(load_src_depth_clamped(px));
            vec2 uv = (vec2(8 * u) + 0.5 + 2.0 * vec2(o)) * inv;
            pos[j][i] = view_pos(uv, in_rect(px, src_size) ? zc[j][i] : z0);
#else
            zc[j][i] = view_z(dz[j][i]);
            vec2 uv = (vec2(4 * u) + 0.5 + vec2(o)) * inv;
            pos[j][i] = view_pos(uv, zc[j][i]);
#endif
        }
    }

    vec4 z[4]; /* z[q][k]: level 0 at quad texel q, slice k (the mips' input) */
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
                imageStore(depths_out0, ivec3(t, layer), vec4(z[q][k]));
                imageStore(normals_out, ivec3(t, layer), vec4(n, 1.0));
            }
        }
    }
#if CACAO_VARIANT == CACAO_DEPTHS_MIPS
    reduce_mips(u, z);
#endif
}
#endif /* PREPARE main */
#endif /* PREPARE_DEPTHS, PREPARE */

/* ============================== PREPARE_NORMALS ============================== */
#if CACAO_PASS == CACAO_PASS_PREPARE_NORMALS
/* spec: prepare.md "Normals from input normals" (normals from depth: the fused PREPARE above) */
layout(local_size_x = CACAO_WG_PREPARE_X, local_size_y = CACAO_WG_PREPARE_Y) in;

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!in_rect(t, imageSize(normals_out).xy)) return; /* no side effects: no LDS, no atomics */
    /* Transform the caller's normal; not renormalised ([quirk] NORMALS-NOT-NORMALIZED). */
    ivec2 size = textureSize(src_normals, 0);
    [[unroll]] for (int layer = 0; layer < 4; ++layer) {
        if (layer >= CB.slice_count) break;
        ivec2 p = full_res_pixel(t, slice_of_layer(layer));
        vec3 rgb = in_rect(p, size) ? texelFetch(src_normals, p, 0).rgb : vec3(0.0);
        vec3 n = rgb * CB.normals_unpack_mul + CB.normals_unpack_add;
        vec3 nv = (CB.normals_to_view * vec4(n, 0.0)).xyz; /* n'_j = sum_i E[j][i] n_i */
        imageStore(normals_out, ivec3(t, layer), vec4(clamp(nv, vec3(-1.0), vec3(1.0)), 1.0));
    }
}
#endif /* PREPARE_NORMALS */

/* ============================== GENERATE ============================== */
#if CACAO_PASS == CACAO_PASS_GENERATE
/* spec: generate.md steps 1-10, adaptive.md (Q3) */
layout(local_size_x = CACAO_WG_GENERATE_X, local_size_y = CACAO_WG_GENERATE_Y) in;

#if CACAO_VARIANT == CACAO_GENERATE_Q3_BASE
#define GEN_Q 3
#define GEN_BASE 1
#define GEN_TAPS CACAO_TAPS_Q3_BASE
#else
#define GEN_Q CACAO_VARIANT
#define GEN_BASE 0
#if CACAO_VARIANT == CACAO_GENERATE_Q0
#define GEN_TAPS CACAO_TAPS_Q0
#elif CACAO_VARIANT == CACAO_GENERATE_Q1
#define GEN_TAPS CACAO_TAPS_Q1
#elif CACAO_VARIANT == CACAO_GENERATE_Q2
#define GEN_TAPS CACAO_TAPS_Q2
#else
#define GEN_TAPS 0 /* Q3: taps 0..4 come from the base pass */
#endif
#endif

/* Sample pattern entries (x, y, weight, mip term), two ways:
 * - pattern_entry(i): from the constant block, for the adaptive pass's loop, whose trip count
 *   varies per pixel. A GLSL const array indexed by such a loop variable is copied into function
 *   memory at every call (40x slower on lavapipe).
 * - pattern_const(i): from a const array, for the fixed tap loops. Unrolled, each index is a
 *   constant and the entry becomes immediates. Lavapipe 22.3 loads every constant-block value
 *   lane by lane with a bounds check (8 loads), and it did so four times per tap: this is 8%
 *   faster per HIGH generate pass and 14% per MEDIUM one (interleaved A/B, interior_fzkhaus),
 *   with output that differs in a few pixels by one 8-bit step (a rounding tie of a tap offset). */
vec4 pattern_entry(int i) { return cb.sample_pattern[i]; }
const float k_sample_pattern[128] = float[128](CACAO_SAMPLE_PATTERN_VALUES);
#define pattern_const(i) vec4(k_sample_pattern[4 * (i)], k_sample_pattern[4 * (i) + 1], \
                              k_sample_pattern[4 * (i) + 2], k_sample_pattern[4 * (i) + 3])


/* Normal at slice texel p, clamped to the slice (as the nearest sampler at its centre). */
vec3 load_normal(ivec2 p, int layer)
{
    return imageLoad(normal_texels, ivec3(clamp(p, ivec2(0), slice_size() - 1), layer)).xyz;
}

/* Normal at slice texel p; OOB -> (0,0,0) ([quirk] NORMAL-EDGE-OOB kept). */
vec3 load_normal_or_zero(ivec2 p, ivec2 s, int layer)
{
    vec3 v = load_normal(p, layer);
    return in_rect(p, s) ? v : vec3(0.0);
}

/* The depth atlas (cacao_shared.h), per level l = 0..3: (width, height, x, y) of the level in
 * texels, as floats, the last level of the slice's chain, and 1 / the image's size (the atlas at
 * Q2, Q3). Q0, Q1 read level 0 only, which is the slice. Set once per invocation in main (the Q3
 * base pass computes 16 texels with them). */
vec4 g_level[4];
float g_top_level;
vec2 g_inv_d;

void init_atlas(ivec2 s0)
{
    for (int l = 0; l < 4; ++l) g_level[l] = vec4(depth_atlas_level(s0, l));
    g_top_level = float(CACAO_DEPTH_MIP_LEVELS(max(s0.x, s0.y)) - 1);
    g_inv_d = 1.0 / vec2(textureSize(depths, 0).xy);
}

/* The two mirrored samples of one tap (generate.md step 9 / adaptive.md D). */
void accumulate_tap(vec4 s, bool use_pattern_weight, vec2 uvd, vec2 inv_s, int layer, vec4 rot_scale,
                    float mip_offset, vec3 pc, vec3 n, float falloff, inout float obsc_sum, inout float weight_sum)
{
    vec2 off = vec2(rot_scale.x * s.x + rot_scale.y * s.y, rot_scale.z * s.x + rot_scale.w * s.y);
    ivec2 o = ivec2(roundEven(off)); /* snap to whole slice texels */
    /* ViewspaceDepthTap: a point sample (nearest texel, nearest mip, clamp to edge) at the tap's
     * texel-centre UV and explicit LOD (Q0, Q1: LOD 0), as the spec states it. The level and texel
     * are chosen here as lavapipe's sampler does (the level is the LOD rounded to nearest even, at
     * most the last; the texel is the truncated UV times the level's size, clamped to the level),
     * and the texel is loaded from the atlas. The max maps a -inf LOD (radius 0) and NaN to level 0. */
#if GEN_Q >= 2
    float level = min(roundEven(max(s.w + mip_offset, 0.0)), g_top_level);
    vec4 lv = level < 0.5 ? g_level[0] : level < 1.5 ? g_level[1] : level < 2.5 ? g_level[2] : g_level[3];
#else
    vec4 lv = g_level[0];
#endif
    [[unroll]] for (int side = 0; side < 2; ++side) {
        ivec2 os = side == 0 ? o : -o;
        vec2 uv = uvd + vec2(os) * inv_s;
        ivec2 t = clamp(ivec2(uv * lv.xy), ivec2(0), ivec2(lv.xy) - 1);
        float z = imageLoad(depth_texels, ivec3(t + ivec2(lv.zw), layer)).r;
        vec3 delta = vec3((CB.depth_uv_to_view_mul * uv + CB.depth_uv_to_view_add) * view_xy_scale(z), z) - pc;
        float ob = obscurance(n, delta, falloff, CB.effect_horizon_angle_threshold);
        float w = 1.0;
#if GEN_Q >= 1
        /* haloing reduction, with the global radius ([quirk] HALO-GLOBAL-RADIUS) */
        w = CACAO_HALO_AMOUNT * sat(max0(-delta.z) * CB.neg_rec_effect_radius + 2.0) + (1.0 - CACAO_HALO_AMOUNT);
#endif
        if (use_pattern_weight) w *= s.z; /* adaptive taps: halo only ([quirk] ADAPTIVE-WEIGHTMOD) */
        obsc_sum += ob * w;
        weight_sum += w;
    }
}

/* Steps 1-10 for slice texel xy (in the slice) of layer: stores its AO. The Q3 base pass returns
 * the raw obscurance it stores, the others 0. */
float generate_texel(ivec2 xy, int layer)
{
    int slice = slice_of_layer(layer);
    ivec2 size = slice_size();
    vec2 inv_s = CB.ssao_buffer_inverse_dimensions; /* = 1 / slice size */

    /* 1. centre, neighbours (mirror), view position, normal, pixel size */
    vec2 uvd = (vec2(xy) + 0.5) * inv_s;
    /* Centre and its 4 neighbours from two 2x2 gathers at the texel corners before and after xy.
     * For a neighbour one texel away, clamping to the edge gives what mirror addressing gives
     * (-1 -> 0, n -> n - 1): the sampler's clamp at the left and top; at the right and bottom the
     * atlas can continue past the slice, so the clamp is done here. Gather order: x = (0,1),
     * y = (1,1), z = (1,0), w = (0,0). */
    vec4 g_ul = textureGather(depths, vec3(vec2(xy) * g_inv_d, float(layer)), 0);
    vec4 g_br = textureGather(depths, vec3(vec2(xy + 1) * g_inv_d, float(layer)), 0);
    float zc = g_ul.y;
    float zl = g_ul.x;
    float zt = g_ul.z;
    float zr = xy.x + 1 < size.x ? g_br.z : zc;
    float zb = xy.y + 1 < size.y ? g_br.x : zc;
    vec2 uvs = uvd; /* slice UV used as screen UV ([quirk] SLICE-SUBPIXEL) */
    vec3 pc = view_pos(uvs, zc);
    vec3 n = load_normal(xy, layer);
    vec2 px_size = view_xy_scale(zc) * CB.ndc_to_view_mul * inv_s; /* .y negative */

    /* 2. radius parameters from the unscaled centre */
    float near_mod = sat(length(pc) * CB.effect_sampling_radius_near_limit_rec) * CACAO_NEAR_LIMIT_SCALE + CACAO_NEAR_LIMIT_BIAS;
    float r_eff = CB.effect_radius * near_mod;
    float radius_px = CACAO_LOOKUP_RADIUS_FACTOR * r_eff / px_size.x;
    float falloff = -1.0 / (r_eff * r_eff);

    /* 3. per-pixel rotation/scale of the pattern */
    int ri = (2 * xy.y + xy.x) % 5;
    vec4 rot_scale = cb.pattern_rot_scale[slice * 5 + ri] * radius_px;

    /* 4. self-occlusion guard for the R16F depths */
    pc *= CB.depth_precision_offset_mod;

    /* A pixel the fade-out has taken entirely (fade 0 beyond fade_out_to: the distance of open
     * worlds) ends as AO 1 whatever its taps give, since its obscurance is multiplied by 0 below;
     * so does background (the far plane, invalid depth: the sky), which has no surface to
     * occlude. Their detail AO, taps and adaptive taps are skipped (a subgroup whose pixels are
     * all quiet skips the loops; whole quiet tiles are not dispatched: docs/tiles.md). Edges are
     * still computed: the blur of a visible neighbour reads them. The Q3 base pass keeps every
     * pixel: its raw values feed the importance map and the load counter, which steer the
     * adaptive pass elsewhere. compute_all_tiles (CB.tiles_all) skips nothing: test_tiles's
     * reference, which checks that the skip changes no pixel. */
#if GEN_BASE == 0
    bool faded = CB.tiles_all == 0 &&
                 (zc >= CB.background_z || sat(pc.z * CB.effect_fade_out_mul + CB.effect_fade_out_add) == 0.0);
#else
    const bool faded = false;
#endif

    /* 5. depth edges; 6. detail AO */
    vec4 edges = vec4(1.0);
    float obsc_sum = 0.0;
    float weight_sum = 0.0;
#if GEN_Q >= 1 && GEN_BASE == 0
    edges = depth_edges(zc, zl, zr, zt, zb);
    {
        vec3 v = vec3((CB.ndc_to_view_mul * uvs + CB.ndc_to_view_add) * CB.view_xy_z.x, 1.0); /* d pos / d z */
        vec3 dl = vec3(-px_size.x, 0.0, 0.0) + v * (zl - pc.z);
        vec3 dr = vec3(px_size.x, 0.0, 0.0) + v * (zr - pc.z);
        vec3 dt = vec3(0.0, -px_size.y, 0.0) + v * (zt - pc.z);
        vec3 db = vec3(0.0, px_size.y, 0.0) + v * (zb - pc.z);
        float f4 = CACAO_DETAIL_FALLOFF_MUL * falloff;
        float h = CB.effect_horizon_angle_threshold;
        if (!faded) {
            vec4 ob = vec4(obscurance(n, dl, f4, h), obscurance(n, dr, f4, h), obscurance(n, dt, f4, h),
                           obscurance(n, db, f4, h));
            obsc_sum = CB.detail_ao_strength * dot(edges, ob);
        }
    }
#endif

    /* 7. normal edges */
#if GEN_Q >= 2 && GEN_BASE == 0
    {
        vec3 nl = load_normal_or_zero(xy + ivec2(-1, 0), size, layer);
        vec3 nr = load_normal_or_zero(xy + ivec2(1, 0), size, layer);
        vec3 nt = load_normal_or_zero(xy + ivec2(0, -1), size, layer);
        vec3 nb = load_normal_or_zero(xy + ivec2(0, 1), size, layer);
        edges *= sat(vec4(dot(n, nl), dot(n, nr), dot(n, nt), dot(n, nb)) + CACAO_NORMAL_EDGE_THRESHOLD);
    }
#endif

    /* 8. mip offset */
#if GEN_Q >= 2
    float mip_offset = log2(radius_px) + (CACAO_MIP_OFFSET);
#else
    float mip_offset = 0.0;
#endif

    /* 9. taps */
#if GEN_TAPS > 0
    if (!faded) {
        [[unroll]] for (int i = 0; i < GEN_TAPS; ++i)
            accumulate_tap(pattern_const(i), true, uvd, inv_s, layer, rot_scale,
                           mip_offset, pc, n, falloff, obsc_sum, weight_sum);
    }
#endif

#if GEN_BASE == 1
    /* 10a. raw obscurance and weight/20 for the adaptive pass */
    float raw = obsc_sum / weight_sum;
    imageStore(ssao_out, ivec3(xy, layer), vec4(raw, weight_sum / CACAO_BASE_WEIGHT_SCALE, 0.0, 0.0));
    return raw;
#else

#if CACAO_VARIANT == CACAO_GENERATE_Q3
  if (!faded) {
    /* adaptive.md A: importance at the (offset) full-res UV ([quirk] FULLRES-UV kept) */
    vec2 uv_full = uvs + cb.per_slice_full_res_uv_offset[slice].xy;
    float importance = textureLod(importance_in, uv_full, 0.0).r;

    /* B: detail AO rescale (raw importance, [quirk] ADAPTIVE-DETAIL-SCALE), then the base taps.
     * Every slice reads its own slice's base ([quirk] BASE-SLICE-VIEW fixed; v1.2 under D3D
     * rules finds only slice 0's and reads (0,0) in the others). */
    obsc_sum *= float(CACAO_ADAPTIVE_TAP_BASE_COUNT) / float(CACAO_MAX_TAPS) +
                importance * float(CACAO_ADAPTIVE_TAP_FLEXIBLE_COUNT) / float(CACAO_MAX_TAPS);
    vec2 base = texelFetch(ssao_base, ivec3(xy, layer), 0).rg;
    weight_sum += base.g * CACAO_BASE_WEIGHT_SCALE;
    obsc_sum += base.r * weight_sum;

    /* C: number of extra taps (limiter with D3D's saturate: NaN -> 0, +inf -> 1) */
    float avg_importance = float(load_counter) * CB.load_counter_avg_div;
    float limiter = CB.adaptive_sample_count_limit / avg_importance;
    limiter = limiter > 0.0 ? min(limiter, 1.0) : 0.0;
    uint extra = uint(float(CACAO_ADAPTIVE_TAP_FLEXIBLE_COUNT) * (importance * limiter) + 1.5);
    int tap_end = int(min(uint(CACAO_MAX_TAPS), extra + uint(CACAO_ADAPTIVE_TAP_BASE_COUNT)));

    /* D: extra taps, halo weight only */
    for (int i = CACAO_ADAPTIVE_TAP_BASE_COUNT; i < tap_end; ++i)
        accumulate_tap(pattern_entry(i), false, uvd, inv_s, layer, rot_scale,
                       mip_offset, pc, n, falloff, obsc_sum, weight_sum);
  }
#endif

    /* 10b. final shaping (a faded pixel: obscurance 0, which the fade below would make of any) */
    float obsc = faded ? 0.0 : obsc_sum / weight_sum;
    float fade = sat(pc.z * CB.effect_fade_out_mul + CB.effect_fade_out_add);
#if GEN_Q >= 1
    float edge_fade = sat((1.0 - edges.x - edges.y) * CACAO_EDGE_FADE) + sat((1.0 - edges.z - edges.w) * CACAO_EDGE_FADE);
    fade *= sat(1.0 - edge_fade);
#endif
    obsc = min(CB.effect_shadow_strength * obsc, CB.effect_shadow_clamp) * fade;
    float ao = pow(sat(1.0 - obsc), CB.effect_shadow_pow);
#if GEN_Q >= 1
    float packed_edges = pack_edges(edges);
#else
    float packed_edges = 1.0; /* Q0: no edges */
#endif
    imageStore(ssao_out, ivec3(xy, layer), vec4(ao, packed_edges, 0.0, 0.0));
    return 0.0;
#endif
}

#if GEN_BASE == 0
void main()
{
    hoist_constants();
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 xy = texel_of(group);
    ivec2 size = slice_size();
    if (!in_rect(xy, size)) return; /* no LDS, no barriers, no atomics: safe to leave */
    init_atlas(size);
    generate_texel(xy, int(gl_WorkGroupID.z));
}
#else
/* The Q3 base pass and the importance map (importance.md "GenerateImportanceMap") in one
 * dispatch: invocation t computes the 2x2 slice texels 2t .. 2t + 1 of all four layers, which are
 * exactly the texels importance texel t reads, and so writes that texel too (one dispatch less:
 * each costs lavapipe about 0.3 ms whatever its size). The map reads the base AO as stored, in 8
 * bits: the stored value is re-made here with the store's rounding (round to nearest even) and
 * the load's scale. A texel past the slice's edge reads the edge's (the sampler's clamp), which
 * the same invocation computes, so it is skipped. HIGHEST always has four slices. Unrolled: as a
 * loop the pass took 27.9 ms against 26.7 (interior_fzkhaus, HIGHEST native); unrolled, base and
 * map together cost what the two passes did, within noise (docs/speed-notes.md). */
void main()
{
    hoist_constants();
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = slice_size();
    if (!in_rect(t, imageSize(importance_out))) return;
    init_atlas(size);
    float vmin = 1.0e30, vmax = -1.0e30;
    [[unroll]] for (int layer = 0; layer < 4; ++layer) {
        [[unroll]] for (int q = 0; q < 4; ++q) {
            ivec2 xy = quad_texel(t, q);
            if (!in_rect(xy, size)) continue;
            float v = float(uint(roundEven(sat(generate_texel(xy, layer)) * 255.0))) * (1.0 / 255.0);
            vmin = min(vmin, v);
            vmax = max(vmax, v);
        }
    }
    /* The per-texel shaping pow(sat(1 - strength v), power) (no clamp, no fade) is monotone in v
     * (strength and power are >= 0), so the max and min of the shaped values are the shaped
     * min and max of the raw ones: 2 pow calls per texel instead of 16. */
    float mx = max(pow(sat(1.0 - CB.effect_shadow_strength * vmin), CB.effect_shadow_pow), 0.0);
    float mn = min(pow(sat(1.0 - CB.effect_shadow_strength * vmax), CB.effect_shadow_pow), 1.0);
    imageStore(importance_out, t, vec4(pow(sat(2.0 * (mx - mn)), CACAO_IMPORTANCE_POWER)));
}
#endif
#endif /* GENERATE */

/* ============================== IMPORTANCE_A / IMPORTANCE_B ============================== */
#if CACAO_PASS == CACAO_PASS_IMPORTANCE_A || CACAO_PASS == CACAO_PASS_IMPORTANCE_B
/* spec: importance.md "PostprocessImportanceMapA", "PostprocessImportanceMapB", "Load counter" */
layout(local_size_x = CACAO_WG_IMPORTANCE_X, local_size_y = CACAO_WG_IMPORTANCE_Y) in;

float importance_at(vec2 uv) { return textureLod(importance_in, uv, 0.0).r; }

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    vec2 c = (vec2(t) + 0.5) * CB.importance_map_inverse_dimensions;
    vec2 h = 0.5 * CB.importance_map_inverse_dimensions;
#if CACAO_PASS == CACAO_PASS_IMPORTANCE_A
    float v0 = importance_at(c + vec2(-3.0 * h.x, -h.y));
    float v1 = importance_at(c + vec2(h.x, -3.0 * h.y));
    float v2 = importance_at(c + vec2(3.0 * h.x, h.y));
    float v3 = importance_at(c + vec2(-h.x, 3.0 * h.y));
#else
    float v0 = importance_at(c + vec2(-h.x, -3.0 * h.y));
    float v1 = importance_at(c + vec2(3.0 * h.x, -h.y));
    float v2 = importance_at(c + vec2(h.x, 3.0 * h.y));
    float v3 = importance_at(c + vec2(-3.0 * h.x, h.y));
#endif
    float ret = (v0 + v1 + v2 + v3) / 4.0; /* lerp(max, avg, 1.0) == avg ([quirk] IMPORTANCE-DEAD-CODE) */
    if (in_rect(t, imageSize(importance_out))) imageStore(importance_out, t, vec4(ret));
#if CACAO_PASS == CACAO_PASS_IMPORTANCE_B
    /* every dispatched thread counts, in range or not ([quirk] LOADCOUNTER-OOB kept) */
    if (t.x % CACAO_LOAD_COUNTER_STRIDE == 0 && t.y % CACAO_LOAD_COUNTER_STRIDE == 0)
        atomicAdd(load_counter, uint(sat(ret) * 255.0 + 0.5));
#endif
}
#endif /* IMPORTANCE_A / B */

/* ============================== BLUR ============================== */
#if CACAO_PASS == CACAO_PASS_BLUR
/* spec: blur.md (padded-domain formulation, N Jacobi iterations in one dispatch), two ways:
 * - up to CACAO_BLUR_REGISTER_PASSES passes, each thread computes a block of BX x BY output
 *   texels from its footprint, the block and N more texels on every side, held in registers:
 *   iteration it is right at the texels at least it from the footprint's edge, so after N the
 *   block is exact. The footprints overlap (each texel is loaded and updated by several threads),
 *   but no texel goes through shared memory: on lavapipe, whose shared loads run lane by lane and
 *   whose barriers switch between all the group's invocations, that exchange was 2/3 of the blur
 *   (docs/speed-notes.md). Its fully unrolled code grows with N x footprint: past 3 passes
 *   lavapipe's compile time grows to seconds (7.9 s at 4, 26 s at 6), so
 * - beyond, a group owns a padded tile of BX x BY blocks, one per thread, whose values and edge
 *   weights stay in registers for all N iterations; shared memory carries only the values the
 *   neighbours need (one barrier per iteration, double-buffered). The inner
 *   (WG BX - 2N) x (WG BY - 2N) texels are exact: values at distance d from the padded border
 *   are wrong after d iterations at most, and the inner region is N away from it. */
layout(local_size_x = CACAO_WG_BLUR_X, local_size_y = CACAO_WG_BLUR_Y) in;

#define BLUR_N CACAO_BLUR_PASSES
#define BX CACAO_BLUR_BLOCK_X
#define BY CACAO_BLUR_BLOCK_Y

rfloat blur_store_value(float v)
{
#if CACAO_FP16 == 1
    return rfloat(v);
#else
    return round_to_half(v); /* AMD keeps the values as half between iterations */
#endif
}

/* Sum of a texel's blur weights: the centre's and its four edges'. */
rfloat blur_weight_sum(rvec4 e) { return rfloat(CACAO_BLUR_CENTRE_WEIGHT) + e.x + e.y + e.z + e.w; }

/* One Jacobi update of a texel: its value c and its neighbours' (left, right, top, bottom),
 * weighted by its edges w, over their sum wsum; stored as the iterations keep it. */
rfloat blur_update(rfloat c, rfloat l, rfloat r, rfloat t, rfloat b, rvec4 w, rfloat wsum)
{
    rfloat sum = rfloat(CACAO_BLUR_CENTRE_WEIGHT) * c + w.x * l + w.y * r + w.z * t + w.w * b;
    return blur_store_value(float(sum / wsum));
}

/* Value (r) and packed edges (g) of padded-domain texels c .. c + 1 (2x2), mirrored at the
 * slice's edges ([quirk] BLUR-BORDER-EDGES), from one gather per channel: the mirrored
 * coordinates m0, m1 of a pair differ by at most 1 (mirroring and its clamp are continuous), so
 * they lie in lo = min(m0, m1), lo + 1 (clamped by the sampler at the last texel), which one gather
 * at the corner between them reads; each texel then takes its own of the two. Out: [y][x]. */
void load_blur_piece(ivec2 c, ivec2 s, int layer, out vec2 ae[2][2])
{
    ivec2 m0 = mirror_coord(c, s), m1 = mirror_coord(c + 1, s);
    ivec2 lo = min(m0, m1);
    vec3 at = vec3(vec2(lo + 1) / vec2(s), float(layer));
    /* gather order: x = (lo.x, lo.y + 1), y = (lo.x + 1, lo.y + 1), z = (lo.x + 1, lo.y), w = (lo.x, lo.y) */
    vec4 ga = textureGather(ssao_in, at, 0);
    vec4 ge = textureGather(ssao_in, at, 1);
    [[unroll]] for (int j = 0; j < 2; ++j) {
        [[unroll]] for (int i = 0; i < 2; ++i) {
            bool first_x = (i == 0 ? m0.x : m1.x) == lo.x;
            bool first_y = (j == 0 ? m0.y : m1.y) == lo.y;
            ae[j][i] = first_y ? (first_x ? vec2(ga.w, ge.w) : vec2(ga.z, ge.z))
                               : (first_x ? vec2(ga.x, ge.x) : vec2(ga.y, ge.y));
        }
    }
}

#if BLUR_N <= CACAO_BLUR_REGISTER_PASSES
#define FX (BX + 2 * BLUR_N) /* the footprint */
#define FY (BY + 2 * BLUR_N)
#if FX % 2 != 0 || FY % 2 != 0
#error "the blur loads its footprint in 2x2 pieces"
#endif

void main()
{
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 s = textureSize(ssao_in, 0).xy;
    int layer = int(gl_WorkGroupID.z);
    ivec2 out0 = group * ivec2(CACAO_BLUR_OUT_X(BLUR_N), CACAO_BLUR_OUT_Y(BLUR_N)) + ivec2(gl_LocalInvocationID.xy) * ivec2(BX, BY);

    rfloat v[FY][FX];
    float packed[FY][FX];
    [[unroll]] for (int py = 0; py < FY; py += 2) {
        [[unroll]] for (int px = 0; px < FX; px += 2) {
            vec2 ae[2][2];
            load_blur_piece(out0 - BLUR_N + ivec2(px, py), s, layer, ae);
            [[unroll]] for (int j = 0; j < 2; ++j) {
                [[unroll]] for (int i = 0; i < 2; ++i) {
                    v[py + j][px + i] = blur_store_value(ae[j][i].r);
                    packed[py + j][px + i] = ae[j][i].g;
                }
            }
        }
    }
    /* edge weights of the texels the iterations update: all but the footprint's outer ring */
    rvec4 e[FY][FX];
    rfloat wsum[FY][FX];
    [[unroll]] for (int y = 1; y < FY - 1; ++y) {
        [[unroll]] for (int x = 1; x < FX - 1; ++x) {
            e[y][x] = unpack_edges(packed[y][x]);
            wsum[y][x] = blur_weight_sum(e[y][x]);
        }
    }
    /* Every iteration updates the whole inner region (constant bounds: shrinking it by one per
     * iteration made the loops too irregular for the driver to unroll, and the arrays went to
     * memory, 6x slower); what it gets wrong near the edge no block texel depends on. */
    [[unroll]] for (int it = 0; it < BLUR_N; ++it) {
        rfloat nv[FY][FX] = v;
        [[unroll]] for (int y = 1; y < FY - 1; ++y) {
            [[unroll]] for (int x = 1; x < FX - 1; ++x) {
                nv[y][x] = blur_update(v[y][x], v[y][x - 1], v[y][x + 1], v[y - 1][x], v[y + 1][x], e[y][x], wsum[y][x]);
            }
        }
        v = nv;
    }

    /* the block: (blurred AO, original packed edges) */
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 p = out0 + ivec2(x, y);
            if (in_rect(p, s))
                imageStore(ssao_out, ivec3(p, layer),
                           vec4(float(v[BLUR_N + y][BLUR_N + x]), packed[BLUR_N + y][BLUR_N + x], 0.0, 0.0));
        }
    }
}
#else
#define BLUR_PX (CACAO_WG_BLUR_X * BX) /* padded tile width */
#define BLUR_PY (CACAO_WG_BLUR_Y * BY) /* padded tile height */

/* 2 x 2048 values: 16 KiB (fp32), 8 KiB (fp16). */
shared rfloat blur_values[2][BLUR_PY][BLUR_PX];

void main()
{
    ivec2 group;
    if (!group_of(group)) return; /* the whole group: before any barrier */
    ivec2 s = textureSize(ssao_in, 0).xy;
    int layer = int(gl_WorkGroupID.z);
    ivec2 tile_origin = group * ivec2(CACAO_BLUR_OUT_X(BLUR_N), CACAO_BLUR_OUT_Y(BLUR_N));
    ivec2 b0 = ivec2(gl_LocalInvocationID.xy) * ivec2(BX, BY); /* block origin in the padded tile */

    /* the block: value and edges both from the mirrored texel ([quirk] BLUR-BORDER-EDGES) */
    rfloat v[BY][BX];
    rvec4 e[BY][BX];
    rfloat wsum[BY][BX];
    float packed[BY][BX];
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 c = mirror_coord(tile_origin - BLUR_N + b0 + ivec2(x, y), s);
            vec2 ae = texelFetch(ssao_in, ivec3(c, layer), 0).rg;
            v[y][x] = blur_store_value(ae.r);
            packed[y][x] = ae.g;
            e[y][x] = unpack_edges(ae.g);
            wsum[y][x] = blur_weight_sum(e[y][x]);
        }
    }

    /* neighbours outside the block; reads past the padded tile clamp to it */
    int xl = max(b0.x - 1, 0), xr = min(b0.x + BX, BLUR_PX - 1);
    int yt = max(b0.y - 1, 0), yb = min(b0.y + BY, BLUR_PY - 1);

    [[unroll]] for (int it = 0; it < BLUR_N; ++it) {
        int buf = it & 1;
        [[unroll]] for (int y = 0; y < BY; ++y)
            [[unroll]] for (int x = 0; x < BX; ++x) blur_values[buf][b0.y + y][b0.x + x] = v[y][x];
        barrier();
        rfloat left[BY], right[BY], top[BX], bottom[BX];
        [[unroll]] for (int y = 0; y < BY; ++y) {
            left[y] = xl == b0.x ? v[y][0] : blur_values[buf][b0.y + y][xl];
            right[y] = xr == b0.x + BX - 1 ? v[y][BX - 1] : blur_values[buf][b0.y + y][xr];
        }
        [[unroll]] for (int x = 0; x < BX; ++x) {
            top[x] = yt == b0.y ? v[0][x] : blur_values[buf][yt][b0.x + x];
            bottom[x] = yb == b0.y + BY - 1 ? v[BY - 1][x] : blur_values[buf][yb][b0.x + x];
        }
        rfloat nv[BY][BX];
        [[unroll]] for (int y = 0; y < BY; ++y) {
            [[unroll]] for (int x = 0; x < BX; ++x) {
                rfloat al = x > 0 ? v[y][x - 1] : left[y];
                rfloat ar = x < BX - 1 ? v[y][x + 1] : right[y];
                rfloat at = y > 0 ? v[y - 1][x] : top[x];
                rfloat ab = y < BY - 1 ? v[y + 1][x] : bottom[x];
                nv[y][x] = blur_update(v[y][x], al, ar, at, ab, e[y][x], wsum[y][x]);
            }
        }
        v = nv;
        /* no second barrier: the next iteration writes the other buffer, and the one after
         * this buffer again only after that iteration's barrier */
    }

    /* inner texels: (blurred AO, original packed edges) */
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 o = b0 + ivec2(x, y) - BLUR_N;
            ivec2 p = tile_origin + o;
            if (in_rect(o, ivec2(CACAO_BLUR_OUT_X(BLUR_N), CACAO_BLUR_OUT_Y(BLUR_N))) && in_rect(p, s))
                imageStore(ssao_out, ivec3(p, layer), vec4(float(v[y][x]), packed[y][x], 0.0, 0.0));
        }
    }
}
#endif /* register or shared-memory blur */
#endif /* BLUR */

/* ============================== APPLY / UPSAMPLE shared ============================== */
#if CACAO_PASS == CACAO_PASS_APPLY || CACAO_PASS == CACAO_PASS_UPSAMPLE

/* Bilinear read of one layer of the AO texture (LinearClamp). */
rfloat ao_bilinear(vec2 uv, int layer) { return rfloat(textureLod(ssao_in, vec3(uv, float(layer)), 0.0).r); }

/* The edge-aware interleave of the 2S-sized re-interleaved image at integer position p (spec:
 * apply.md "Apply", integer p as written: [quirk] APPLY-HALF-PIXEL) from the pixel's edges e:
 * where it reads its three neighbour layers (uv of the horizontal, vertical and diagonal ones). */
void smart_apply_taps(ivec2 p, rvec4 e, out vec2 uvh, out vec2 uvv, out vec2 uvd)
{
    int mx = p.x & 1, my = p.y & 1;
    float sx = float(e.y - e.x); /* push samples away from edges */
    float sy = float(e.w - e.z);
    vec2 pf = vec2(p);
    vec2 inv_s = CB.ssao_buffer_inverse_dimensions;
    uvh = (pf + vec2(float(mx) + sx - 0.5, 0.5 - float(my))) * 0.5 * inv_s;
    uvv = (pf + vec2(0.5 - float(mx), float(my) - 0.5 + sy)) * 0.5 * inv_s;
    uvd = (pf + vec2(float(mx) - 0.5 + sx, float(my) - 0.5 + sy)) * 0.5 * inv_s;
}

/* ... and the pixel's value from its own texel's AO and the three reads. */
rfloat smart_apply_mix(rfloat ao, rvec4 e, rfloat ah, rfloat av, rfloat ad)
{
    rfloat wh = (e.x + e.y) * rfloat(0.5);
    rfloat wv = (e.z + e.w) * rfloat(0.5);
    rfloat wd = (wh + wv) * rfloat(0.5);
    return (ao + wh * ah + wv * av + wd * ad) / (rfloat(1.0) + wh + wv + wd);
}

rfloat smart_apply(ivec2 p)
{
    int mx = p.x & 1, my = p.y & 1;
    int ic = mx + 2 * my;
    int ih = (1 - mx) + 2 * my;
    int iv = mx + 2 * (1 - my);
    int id = (1 - mx) + 2 * (1 - my);
    vec2 ae = texelFetch(ssao_in, ivec3(p >> 1, ic), 0).rg;
    rvec4 e = unpack_edges(ae.g);
    vec2 uvh, uvv, uvd;
    smart_apply_taps(p, e, uvh, uvv, uvd);
    return smart_apply_mix(rfloat(ae.r), e, ao_bilinear(uvh, ih), ao_bilinear(uvv, iv), ao_bilinear(uvd, id));
}
#endif

/* ============================== APPLY ============================== */
#if CACAO_PASS == CACAO_PASS_APPLY
/* spec: apply.md (Apply, NonSmartApply, NonSmartHalfApply) */
layout(local_size_x = CACAO_WG_APPLY_X, local_size_y = CACAO_WG_APPLY_Y) in;

/* One axis of the linear sampler's filter on 8-bit texels: a weight of f / 256 (8 fractional
 * coordinate bits), the product rounded, a + round(f (b - a) / 256). */
int lerp_texel8(int f, int a, int b) { return a + ((f * (b - a) + 128) >> 8); }

/* The 8-bit texels of unorm values as gathered. */
int texel8(float v) { return int(v * 255.0 + 0.5); }
ivec4 texel8(vec4 v) { return ivec4(v * 255.0 + 0.5); }

#if CACAO_VARIANT == CACAO_OUTPUT_SMART
/* The sampler's bilinear read, to the bit, from a 4x4 window w of one layer's texels (window
 * texel 0 at slice texel base) at sampler coordinate uv. Along an axis the read starts at window
 * texel lo, or (shift: where the edges can move it by one) at lo or lo + 1. */
int window_read(float w[4][4], ivec2 base, vec2 uv, vec2 fixed_size, ivec2 lo, bvec2 shift)
{
    ivec2 c = ivec2(roundEven(uv * fixed_size)) - 128; /* 8.8 fixed point, less half a texel */
    ivec2 f = c & 255;
    bvec2 hi = bvec2(shift.x && (c.x >> 8) - base.x != lo.x, shift.y && (c.y >> 8) - base.y != lo.y);
    int row[3];
    [[unroll]] for (int k = 0; k < 3; ++k) {
        int y = min(lo.y + k, 3);
        int v0 = texel8(w[y][lo.x]), v1 = texel8(w[y][min(lo.x + 1, 3)]), v2 = texel8(w[y][min(lo.x + 2, 3)]);
        row[k] = lerp_texel8(f.x, hi.x ? v1 : v0, hi.x ? v2 : v1);
    }
    return lerp_texel8(f.y, hi.y ? row[1] : row[0], hi.y ? row[2] : row[1]);
}

/* One invocation computes 4x4 output pixels, those of slice texels Q, Q + 1 (x and y). Their reads
 * of a layer with parity (lx, ly) all lie in the 4x4 texels from Q - 1 - (lx, ly): where the edges
 * push a pixel's read, it moves by at most half a texel, towards the texels that pixel's parity
 * leaves room for. So 4 gathers per layer and one of the edges give every texel the 16 pixels read
 * (20 sampler operations, against 64), and the shader filters as the sampler does on 8-bit texels
 * (as the non-smart apply below). */
void main()
{
    ivec2 Q = 2 * ivec2(gl_GlobalInvocationID.xy);
    ivec2 osize = imageSize(output_image);
    ivec2 ssize = textureSize(ssao_in, 0).xy;
    if (!in_rect(2 * Q, osize)) return;
    const vec2 fixed_size = vec2(ssize * 256);
    float w[4][4][4]; /* layer, y, x */
    [[unroll]] for (int l = 0; l < 4; ++l) {
        ivec2 base = Q - 1 - ivec2(l & 1, l >> 1);
        [[unroll]] for (int gy = 0; gy < 2; ++gy) {
            [[unroll]] for (int gx = 0; gx < 2; ++gx) {
                /* x: (x0, y1), y: (x1, y1), z: (x1, y0), w: (x0, y0) */
                vec4 g = textureGather(ssao_in, vec3(vec2(base + 1 + 2 * ivec2(gx, gy)) / vec2(ssize), float(l)), 0);
                w[l][2 * gy][2 * gx] = g.w;
                w[l][2 * gy][2 * gx + 1] = g.z;
                w[l][2 * gy + 1][2 * gx] = g.x;
                w[l][2 * gy + 1][2 * gx + 1] = g.y;
            }
        }
    }
    vec4 edges[4]; /* per layer, the packed edges of texels Q .. Q + 1, in gather order */
    [[unroll]] for (int l = 0; l < 4; ++l)
        edges[l] = textureGather(ssao_in, vec3(vec2(Q + 1) / vec2(ssize), float(l)), 1);
    [[unroll]] for (int i = 0; i < 16; ++i) {
        ivec2 d = ivec2((i >> 1) & 1, i >> 3);  /* texel Q + d */
        ivec2 m = ivec2(i & 1, (i >> 2) & 1);   /* parity */
        ivec2 p = 2 * (Q + d) + m;
        int ic = m.x + 2 * m.y, ih = (1 - m.x) + 2 * m.y, iv = m.x + 2 * (1 - m.y), id = (1 - m.x) + 2 * (1 - m.y);
        int gather_index = d.y == 0 ? 3 - d.x : d.x; /* (0,0) w, (1,0) z, (0,1) x, (1,1) y */
        rvec4 e = unpack_edges(edges[ic][gather_index]);
        vec2 uvh, uvv, uvd;
        smart_apply_taps(p, e, uvh, uvv, uvd);
        /* window texel of slice texel t in a layer of parity l: t - Q + 1 + l; an axis the edges
         * shift starts at t + m - 2 (window d + m - 1 + l), a fixed one at t - 1 (d + l) */
        ivec2 lh = ivec2(1 - m.x, m.y), lv = ivec2(m.x, 1 - m.y), ld = 1 - m;
        int ah = window_read(w[ih], Q - 1 - lh, uvh, fixed_size, ivec2(d.x + m.x - 1 + lh.x, d.y + lh.y), bvec2(true, false));
        int av = window_read(w[iv], Q - 1 - lv, uvv, fixed_size, ivec2(d.x + lv.x, d.y + m.y - 1 + lv.y), bvec2(false, true));
        int ad = window_read(w[id], Q - 1 - ld, uvd, fixed_size, d + m - 1 + ld, bvec2(true, true));
        rfloat ao = rfloat(w[ic][d.y + 1 + m.y][d.x + 1 + m.x]);
        rfloat v = smart_apply_mix(ao, e, rfloat(float(ah) * (1.0 / 255.0)), rfloat(float(av) * (1.0 / 255.0)),
                                   rfloat(float(ad) * (1.0 / 255.0)));
        if (in_rect(p, osize))
            imageStore(output_image, p, vec4(float(v), 0.0, 0.0, 0.0));
    }
}
#else
/* Non-smart and half: the mean of the layers (all four, or slices 0 and 3) read bilinearly at
 * uv = p / output size (no +0.5, as AMD). One invocation computes a 2x2 quad of output pixels. */
#if CACAO_VARIANT == CACAO_OUTPUT_NON_SMART
#define APPLY_LAYERS 4
#else
#define APPLY_LAYERS 2 /* layers 0,1 = slices 0,3 */
#endif

void main()
{
    /* Quad q holds the output pixels o .. o + 1, o = 2q (even size) or 2q - 1 (odd): in either
     * case both of them read, per axis, between slice texels q - 1 and q (p / O in a slice of
     * S = ceil(O / 2) texels, less half a texel, lies in [q - 1, q] for those p). So one gather
     * per layer at the corner between those texels reads the four texels of all four pixels, and
     * the filter is done here as the sampler does it on 8-bit texels, to the bit, with a quarter of
     * its reads. */
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 osize = imageSize(output_image);
    ivec2 ssize = textureSize(ssao_in, 0).xy;
    vec2 inv_o = CB.output_buffer_inverse_dimensions;
    if (!in_rect(q, ssize)) return;
    ivec2 o = 2 * q - (osize & 1);
    /* each pixel's weight of texel q, in 256ths: its coordinate in 8.8 fixed point, rounded as
     * the sampler rounds it, less the half texel, relative to texel q - 1 (0 < weight <= 256) */
    const vec2 fixed_size = vec2(ssize * 256);
    ivec2 w[2];
    [[unroll]] for (int i = 0; i < 2; ++i)
        w[i] = ivec2(roundEven(vec2(o + i) * inv_o * fixed_size)) - 128 - 256 * (q - 1);
    /* precise: otherwise the compiler factors the 1/255 out of the sum and the last bit moves;
     * and the sampler converts an 8-bit value v to v * (1/255), not v / 255 */
    precise rfloat sum[4] = rfloat[4](rfloat(0.0), rfloat(0.0), rfloat(0.0), rfloat(0.0));
    vec2 corner = vec2(q) / vec2(ssize);
    [[unroll]] for (int l = 0; l < APPLY_LAYERS; ++l) {
        /* x: (q-1, q), y: (q, q), z: (q, q-1), w: (q-1, q-1) */
        ivec4 t = texel8(textureGather(ssao_in, vec3(corner, float(l)), 0));
        [[unroll]] for (int i = 0; i < 4; ++i) {
            int fx = w[i & 1].x, fy = w[i >> 1].y;
            int v = lerp_texel8(fy, lerp_texel8(fx, t.w, t.z), lerp_texel8(fx, t.x, t.y));
            sum[i] += rfloat(float(v) * (1.0 / 255.0));
        }
    }
    [[unroll]] for (int i = 0; i < 4; ++i) {
        ivec2 p = o + ivec2(i & 1, i >> 1);
        if (all(greaterThanEqual(p, ivec2(0))))
            imageStore(output_image, p, vec4(float(sum[i] / rfloat(APPLY_LAYERS)), 0.0, 0.0, 0.0));
    }
}
#endif
#endif /* APPLY */

/* ============================== UPSAMPLE ============================== */
#if CACAO_PASS == CACAO_PASS_UPSAMPLE
/* spec: upsample.md (bilateral 5x5, Smart / NonSmart / Half) */
layout(local_size_x = CACAO_WG_UPSAMPLE_X, local_size_y = CACAO_WG_UPSAMPLE_Y) in;

#define UP_B CACAO_UPSAMPLE_BLOCK
#define UP_TABLE_X (CACAO_UPSAMPLE_SPAN_X + 4) /* the group's half-res positions + 2 apron each side */
#define UP_TABLE_Y (CACAO_UPSAMPLE_SPAN_Y + 4)
#define UP_WIN (UP_B + 4)                       /* one thread's window of table entries */
#define UP_NO_DEPTH -1.0e30 /* marks an entry outside the Q image: weight 0 */

shared rfloat up_value[UP_TABLE_X * UP_TABLE_Y];
shared float up_depth[UP_TABLE_X * UP_TABLE_Y];

/* Deinterleaved depth (mip 0) at slice texel c of a layer; OOB -> 0 (D3D load rule). */
float load_depth_or_zero(ivec2 c, int layer)
{
    return in_rect(c, slice_size()) ? texelFetch(depths, ivec3(c, layer), 0).r : 0.0;
}

rfloat table_value(float v)
{
#if CACAO_FP16 == 1
    return rfloat(v);
#else
    return round_to_half(v); /* AMD stores the table as half */
#endif
}

void main()
{
    /* The block values step 2 uses in its 5x5 loop, read as main's first statements: on lavapipe
     * a block load after step 1's loop is made lane by lane with a bounds check, at every use
     * (docs/speed-notes.md). This copy takes the pass from 34 to 25 ms. */
    float axis_weight[6]; /* exp(-(i/2)^2 / spatial variance) for i = 0..5 */
    [[unroll]] for (int i = 0; i < 6; ++i) axis_weight[i] = cb.bilateral_axis_weight[i >> 2][i & 3];
    const float depth_exp2_mul = CB.bilateral_depth_exp2_mul;
    ivec2 s = textureSize(ssao_in, 0).xy;
    ivec2 qsize = 2 * s;
    ivec2 g = ivec2(gl_WorkGroupID.xy);
    vec2 inv_s = CB.ssao_buffer_inverse_dimensions;

    /* Step 1: (value, depth) of Q-positions g*SPAN - 2 .. g*SPAN + SPAN + 1, filled by all
     * threads. Entries outside [0, 2S) get weight 0 ([quirk] BILATERAL-LEFT-BORDER fixed). */
    const ivec2 span = ivec2(CACAO_UPSAMPLE_SPAN_X, CACAO_UPSAMPLE_SPAN_Y);
    for (int i = int(gl_LocalInvocationIndex); i < UP_TABLE_X * UP_TABLE_Y; i += CACAO_WG_UPSAMPLE_X * CACAO_WG_UPSAMPLE_Y) {
        ivec2 q = g * span + ivec2(i % UP_TABLE_X, i / UP_TABLE_X) - 2;
        float value = 0.0;
        float depth = UP_NO_DEPTH;
        if (in_rect(q, qsize)) {
            int cx = q.x & 1, cy = q.y & 1;
            ivec2 c = q >> 1;
#if CACAO_VARIANT == CACAO_OUTPUT_SMART
            value = float(smart_apply(q));
            /* depth from ((qx+1)/2, qy/2) ([quirk] BILATERAL-DEPTH-SHIFT kept; OOB -> 0) */
            depth = load_depth_or_zero(ivec2((q.x + 1) >> 1, c.y), cx + 2 * cy);
#elif CACAO_VARIANT == CACAO_OUTPUT_NON_SMART
            /* 3x3 tent: bilinear reads at +-1/2 texel around the slice texel centre */
            vec2 cc = vec2(c) + 0.5;
            float sum = 0.0;
            for (int k = 0; k < 4; ++k) {
                vec2 delta = 0.5 * vec2(cx - (k & 1), cy - (k >> 1));
                sum += textureLod(ssao_in, vec3((cc + delta) * inv_s, float(k)), 0.0).r;
            }
            value = sum / 4.0;
            depth = load_depth_or_zero(c, cx + 2 * cy);
#else
            /* slices 0 and 3 only (layers 0 and 1) */
            vec2 cc = vec2(c) + 0.5;
            float s0 = textureLod(ssao_in, vec3((cc + 0.5 * vec2(cx, cy)) * inv_s, 0.0), 0.0).r;
            float s3 = textureLod(ssao_in, vec3((cc + 0.5 * vec2(cx - 1, cy - 1)) * inv_s, 1.0), 0.0).r;
            value = (s0 + s3) / 2.0;
            depth = load_depth_or_zero(c, cy); /* layer 0 (slice 0) on even rows, 1 (slice 3) on odd */
#endif
        }
        up_value[i] = table_value(value);
        up_depth[i] = depth;
    }
    barrier();

    /* Step 2: bilateral filter for the 2x2 full-res pixels of each of this thread's BxB
     * half-res positions. The thread's (B+4)^2 window of the table is read once into registers:
     * with B = 2 that is 36 shared-memory reads for 4 positions instead of 100, which is most of
     * this pass's time on a CPU device (every such read is a gather). */
    ivec2 l = ivec2(gl_LocalInvocationID.xy) * UP_B;
    ivec2 t0 = g * span + l;
    rfloat win_v[UP_WIN][UP_WIN];
    float win_z[UP_WIN][UP_WIN];
    [[unroll]] for (int y = 0; y < UP_WIN; ++y) {
        [[unroll]] for (int x = 0; x < UP_WIN; ++x) {
            int idx = (l.y + y) * UP_TABLE_X + l.x + x;
            win_v[y][x] = up_value[idx];
            win_z[y][x] = up_depth[idx];
        }
    }

    ivec2 out_size = imageSize(output_image);
    [[unroll]] for (int by = 0; by < UP_B; ++by) {
        [[unroll]] for (int bx = 0; bx < UP_B; ++bx) {
            ivec2 t = t0 + ivec2(bx, by);
            float zf[4];
            [[unroll]] for (int o = 0; o < 4; ++o) zf[o] = view_z(load_src_depth_or_zero(2 * t + ivec2(o & 1, o >> 1)));

            rfloat centre = win_v[by + 2][bx + 2];
            rfloat tot[4], wsum[4];
            [[unroll]] for (int o = 0; o < 4; ++o) {
                tot[o] = rfloat(CACAO_BILATERAL_EPSILON) * centre;
                wsum[o] = rfloat(CACAO_BILATERAL_EPSILON);
            }
            /* fully unrolled: tot[] and wsum[] stay in registers */
            [[unroll]] for (int y = -2; y <= 2; ++y) {
                [[unroll]] for (int x = -2; x <= 2; ++x) {
                    rfloat v = win_v[by + 2 + y][bx + 2 + x];
                    float zq = win_z[by + 2 + y][bx + 2 + x];
                    bool valid = zq > -1.0e29;
                    [[unroll]] for (int o = 0; o < 4; ++o) {
                        /* |dx|, |dy| in half texels: x - (o & 1) / 2 and y - (o >> 1) / 2 */
                        float ws = axis_weight[abs(2 * x - (o & 1))] * axis_weight[abs(2 * y - (o >> 1))];
                        float dz = zf[o] - zq; /* sigma is used as a variance, as AMD does */
                        float wz = valid ? exp2(dz * dz * depth_exp2_mul) : 0.0;
                        rfloat w = rfloat(ws * wz);
                        tot[o] += v * w;
                        wsum[o] += w;
                    }
                }
            }
            [[unroll]] for (int o = 0; o < 4; ++o) {
                ivec2 p = 2 * t + ivec2(o & 1, o >> 1);
                if (in_rect(p, out_size)) imageStore(output_image, p, vec4(float(tot[o] / wsum[o]), 0.0, 0.0, 0.0));
            }
        }
    }
}
#endif /* UPSAMPLE */

/* ============================== CLASSIFY ============================== */
#if CACAO_PASS == CACAO_PASS_CLASSIFY
/* docs/tiles.md: one invocation per tile, no barriers. A texel is quiet where every layer's
 * stored view z is background or faded (with the margin of CB.quiet_margin, so that generate
 * finds it faded too); the tile is active when some texel is not quiet (the scan stops there),
 * else faded when some texel is not background, else background. Gathers read 2x2 texels; past
 * the slice's edge they clamp to texels of the same tile. */
layout(local_size_x = CACAO_WG_CLASSIFY, local_size_y = CACAO_WG_CLASSIFY) in;

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
    uint cls = (flags & 1u) != 0u ? CACAO_TILE_CLASS_ACTIVE
             : (flags & 2u) != 0u ? CACAO_TILE_CLASS_FADED : CACAO_TILE_CLASS_BACKGROUND;
    tiles[CACAO_TILE_HEADER + t.y * CB.tiles_x + t.x] = cls;
    atomicAdd(tiles[CACAO_TILE_COUNT_ACTIVE + cls], 1u);
}
#endif /* CLASSIFY */

/* ============================== COMPACT ============================== */
#if CACAO_PASS == CACAO_PASS_COMPACT
/* docs/tiles.md: one invocation per tile, then one per blur group; each goes into the list that
 * computes it (or, a tile, into the one that fills it with 1). Order within a list is arbitrary:
 * every group writes only its own texels. */
layout(local_size_x = CACAO_WG_COMPACT) in;

/* Some tile within one tile of the tiles [t0, t1] is active: a needed tile lies in [t0, t1]. */
bool touches_needed(ivec2 t0, ivec2 t1)
{
    ivec2 last = ivec2(CB.tiles_x, CB.tiles_y) - 1;
    t0 = clamp(t0 - 1, ivec2(0), last);
    t1 = clamp(t1 + 1, ivec2(0), last);
    for (int y = t0.y; y <= t1.y; ++y)
        for (int x = t0.x; x <= t1.x; ++x)
            if (tiles[CACAO_TILE_HEADER + y * CB.tiles_x + x] == CACAO_TILE_CLASS_ACTIVE) return true;
    return false;
}

/* Entry i goes to grid row i / width: the command's rows cover every entry. */
void append(int list, ivec2 g)
{
    uint i = atomicAdd(tiles[CACAO_TILE_LIST_COUNT + list], 1u);
    tiles[list_base(list) + i] = uint(g.x) | (uint(g.y) << 16);
    atomicMax(tiles[3 * (list - 1) + 1], i / list_width(list) + 1u);
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    int t = CB.tiles_x * CB.tiles_y, b = CB.blur_groups_x * CB.blur_groups_y;
    if (i < t) {
        ivec2 g = ivec2(i % CB.tiles_x, i / CB.tiles_x);
        append(touches_needed(g, g) ? CACAO_LIST_GENERATE : CACAO_LIST_FILL_SLICES, g);
    } else if (i < t + b) {
        i -= t;
        ivec2 g = ivec2(i % CB.blur_groups_x, i / CB.blur_groups_x);
        ivec2 out_size = ivec2(CB.blur_out_x, CB.blur_out_y);
        ivec2 lo = g * out_size, hi = lo + out_size - 1; /* its output texels */
        if (touches_needed(lo / CACAO_TILE, hi / CACAO_TILE)) append(CACAO_LIST_BLUR, g);
    }
}
#endif /* COMPACT */

/* ============================== FILL ============================== */
#if CACAO_PASS == CACAO_PASS_FILL
/* docs/tiles.md: AO 1, the value the full computation gives every texel of a tile that is not
 * needed (edges 1: nothing reads them there). */
layout(local_size_x = CACAO_TILE, local_size_y = CACAO_TILE) in;

void main()
{
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 p = texel_of(group);
    if (in_rect(p, imageSize(ssao_out).xy)) imageStore(ssao_out, ivec3(p, int(gl_WorkGroupID.z)), vec4(1.0, 1.0, 0.0, 0.0));
}
#endif /* FILL */

/* ============================== HORIZON-SLICE ESTIMATORS ============================== */
#if CACAO_PASS == CACAO_PASS_SLICE_PREPARE || CACAO_PASS == CACAO_PASS_SLICE_MAIN || \
    CACAO_PASS == CACAO_PASS_SLICE_DENOISE
/* spec: estimators.md. GTAO and the cosine-weighted visibility bitmask, at full resolution, one
 * invocation per pixel, all in fp32. View z of background pixels (the far plane, or depth that
 * gives no finite positive z: NaN, Inf, an infinite far plane) is stored as -1: such pixels output
 * 1 and are ignored as samples and as denoise neighbours. */
layout(local_size_x = CACAO_WG_SLICE_X, local_size_y = CACAO_WG_SLICE_Y) in;

const float SLICE_PI = 3.14159265358979;
const float SLICE_HALF_PI = 1.57079632679490;

/* View-space position of pixel p's centre at view z (estimators.md section 1). */
vec3 slice_pos(ivec2 p, float z) { return view_pos((vec2(p) + 0.5) * CB.depth_buffer_inverse_dimensions, z); }

/* Unit vector from the surface point towards the camera. */
vec3 slice_to_camera(vec3 pos) { return CB.slice_ortho != 0 ? vec3(0.0, 0.0, -1.0) : -normalize(pos); }

/* A stored normal, renormalised; zero or non-finite -> facing the camera. */
vec3 slice_normal(vec3 stored, vec3 to_camera)
{
    float len2 = dot(stored, stored);
    return (len2 > 1e-12 && len2 < 1e30) ? stored * inversesqrt(len2) : to_camera;
}

#if CACAO_PASS == CACAO_PASS_SLICE_PREPARE
layout(set = 0, binding = CACAO_BINDING_SRC_DEPTH) uniform sampler2D src_depth;
#if CACAO_VARIANT == CACAO_SLICE_NORMALS_INPUT
layout(set = 0, binding = CACAO_BINDING_SRC_NORMALS) uniform sampler2D src_normals;
#endif
layout(set = 0, binding = CACAO_BINDING_DEPTHS_OUT0, CACAO_FORMAT_DEPTHS_OUT0) uniform writeonly image2D view_depth_out;
layout(set = 0, binding = CACAO_BINDING_NORMALS_OUT, CACAO_FORMAT_NORMALS_OUT) uniform writeonly image2D view_normals_out;

/* Raw depth -> view z, -1 for background (estimators.md section 1: the denominator keeps 1 - d
 * exact where d is near 1). */
float slice_view_z(float d)
{
    if (d == CB.slice_far_depth) return -1.0;
    float z = (CB.depth_unpack.x + CB.depth_unpack_d.x * d) /
              (CB.slice_depth_den_a + CB.slice_depth_den_b * d + CB.slice_depth_den_c * (1.0 - d));
    return (z > 0.0 && z < 3.0e38) ? z : -1.0; /* NaN fails z > 0 */
}

float load_view_z(ivec2 p, ivec2 size) { return in_rect(p, size) ? slice_view_z(texelFetch(src_depth, p, 0).r) : -1.0; }

#if CACAO_VARIANT == CACAO_SLICE_NORMALS_DEPTH
/* Unit direction from pc to a neighbour, zero where the neighbour is missing (off-image or
 * background): its cross products then carry no weight. */
vec3 neighbour_dir(vec3 pc, ivec2 q, float zq)
{
    if (!(zq > 0.0)) return vec3(0.0);
    vec3 d = slice_pos(q, zq) - pc;
    float len2 = dot(d, d);
    return len2 > 0.0 ? d * inversesqrt(len2) : vec3(0.0);
}
#endif

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(src_depth, 0);
    if (!in_rect(p, size)) return;
    float z = load_view_z(p, size);
    vec3 n = vec3(0.0, 0.0, -1.0);
    if (z > 0.0) {
        vec3 pc = slice_pos(p, z);
        vec3 to_camera = slice_to_camera(pc);
#if CACAO_VARIANT == CACAO_SLICE_NORMALS_INPUT
        vec3 rgb = texelFetch(src_normals, p, 0).rgb;
        n = (CB.normals_to_view * vec4(rgb * CB.normals_unpack_mul + CB.normals_unpack_add, 0.0)).xyz;
        n = slice_normal(n, to_camera);
#else
        ivec2 ql = p - ivec2(1, 0), qr = p + ivec2(1, 0), qt = p - ivec2(0, 1), qb = p + ivec2(0, 1);
        float zl = load_view_z(ql, size), zr = load_view_z(qr, size);
        float zt = load_view_z(qt, size), zb = load_view_z(qb, size);
        /* a missing neighbour counts as a full edge (weight 0) */
        vec4 e = depth_edges(z, zl > 0.0 ? zl : 1e30, zr > 0.0 ? zr : 1e30, zt > 0.0 ? zt : 1e30,
                             zb > 0.0 ? zb : 1e30);
        n = normal_from_neighbours(neighbour_dir(pc, ql, zl), neighbour_dir(pc, qr, zr), neighbour_dir(pc, qt, zt),
                                   neighbour_dir(pc, qb, zb), e);
        n = slice_normal(n, to_camera);
#endif
    }
    imageStore(view_depth_out, p, vec4(z));
    imageStore(view_normals_out, p, vec4(n, 0.0));
}
#endif /* SLICE_PREPARE */

#if CACAO_PASS == CACAO_PASS_SLICE_MAIN || CACAO_PASS == CACAO_PASS_SLICE_DENOISE
/* The full-resolution intermediates are read as storage images: lavapipe loads those at a fraction
 * of the cost of a sampled fetch (measured: the GTAO pass 35% faster at 64 reads). */
layout(set = 0, binding = CACAO_BINDING_DEPTHS_OUT0, CACAO_FORMAT_DEPTHS_OUT0) uniform readonly image2D view_depth;
layout(set = 0, binding = CACAO_BINDING_NORMALS_OUT, CACAO_FORMAT_NORMALS_OUT) uniform readonly image2D view_normals;

float fetch_view_z(ivec2 p) { return imageLoad(view_depth, p).r; }
vec3 fetch_stored_normal(ivec2 p) { return imageLoad(view_normals, p).xyz; }
vec3 fetch_normal(ivec2 p, vec3 to_camera) { return slice_normal(fetch_stored_normal(p), to_camera); }

#if (CACAO_PASS == CACAO_PASS_SLICE_MAIN && CACAO_VARIANT >= CACAO_SLICE_GTAO_DIRECT) || \
    (CACAO_PASS == CACAO_PASS_SLICE_DENOISE && CACAO_VARIANT == CACAO_DENOISE_FINAL)
layout(set = 0, binding = CACAO_BINDING_OUTPUT) uniform writeonly image2D output_image;
void store_visibility(ivec2 p, float v) { imageStore(output_image, p, vec4(v, 0.0, 0.0, 0.0)); }
#else
layout(set = 0, binding = CACAO_BINDING_SSAO_OUT, CACAO_FORMAT_SSAO_OUT) uniform writeonly image2D ao_out;
void store_visibility(ivec2 p, float v) { imageStore(ao_out, p, vec4(v)); }
#endif
#endif

#if CACAO_PASS == CACAO_PASS_SLICE_MAIN
#define SLICE_BITMASK (CACAO_VARIANT == CACAO_SLICE_BITMASK || CACAO_VARIANT == CACAO_SLICE_BITMASK_DIRECT)

/* Hilbert-curve index of (x, y) in a 64x64 tile (estimators.md section 2.1). */
uint hilbert_index(uint x, uint y)
{
    uint h = 0u;
    [[unroll]] for (uint c = 32u; c > 0u; c >>= 1u) {
        uint rx = (x & c) != 0u ? 1u : 0u, ry = (y & c) != 0u ? 1u : 0u;
        h += c * c * ((3u * rx) ^ ry);
        if (ry == 0u) {
            if (rx == 1u) {
                x = 63u - x;
                y = 63u - y;
            }
            uint t = x;
            x = y;
            y = t;
        }
    }
    return h;
}

/* frac(x) of a 0.32 fixed-point fraction, below 1 (24 significant bits). */
float unit_fraction(uint fixed_point) { return float(fixed_point >> 8u) * (1.0 / 16777216.0); }

/* R2 / R1 sequences in 0.32 fixed point: h * alpha mod 1 is exact in uint arithmetic, where the
 * float product of XeGTAO loses bits at large h (alpha * 2^32: 0.7548776662, 0.5698402910,
 * 0.6180339887; 2^31 is the 0.5 offset). */
const uint R2_X = 3242174889u, R2_Y = 2447445414u, R1 = 2654435769u, HALF = 2147483648u;

/* atan2(y, x) in [-pi, pi] by a minimax polynomial on [0, 1] (max error about 1e-5 rad, far below
 * a 32nd of the half-circle); GLSL's atan costs several times more on lavapipe. */
float fast_atan2(float y, float x)
{
    float ax = abs(x), ay = abs(y);
    float a = min(ax, ay) / max(max(ax, ay), 1e-30);
    float s = a * a;
    float r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
    if (ay > ax) r = SLICE_HALF_PI - r;
    if (x < 0.0) r = SLICE_PI - r;
    return y < 0.0 ? -r : r;
}

/* One slice's frame (estimators.md section 2.2): tangent t, the normal's signed angle n from the
 * view vector and cos n, sin n, the projected normal's length pl, F(n) = cos n + n sin n. Since
 * t and v span the slice plane, pN . t = N . t and pN . v = N . v: no projection is needed. */
struct slice_frame {
    vec3 t;
    float n, cos_n, sin_n, pl, full;
};

slice_frame make_slice_frame(vec2 dir, vec3 v, vec3 nrm)
{
    slice_frame f;
    vec3 d3 = vec3(dir, 0.0);
    float dv = dot(d3, v);
    f.t = (d3 - dv * v) * inversesqrt(max(1.0 - dv * dv, 1e-12));
    float nt = dot(nrm, f.t), nv = max(dot(nrm, v), 0.0); /* n is clamped to +-pi/2 */
    f.pl = sqrt(nt * nt + nv * nv);
    float inv_pl = f.pl > 0.0 ? 1.0 / f.pl : 0.0;
    f.cos_n = nv * inv_pl;
    f.sin_n = nt * inv_pl;
    f.n = fast_atan2(nt, nv);
    f.full = f.cos_n + f.n * f.sin_n;
    return f;
}

/* 4 G(theta) of estimators.md section 2.3, with cos(2 theta) and sin(2 theta) given. */
float arc_g4(float theta, float cos2, float sin2, slice_frame f)
{
    return f.cos_n + 2.0 * theta * f.sin_n - (cos2 * f.cos_n + sin2 * f.sin_n);
}

#if SLICE_BITMASK
/* Fraction U of the slice's cosine-weighted half-circle below the direction (x, y) = (along v,
 * along t) (estimators.md section 4.2); c_low4 = 4 C(n - pi/2), inv_full4 = 1 / (4 F(n)). */
float sector_fraction(float x, float y, slice_frame f, float c_low4, float inv_full4)
{
    float theta = fast_atan2(y, x);
    if (theta >= f.n + SLICE_HALF_PI) return 1.0;
    if (theta <= f.n - SLICE_HALF_PI) return 0.0;
    float inv_r2 = 1.0 / max(x * x + y * y, 1e-30);
    float c4 = arc_g4(theta, (x * x - y * y) * inv_r2, 2.0 * x * y * inv_r2, f);
    return sat(((theta < 0.0 ? -c4 : c4) - c_low4) * inv_full4);
}
#endif

float slice_visibility(ivec2 p, float z, ivec2 size)
{
    vec3 pos = slice_pos(p, z);
    vec3 v = slice_to_camera(pos);
    vec3 nrm = fetch_normal(p, v);
    const float radius = CB.slice_radius, radius2 = radius * radius, inv_radius2 = 1.0 / radius2;
    float rpx = radius / (CB.slice_pixel_size * view_xy_scale(z)); /* radius in pixels */
    float min_s = CACAO_SLICE_MIN_OFFSET_PX / rpx;
    uint h = hilbert_index(uint(p.x) & 63u, uint(p.y) & 63u) + uint(CB.slice_noise_offset);
    float xi_s = unit_fraction(h * R2_X + HALF);
    uint xi_t = h * R2_Y + HALF;
    const int ns = CB.slice_directions, m = CB.slice_steps;
    const vec2 rotation = vec2(CB.slice_rotation_cos, CB.slice_rotation_sin);
    float phi0 = SLICE_PI * xi_s / float(ns);
    vec2 dir = vec2(cos(phi0), sin(phi0)); /* slice i: angle pi (i + xi_s) / ns */
    float sum_vis = 0.0, sum_full = 0.0;
    for (int i = 0; i < ns; ++i) {
        slice_frame f = make_slice_frame(dir, v, nrm);
        vec2 offset_dir = vec2(dir.x, -dir.y); /* rows grow downwards */
        dir = vec2(dir.x * rotation.x - dir.y * rotation.y, dir.x * rotation.y + dir.y * rotation.x);
#if SLICE_BITMASK
        /* 4 C(n - pi/2) = -G4(n - pi/2) for n - pi/2 <= 0: cos(2 theta - n) = -cos n there */
        float c_low4 = -(f.cos_n + 2.0 * (f.n - SLICE_HALF_PI) * f.sin_n + f.cos_n);
        float inv_full4 = 0.25 / max(f.full, 1e-12);
        uint bits = 0u;
        float occluded = 0.0;
#else
        float low_pos = -f.sin_n, low_neg = f.sin_n; /* cos(n +- pi/2): the half-circle edges */
        float c_pos = low_pos, c_neg = low_neg;
#endif
        bool open_pos = true, open_neg = true; /* a side stops at its first off-screen sample */
        for (int j = 0; j < m; ++j) {
            float xi = unit_fraction(xi_t + uint(i + j * m) * R1);
            float s = (float(j) + xi) / float(m);
#if !SLICE_BITMASK
            s *= s; /* GTAO: quadratic step spacing */
#endif
            float len = (s + min_s) * rpx;
            ivec2 delta = ivec2(roundEven(len * offset_dir));
            [[unroll]] for (int side = 0; side < 2; ++side) {
                bool positive = side == 0;
                if (!(positive ? open_pos : open_neg)) continue;
                ivec2 q = positive ? p + delta : p - delta;
                if (!in_rect(q, size)) {
                    if (positive) open_pos = false;
                    else open_neg = false;
                    continue;
                }
                float zq = fetch_view_z(q);
                if (!(zq > 0.0)) continue; /* background: weight 0 */
                vec3 sample_pos = slice_pos(q, zq);
                vec3 delta3 = sample_pos - pos;
                float dist2 = dot(delta3, delta3);
                float x = dot(delta3, v), y = dot(delta3, f.t);
#if SLICE_BITMASK
                float w = CB.slice_binary != 0 ? (dist2 <= radius2 ? 1.0 : 0.0) : max(0.0, 1.0 - dist2 * inv_radius2);
                if (!(w > 0.0)) continue;
                /* back point: T further along the sample's own view ray (y: S . t = delta . t) */
                float xb = x, yb = y;
                if (CB.slice_ortho != 0) {
                    xb -= CB.slice_thickness * v.z;
                } else {
                    float along = CB.slice_thickness * inversesqrt(dot(sample_pos, sample_pos));
                    xb += along * dot(sample_pos, v);
                    yb += along * y;
                }
                float u_front = sector_fraction(x, y, f, c_low4, inv_full4);
                float u_back = sector_fraction(xb, yb, f, c_low4, inv_full4);
                float u_lo = min(u_front, u_back), u_hi = max(u_front, u_back);
                int b0 = int(floor(32.0 * u_lo));
                int nb = clamp(int(roundEven(32.0 * (u_hi - u_lo))), 0, 32 - b0);
                uint mask = nb == 0 ? 0u : (0xFFFFFFFFu >> uint(32 - nb)) << uint(b0);
                occluded += w * float(bitCount(mask & ~bits));
                bits |= mask;
#else
                float inv_dist = inversesqrt(dist2);
                float w = sat((radius - dist2 * inv_dist) * CB.slice_falloff_mul);
                float cs = x * inv_dist;
                if (positive) c_pos = max(c_pos, low_pos + (cs - low_pos) * w);
                else c_neg = max(c_neg, low_neg + (cs - low_neg) * w);
#endif
            }
#if SLICE_BITMASK
            if (bits == 0xFFFFFFFFu) break; /* every sector is taken: later samples change nothing */
#endif
        }
#if SLICE_BITMASK
        sum_vis += f.pl * f.full * occluded * (1.0 / 32.0); /* occluded share, summed as O_i */
#else
        /* theta1 = acos(c+) in [0, pi], theta0 = -acos(c-): cos 2 theta = 2 c^2 - 1,
         * sin 2 theta = 2 c sin theta with sin theta = +-sqrt(1 - c^2) */
        c_pos = clamp(c_pos, -1.0, 1.0);
        c_neg = clamp(c_neg, -1.0, 1.0);
        float s_pos = sqrt(1.0 - c_pos * c_pos), s_neg = -sqrt(1.0 - c_neg * c_neg);
        float g4 = arc_g4(acos(c_pos), 2.0 * c_pos * c_pos - 1.0, 2.0 * c_pos * s_pos, f) +
                   arc_g4(-acos(c_neg), 2.0 * c_neg * c_neg - 1.0, 2.0 * c_neg * s_neg, f);
        sum_vis += f.pl * 0.25 * g4;
#endif
        sum_full += f.pl * f.full;
    }
#if SLICE_BITMASK
    float vis = sat(1.0 - sum_vis / max(sum_full, 1e-9));
#else
    float vis = sat(sum_vis / max(sum_full, 1e-9));
#endif
    /* the fade-out distance range of the settings: occlusion fades to none */
    return 1.0 - (1.0 - vis) * sat(z * CB.effect_fade_out_mul + CB.effect_fade_out_add);
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(view_depth);
    if (!in_rect(p, size)) return;
    float z = fetch_view_z(p);
    store_visibility(p, z > 0.0 ? slice_visibility(p, z, size) : 1.0);
}
#endif /* SLICE_MAIN */

#if CACAO_PASS == CACAO_PASS_SLICE_DENOISE
layout(set = 0, binding = CACAO_BINDING_DEPTHS_OUT1, CACAO_FORMAT_DEPTHS_OUT1) uniform readonly image2D ao_in;

/* 3x3 bilateral filter (estimators.md section 5): weight by the distance of the neighbour's point
 * from this pixel's tangent plane (relative to sigma z) and by the agreement of the normals. */
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(view_depth);
    if (!in_rect(p, size)) return;
    float z = fetch_view_z(p);
    if (!(z > 0.0)) {
        store_visibility(p, 1.0);
        return;
    }
    vec3 pos = slice_pos(p, z);
    vec3 nrm = fetch_normal(p, slice_to_camera(pos));
    float inv_scale = 1.0 / max(CB.slice_denoise_sigma * z, 1e-30);
    float sum = imageLoad(ao_in, p).r, weight_sum = 1.0;
    [[unroll]] for (int j = -1; j <= 1; ++j) {
        [[unroll]] for (int i = -1; i <= 1; ++i) {
            ivec2 q = p + ivec2(i, j);
            if ((i == 0 && j == 0) || !in_rect(q, size)) continue;
            float zq = fetch_view_z(q);
            if (!(zq > 0.0)) continue;
            /* the stored normal as it is: unit to 8 bits, and one that is zero only weighs 0 */
            float plane = dot(nrm, slice_pos(q, zq) - pos) * inv_scale;
            float agree = sat(dot(nrm, fetch_stored_normal(q)));
            agree *= agree;
            float w = exp2(-1.44269504 * plane * plane) * agree * agree; /* exp(-plane^2) */
            sum += w * imageLoad(ao_in, q).r;
            weight_sum += w;
        }
    }
    store_visibility(p, sum / weight_sum);
}
#endif /* SLICE_DENOISE */
#endif /* HORIZON-SLICE ESTIMATORS */
