/* settings.c - defaults and validation of cacao_settings (spec: constants.md section 6). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

void cacaoi_set_error_v(char *error, size_t error_size, const char *fmt, va_list ap) {
    if (error && error_size > 0) vsnprintf(error, error_size, fmt, ap);
}

void cacaoi_set_error(char *error, size_t error_size, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    cacaoi_set_error_v(error, error_size, fmt, ap);
    va_end(ap);
}

const char *cacao_result_string(cacao_result result) {
    switch (result) {
    case CACAO_SUCCESS: return "success";
    case CACAO_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case CACAO_ERROR_INVALID_SIZE: return "invalid size";
    case CACAO_ERROR_UNSUPPORTED_FORMAT: return "unsupported format";
    case CACAO_ERROR_PERMUTATION_MISSING: return "shader permutation not embedded in this build";
    case CACAO_ERROR_UNSUPPORTED_DEVICE: return "unsupported device";
    case CACAO_ERROR_NOT_READY: return "context not ready (call cacao_context_resize first)";
    case CACAO_ERROR_OUT_OF_MEMORY: return "out of memory";
    case CACAO_ERROR_VULKAN: return "Vulkan error";
    }
    return "unknown result";
}

/* ---- Names of the enum settings ------------------------------------------------------------ */

/* One enum's names, indexed by value - 1, and the value its DEFAULT (0) stands for: the one place
 * each default is written (cacao_settings_resolve fills it from here). */
typedef struct enum_names {
    const char *const *names;
    int count;
    int default_value;
} enum_names;

#define NAMES(words, default_value) {words, (int)(sizeof words / sizeof words[0]), default_value}
static const enum_names quality_names = NAMES(cacaoi_quality_names, CACAO_QUALITY_HIGHEST);
static const enum_names precision_names = NAMES(cacaoi_precision_names, CACAO_PRECISION_FP32);
static const enum_names estimator_names = NAMES(cacaoi_estimator_names, CACAO_ESTIMATOR_CACAO);
static const enum_names visibility_names = NAMES(cacaoi_visibility_names, CACAO_VISIBILITY_FALLOFF);
static const enum_names shader_forms_names = NAMES(cacaoi_shader_forms_names, CACAO_SHADER_FORMS_CPU);

static const char *name_of(const enum_names *e, int value) {
    if (value == 0) value = e->default_value;
    return value >= 1 && value <= e->count ? e->names[value - 1] : NULL;
}

/* The value name spells, or 0 (no name spells the DEFAULT). */
static int value_of(const enum_names *e, const char *name) {
    for (int i = 0; name && i < e->count; ++i)
        if (strcmp(name, e->names[i]) == 0) return i + 1;
    return 0;
}

/* cacao_<kind>_name and cacao_<kind>_from_name of one enum (cacao.h), over its names above. */
#define ENUM_NAME_FUNCTIONS(kind, list)                                                                                \
    const char *cacao_##kind##_name(cacao_##kind value) { return name_of(&list, (int)value); }                         \
    cacao_result cacao_##kind##_from_name(const char *name, cacao_##kind *out) {                                       \
        const int value = value_of(&list, name);                                                                       \
        if (!value || !out) return CACAO_ERROR_INVALID_ARGUMENT;                                                       \
        *out = (cacao_##kind)value;                                                                                    \
        return CACAO_SUCCESS;                                                                                          \
    }
ENUM_NAME_FUNCTIONS(quality, quality_names)
ENUM_NAME_FUNCTIONS(precision, precision_names)
ENUM_NAME_FUNCTIONS(estimator, estimator_names)
ENUM_NAME_FUNCTIONS(visibility, visibility_names)
ENUM_NAME_FUNCTIONS(shader_forms, shader_forms_names)

/* How a float field defaults and which values it accepts. */
typedef struct float_rule {
    const char *name;
    size_t offset;
    float fallback;      /* value used for 0 */
    bool zero_allowed;   /* CACAO_ZERO selects a literal 0 */
    float min, max;      /* accepted literal range (after defaults) */
    bool min_exclusive;
} float_rule;

#define RULE(field, fallback, zero_ok, lo, hi, lo_excl) \
    {#field, offsetof(cacao_settings, field), fallback, zero_ok, lo, hi, lo_excl}

static const float_rule float_rules[] = {
    RULE(radius, 1.2f, false, 0.0f, 100000.0f, true),
    RULE(shadow_multiplier, 1.0f, false, 0.0f, 5.0f, true),
    RULE(shadow_power, 1.5f, false, 0.0f, 10.0f, true),
    RULE(shadow_clamp, 0.98f, false, 0.0f, 1.0f, true),
    RULE(horizon_angle_threshold, 0.06f, true, 0.0f, 1.0f, false),
    RULE(fade_out_from, 50.0f, true, 0.0f, 1e30f, false),
    RULE(fade_out_to, 300.0f, false, 0.0f, 1e30f, true),
    RULE(sharpness, 0.98f, true, 0.0f, 1.0f, false),
    RULE(detail_shadow_strength, 0.5f, true, 0.0f, 5.0f, false),
    RULE(adaptive_quality_limit, 0.45f, true, 0.0f, 1.0f, false),
    RULE(bilateral_sigma_squared, 5.0f, false, 0.0f, 1e30f, true),
    RULE(bilateral_similarity_distance_sigma, 0.01f, false, 0.0f, 1e30f, true),
    RULE(thickness, 0.0f, false, 0.0f, 1e30f, false), /* 0 stays 0: "relative to R", see the plan */
};

cacao_result cacao_settings_resolve(const cacao_settings *in, cacao_settings *out, char *error,
                                    size_t error_size) {
    if (!in || !out) {
        cacaoi_set_error(error, error_size, "settings: NULL pointer");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    cacao_settings s = *in;
    for (size_t i = 0; i < sizeof float_rules / sizeof float_rules[0]; ++i) {
        const float_rule *r = &float_rules[i];
        float *v = (float *)((char *)&s + r->offset);
        if (!isfinite(*v)) {
            cacaoi_set_error(error, error_size, "settings.%s is not a finite number", r->name);
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
        if (*v == 0.0f) *v = r->fallback;
        /* An explicit zero stays CACAO_ZERO, so resolving a resolved struct changes nothing. */
        const float literal = r->zero_allowed && *v == CACAO_ZERO ? 0.0f : *v;
        bool low_ok = r->min_exclusive ? literal > r->min : literal >= r->min;
        if (!low_ok || literal > r->max) {
            cacaoi_set_error(error, error_size, "settings.%s = %g is outside %s%g, %g]%s", r->name, (double)*v,
                            r->min_exclusive ? "(" : "[", (double)r->min, (double)r->max,
                            r->zero_allowed ? " (use CACAO_ZERO for 0)" : "");
            return CACAO_ERROR_INVALID_ARGUMENT;
        }
    }
    const float fade_from = s.fade_out_from == CACAO_ZERO ? 0.0f : s.fade_out_from;
    if (!(s.fade_out_to > fade_from)) {
        cacaoi_set_error(error, error_size, "settings.fade_out_to (%g) must be greater than fade_out_from (%g)",
                        (double)s.fade_out_to, (double)fade_from);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    /* shader_forms stays DEFAULT: a context replaces it by its device's forms; a plan alone takes
     * CPU (cacaoi_key_config_of), and a settings file written from these settings does not pin
     * one device's choice on another. */
    if ((int)s.shader_forms < CACAO_SHADER_FORMS_DEFAULT || (int)s.shader_forms > CACAO_SHADER_FORMS_GPU) {
        cacaoi_set_error(error, error_size, "settings.shader_forms = %d is not a cacao_shader_forms", (int)in->shader_forms);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.estimator == CACAO_ESTIMATOR_DEFAULT) s.estimator = (cacao_estimator)estimator_names.default_value;
    if ((int)s.estimator < CACAO_ESTIMATOR_CACAO || (int)s.estimator > CACAO_ESTIMATOR_BITMASK) {
        cacaoi_set_error(error, error_size, "settings.estimator = %d is not a cacao_estimator", (int)in->estimator);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.visibility == CACAO_VISIBILITY_DEFAULT) s.visibility = (cacao_visibility)visibility_names.default_value;
    if ((int)s.visibility < CACAO_VISIBILITY_FALLOFF || (int)s.visibility > CACAO_VISIBILITY_BINARY) {
        cacaoi_set_error(error, error_size, "settings.visibility = %d is not a cacao_visibility", (int)in->visibility);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    const bool slice = s.estimator != CACAO_ESTIMATOR_CACAO;
    if (s.horizon_slices < 0 || s.horizon_slices > CACAO_HORIZON_MAX_DIRECTIONS) {
        cacaoi_set_error(error, error_size, "settings.horizon_slices = %d is outside 1..%d (0 = by quality)",
                        s.horizon_slices, CACAO_HORIZON_MAX_DIRECTIONS);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.horizon_steps < 0 || s.horizon_steps > CACAO_HORIZON_MAX_STEPS) {
        cacaoi_set_error(error, error_size, "settings.horizon_steps = %d is outside 1..%d (0 = by quality)",
                        s.horizon_steps, CACAO_HORIZON_MAX_STEPS);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.blur_pass_count == 0) s.blur_pass_count = slice ? 1 : 2;
    else if (s.blur_pass_count == CACAO_BLUR_NONE) {
        /* stays CACAO_BLUR_NONE (see cacaoi_settings_literal) */
    } else if (s.blur_pass_count < 1 || s.blur_pass_count > 8) {
        cacaoi_set_error(error, error_size, "settings.blur_pass_count = %d is outside 1..8 (0 = default, %d = none)",
                        s.blur_pass_count, CACAO_BLUR_NONE);
        return CACAO_ERROR_INVALID_ARGUMENT;
    } else if (slice && s.downsample && s.blur_pass_count > CACAO_HORIZON_HALF_MAX_PASSES) {
        cacaoi_set_error(error, error_size,
                         "settings.blur_pass_count = %d: downsampled, the %s estimator runs at most %d filter passes "
                         "(the upsample and %d denoise passes)",
                         s.blur_pass_count, cacao_estimator_name(s.estimator), CACAO_HORIZON_HALF_MAX_PASSES,
                         CACAO_HORIZON_HALF_MAX_PASSES - 1);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.quality == CACAO_QUALITY_DEFAULT) s.quality = (cacao_quality)quality_names.default_value;
    if ((int)s.quality < CACAO_QUALITY_LOWEST || (int)s.quality > CACAO_QUALITY_HIGHEST) {
        cacaoi_set_error(error, error_size, "settings.quality = %d is not a cacao_quality", (int)in->quality);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.precision == CACAO_PRECISION_DEFAULT) s.precision = (cacao_precision)precision_names.default_value;
    if (slice && s.precision == CACAO_PRECISION_FP16) s.precision = CACAO_PRECISION_FP32; /* documented */
    if (slice) {
        const unsigned q = cacaoi_key_quality(s.quality);
        const unsigned e = s.estimator == CACAO_ESTIMATOR_BITMASK ? CACAO_KEY_ESTIMATOR_BITMASK : CACAO_KEY_ESTIMATOR_GTAO;
        if (s.horizon_slices == 0) s.horizon_slices = CACAOI_HORIZON_SLICES(q, e); /* by quality and estimator */
        if (s.horizon_steps == 0) s.horizon_steps = CACAOI_HORIZON_STEPS(q, e);
    }
    if (s.temporal_frames != 0 && (s.temporal_frames < 2 || s.temporal_frames > CACAO_TEMPORAL_MAX_FRAMES)) {
        cacaoi_set_error(error, error_size, "settings.temporal_frames = %d is outside 2..%d (0 = off)", s.temporal_frames,
                         CACAO_TEMPORAL_MAX_FRAMES);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.temporal_frames != 0 && !slice) {
        cacaoi_set_error(error, error_size,
                         "settings.temporal_frames = %d: temporal accumulation needs the GTAO or BITMASK estimator "
                         "(CACAO's frames do not vary)",
                         s.temporal_frames);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if (s.temporal_frames != 0 && s.reuse_unchanged) {
        cacaoi_set_error(error, error_size, "settings.temporal_frames and settings.reuse_unchanged exclude each other");
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    if ((int)s.precision != CACAO_PRECISION_FP32 && (int)s.precision != CACAO_PRECISION_FP16) {
        cacaoi_set_error(error, error_size, "settings.precision = %d is not a cacao_precision", (int)in->precision);
        return CACAO_ERROR_INVALID_ARGUMENT;
    }
    *out = s;
    return CACAO_SUCCESS;
}

void cacaoi_settings_literal(const cacao_settings *resolved, cacao_settings *out) {
    *out = *resolved;
    for (size_t i = 0; i < sizeof float_rules / sizeof float_rules[0]; ++i) {
        float *v = (float *)((char *)out + float_rules[i].offset);
        if (float_rules[i].zero_allowed && *v == CACAO_ZERO) *v = 0.0f;
    }
    if (out->blur_pass_count == CACAO_BLUR_NONE) out->blur_pass_count = 0;
}
