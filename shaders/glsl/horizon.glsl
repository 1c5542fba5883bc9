/* horizon.glsl - the horizon estimators (GTAO and the visibility bitmask): prepare, the estimator,
 * and the denoise passes. */

/* The GPU forms (CACAO_PASS_HORIZON_*_GPU) are the same code on direct grids (cacao_shared.h). */
#define HORIZON_PREPARE_PASS (CACAO_PASS == CACAO_PASS_HORIZON_PREPARE || CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU)
#define HORIZON_MAIN_PASS (CACAO_PASS == CACAO_PASS_HORIZON_MAIN || CACAO_PASS == CACAO_PASS_HORIZON_MAIN_GPU)
#define HORIZON_DENOISE_PASS (CACAO_PASS == CACAO_PASS_HORIZON_DENOISE || CACAO_PASS == CACAO_PASS_HORIZON_DENOISE_GPU)
#define HORIZON_TEMPORAL_PASS (CACAO_PASS == CACAO_PASS_HORIZON_TEMPORAL)
#if HORIZON_PREPARE_PASS || HORIZON_MAIN_PASS || HORIZON_DENOISE_PASS || HORIZON_TEMPORAL_PASS
/* spec: estimators.md. GTAO and the cosine-weighted visibility bitmask, at full resolution, one
 * invocation per pixel, all in fp32. View z of background pixels (the far plane, or depth that
 * gives no finite positive z: NaN, Inf, an infinite far plane) is stored as -1: such pixels output
 * 1 and are ignored as samples and as denoise neighbours. */
layout(local_size_x = CACAO_WG_HORIZON_X, local_size_y = CACAO_WG_HORIZON_Y) in;

const float HORIZON_PI = 3.14159265358979;
const float HORIZON_HALF_PI = 1.57079632679490;

/* View-space position of pixel p's centre at view z (estimators.md section 1). */
vec3 horizon_pos(ivec2 p, float z) { return view_pos((vec2(p) + 0.5) * CB.depth_buffer_inverse_dimensions, z); }

/* Unit vector from the surface point towards the camera. */
vec3 horizon_to_camera(vec3 pos) { return CB.horizon_ortho != 0 ? vec3(0.0, 0.0, -1.0) : -normalize(pos); }

/* A stored normal, renormalised; zero or non-finite -> facing the camera. */
vec3 horizon_normal(vec3 stored, vec3 to_camera)
{
    float len2 = dot(stored, stored);
    return (len2 > 1e-12 && len2 < 1e30) ? stored * inversesqrt(len2) : to_camera;
}

#if HORIZON_PREPARE_PASS

#if CACAO_PASS == CACAO_PASS_HORIZON_PREPARE && CACAO_VARIANT == CACAO_HORIZON_NORMALS_DEPTH
/* The CPU form of the normals from depth: the view z its view z variant stored before, the same
 * horizon_view_z of the same depth (an image load costs lavapipe less than a fetch and the
 * division, five of them a pixel). */
float load_view_z(ivec2 p, ivec2 size) { return in_rect(p, size) ? imageLoad(view_depth, p).r : -1.0; }
#else
float load_view_z(ivec2 p, ivec2 size) { return in_rect(p, size) ? horizon_view_z(texelFetch(src_depth, p, 0).r) : -1.0; }
#endif
#define HORIZON_STORES_VIEW_Z (CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU || CACAO_VARIANT != CACAO_HORIZON_NORMALS_DEPTH)

#if CACAO_VARIANT == CACAO_HORIZON_NORMALS_DEPTH
/* Unit direction from pc to a neighbour, zero where the neighbour is missing (off-image or
 * background): its cross products then carry no weight. */
vec3 neighbour_dir(vec3 pc, ivec2 q, float zq)
{
    if (!(zq > 0.0)) return vec3(0.0);
    vec3 d = horizon_pos(q, zq) - pc;
    float len2 = dot(d, d);
    return len2 > 0.0 ? d * inversesqrt(len2) : vec3(0.0);
}
#endif

/* The view z and normal of pixel p (inside the image): the view z alone (CACAO_HORIZON_VIEW_Z_ONLY),
 * or the normal and, unless the view z is already stored (HORIZON_STORES_VIEW_Z), the view z. */
void prepare_pixel(ivec2 p, ivec2 size)
{
    float z = load_view_z(p, size);
#if CACAO_VARIANT == CACAO_HORIZON_VIEW_Z_ONLY
    imageStore(view_depth, p, vec4(z)); /* the normals: none read here, or computed next from this */
#else
    vec3 n = vec3(0.0, 0.0, -1.0);
    if (z > 0.0) {
        vec3 pc = horizon_pos(p, z);
        vec3 to_camera = horizon_to_camera(pc);
#if CACAO_VARIANT == CACAO_HORIZON_NORMALS_INPUT
        vec3 rgb = texelFetch(src_normals, p, 0).rgb;
        n = (CB.normals_to_view * vec4(rgb * CB.normals_unpack_mul + CB.normals_unpack_add, 0.0)).xyz;
        n = horizon_normal(n, to_camera);
#else
        ivec2 ql = p - ivec2(1, 0), qr = p + ivec2(1, 0), qt = p - ivec2(0, 1), qb = p + ivec2(0, 1);
        float zl = load_view_z(ql, size), zr = load_view_z(qr, size);
        float zt = load_view_z(qt, size), zb = load_view_z(qb, size);
        /* a missing neighbour counts as a full edge (weight 0) */
        vec4 e = depth_edges(z, zl > 0.0 ? zl : 1e30, zr > 0.0 ? zr : 1e30, zt > 0.0 ? zt : 1e30,
                             zb > 0.0 ? zb : 1e30);
        n = normal_from_neighbours(neighbour_dir(pc, ql, zl), neighbour_dir(pc, qr, zr), neighbour_dir(pc, qt, zt),
                                   neighbour_dir(pc, qb, zb), e);
        n = horizon_normal(n, to_camera);
#endif
    }
#if HORIZON_STORES_VIEW_Z
    imageStore(view_depth, p, vec4(z));
#endif
    imageStore(view_normals, p, vec4(n, 0.0));
#endif
}

/* A workgroup is one tile: the CPU forms run over the tiles that are not all background
 * (docs/tiles.md), the GPU form over every tile, classifying it (the classify pass's rules,
 * tiles.glsl depth_flags: its class, its count and the needed tiles around an active one). */
void main()
{
#if CACAO_HOISTS_CONSTANTS
    hoist_constants();
#endif
    ivec2 group;
#if CACAO_PASS == CACAO_PASS_HORIZON_PREPARE_GPU
    group = ivec2(gl_WorkGroupID.xy);
    classify_group_begin(1);
    ivec2 p = texel_of(group);
    ivec2 size = textureSize(src_depth, 0);
    if (in_rect(p, size)) {
        classify_group_flag(1, ivec2(0), depth_flags(texelFetch(src_depth, p, 0).r));
        prepare_pixel(p, size);
    }
    classify_group_end(group, 1);
#else
    if (!group_of(group)) return;
    ivec2 p = texel_of(group);
    ivec2 size = imageSize(view_depth);
    if (in_rect(p, size)) prepare_pixel(p, size);
#endif
}
#endif /* HORIZON_PREPARE */


#if HORIZON_MAIN_PASS || HORIZON_DENOISE_PASS
float fetch_view_z(ivec2 p) { return imageLoad(view_depth, p).r; }
vec3 fetch_stored_normal(ivec2 p) { return imageLoad(view_normals, p).xyz; }
vec3 fetch_normal(ivec2 p, vec3 to_camera) { return horizon_normal(fetch_stored_normal(p), to_camera); }

/* Into the caller's output where no (further) denoise pass runs, else the intermediate. */
#ifdef CACAO_BIND_OUTPUT
void store_visibility(ivec2 p, float v) { imageStore(output_image, p, vec4(v, 0.0, 0.0, 0.0)); }
#else
void store_visibility(ivec2 p, float v) { imageStore(horizon_ao_out, p, vec4(v)); }
#endif
#endif

#if HORIZON_MAIN_PASS
#define HORIZON_BITMASK                                                                                    \
    (CACAO_VARIANT == CACAO_HORIZON_BITMASK || CACAO_VARIANT == CACAO_HORIZON_BITMASK_DIRECT ||             \
     CACAO_VARIANT == CACAO_HORIZON_BITMASK_HALF)
#define HORIZON_HALF (CACAO_VARIANT == CACAO_HORIZON_GTAO_HALF || CACAO_VARIANT == CACAO_HORIZON_BITMASK_HALF)

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
    if (ay > ax) r = HORIZON_HALF_PI - r;
    if (x < 0.0) r = HORIZON_PI - r;
    return y < 0.0 ? -r : r;
}

/* One slice's frame (estimators.md section 2.2): tangent t, the normal's signed angle n from the
 * view vector and cos n, sin n, the projected normal's length pl, F(n) = cos n + n sin n. Since
 * t and v span the slice plane, pN . t = N . t and pN . v = N . v: no projection is needed. */
struct horizon_frame {
    vec3 t;
    float n, cos_n, sin_n, pl, full;
    vec3 a;         /* the slice plane's normal */
    float snap_v, snap_t; /* a sample's offset along a moves it by -(that) * (snap_v, snap_t) in (v, t) */
};

horizon_frame make_horizon_frame(vec2 dir, vec3 v, vec3 nrm)
{
    horizon_frame f;
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
    /* Snapped samples (estimators.md pitfall 6): a sample pixel lies off the slice plane, and
     * dropping that offset along a lifts half of the samples of a flat surface above its tangent
     * line (a grazing floor darkens, more with more steps). Instead the offset is removed along
     * u, a's part in the centre's tangent plane: a sample keeps its height above that plane, so a
     * plane through the centre occludes nothing at any budget. Where u is nearly orthogonal to
     * the slice (a close to the normal: the slice weighs pl ~ 0) the offset is dropped as before. */
    f.a = cross(f.t, v);
    float an = dot(f.a, nrm);
    vec3 u = f.a - an * nrm;
    float ua = 1.0 - an * an; /* u . a */
    float k = ua > 0.05 ? 1.0 / ua : 0.0;
    f.snap_v = k * dot(u, v);
    f.snap_t = k * dot(u, f.t);
    return f;
}

/* 4 G(theta) of estimators.md section 2.3, with cos(2 theta) and sin(2 theta) given. */
float arc_g4(float theta, float cos2, float sin2, horizon_frame f)
{
    return f.cos_n + 2.0 * theta * f.sin_n - (cos2 * f.cos_n + sin2 * f.sin_n);
}

#if HORIZON_BITMASK
/* Fraction U of the slice's cosine-weighted half-circle below the direction (x, y) = (along v,
 * along t) (estimators.md section 4.2); c_low4 = 4 C(n - pi/2), inv_full4 = 1 / (4 F(n)).
 * Directions beyond the half-circle's edges give 1 and 0. The GPU form returns early for them;
 * the CPU form computes the arc for every direction and selects, since lavapipe runs every lane
 * through both paths of an early return and pays for the masks: a third of the sector math, an
 * eighth of the bitmask's main pass (docs/speed-notes.md). */
float sector_fraction(float x, float y, horizon_frame f, float c_low4, float inv_full4)
{
    float theta = fast_atan2(y, x);
#if CACAO_PASS == CACAO_PASS_HORIZON_MAIN_GPU
    if (theta >= f.n + HORIZON_HALF_PI) return 1.0;
    if (theta <= f.n - HORIZON_HALF_PI) return 0.0;
#endif
    float inv_r2 = 1.0 / max(x * x + y * y, 1e-30);
    float c4 = arc_g4(theta, (x * x - y * y) * inv_r2, 2.0 * x * y * inv_r2, f);
#if CACAO_PASS == CACAO_PASS_HORIZON_MAIN_GPU
    return sat(((theta < 0.0 ? -c4 : c4) - c_low4) * inv_full4);
#else
    float u = sat(((theta < 0.0 ? -c4 : c4) - c_low4) * inv_full4);
    u = theta <= f.n - HORIZON_HALF_PI ? 0.0 : u;
    return theta >= f.n + HORIZON_HALF_PI ? 1.0 : u;
#endif
}
#endif

/* Past the image's edge (the spec's prototype stops a side at its first sample there) the surface
 * is taken to go on as the tangent plane of the image's last pixel e on the side's line: its
 * stored view z and normal n. On a view ray view_pos(uv, z) = (c (view_xy_z.x z + view_xy_z.y),
 * z), c = ndc_to_view (uv), that plane n . x = n . p_e is met where 1 / z (perspective: view_xy_z
 * = (1, 0)) or z (orthographic: (0, 1)) is an affine function of the pixel q: plane.x + plane.y
 * q.x + plane.z q.y (plane_z). A zero plane (no sample past the edge) where e is background, or
 * where no sample of the side can leave the image: a step reaches len_max pixels at most, half a
 * pixel more per axis rounded. The CPU forms store the normals of every border tile that is not
 * all background (compact.horizon). estimators-design.md: the mean RMSE over the shared scenes
 * fell by 2-3% (nothing changed on the one whose samples stay inside). */
vec3 side_plane(ivec2 p, vec2 d, ivec2 size, float len_max)
{
    vec2 lim = mix(vec2(-0.5), vec2(size) - 0.5, greaterThan(d, vec2(0.0)));
    vec2 tt = abs(lim - vec2(p)) / max(abs(d), vec2(1e-6));
    float t = min(tt.x, tt.y); /* from p to the image's border along d */
    if (t > len_max + 1.0) return vec3(0.0);
    ivec2 e = clamp(ivec2(roundEven(vec2(p) + t * d)), ivec2(0), size - 1);
    float ze = fetch_view_z(e);
    if (!(ze > 0.0)) return vec3(0.0);
    vec3 ne = fetch_stored_normal(e); /* a direction is all the plane needs: not renormalised */
    /* n.xy . c(q) = k.x + k.y q.x + k.z q.y, c(q) = ndc_to_view ((q + 0.5) / size) */
    vec2 m = ne.xy * CB.ndc_to_view_mul * CB.depth_buffer_inverse_dimensions;
    vec3 k = vec3(dot(ne.xy, CB.ndc_to_view_add) + 0.5 * (m.x + m.y), m);
    float w = dot(ne, horizon_pos(e, ze));
    /* perspective: z (k(q) + n.z) = w; orthographic: k(q) + n.z z = w */
    return CB.horizon_ortho != 0 ? vec3(w - k.x, -k.yz) / ne.z : vec3(k.x + ne.z, k.yz) / w;
}

/* The view z where q's view ray meets the side's plane; not positive, or not finite, where it
 * meets it behind the camera or not at all (the caller rejects those). */
float plane_z(vec3 plane, ivec2 q)
{
    float u = plane.x + plane.y * float(q.x) + plane.z * float(q.y);
    return CB.horizon_ortho != 0 ? u : 1.0 / u;
}

/* The visibility of pixel p; noise_p indexes the per-pixel noise (the pixel itself, or its 2x2
 * block downsampled, so that neighbouring blocks see well-spread slice angles). */
float horizon_visibility(ivec2 p, ivec2 noise_p, float z, float fade, ivec2 size)
{
    vec3 pos = horizon_pos(p, z);
    vec3 v = horizon_to_camera(pos);
    vec3 nrm = fetch_normal(p, v);
    const float radius = CB.horizon_radius, radius2 = radius * radius, inv_radius2 = 1.0 / radius2;
    float rpx = radius / (CB.horizon_pixel_size * view_xy_scale(z)); /* radius in pixels */
    float min_s = CACAO_HORIZON_MIN_OFFSET_PX / rpx;
    float len_max = (1.0 + min_s) * rpx; /* the longest step below (s < 1) */
    uint h = hilbert_index(uint(noise_p.x) & 63u, uint(noise_p.y) & 63u) + uint(CB.horizon_noise_offset);
    float xi_s = unit_fraction(h * R2_X + HALF);
    uint xi_t = h * R2_Y + HALF;
    const int ns = CB.horizon_directions, m = CB.horizon_steps;
    const vec2 rotation = vec2(CB.horizon_rotation_cos, CB.horizon_rotation_sin);
    float phi0 = HORIZON_PI * xi_s / float(ns);
    vec2 dir = vec2(cos(phi0), sin(phi0)); /* slice i: angle pi (i + xi_s) / ns */
    float sum_vis = 0.0, sum_full = 0.0;
    for (int i = 0; i < ns; ++i) {
        horizon_frame f = make_horizon_frame(dir, v, nrm);
        vec2 offset_dir = vec2(dir.x, -dir.y); /* rows grow downwards */
        dir = vec2(dir.x * rotation.x - dir.y * rotation.y, dir.x * rotation.y + dir.y * rotation.x);
#if HORIZON_BITMASK
        /* 4 C(n - pi/2) = -G4(n - pi/2) for n - pi/2 <= 0: cos(2 theta - n) = -cos n there */
        float c_low4 = -(f.cos_n + 2.0 * (f.n - HORIZON_HALF_PI) * f.sin_n + f.cos_n);
        float inv_full4 = 0.25 / max(f.full, 1e-12);
        uint bits = 0u;
        float occluded = 0.0;
#else
        float low_pos = -f.sin_n, low_neg = f.sin_n; /* cos(n +- pi/2): the half-circle edges */
        float c_pos = low_pos, c_neg = low_neg;
#endif
        vec3 plane_pos = side_plane(p, offset_dir, size, len_max);
        vec3 plane_neg = side_plane(p, -offset_dir, size, len_max);
        for (int j = 0; j < m; ++j) {
            float xi = unit_fraction(xi_t + uint(i + j * m) * R1);
            float s = (float(j) + xi) / float(m);
#if !HORIZON_BITMASK
            s *= s; /* GTAO: quadratic step spacing */
#endif
            float len = (s + min_s) * rpx;
            ivec2 delta = ivec2(roundEven(len * offset_dir));
            [[unroll]] for (int side = 0; side < 2; ++side) {
                bool positive = side == 0;
                ivec2 q = positive ? p + delta : p - delta;
                ivec2 qc = clamp(q, ivec2(0), size - 1);
                float zq = fetch_view_z(qc);
                /* past the edge: a plane's sample more than the radius in front of or behind the
                 * pixel weighs 0 (and one beyond all reach would overflow the distance). The GPU
                 * form computes zp under the branch (a wave's samples mostly stay inside: ACO
                 * estimates 2% fewer cycles a wave on navi21, gfx1100 and vega10); the CPU form
                 * computes it for every sample and selects: lavapipe runs both arms of a branch. */
#if CACAO_PASS == CACAO_PASS_HORIZON_MAIN_GPU
                if (qc != q) {
                    float zp = plane_z(positive ? plane_pos : plane_neg, q);
                    zq = abs(zp - z) <= radius ? zp : -1.0;
                }
#else
                float zp = plane_z(positive ? plane_pos : plane_neg, q);
                if (qc != q) zq = abs(zp - z) <= radius ? zp : -1.0;
#endif
                if (!(zq > 0.0)) continue; /* background (or no plane's sample): weight 0 */
                vec3 sample_pos = horizon_pos(q, zq);
                vec3 delta3 = sample_pos - pos;
                float dist2 = dot(delta3, delta3);
                float off = dot(delta3, f.a);
                float x = dot(delta3, v) - off * f.snap_v, y = dot(delta3, f.t) - off * f.snap_t;
#if HORIZON_BITMASK
                float w = CB.horizon_binary != 0 ? (dist2 <= radius2 ? 1.0 : 0.0) : max(0.0, 1.0 - dist2 * inv_radius2);
                if (!(w > 0.0)) continue;
                /* back point: T further along the sample's own view ray, away from the camera
                 * (y: S . t = delta . t). Orthographic: the ray is -v, so x loses T and y (t is
                 * orthogonal to v) keeps its value. */
                float xb = x, yb = y;
                if (CB.horizon_ortho != 0) {
                    xb -= CB.horizon_thickness;
                } else {
                    float along = CB.horizon_thickness * inversesqrt(dot(sample_pos, sample_pos));
                    xb += along * dot(sample_pos, v);
                    yb += along * dot(sample_pos, f.t);
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
                float w = sat((radius - dist2 * inv_dist) * CB.horizon_falloff_mul);
                float cs = x * inversesqrt(max(x * x + y * y, 1e-30)); /* in the slice plane */
                if (positive) c_pos = max(c_pos, low_pos + (cs - low_pos) * w);
                else c_neg = max(c_neg, low_neg + (cs - low_neg) * w);
#endif
            }
#if HORIZON_BITMASK
            if (bits == 0xFFFFFFFFu) break; /* every sector is taken: later samples change nothing */
#endif
        }
#if HORIZON_BITMASK
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
#if HORIZON_BITMASK
    float vis = sat(1.0 - sum_vis / max(sum_full, 1e-9));
#else
    float vis = sat(sum_vis / max(sum_full, 1e-9));
#endif
    return 1.0 - (1.0 - vis) * fade; /* the fade-out: occlusion fades to none */
}

/* The fade-out distance range of the settings at view z: 0 where occlusion has faded completely.
 * There the result is 1 whatever the estimate, so main makes none (a faded pixel of an active tile,
 * or a faded block downsampled, costs this test only; one branch with the background test). */
float horizon_fade(float z) { return sat(z * CB.effect_fade_out_mul + CB.effect_fade_out_add); }

/* Native: over the needed tiles (docs/tiles.md), a workgroup is one tile of pixels, invocation t
 * computes pixel t (the GPU form: every tile; one that is not needed stores 1). Downsampled:
 * invocation t computes pixel 2t, the top-left of its 2x2 block, into texel t of the half-size
 * intermediate (background and faded blocks store 1 at once), and a workgroup's blocks cover 2x2
 * tiles: the CPU form runs over compact's list of those holding an active tile (the clear before
 * stores the 1 of the others), the GPU form over all of them, a group whose tiles hold no active
 * one storing 1 (their blocks are all quiet). The noise follows t. */
void main()
{
    ivec2 group;
    if (!group_of(group)) return;
#if CACAO_SKIPS_BY_CLASS
    bool needed = group_work(group) == GROUP_COMPUTE;
#endif
    ivec2 t = texel_of(group);
    ivec2 size = imageSize(view_depth);
#if HORIZON_HALF
    if (!in_rect(t, (size + 1) >> 1)) return;
    ivec2 p = 2 * t;
#if CACAO_READS_CLASSES
    if (!block_has_active(group)) { /* the same for the group */
        store_visibility(t, 1.0);
        return;
    }
#endif
#else
    if (!in_rect(t, size)) return;
    ivec2 p = t;
#endif
#if CACAO_SKIPS_BY_CLASS
    if (!needed) {
        store_visibility(t, 1.0);
        return;
    }
#endif
    float z = fetch_view_z(p), fade = horizon_fade(z);
    store_visibility(t, z > 0.0 && fade > 0.0 ? horizon_visibility(p, t, z, fade, size) : 1.0);
}
#endif /* HORIZON_MAIN */

#if HORIZON_DENOISE_PASS

/* Weight of neighbour point q (view z zq) for a pixel at pos with normal nrm (estimators.md
 * section 5): its distance from the pixel's tangent plane relative to sigma z, and the agreement
 * of the normals (the stored normal as it is: unit to 8 bits, and one that is zero weighs 0). */
float denoise_weight(vec3 pos, vec3 nrm, float inv_scale, ivec2 q, float zq)
{
    float plane = dot(nrm, horizon_pos(q, zq) - pos) * inv_scale;
    float agree = sat(dot(nrm, fetch_stored_normal(q)));
    agree *= agree;
    return exp2(-1.44269504 * plane * plane) * agree * agree; /* exp(-plane^2) */
}

/* Over the needed tiles (the GPU form: every tile; one that is not needed stores 1). */
void main()
{
#if CACAO_HOISTS_CONSTANTS
    hoist_constants();
#endif
    ivec2 group;
    if (!group_of(group)) return;
#if CACAO_SKIPS_BY_CLASS
    bool needed = group_work(group) == GROUP_COMPUTE;
#endif
    ivec2 p = texel_of(group);
    ivec2 size = imageSize(view_depth);
    if (!in_rect(p, size)) return;
#if CACAO_SKIPS_BY_CLASS
    if (!needed) { /* the 1 of the CPU forms' fills and clears */
        store_visibility(p, 1.0);
        return;
    }
#endif
    float z = fetch_view_z(p);
    if (!(z > 0.0)) {
        store_visibility(p, 1.0);
        return;
    }
    vec3 pos = horizon_pos(p, z);
    vec3 nrm = fetch_normal(p, horizon_to_camera(pos));
    float inv_scale = 1.0 / max(CB.horizon_denoise_sigma * z, 1e-30);
#if CACAO_VARIANT == CACAO_DENOISE_UPSAMPLE || CACAO_VARIANT == CACAO_DENOISE_UPSAMPLE_FINAL
    /* Downsampled: the 3x3 blocks' AO (texel q holds pixel 2q's) around p, each weighed by a tent
     * of radius HORIZON_UPSAMPLE_TENT pixels in x and y from p (the blocks' pixels lie 0 to 3
     * pixels away: every weight is positive) times the denoise weight of its pixel; where no
     * block's pixel lies on p's surface (a thin feature between them), the AO of the most similar
     * one. */
    const float HORIZON_UPSAMPLE_TENT = 4.0;
    ivec2 half_size = (size + 1) >> 1, base = p >> 1;
    float sum = 0.0, weight_sum = 0.0, best = -1.0, best_ao = 1.0;
    [[unroll]] for (int j = -1; j <= 1; ++j) {
        [[unroll]] for (int i = -1; i <= 1; ++i) {
            ivec2 q = base + ivec2(i, j);
            vec2 d = abs(vec2(p - 2 * q));
            float tent = max(HORIZON_UPSAMPLE_TENT - d.x, 0.0) * max(HORIZON_UPSAMPLE_TENT - d.y, 0.0);
            if (!in_rect(q, half_size)) continue;
            float zq = fetch_view_z(2 * q);
            if (!(zq > 0.0)) continue;
            float g = denoise_weight(pos, nrm, inv_scale, 2 * q, zq);
            float ao = imageLoad(horizon_ao, q).r;
            if (g > best) {
                best = g;
                best_ao = ao;
            }
            float w = tent * g;
            sum += w * ao;
            weight_sum += w;
        }
    }
    store_visibility(p, weight_sum > 1e-4 ? sum / weight_sum : best_ao);
#else
    /* 3x3 bilateral filter (estimators.md section 5) */
    float sum = imageLoad(horizon_ao, p).r, weight_sum = 1.0;
    [[unroll]] for (int j = -1; j <= 1; ++j) {
        [[unroll]] for (int i = -1; i <= 1; ++i) {
            ivec2 q = p + ivec2(i, j);
            if ((i == 0 && j == 0) || !in_rect(q, size)) continue;
            float zq = fetch_view_z(q);
            if (!(zq > 0.0)) continue;
            float w = denoise_weight(pos, nrm, inv_scale, q, zq);
            sum += w * imageLoad(horizon_ao, q).r;
            weight_sum += w;
        }
    }
    store_visibility(p, sum / weight_sum);
#endif
}
#endif /* HORIZON_DENOISE */

#if HORIZON_TEMPORAL_PASS
/* Temporal accumulation (cacao_settings.temporal_frames; docs/estimators.md "Temporal
 * accumulation"). A history texel holds x = 2 n + AO (the AO of the last n frames, n >= 1, AO in
 * [0, 1]) and y = the view z of its surface (-1: none). Every pixel: its point, moved into the last
 * frame's view space (static geometry), projected into the last frame's pixels (its projection is
 * this frame's), takes the bilinear mean of the history texels around it whose view z is that
 * point's, within 1% and the depth's own slope across a pixel (the smaller one-sided difference
 * of each axis: a silhouette's far side does not widen it); none match: disoccluded, the history
 * starts again. The frame's AO then weighs max(1 / (n + 1), 1 / temporal_frames). */
float temporal_view_z(ivec2 q, ivec2 size) { return in_rect(q, size) ? imageLoad(view_depth, q).r : -1.0; }

/* |z - zq| for a neighbour, huge where it is missing */
float temporal_step(float z, float zq) { return zq > 0.0 ? abs(zq - z) : 1e30; }

void main()
{
    hoist_constants();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(history_out);
    if (!in_rect(p, size)) return;
    float z = imageLoad(view_depth, p).r;
    float ao = imageLoad(horizon_ao, p).r;
    float frames = 0.0, previous = 1.0;
    if (z > 0.0 && CB.temporal_history != 0) {
        vec3 pos = (CB.view_to_previous_view * vec4(horizon_pos(p, z), 1.0)).xyz;
        float scale = view_xy_scale(pos.z);
        if (pos.z > 0.0 && scale > 0.0) {
            float slope = max(min(temporal_step(z, temporal_view_z(p - ivec2(1, 0), size)),
                                  temporal_step(z, temporal_view_z(p + ivec2(1, 0), size))),
                              min(temporal_step(z, temporal_view_z(p - ivec2(0, 1), size)),
                                  temporal_step(z, temporal_view_z(p + ivec2(0, 1), size))));
            float tolerance = 0.01 * pos.z + min(slope, pos.z);
            vec2 uv = (pos.xy / scale - CB.ndc_to_view_add) / CB.ndc_to_view_mul;
            vec2 f = uv * vec2(size) - 0.5; /* texel centres at integers */
            ivec2 b = ivec2(floor(f));
            vec2 t = f - vec2(b);
            float weight_sum = 0.0, sum = 0.0, fewest = 1e9;
            [[unroll]] for (int k = 0; k < 4; ++k) {
                ivec2 q = b + ivec2(k & 1, k >> 1);
                float w = ((k & 1) != 0 ? t.x : 1.0 - t.x) * ((k >> 1) != 0 ? t.y : 1.0 - t.y);
                vec2 h = imageLoad(history, clamp(q, ivec2(0), size - 1)).xy;
                if (in_rect(q, size) && w > 0.0 && h.y > 0.0 && abs(h.y - pos.z) <= tolerance) {
                    float n = floor(0.5 * h.x);
                    sum += w * (h.x - 2.0 * n);
                    weight_sum += w;
                    fewest = min(fewest, n);
                }
            }
            if (weight_sum > 1e-3) {
                previous = sum / weight_sum;
                frames = fewest;
            }
        }
    }
    float weight = max(1.0 / (frames + 1.0), CB.temporal_min_weight);
    float blended = frames == 0.0 ? ao : sat(mix(previous, ao, weight)); /* the first frame: its own AO */
    float kept = min(frames + 1.0, floor(1.0 / CB.temporal_min_weight + 0.5));
    imageStore(history_out, p, vec4(2.0 * kept + blended, z > 0.0 ? z : -1.0, 0.0, 0.0));
    imageStore(output_image, p, vec4(blended, 0.0, 0.0, 0.0));
}
#endif /* HORIZON_TEMPORAL */
#endif /* horizon estimators */
