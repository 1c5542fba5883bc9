/* constants.c - the constant-buffer math in one place (spec: constants.md sections 4, 5, 8, 8b).
 * Pure: settings + plan sizes + the frame's matrices in, cacao_constants out. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "internal.h"

/* Element (row, col) of a math-convention matrix stored row- or column-major. */
static float mat_at(const float m[16], bool row_major, int row, int col) {
    return row_major ? m[row * 4 + col] : m[col * 4 + row];
}

static bool all_zero(const float m[16]) {
    for (int i = 0; i < 16; ++i)
        if (m[i] != 0.0f) return false;
    return true;
}

/* A caller's matrix as the constant block holds it: GLSL reads a mat4 column-major, m[4*col + row]
 * = M(row, col), so v' = M * v; the identity where it is all zero (the inputs' convention) or where
 * `identity` says so. */
static cacao_mat4 block_mat4(const float m[16], bool row_major, bool identity) {
    identity = identity || all_zero(m);
    cacao_mat4 out;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            out.m[4 * col + row] = identity ? (row == col ? 1.0f : 0.0f) : mat_at(m, row_major, row, col);
    return out;
}

/* The projection's view: x right, y up, z = distance forward (cacao's view space), whatever the
 * caller's handedness, depth convention, jitter or asymmetric frustum. */
typedef struct projection_view {
    bool ortho;
    float h;                    /* +1: the caller's view looks down +z (LH), -1: down -z (RH) */
    float xy_mul[2], xy_add[2]; /* view xy = (xy_mul * uv + xy_add) * (perspective ? z : 1) */
    float z_num[2], z_den[2];   /* view z = (z_num[0] + z_num[1] d) / (z_den[0] + z_den[1] d) */
} projection_view;

static projection_view projection_view_of(const cacao_inputs *in) {
    const bool rm = in->matrices_row_major;
    const float p00 = mat_at(in->projection, rm, 0, 0), p11 = mat_at(in->projection, rm, 1, 1);
    const float p02 = mat_at(in->projection, rm, 0, 2), p12 = mat_at(in->projection, rm, 1, 2);
    const float p03 = mat_at(in->projection, rm, 0, 3), p13 = mat_at(in->projection, rm, 1, 3);
    const float p22 = mat_at(in->projection, rm, 2, 2), p23 = mat_at(in->projection, rm, 2, 3);
    const float p32 = mat_at(in->projection, rm, 3, 2), p33 = mat_at(in->projection, rm, 3, 3);
    projection_view v = {.ortho = p32 == 0.0f};
    if (!v.ortho) {
        /* clip w = p32 * z_caller = |p32| * z; ndc = 2u - 1 (x), 1 - 2v (y, clip y up). */
        const float w = fabsf(p32);
        v.h = p32 > 0.0f ? 1.0f : -1.0f;
        v.xy_mul[0] = 2.0f * w / p00;
        v.xy_add[0] = (-w - v.h * p02) / p00;
        v.xy_mul[1] = -2.0f * w / p11;
        v.xy_add[1] = (w - v.h * p12) / p11;
        /* d = (p22 h z + p23) / (|p32| z)  =>  z = (-p23 / |p32|) / (h p22 / |p32| - d): AMD's
         * DepthUnpackConsts (M, A) for a unit w row. */
        v.z_num[0] = -p23 / w;
        v.z_den[0] = v.h * p22 / w;
        v.z_den[1] = -1.0f;
    } else {
        /* clip w = p33 > 0; depth grows away from the camera unless depth_reversed. */
        v.h = ((p22 > 0.0f) != in->depth_reversed) ? 1.0f : -1.0f;
        v.xy_mul[0] = 2.0f * p33 / p00;
        v.xy_add[0] = (-p33 - p03) / p00;
        v.xy_mul[1] = -2.0f * p33 / p11;
        v.xy_add[1] = (p33 - p13) / p11;
        /* d = (p22 h z + p23) / p33  =>  z = (p33 d - p23) / (h p22), measured from the eye plane,
         * or from the near plane when that lies behind the eye (z >= 0 is in front). */
        const float near_d = in->depth_reversed ? 1.0f : 0.0f;
        const float near_z = (p33 * near_d - p23) / (v.h * p22);
        const float shift = near_z < 0.0f ? near_z : 0.0f;
        v.z_num[0] = -p23 - shift * v.h * p22;
        v.z_num[1] = p33;
        v.z_den[0] = v.h * p22;
    }
    return v;
}

/* View z at raw depth 0 and 1, in double; INFINITY where the projection gives no finite positive
 * z (an infinite far plane). */
static void depth_end_z(const projection_view *v, double z_at[2]) {
    for (int d = 0; d <= 1; ++d) {
        const double z = ((double)v->z_num[0] + v->z_num[1] * d) / ((double)v->z_den[0] + v->z_den[1] * d);
        z_at[d] = isfinite(z) && z > 0.0 ? z : INFINITY;
    }
}

/* View-space scale that keeps the far plane inside half's range (see cacaoi_fill_constants), but
 * never pushes the near plane into half's subnormals; a near plane inside them (a world scaled
 * down to 1e-30) is scaled up, by a power of two, as far as the far plane allows. */
static float view_scale(const projection_view *v) {
    double z_at[2], z_far = 0.0, z_near = INFINITY;
    depth_end_z(v, z_at);
    for (int d = 0; d <= 1; ++d)
        if (isfinite(z_at[d])) z_far = fmax(z_far, z_at[d]), z_near = fmin(z_near, z_at[d]);
    const double limit = 60000.0, smallest_normal = 6.2e-5;
    if (isfinite(z_near) && z_near < smallest_normal && z_far <= limit) {
        const int up = (int)ceil(log2(smallest_normal / z_near));
        const int room = z_far > 0.0 ? (int)floor(log2(limit / z_far)) : up;
        return (float)ldexp(1.0, up < room ? up : room);
    }
    if (!(z_far > limit)) return 1.0f;
    double k = limit / z_far;
    if (isfinite(z_near) && z_near * k < smallest_normal) k = fmin(1.0, smallest_normal / z_near);
    return (float)k;
}

/* The horizon estimators work in fp32 throughout; their view space is scaled by a further power of
 * two that brings the radius near 1, so that squared distances neither underflow (a near plane of
 * 1e-30 with a matching radius) nor overflow. A power of two scales every product exactly, so AO
 * is unchanged wherever nothing left fp32's range. */
static float horizon_scale(float k, float radius) {
    const double r = (double)k * radius;
    if (!(r > 0.0) || !isfinite(r)) return k;
    return (float)ldexp(k, -(int)lround(log2(r)));
}

cacao_result cacaoi_check_projection(const cacao_inputs *in, char *error, size_t error_size) {
    for (int i = 0; i < 16; ++i) {
        if (!isfinite(in->projection[i])) {
            cacaoi_set_error(error, error_size, "inputs.projection[%d] is not a finite number", i);
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        if (!isfinite(in->normals_to_view[i])) {
            cacaoi_set_error(error, error_size, "inputs.normals_to_view[%d] is not a finite number", i);
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        if (!isfinite(in->view_to_previous_view[i])) {
            cacaoi_set_error(error, error_size, "inputs.view_to_previous_view[%d] is not a finite number", i);
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
    }
    const bool rm = in->matrices_row_major;
#define P(r, c) mat_at(in->projection, rm, r, c)
    if (!(P(0, 0) > 0.0f) || !(P(1, 1) > 0.0f)) {
        cacaoi_set_error(error, error_size,
                        "inputs.projection: P(0,0) and P(1,1) must be positive (clip y up; check matrices_row_major)");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (P(0, 1) != 0.0f || P(1, 0) != 0.0f || P(2, 0) != 0.0f || P(2, 1) != 0.0f || P(3, 0) != 0.0f ||
        P(3, 1) != 0.0f) {
        cacaoi_set_error(error, error_size,
                        "inputs.projection: P(0,1), P(1,0), P(2,0), P(2,1), P(3,0) and P(3,1) must be 0 (a skewed or "
                        "rotated projection is not supported; check matrices_row_major)");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    const bool ortho = P(3, 2) == 0.0f;
    if (!ortho) {
        if (P(3, 3) != 0.0f || P(0, 3) != 0.0f || P(1, 3) != 0.0f) {
            cacaoi_set_error(error, error_size,
                            "inputs.projection: P(3,2) != 0 (perspective) needs P(3,3), P(0,3) and P(1,3) to be 0");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        if (P(2, 3) == 0.0f) {
            cacaoi_set_error(
                error, error_size,
                "inputs.projection: P(2,3) is 0, so depth cannot be linearised (not a perspective projection)");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
    } else {
        if (!(P(3, 3) > 0.0f) || P(2, 2) == 0.0f) {
            cacaoi_set_error(error, error_size,
                            "inputs.projection: P(3,2) is 0 (orthographic), which needs P(3,3) > 0 and P(2,2) != 0");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        if (P(0, 2) != 0.0f || P(1, 2) != 0.0f) {
            cacaoi_set_error(error, error_size,
                            "inputs.projection: orthographic with P(0,2) or P(1,2) != 0 (oblique) is not supported; "
                            "offset an orthographic frustum with P(0,3), P(1,3)");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
    }
#undef P
    /* Every constant derived below must be a finite number (no overflow for extreme matrices). */
    const projection_view v = projection_view_of(in);
    const float all[] = {v.xy_mul[0], v.xy_mul[1], v.xy_add[0], v.xy_add[1],
                         v.z_num[0],  v.z_num[1],  v.z_den[0],  v.z_den[1]};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        if (!isfinite(all[i])) {
            cacaoi_set_error(error, error_size,
                            "inputs.projection: too extreme for single precision (derived unprojection is not finite)");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
    if (!isfinite(in->normals_unpack_mul) || !isfinite(in->normals_unpack_add)) {
        cacaoi_set_error(error, error_size, "inputs.normals_unpack_mul/add must be finite numbers");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    return CACAO_SUCCESS;
}

static cacao_vec2 v2(float x, float y) { return (cacao_vec2){x, y}; }

/* spec: constants.md section 4 - per-slice rotation/scale of the sample pattern. */
static void fill_pattern(cacao_constants *c) {
    static const int spmap[5] = {0, 1, 4, 3, 2};
    const float pi = 3.1415926535897932f;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 5; ++j) {
            const float b = (float)spmap[j];
            const float angle = ((float)k + b / 5.0f) * pi * 0.5f;
            const float scale = 1.0f + ((float)k - 1.5f + (b - 2.0f) / 5.0f) * 0.07f;
            const float cs = cosf(angle) * scale, sn = sinf(angle) * scale;
            c->pattern_rot_scale[k * 5 + j] = (cacao_vec4){cs, -sn, -sn, -cs};
        }
}

/* spec: estimators.md sections 1-6 - the horizon-slice estimators' constants. k is the view scale
 * (every length scales with it, AO does not). */
static void fill_horizon_constants(const cacao_settings *s, const projection_view *v, float k, const cacao_plan *plan,
                                 const cacao_inputs *in, cacao_constants *c) {
    /* Depth denominator z_den[0] + z_den[1] d. Where z_den[0] is near 1 (standard Z), it is
     * written (z_den[0] - 1) + (1 - d): 1 - d is exact in fp32 for d >= 0.5, so the far range keeps
     * its precision instead of losing it to the cancellation in z_den[0] - d. */
    const double den0 = v->z_den[0];
    if (!v->ortho && fabs(den0 - 1.0) < 0.5 && v->z_den[1] == -1.0f) {
        c->horizon_depth_den_a = (float)(den0 - 1.0);
        c->horizon_depth_den_b = 0.0f;
        c->horizon_depth_den_c = 1.0f;
    } else {
        c->horizon_depth_den_a = v->z_den[0];
        c->horizon_depth_den_b = v->z_den[1];
        c->horizon_depth_den_c = 0.0f;
    }
    /* Background: the far plane's raw depth (the end of [0,1] with the larger view z); an infinite
     * far plane gives no finite z there, which the shader treats as background anyway. */
    double z_at[2];
    depth_end_z(v, z_at);
    c->horizon_far_depth = z_at[1] >= z_at[0] ? 1.0f : 0.0f;
    const bool gtao = s->estimator == CACAO_ESTIMATOR_GTAO, binary = s->visibility == CACAO_VISIBILITY_BINARY;
    const float radius = k * s->radius;
    c->horizon_radius = gtao ? radius * (float)CACAO_HORIZON_GTAO_RADIUS_FACTOR : radius;
    const float falloff_range = (float)(binary ? CACAO_HORIZON_GTAO_BINARY_FALLOFF_RANGE : CACAO_HORIZON_GTAO_FALLOFF_RANGE);
    c->horizon_falloff_mul = 1.0f / (falloff_range * c->horizon_radius);
    const float thickness_factor = (float)(binary ? CACAO_HORIZON_THICKNESS_BINARY : CACAO_HORIZON_THICKNESS_FALLOFF);
    c->horizon_thickness = s->thickness > 0.0f ? k * s->thickness : thickness_factor * radius;
    c->horizon_pixel_size = fabsf(c->ndc_to_view_mul.y) / (float)plan->height;
    c->horizon_directions = s->horizon_slices;
    c->horizon_steps = s->horizon_steps;
    c->horizon_binary = binary ? 1 : 0;
    c->horizon_noise_offset = (int)(288u * (in->frame_index % 64u));
    c->horizon_ortho = v->ortho ? 1 : 0;
    c->horizon_denoise_sigma = (float)CACAO_HORIZON_DENOISE_SIGMA;
    const double step = 3.14159265358979323846 / s->horizon_slices;
    c->horizon_rotation_cos = (float)cos(step);
    c->horizon_rotation_sin = (float)sin(step);
}

/* Tile classification (docs/tiles.md). Background: the stored (R16F) view z of the far plane,
 * less 2^-9 of it to cover the GPU's fp32 z and its rounding to half (geometry that close to the
 * far plane counts as background); no finite far plane: the invalid-depth value. Quiet by fade:
 * the fade argument z f_mul + f_add (0 or below: fade 0) below -quiet_margin, a margin far above
 * the few ulps by which the classify and generate passes can evaluate it differently. */
static void fill_tile_constants(const cacao_plan *plan, const projection_view *v, float k, cacao_constants *c) {
    double z_at[2];
    depth_end_z(v, z_at);
    const double z_stored = fmin(k * fmax(z_at[0], z_at[1]), CACAO_MAX_VIEW_Z);
    c->background_z = (float)(z_stored * (1.0 - 1.0 / 512.0));
    if (z_stored >= CACAO_MAX_VIEW_Z) c->background_z = (float)CACAO_MAX_VIEW_Z;
    c->quiet_margin = 1.0e-5f * fmaxf(1.0f, fabsf(c->effect_fade_out_add));
    c->tiles_all = plan->settings.compute_all_tiles ? 1 : 0;
    for (uint32_t i = 0; i < plan->step_count; ++i) /* a step over compact's blocks, or the needed tiles (docs/tiles.md) */
        if (plan->steps[i].list == CACAO_LIST_BLOCKS) c->active_blocks = 1;
        else if (plan->steps[i].list == CACAO_LIST_NORMALS)
            /* the horizon estimators' normals from depth: the view z list holds every tile not all
             * background (their CPU prepare computes the normals from the stored view z) */
            c->normals_list = plan->steps[i].key[0] == CACAO_PASS_HORIZON_PREPARE &&
                                      plan->steps[i].key[1] == CACAO_HORIZON_NORMALS_DEPTH
                                  ? 2
                                  : 1;
        else if (plan->steps[i].list == CACAO_LIST_PREPARE && plan->settings.estimator == CACAO_ESTIMATOR_CACAO)
            /* the upsample's groups are the needed tiles, smart apply's blocks of 2x2 tiles, the
             * other applies' the tiles whose quads touch one (a pixel left, up where the output's
             * width, height is odd) */
            c->needed_list = plan->settings.downsample ? 1 : plan->steps[i].key[1] == CACAO_APPLY_SMART_LIST ? 2 : 3;
    c->tile_pixels = plan->settings.estimator != CACAO_ESTIMATOR_CACAO ? CACAO_TILE
                                                                        : (int)(CACAO_TILE * (plan->settings.downsample ? 4 : 2));
    /* A plan that can find its frame quiet (classify.quiet first: docs/tiles.md "A quiet frame"):
     * every direct step after that pass runs from a gate it opens. The prepare reads depth 0 past
     * the image's edge where its slice texels cover more than the image: the test takes that depth
     * too. */
    for (uint32_t i = 0; i < plan->step_count; ++i) {
        const cacao_plan_step *st = &plan->steps[i];
        if (st->key[0] == CACAO_PASS_CLASSIFY && st->key[1] == CACAO_CLASSIFY_QUIET) c->quiet_test = 1;
        if (st->gate > c->gate_count) c->gate_count = st->gate;
        /* the direct apply before the listed one (needed_list 3): compact closes its gate where it
         * lists the groups */
        if (st->key[0] == CACAO_PASS_APPLY && (st->key[1] == CACAO_OUTPUT_NON_SMART || st->key[1] == CACAO_OUTPUT_HALF))
            c->apply_gate = st->gate;
    }
    if (c->needed_list == 3) c->needed_shift = (int)((plan->width & 1) | (plan->height & 1) << 1);
    else c->apply_gate = 0;
    const uint32_t scale = plan->settings.downsample ? 4 : 2;
    c->quiet_zero_depth = plan->slice_width * scale > plan->width || plan->slice_height * scale > plan->height;
    c->tiles_x = (int)plan->tiles_x;
    c->tiles_y = (int)plan->tiles_y;
    c->blur_groups_x = (int)plan->blur_groups_x;
    c->blur_groups_y = (int)plan->blur_groups_y;
    const int blur = plan->settings.blur_pass_count == CACAO_BLUR_NONE ? 0 : plan->settings.blur_pass_count;
    uint32_t blur_out[2];
    cacaoi_blur_out(cacaoi_form_pass(CACAO_PASS_BLUR, plan->settings.shader_forms == CACAO_SHADER_FORMS_GPU),
                    (unsigned)blur, blur_out);
    c->blur_out_x = (int)blur_out[0];
    c->blur_out_y = (int)blur_out[1];
}

/* Reuse of the previous frame (docs/tiles.md "Reusing the previous frame"): how far a changed
 * depth can move the output, in slice texels. A tap lies at most reuse_tap_reach times the lookup
 * radius from its texel (the longest pattern entry times the largest per-slice scale; the radius
 * in texels is bounded in the shader by the tile's least view z); besides the taps: the depth
 * mips' texel footprint (8 texels at level 3, HIGH and HIGHEST; 8 more for the GPU forms' mip chain,
 * below), the tap's rounding (1), depth and normal edges and
 * normals from depth (2), the blur's passes, the apply's or upsample's footprint (2) and one
 * texel to spare. cacao_record sets reuse (1 or 2) and gate_count per frame. Orthographic (no
 * perspective scale of xy with z): near_k only enters the near limit, which is 1 there. */
static void fill_reuse_constants(const cacao_plan *plan, cacao_constants *c) {
    if (!plan->settings.reuse_unchanged) return;
    if (plan->settings.estimator != CACAO_ESTIMATOR_CACAO) {
        /* the horizon estimators: any change recomputes the whole frame (no reach bound); their
         * tiles are 8x8 pixels, native and downsampled */
        c->reuse_all_or_nothing = 1;
        return;
    }
    float longest = 0.0f, scale = 0.0f;
    for (int i = 0; i < 32; ++i) {
        const cacao_vec4 e = c->sample_pattern[i];
        longest = fmaxf(longest, sqrtf(e.x * e.x + e.y * e.y));
    }
    for (int i = 0; i < 20; ++i) { /* (cs, -sn, -sn, -cs): a reflection times its scale */
        const cacao_vec4 m = c->pattern_rot_scale[i];
        scale = fmaxf(scale, sqrtf(m.x * m.x + m.y * m.y));
    }
    c->reuse_tap_reach = longest * scale * 1.01f; /* 1%: the R16F z the taps see is rounded */
    const int blur = plan->settings.blur_pass_count == CACAO_BLUR_NONE ? 0 : plan->settings.blur_pass_count;
    const bool mips = plan->settings.quality >= CACAO_QUALITY_HIGH; /* Q2 and Q3 read the depth mips */
    /* The GPU forms sample a mip chain: a GPU's sampler rounds a tap's coordinate to its sub-texel
     * precision, so near a texel's edge it may take the neighbouring texel of the level, up to 8
     * slice texels further at level 3 (the CPU forms choose as lavapipe's sampler does, exactly). */
    bool chain = false;
    for (uint32_t i = 0; i < plan->image_count; ++i)
        chain |= plan->images[i].resource == CACAO_RES_DEPTHS && plan->images[i].image_levels > 1;
    c->reuse_margin = (mips ? 8 : 0) + (chain ? 8 : 0) + 1 + 2 + blur + 2 + 1;
    c->reuse_all_or_nothing = plan->settings.quality == CACAO_QUALITY_HIGHEST ? 1 : 0;
    /* the near limit scales the radius by sat(|p| near_limit_rec) 0.8 + 0.2, and |p| <= z near_k,
     * near_k the length of (ndc_to_view xy, 1) at the image's farthest corner */
    const float ax = fmaxf(fabsf(c->ndc_to_view_add.x), fabsf(c->ndc_to_view_mul.x + c->ndc_to_view_add.x));
    const float ay = fmaxf(fabsf(c->ndc_to_view_add.y), fabsf(c->ndc_to_view_mul.y + c->ndc_to_view_add.y));
    c->reuse_near_k = sqrtf(1.0f + ax * ax + ay * ay) * 1.01f;
}

void cacaoi_fill_constants(const cacao_plan *plan, const cacao_inputs *in, cacao_constants *c) {
    cacao_settings literal;
    cacaoi_settings_literal(&plan->settings, &literal);
    const cacao_settings *s = &literal;
    const bool rm = in->matrices_row_major;
    memset(c, 0, sizeof *c);

    const projection_view v = projection_view_of(in);
    /* The deinterleaved view z is R16F (largest value 65504): when the far plane lies beyond that,
     * the whole view space is scaled by k < 1 (positions, radius, fade-out, near limit, bilateral
     * distance), which AO does not see; half's relative precision is the same at every scale.
     * k stays 1 for a far plane within range and for an infinite one. The horizon estimators
     * scale it further by a power of two (horizon_scale). */
    const float k = s->estimator == CACAO_ESTIMATOR_CACAO ? view_scale(&v) : horizon_scale(view_scale(&v), s->radius);
    c->depth_unpack = v2(k * v.z_num[0], v.z_den[0]);
    c->depth_unpack_d = v2(k * v.z_num[1], v.z_den[1]);
    c->view_xy_z = v.ortho ? v2(0.0f, 1.0f) : v2(1.0f, 0.0f);
    const float xy_k = v.ortho ? k : 1.0f; /* perspective xy scale with z already */
    c->ndc_to_view_mul = v2(xy_k * v.xy_mul[0], xy_k * v.xy_mul[1]);
    c->ndc_to_view_add = v2(xy_k * v.xy_add[0], xy_k * v.xy_add[1]);
    c->depth_uv_to_view_mul = c->ndc_to_view_mul; /* depth size == output size */
    c->depth_uv_to_view_add = c->ndc_to_view_add;
    const float tan_y = -0.5f * v.xy_mul[1]; /* tan of half the vertical fov; ortho: half the height */
    /* Depth edges compare depth differences with a fraction of a depth; orthographic pixels all
     * have one footprint, that of a perspective pixel at the depth where a 60-degree fov has it. */
    c->edge_depth = v.ortho ? v2(0.0f, xy_k * tan_y / 0.57735027f) : v2(1.0f, 0.0f);

    const unsigned quality = cacaoi_key_quality(s->quality);
    float radius = fminf(fmaxf(s->radius, 0.0f), 100000.0f);
    radius *= cacaoi_qualities[quality].radius_scale;
    radius *= k;
    c->effect_radius = radius;
    c->effect_shadow_strength = fminf(fmaxf(s->shadow_multiplier * (float)CACAO_STRENGTH_MULTIPLIER, 0.0f), 10.0f);
    c->effect_shadow_pow = fminf(fmaxf(s->shadow_power, 0.0f), 10.0f);
    c->effect_shadow_clamp = fminf(fmaxf(s->shadow_clamp, 0.0f), 1.0f);
    c->effect_fade_out_mul = -1.0f / (k * (s->fade_out_to - s->fade_out_from));
    c->effect_fade_out_add = s->fade_out_from / (s->fade_out_to - s->fade_out_from) + 1.0f;
    c->effect_horizon_angle_threshold = fminf(fmaxf(s->horizon_angle_threshold, 0.0f), 1.0f);
    /* Near limit from the raw radius, not the LOWEST-reduced one ([quirk] NEARLIMIT-RAW-RADIUS). */
    float near_limit = k * s->radius * (float)CACAO_NEAR_LIMIT_RADIUS_FACTOR;
    near_limit *= cacaoi_qualities[quality].near_limit_scale;
    near_limit /= tan_y;
    /* Orthographic: the footprint does not grow near the camera, so no near limit (factor 1). */
    c->effect_sampling_radius_near_limit_rec = v.ortho ? 1.0e30f : 1.0f / near_limit;
    c->depth_precision_offset_mod = (float)CACAO_DEPTH_PRECISION_OFFSET_MOD;
    c->neg_rec_effect_radius = -1.0f / radius;
    c->load_counter_avg_div = (float)(9.0 / ((double)plan->importance_width * (double)plan->importance_height * 255.0));
    c->adaptive_sample_count_limit = s->adaptive_quality_limit;
    c->inv_sharpness = fminf(fmaxf(1.0f - s->sharpness, 0.0f), 1.0f);
    c->slice_count = (int)plan->slice_count;
    fill_tile_constants(plan, &v, k, c);
    /* The upsample's weights as exp2 of precomputed products: no division per weight, and the
     * spatial Gaussian separates, exp(-(dx^2 + dy^2) / v) = exp(-dx^2 / v) exp(-dy^2 / v), so its
     * 6 distinct axis factors (|d| = 0, 0.5, .., 2.5 texels) come from this block. */
    const double log2e = 1.4426950408889634;
    /* below -FLT_MIN, never -0 or a denormal: the upsample weighs an entry outside the image 0 through
     * exp2(+inf * this) (apply.glsl); against a multiplier as small, a finite depth difference
     * (|dz| <= CACAO_MAX_VIEW_Z, dz^2 < 2^32) makes an exponent of at most 2^-94: weight 1 either way */
    c->bilateral_depth_exp2_mul =
        fminf((float)(-log2e / ((double)s->bilateral_similarity_distance_sigma * k * k)), -FLT_MIN);
    float *axis = &c->bilateral_axis_weight[0].x;
    for (int i = 0; i < 6; ++i) axis[i] = (float)exp(-(0.25 * i * i) / (double)s->bilateral_sigma_squared);
    axis[6] = axis[7] = 0.0f;
    const bool default_unpack = in->normals_unpack_mul == 0.0f && in->normals_unpack_add == 0.0f;
    c->normals_unpack_mul = default_unpack ? 2.0f : in->normals_unpack_mul;
    c->normals_unpack_add = default_unpack ? -1.0f : in->normals_unpack_add;
    c->detail_ao_strength = s->detail_shadow_strength;

    const float sw = (float)plan->slice_width, sh = (float)plan->slice_height;
    const float w = (float)plan->width, h = (float)plan->height;
    const float iw = (float)plan->importance_width, ih = (float)plan->importance_height;
    c->ssao_buffer_inverse_dimensions = v2(1.0f / sw, 1.0f / sh);
    c->slice_width = (int)plan->slice_width;
    c->slice_height = (int)plan->slice_height;
    c->depth_buffer_inverse_dimensions = v2(1.0f / w, 1.0f / h);
    c->output_buffer_inverse_dimensions = v2(1.0f / w, 1.0f / h);
    c->importance_map_inverse_dimensions = v2(1.0f / iw, 1.0f / ih);
    for (int k = 0; k < 4; ++k)
        c->per_slice_full_res_uv_offset[k] = (cacao_vec4){(float)(k % 2) / sw, (float)(k / 2) / sh, 0.0f, 0.0f};
    fill_pattern(c);
    static const float sample_pattern[128] = {CACAO_SAMPLE_PATTERN_VALUES};
    memcpy(c->sample_pattern, sample_pattern, sizeof sample_pattern);

    c->normals_to_view = block_mat4(in->normals_to_view, rm, s->generate_normals);
    /* temporal accumulation: the camera's motion; record.c sets temporal_history */
    c->view_to_previous_view = block_mat4(in->view_to_previous_view, rm, false);
    c->temporal_min_weight = s->temporal_frames ? 1.0f / (float)s->temporal_frames : 1.0f;
    if (s->estimator != CACAO_ESTIMATOR_CACAO) fill_horizon_constants(s, &v, k, plan, in, c);
    fill_reuse_constants(plan, c);
}
