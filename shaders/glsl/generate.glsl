/* generate.glsl - the AO passes: generate (Q0..Q3 and the Q3 base pass) and the importance map's
 * smoothing passes. */

/* ============================== GENERATE, GENERATE_GPU ============================== */
#if CACAO_PASS == CACAO_PASS_GENERATE || CACAO_PASS == CACAO_PASS_GENERATE_GPU
/* spec: generate.md steps 1-10, adaptive.md (Q3). The GPU form (GENERATE_GPU) computes the same
 * values with fewer instructions where a GPU compiler counts them (GEN_GPU below). */
layout(local_size_x = CACAO_WG_GENERATE_X, local_size_y = CACAO_WG_GENERATE_Y) in;

#if CACAO_PASS == CACAO_PASS_GENERATE_GPU
#define GEN_GPU 1
#else
#define GEN_GPU 0
#endif

#if CACAO_VARIANT == CACAO_GENERATE_Q3_BASE
#define GEN_Q 3
#define GEN_BASE 1
#define GEN_TAPS CACAO_TAPS_Q3_BASE
#elif CACAO_VARIANT == CACAO_GENERATE_Q0_INPUT
#define GEN_Q 0
#define GEN_BASE 0
#define GEN_TAPS CACAO_TAPS_Q0
#elif CACAO_VARIANT == CACAO_GENERATE_Q1_INPUT
#define GEN_Q 1
#define GEN_BASE 0
#define GEN_TAPS CACAO_TAPS_Q1
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
 *   memory at every call, which lavapipe runs many times slower.
 * - pattern_const(i): from a const array, for the fixed tap loops. Unrolled, each index is a
 *   constant and the entry becomes immediates. Lavapipe 22.3 loads every constant-block value
 *   lane by lane with a bounds check, and it did so four times per tap (docs/speed-notes.md);
 *   this changed a few pixels by one 8-bit step (a rounding tie of a tap offset). */
vec4 pattern_entry(int i) { return cb.sample_pattern[i]; }
const float k_sample_pattern[128] = float[128](CACAO_SAMPLE_PATTERN_VALUES);
#define pattern_const(i) vec4(k_sample_pattern[4 * (i)], k_sample_pattern[4 * (i) + 1], \
                              k_sample_pattern[4 * (i) + 2], k_sample_pattern[4 * (i) + 3])


#ifdef CACAO_BIND_SRC_NORMALS
/* A value in [-1, 1] as the normals' R8G8B8A8_SNORM image stores and loads it: round to the
 * nearest of the 255 codes c / 127 (Vulkan's conversions; -128 never arises from a clamped value). */
vec3 snorm8_round_trip(vec3 v) { return roundEven(v * 127.0) / 127.0; }
#else
/* Normal at slice texel p, clamped to the slice (as the nearest sampler at its centre). */
vec3 load_normal(ivec2 p, int layer)
{
    return imageLoad(normals_image, ivec3(clamp(p, ivec2(0), slice_size() - 1), layer)).xyz;
}

/* Normal at slice texel p; OOB -> (0,0,0) ([quirk] NORMAL-EDGE-OOB kept). */
vec3 load_normal_or_zero(ivec2 p, ivec2 s, int layer)
{
    vec3 v = load_normal(p, layer);
    return in_rect(p, s) ? v : vec3(0.0);
}
#endif

/* The depth atlas (cacao_shared.h; the CPU form), per level l = 0..3: (width, height, x, y) of the
 * level in texels, as floats, the last level of the slice's chain, and 1 / level 0's size (the
 * atlas at Q2, Q3 in the CPU form). Q0, Q1 read level 0 only, which is the slice. Set once per invocation in main (the Q3
 * base pass computes 16 texels with them). */
vec4 g_level[4];
float g_top_level;
vec2 g_inv_d;

/* The adaptive pass's load counter (importance_b's sum). The CPU form reads it once, first in
 * main: lavapipe loads a storage buffer inside control flow lane by lane with a bounds check, and
 * at the top of main once for every invocation (docs/tiles.md "What a list costs"). */
#if CACAO_VARIANT == CACAO_GENERATE_Q3 && !GEN_GPU
uint g_load_counter;
#define LOAD_COUNTER_VALUE g_load_counter
#else
#define LOAD_COUNTER_VALUE load_counter
#endif

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
#if GEN_GPU
    /* The GPU forms' depths are a mip chain (cacao_shared.h): the sampler picks the level (nearest,
     * at most the last) and the nearest texel, clamped to the level's edge, from the LOD and the
     * texel-centre UV. On lavapipe, whose choices the CPU form reproduces, that is the CPU form's
     * level and texel (test_shader_forms: bit-identical); a GPU rounds a LOD's tie upwards, and a
     * texel coordinate to its sub-texel precision, so near a tie it may pick the neighbour. Below HIGH only level 0 exists. The mirrored offset's
     * float is the negated float of the offset (exact). */
    vec2 fo = vec2(o);
#if GEN_Q >= 2
    float lod = s.w + mip_offset;
#else
    const float lod = 0.0;
#endif
#else
#if GEN_Q >= 2
    float level = min(roundEven(max(s.w + mip_offset, 0.0)), g_top_level);
    vec4 lv = level < 0.5 ? g_level[0] : level < 1.5 ? g_level[1] : level < 2.5 ? g_level[2] : g_level[3];
#else
    vec4 lv = g_level[0];
#endif
#endif
    [[unroll]] for (int side = 0; side < 2; ++side) {
#if GEN_GPU
        vec2 uv = uvd + (side == 0 ? fo : -fo) * inv_s;
        float z = textureLod(depths, vec3(uv, float(layer)), lod).r;
#else
        ivec2 os = side == 0 ? o : -o;
        vec2 uv = uvd + vec2(os) * inv_s;
        ivec2 t = clamp(ivec2(uv * lv.xy), ivec2(0), ivec2(lv.xy) - 1);
        float z = imageLoad(depths_image, ivec3(t + ivec2(lv.zw), layer)).r;
#endif
        vec3 delta = vec3((CB.depth_uv_to_view_mul * uv + CB.depth_uv_to_view_add) * view_xy_scale(z), z) - pc;
        float ob = obscurance(n, delta, falloff, CB.effect_horizon_angle_threshold);
        float w = 1.0;
#if GEN_Q >= 1
        /* haloing reduction, with the global radius ([quirk] HALO-GLOBAL-RADIUS). The GPU form drops
         * the max0: neg_rec_effect_radius < 0, so a positive delta.z makes the sum above 2 and the
         * saturate 1, as the max0's 0 does (delta.z is finite: two finite view z). */
#if GEN_GPU
        w = CACAO_HALO_AMOUNT * sat(-delta.z * CB.neg_rec_effect_radius + 2.0) + (1.0 - CACAO_HALO_AMOUNT);
#else
        w = CACAO_HALO_AMOUNT * sat(max0(-delta.z) * CB.neg_rec_effect_radius + 2.0) + (1.0 - CACAO_HALO_AMOUNT);
#endif
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
#if GEN_GPU && GEN_BASE
    float zc = texelFetch(depths, ivec3(xy, layer), 0).r; /* the base pass reads no neighbour */
    float zl = zc, zt = zc;
    vec4 g_br = vec4(zc);
#elif GEN_GPU
    vec4 g_ul = textureGather(depths, vec3(vec2(xy) * g_inv_d, float(layer)), 0);
    vec4 g_br = textureGather(depths, vec3((vec2(xy) + 1.0) * g_inv_d, float(layer)), 0); /* exact: one conversion */
    float zc = g_ul.y;
    float zl = g_ul.x;
    float zt = g_ul.z;
#else
    vec4 g_ul = textureGather(depths, vec3(vec2(xy) * g_inv_d, float(layer)), 0);
    vec4 g_br = textureGather(depths, vec3(vec2(xy + 1) * g_inv_d, float(layer)), 0);
    float zc = g_ul.y;
    float zl = g_ul.x;
    float zt = g_ul.z;
#endif
    float zr = xy.x + 1 < size.x ? g_br.z : zc;
    float zb = xy.y + 1 < size.y ? g_br.x : zc;
    vec2 uvs = uvd; /* slice UV used as screen UV ([quirk] SLICE-SUBPIXEL) */
    vec3 pc = view_pos(uvs, zc);
#ifdef CACAO_BIND_SRC_NORMALS
    /* the _input variants (Q0, Q1: no normal but this one is read): the caller's normal through
     * prepare_normals' arithmetic and its image's round trip (docs/tiles.md) */
    vec3 n = snorm8_round_trip(input_normal(xy, layer, textureSize(src_normals, 0)));
#elif GEN_GPU
    vec3 n = imageLoad(normals_image, ivec3(xy, layer)).xyz; /* xy is inside the slice (main) */
#else
    vec3 n = load_normal(xy, layer);
#endif
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
     * pixel of an active tile: its raw values feed the importance map and the load counter, which
     * steer the adaptive pass elsewhere; a quiet texel's importance is 0 (the AO 1 it ends as has
     * no detail to sample), whether tiles are skipped or not, and a tile that is not active is all
     * quiet: main skips it. Within an active tile the base pass computes every texel (with a
     * branch around a quiet texel's taps lavapipe, which runs both sides, took 1.05x the time on
     * interior_fzkhaus, which has none). compute_all_tiles (CB.tiles_all) skips nothing:
     * test_tiles's reference, which checks that the skip changes no pixel. */
    bool quiet = zc >= CB.background_z || sat(pc.z * CB.effect_fade_out_mul + CB.effect_fade_out_add) == 0.0;
#if GEN_BASE == 0
    bool faded = CB.tiles_all == 0 && quiet;
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
    /* 10a. raw obscurance and weight/20 for the adaptive pass; what the importance map takes */
    float raw = obsc_sum / weight_sum;
    imageStore(ssao_image, ivec3(xy, layer), vec4(raw, weight_sum / CACAO_BASE_WEIGHT_SCALE, 0.0, 0.0));
    return quiet ? 0.0 : raw;
#else

#if CACAO_VARIANT == CACAO_GENERATE_Q3
  if (!faded) {
    /* adaptive.md A: importance at the (offset) full-res UV ([quirk] FULLRES-UV kept) */
    vec2 uv_full = uvs + cb.per_slice_full_res_uv_offset[slice].xy;
    float importance = textureLod(importance_map, uv_full, 0.0).r;

    /* B: detail AO rescale (raw importance, [quirk] ADAPTIVE-DETAIL-SCALE), then the base taps.
     * Every slice reads its own slice's base ([quirk] BASE-SLICE-VIEW fixed; v1.2 under D3D
     * rules finds only slice 0's and reads (0,0) in the others). */
    obsc_sum *= float(CACAO_ADAPTIVE_TAP_BASE_COUNT) / float(CACAO_MAX_TAPS) +
                importance * float(CACAO_ADAPTIVE_TAP_FLEXIBLE_COUNT) / float(CACAO_MAX_TAPS);
    vec2 base = texelFetch(ssao_base, ivec3(xy, layer), 0).rg;
    weight_sum += base.g * CACAO_BASE_WEIGHT_SCALE;
    obsc_sum += base.r * weight_sum;

    /* C: number of extra taps (limiter with D3D's saturate: NaN -> 0, +inf -> 1) */
    float avg_importance = float(LOAD_COUNTER_VALUE) * CB.load_counter_avg_div;
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
    imageStore(ssao_image, ivec3(xy, layer), vec4(ao, packed_edges, 0.0, 0.0));
    return 0.0;
#endif
}

#if GEN_BASE == 0
void main()
{
    hoist_constants();
#if CACAO_VARIANT == CACAO_GENERATE_Q3 && !GEN_GPU
    g_load_counter = load_counter;
#endif
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 xy = texel_of(group);
    ivec2 size = slice_size();
    if (!in_rect(xy, size)) return; /* no LDS, no barriers: safe to leave */
#if CACAO_SKIPS_BY_CLASS
    /* a group is a tile (in one layer); one the list would leave out stores AO 1 and edges 1, one
     * reuse keeps stores nothing */
    int work = group_work(group);
    if (work != GROUP_COMPUTE) {
        if (work == GROUP_FILL) imageStore(ssao_image, ivec3(xy, int(gl_WorkGroupID.z)), vec4(1.0, 1.0, 0.0, 0.0));
        return;
    }
#endif
    init_atlas(size);
    generate_texel(xy, int(gl_WorkGroupID.z));
}
#else
/* The Q3 base pass and the importance map (importance.md "GenerateImportanceMap") in one
 * dispatch. The map reads the base AO as stored, in 8 bits: the stored value is re-made here with
 * the store's rounding (round to nearest even) and the load's scale. A texel past the slice's edge
 * reads the edge's (the sampler's clamp), which the same invocation or group computes, so it is
 * skipped. HIGHEST always has four slices. The per-texel shaping pow(sat(1 - strength v), power)
 * (no clamp, no fade) is monotone in v (strength and power are >= 0), so the max and min of the
 * shaped values are the shaped min and max of the raw ones: 2 pow calls per map texel. */
void store_importance(ivec2 t, float vmin, float vmax)
{
    float mx = max(pow(sat(1.0 - CB.effect_shadow_strength * vmin), CB.effect_shadow_pow), 0.0);
    float mn = min(pow(sat(1.0 - CB.effect_shadow_strength * vmax), CB.effect_shadow_pow), 1.0);
    imageStore(importance_map_image, t, vec4(pow(sat(2.0 * (mx - mn)), CACAO_IMPORTANCE_POWER)));
}

#if GEN_GPU
/* The GPU form: an invocation per slice texel, its four layers; a group of 8x8 texels reduces
 * the 2x2 quads of its texels in shared memory into 4x4 map texels. Sixteen texels per
 * invocation (the CPU form) leave a GPU a sixteenth of the invocations to hide latency with. */
shared vec2 g_quad_range[CACAO_WG_GENERATE_X * CACAO_WG_GENERATE_Y];

void main()
{
    hoist_constants();
    ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = slice_size();
    ivec2 l = ivec2(gl_LocalInvocationID.xy);
    ivec2 t = ivec2(gl_WorkGroupID.xy) * ivec2(CACAO_WG_GENERATE_X / 2, CACAO_WG_GENERATE_Y / 2) + l;
    bool stores = l.x < CACAO_WG_GENERATE_X / 2 && l.y < CACAO_WG_GENERATE_Y / 2 && in_rect(t, imageSize(importance_map_image));
    /* The group is a tile: one that is not active is all quiet, importance 0, and the base stores
     * nothing there (the adaptive pass reads no quiet texel's). The whole group returns: a
     * workgroup-uniform branch, before the barrier. */
    if (tiles[class_index(ivec2(gl_WorkGroupID.xy))] != CACAO_TILE_CLASS_ACTIVE) {
        if (stores) store_importance(t, 0.0, 0.0);
        return;
    }
    float vmin = 1.0e30, vmax = -1.0e30;
    if (in_rect(xy, size)) { /* no return: every invocation reaches the barrier */
        init_atlas(size);
        [[unroll]] for (int layer = 0; layer < 4; ++layer) {
            /* roundEven's result is already the integer 0..255 the store's conversion makes */
            float v = roundEven(sat(generate_texel(xy, layer)) * 255.0) * (1.0 / 255.0);
            vmin = min(vmin, v);
            vmax = max(vmax, v);
        }
    }
    g_quad_range[l.y * CACAO_WG_GENERATE_X + l.x] = vec2(vmin, vmax);
    barrier();
    if (stores) {
        vmin = 1.0e30;
        vmax = -1.0e30;
        [[unroll]] for (int q = 0; q < 4; ++q) {
            vec2 r = g_quad_range[(2 * l.y + (q >> 1)) * CACAO_WG_GENERATE_X + 2 * l.x + (q & 1)];
            vmin = min(vmin, r.x);
            vmax = max(vmax, r.y);
        }
        store_importance(t, vmin, vmax);
    }
}
#else
/* Invocation t computes the 2x2 slice texels 2t .. 2t + 1 of all four layers, which are exactly
 * the texels importance texel t reads, and so writes that texel too (one dispatch less: lavapipe
 * pays a fixed cost per dispatch). The 16 texels are unrolled, which was faster than a loop
 * (docs/speed-notes.md). */
void main()
{
    hoist_constants();
    /* A group is a block of 2x2 tiles holding an active tile (compact's list); the others keep the
     * clear's importance 0, which their quiet texels give. */
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 t = texel_of(group);
    ivec2 size = slice_size();
    if (!in_rect(t, imageSize(importance_map_image))) return;
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
    store_importance(t, vmin, vmax);
}
#endif
#endif
#endif /* GENERATE, GENERATE_GPU */

/* ============================== IMPORTANCE_A / IMPORTANCE_B ============================== */
#if CACAO_PASS == CACAO_PASS_IMPORTANCE_A || CACAO_PASS == CACAO_PASS_IMPORTANCE_B
/* spec: importance.md "PostprocessImportanceMapA", "PostprocessImportanceMapB", "Load counter" */
layout(local_size_x = CACAO_WG_IMPORTANCE_X, local_size_y = CACAO_WG_IMPORTANCE_Y) in;

float importance_at(vec2 uv) { return textureLod(importance_map, uv, 0.0).r; }

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
    if (in_rect(t, imageSize(importance_map_image))) imageStore(importance_map_image, t, vec4(ret));
#if CACAO_PASS == CACAO_PASS_IMPORTANCE_B
    /* every dispatched thread counts, in range or not ([quirk] LOADCOUNTER-OOB kept) */
    if (t.x % CACAO_LOAD_COUNTER_STRIDE == 0 && t.y % CACAO_LOAD_COUNTER_STRIDE == 0)
        atomicAdd(load_counter, uint(sat(ret) * 255.0 + 0.5));
#endif
}
#endif /* IMPORTANCE_A / B */
