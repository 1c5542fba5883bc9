/* constants.c - the constant-buffer math in one place (spec: constants.md sections 4, 5, 8, 8b).
 * Pure: settings + plan sizes + the frame's matrices in, cacao_constants out. */
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
    }
    const bool rm = in->matrices_row_major;
    if (!(mat_at(in->projection, rm, 0, 0) > 0.0f) || !(mat_at(in->projection, rm, 1, 1) > 0.0f)) {
        cacaoi_set_error(error, error_size,
                        "inputs.projection: P(0,0) and P(1,1) must be positive (clip y up; check matrices_row_major)");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (mat_at(in->projection, rm, 2, 3) == 0.0f) {
        cacaoi_set_error(error, error_size,
                        "inputs.projection: P(2,3) is 0, so depth cannot be linearised (not a perspective projection)");
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

void cacaoi_fill_constants(const cacao_plan *plan, const cacao_inputs *in, cacao_constants *c) {
    cacao_settings literal;
    cacaoi_settings_literal(&plan->settings, &literal);
    const cacao_settings *s = &literal;
    const bool rm = in->matrices_row_major;
    memset(c, 0, sizeof *c);

    /* Depth linearisation: z = M / (A - d); the sign fix makes RH and reversed-Z work. */
    const float depth_mul = -mat_at(in->projection, rm, 2, 3);
    float depth_add = mat_at(in->projection, rm, 2, 2);
    if (depth_mul * depth_add < 0.0f) depth_add = -depth_add;
    c->depth_unpack = v2(depth_mul, depth_add);

    const float tan_y = 1.0f / mat_at(in->projection, rm, 1, 1);
    const float tan_x = 1.0f / mat_at(in->projection, rm, 0, 0);
    c->camera_tan_half_fov = v2(tan_x, tan_y);
    c->ndc_to_view_mul = v2(2.0f * tan_x, -2.0f * tan_y);
    c->ndc_to_view_add = v2(-tan_x, tan_y);
    c->depth_uv_to_view_mul = c->ndc_to_view_mul; /* depth size == output size */
    c->depth_uv_to_view_add = c->ndc_to_view_add;

    const unsigned quality = cacaoi_key_quality(s->quality);
    float radius = fminf(fmaxf(s->radius, 0.0f), 100000.0f);
    if (quality == CACAO_KEY_QUALITY_LOWEST) radius *= (float)CACAO_LOWEST_RADIUS_FACTOR;
    c->effect_radius = radius;
    c->effect_shadow_strength = fminf(fmaxf(s->shadow_multiplier * (float)CACAO_STRENGTH_MULTIPLIER, 0.0f), 10.0f);
    c->effect_shadow_pow = fminf(fmaxf(s->shadow_power, 0.0f), 10.0f);
    c->effect_shadow_clamp = fminf(fmaxf(s->shadow_clamp, 0.0f), 1.0f);
    c->effect_fade_out_mul = -1.0f / (s->fade_out_to - s->fade_out_from);
    c->effect_fade_out_add = s->fade_out_from / (s->fade_out_to - s->fade_out_from) + 1.0f;
    c->effect_horizon_angle_threshold = fminf(fmaxf(s->horizon_angle_threshold, 0.0f), 1.0f);
    /* Near limit from the raw radius, not the LOWEST-reduced one ([quirk] NEARLIMIT-RAW-RADIUS). */
    float near_limit = s->radius * (float)CACAO_NEAR_LIMIT_RADIUS_FACTOR;
    if (quality <= CACAO_KEY_QUALITY_LOW) near_limit *= (float)CACAO_LOW_NEAR_LIMIT_FACTOR;
    near_limit /= tan_y;
    c->effect_sampling_radius_near_limit_rec = 1.0f / near_limit;
    c->depth_precision_offset_mod = (float)CACAO_DEPTH_PRECISION_OFFSET_MOD;
    c->neg_rec_effect_radius = -1.0f / radius;
    c->load_counter_avg_div =
        (float)(9.0 / ((double)plan->importance_width * (double)plan->importance_height * 255.0));
    c->adaptive_sample_count_limit = s->adaptive_quality_limit;
    c->inv_sharpness = fminf(fmaxf(1.0f - s->sharpness, 0.0f), 1.0f);
    c->slice_count = (int)plan->slice_count;
    c->bilateral_sigma_squared = s->bilateral_sigma_squared;
    c->bilateral_similarity_distance_sigma = s->bilateral_similarity_distance_sigma;
    const bool default_unpack = in->normals_unpack_mul == 0.0f && in->normals_unpack_add == 0.0f;
    c->normals_unpack_mul = default_unpack ? 2.0f : in->normals_unpack_mul;
    c->normals_unpack_add = default_unpack ? -1.0f : in->normals_unpack_add;
    c->detail_ao_strength = s->detail_shadow_strength;
    /* Every slice reads its own base-pass result: the fix of [quirk] BASE-SLICE-VIEW. */
    c->base_from_all_slices = 1;

    const float sw = (float)plan->slice_width, sh = (float)plan->slice_height;
    const float w = (float)plan->width, h = (float)plan->height;
    const float iw = (float)plan->importance_width, ih = (float)plan->importance_height;
    c->ssao_buffer_dimensions = v2(sw, sh);
    c->ssao_buffer_inverse_dimensions = v2(1.0f / sw, 1.0f / sh);
    c->depth_buffer_dimensions = v2(w, h);
    c->depth_buffer_inverse_dimensions = v2(1.0f / w, 1.0f / h);
    c->output_buffer_dimensions = v2(w, h);
    c->output_buffer_inverse_dimensions = v2(1.0f / w, 1.0f / h);
    c->importance_map_dimensions = v2(iw, ih);
    c->importance_map_inverse_dimensions = v2(1.0f / iw, 1.0f / ih);
    for (int k = 0; k < 4; ++k)
        c->per_slice_full_res_uv_offset[k] = (cacao_vec4){(float)(k % 2) / sw, (float)(k / 2) / sh, 0.0f, 0.0f};
    fill_pattern(c);
    static const float sample_pattern[128] = {CACAO_SAMPLE_PATTERN_VALUES};
    memcpy(c->sample_pattern, sample_pattern, sizeof sample_pattern);

    /* GLSL reads the mat4 column-major: m[4*col + row] = N(row, col), so n' = N * n. */
    const bool identity = s->generate_normals || all_zero(in->normals_to_view);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            c->normals_to_view.m[4 * col + row] =
                identity ? (row == col ? 1.0f : 0.0f) : mat_at(in->normals_to_view, rm, row, col);
}
