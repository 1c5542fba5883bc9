/* common.glsl - what every pass may use: the precision of the fp16 variants, the arithmetic of
 * the algorithm shared by several passes (depth linearisation, edges, normals, obscurance, edge
 * packing), texel addressing, and the caller's depth reads. */

/* ---- fp16 variant (CACAO_FP16 == 1; blur, apply and upsample only) ----
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

float sat(float x) { return clamp(x, 0.0, 1.0); }
vec4 sat(vec4 x) { return clamp(x, vec4(0.0), vec4(1.0)); }

/* D3D's max(0, x): a NaN operand yields the other operand, i.e. 0. */
float max0(float x) { return x > 0.0 ? x : 0.0; }

/* Layer of a 2D-array resource -> slice index k (spec: README "Notation"). */
int slice_of_layer(int layer) { return CB.slice_count == 2 ? layer * 3 : layer; }

/* Round a value to half precision and back: mirrors AMD's half-precision shared memory. */
float round_to_half(float x) { return unpackHalf2x16(packHalf2x16(vec2(x, 0.0))).x; }

/* Raw hardware depth -> view-space z (spec: prepare.md "Depth linearisation"), as the projection
 * gives it: NaN, infinite or negative where the depth is invalid (classify.quiet tells those apart). */
float view_z_unclamped(float d)
{
    return (CB.depth_unpack.x + CB.depth_unpack_d.x * d) / (CB.depth_unpack.y + CB.depth_unpack_d.y * d);
}

/* ... and positive: a depth that gives no finite positive z (NaN in the depth buffer, d == A on an
 * infinite far plane, d beyond the far plane) becomes CACAO_MAX_VIEW_Z: far background, which the
 * fade-out removes. AMD divides blindly there ([quirk] INF-DEPTH); finite depths are unchanged. */
float view_z(float d)
{
    float z = view_z_unclamped(d);
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
 * reconstructed from depth"); camera-facing (negative z) in cacao's view space. The four weighted
 * products a.x (l x u) + a.y (u x r) + a.z (r x b) + a.w (b x l) are summed as two, l x (a.x u -
 * a.w b) + r x (a.z b - a.y u) (b x l = -(l x b), u x r = -(r x u)): the same sum in fewer
 * operations, rounded differently (docs/speed-notes.md, "The normals' two cross products"). */
vec3 normal_from_neighbours(vec3 l, vec3 r, vec3 u, vec3 b, vec4 e)
{
    vec4 a = vec4(e.x * e.z, e.z * e.y, e.y * e.w, e.w * e.x);
    vec3 n = vec3(0.0, 0.0, CACAO_NORMAL_BIAS_Z) + cross(l, a.x * u - a.w * b) + cross(r, a.z * b - a.y * u);
    return normalize(n);
}

/* Per-sample obscurance (spec: generate.md "Obs"). max0 keeps D3D's NaN rule for a zero delta.
 * The falloff term is at most 1 (len2 >= 0, falloff <= 0), so in generate's GPU form its max0 is a
 * saturate, which a GPU folds into the multiply-add (NaN gives 0 either way); the angle term keeps
 * its max0 (a normal a little longer than 1 takes it above 1). Equal for every input. */
float obscurance(vec3 n, vec3 delta, float falloff, float horizon)
{
    float len2 = dot(delta, delta);
    float cos_a = dot(n, delta) / sqrt(len2);
#if CACAO_PASS == CACAO_PASS_GENERATE_GPU
    return max0(cos_a - horizon) * sat(1.0 + len2 * falloff);
#else
    return max0(cos_a - horizon) * max0(1.0 + len2 * falloff);
#endif
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
 * larger: at HIGH and HIGHEST in the CPU forms it is the atlas of the mip chain (cacao_shared.h). */
ivec2 slice_size() { return ivec2(CB.slice_width, CB.slice_height); }

/* Level l of the depth atlas of a slice of size s0 (cacao_shared.h): (width, height, x, y). */
ivec4 depth_atlas_level(ivec2 s0, int l)
{
    return ivec4(CACAO_DEPTH_LEVEL_EXTENT(s0.x, l), CACAO_DEPTH_LEVEL_EXTENT(s0.y, l), l == 0 ? 0 : s0.x,
                 CACAO_DEPTH_ATLAS_Y(s0.y, l));
}

/* Texel q = 0..3 of the 2x2 quad 2u .. 2u + 1 that one invocation of a quad pass computes. */
ivec2 quad_texel(ivec2 u, int q) { return 2 * u + ivec2(q & 1, q >> 1); }

/* Mirror addressing (-1 -> 0, -2 -> 1, n -> n-1, ...), clamped for padding wider than n, without
 * branches or selects (5 instructions a coordinate on navi21 instead of 9): c ^ (c >> 31) is
 * -c - 1 for a negative c and c otherwise; the min takes the reflection at n exactly where that is
 * >= n; then the clamp. (For every int whose 2n - 1 - c does not overflow.) */
ivec2 mirror_coord(ivec2 c, ivec2 n)
{
    ivec2 a = c ^ (c >> 31);
    return clamp(min(a, 2 * n - 1 - a), ivec2(0), n - 1);
}

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

#if defined(CACAO_BIND_SRC_NORMALS) && (CACAO_PASS == CACAO_PASS_PREPARE_NORMALS || \
                                        CACAO_PASS == CACAO_PASS_GENERATE || CACAO_PASS == CACAO_PASS_GENERATE_GPU)
/* The caller's normal of slice texel t of the layer, in view space and clamped to [-1, 1] (spec:
 * prepare.md "Normals from input normals"; not renormalised, [quirk] NORMALS-NOT-NORMALIZED):
 * what prepare_normals stores, and what generate's _input variants compute themselves. `size` is
 * the caller's normals' (textureSize, read once by the caller of this function). */
vec3 input_normal(ivec2 t, int layer, ivec2 size)
{
#if CACAO_PASS == CACAO_PASS_PREPARE_NORMALS
    ivec2 p = full_res_pixel(t, slice_of_layer(layer));
#else
    /* generate's keys have no resolution axis: a slice texel is tile_pixels / CACAO_TILE pixels
     * wide (2 native, 4 downsampled), full_res_pixel's 2 t + d or 4 t + 2 d */
    int slice = slice_of_layer(layer);
    int f = CB.tile_pixels / CACAO_TILE;
    ivec2 p = f * t + (f >> 1) * ivec2(slice & 1, slice >> 1);
#endif
    vec3 rgb = in_rect(p, size) ? texelFetch(src_normals, p, 0).rgb : vec3(0.0);
    vec3 n = rgb * CB.normals_unpack_mul + CB.normals_unpack_add;
    vec3 nv = (CB.normals_to_view * vec4(n, 0.0)).xyz; /* n'_j = sum_i E[j][i] n_i */
    return clamp(nv, vec3(-1.0), vec3(1.0));
}
#endif

#if CACAO_PASS == CACAO_PASS_HORIZON_PREPARE || CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU || \
    (CACAO_PASS == CACAO_PASS_CLASSIFY && CACAO_VARIANT == CACAO_CLASSIFY_HORIZON)
/* Horizon estimators: raw depth -> view z, -1 for background (estimators.md section 1: the
 * denominator keeps 1 - d exact where d is near 1). Their prepare stores it; their classification
 * reads it from the caller's depth before that. */
float horizon_view_z(float d)
{
    if (d == CB.horizon_far_depth) return -1.0;
    float z = (CB.depth_unpack.x + CB.depth_unpack_d.x * d) /
              (CB.horizon_depth_den_a + CB.horizon_depth_den_b * d + CB.horizon_depth_den_c * (1.0 - d));
    return (z > 0.0 && z < 3.0e38) ? z : -1.0; /* NaN fails z > 0 */
}
#endif

#ifdef CACAO_BIND_SRC_DEPTH
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
