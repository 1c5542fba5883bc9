/* cacao_keys.c - the permutation key space (see cacao_keys.h). */
#include "cacao_keys.h"

#include <stdio.h>
#include <string.h>

static const char *const pass_names[CACAO_PASS_COUNT] = {
    "prepare_depths", "prepare_normals", "generate", "importance", "importance_a",
    "importance_b",   "blur",            "apply",    "upsample",   "slice_prepare",
    "slice_main",     "slice_denoise",
};
static const char *const depths_names[] = {"half", "full", "mips"};
static const char *const normals_names[] = {"depth", "input"};
static const char *const generate_names[] = {"q0", "q1", "q2", "q3", "q3base"};
static const char *const output_names[] = {"smart", "nonsmart", "half"};
static const char *const slice_main_names[] = {"gtao", "bitmask", "gtao_direct", "bitmask_direct"};
static const char *const denoise_names[] = {"intermediate", "final"};
static const char *const resolution_names[] = {"native", "downsampled"};
static const char *const precision_names[] = {"fp32", "fp16"};

/* Axis extents per pass: number of variants, whether resolution / blur / precision apply. */
typedef struct pass_axes {
    uint8_t variants;
    bool has_resolution;
    bool has_blur;
    bool has_precision;
} pass_axes;

static const pass_axes axes[CACAO_PASS_COUNT] = {
    [CACAO_PASS_PREPARE_DEPTHS] = {3, true, false, false},
    [CACAO_PASS_PREPARE_NORMALS] = {2, true, false, false},
    [CACAO_PASS_GENERATE] = {5, false, false, false},
    [CACAO_PASS_IMPORTANCE] = {1, false, false, false},
    [CACAO_PASS_IMPORTANCE_A] = {1, false, false, false},
    [CACAO_PASS_IMPORTANCE_B] = {1, false, false, false},
    [CACAO_PASS_BLUR] = {1, false, true, true},
    [CACAO_PASS_APPLY] = {3, false, false, true},
    [CACAO_PASS_UPSAMPLE] = {3, false, false, true},
    [CACAO_PASS_SLICE_PREPARE] = {2, false, false, false},
    [CACAO_PASS_SLICE_MAIN] = {4, false, false, false},
    [CACAO_PASS_SLICE_DENOISE] = {2, false, false, false},
};

const char *cacaoi_pass_name(unsigned pass) {
    return pass < CACAO_PASS_COUNT ? pass_names[pass] : NULL;
}

bool cacaoi_key_is_valid(const cacao_key *key) {
    if (!key || key->pass >= CACAO_PASS_COUNT) return false;
    const pass_axes *a = &axes[key->pass];
    if (key->variant >= a->variants) return false;
    if (key->downsampled > (a->has_resolution ? 1 : 0)) return false;
    if (a->has_blur ? (key->blur_passes < 1 || key->blur_passes > CACAO_KEY_MAX_BLUR_PASSES)
                    : key->blur_passes != 0)
        return false;
    return key->fp16 <= (a->has_precision ? 1 : 0);
}

size_t cacaoi_key_list(cacao_key *out, size_t cap) {
    size_t n = 0;
    for (unsigned pass = 0; pass < CACAO_PASS_COUNT; ++pass) {
        const pass_axes *a = &axes[pass];
        for (unsigned v = 0; v < a->variants; ++v)
            for (unsigned ds = 0; ds <= (a->has_resolution ? 1u : 0u); ++ds)
                for (unsigned b = a->has_blur ? 1u : 0u;
                     b <= (a->has_blur ? (unsigned)CACAO_KEY_MAX_BLUR_PASSES : 0u); ++b)
                    for (unsigned fp = 0; fp <= (a->has_precision ? 1u : 0u); ++fp) {
                        if (n < cap)
                            out[n] = (cacao_key){(uint8_t)pass, (uint8_t)v, (uint8_t)ds,
                                                 (uint8_t)b, (uint8_t)fp};
                        ++n;
                    }
    }
    return n;
}

int cacaoi_key_compare(const cacao_key *a, const cacao_key *b) {
    const uint8_t av[5] = {a->pass, a->variant, a->downsampled, a->blur_passes, a->fp16};
    const uint8_t bv[5] = {b->pass, b->variant, b->downsampled, b->blur_passes, b->fp16};
    for (int i = 0; i < 5; ++i)
        if (av[i] != bv[i]) return av[i] < bv[i] ? -1 : 1;
    return 0;
}

static const char *variant_name(const cacao_key *key) {
    switch (key->pass) {
    case CACAO_PASS_PREPARE_DEPTHS: return depths_names[key->variant];
    case CACAO_PASS_PREPARE_NORMALS:
    case CACAO_PASS_SLICE_PREPARE: return normals_names[key->variant];
    case CACAO_PASS_SLICE_MAIN: return slice_main_names[key->variant];
    case CACAO_PASS_SLICE_DENOISE: return denoise_names[key->variant];
    case CACAO_PASS_GENERATE: return generate_names[key->variant];
    case CACAO_PASS_APPLY:
    case CACAO_PASS_UPSAMPLE: return output_names[key->variant];
    default: return NULL;
    }
}

size_t cacaoi_key_name(const cacao_key *key, char *buf, size_t buf_size) {
    if (!cacaoi_key_is_valid(key) || !buf || buf_size == 0) return 0;
    const pass_axes *a = &axes[key->pass];
    char tmp[CACAO_KEY_NAME_MAX];
    int len = snprintf(tmp, sizeof tmp, "%s", pass_names[key->pass]);
    const char *variant = variant_name(key);
    if (variant) len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", variant);
    if (a->has_blur) len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%u", key->blur_passes);
    if (a->has_resolution)
        len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", resolution_names[key->downsampled]);
    if (a->has_precision)
        len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", precision_names[key->fp16]);
    if ((size_t)len + 1 > buf_size) return 0;
    memcpy(buf, tmp, (size_t)len + 1);
    return (size_t)len;
}

bool cacaoi_key_parse(const char *name, cacao_key *out) {
    if (!name || !out) return false;
    cacao_key keys[128];
    size_t n = cacaoi_key_list(keys, sizeof keys / sizeof keys[0]);
    for (size_t i = 0; i < n && i < sizeof keys / sizeof keys[0]; ++i) {
        char buf[CACAO_KEY_NAME_MAX];
        if (cacaoi_key_name(&keys[i], buf, sizeof buf) && strcmp(buf, name) == 0) {
            *out = keys[i];
            return true;
        }
    }
    return false;
}

size_t cacaoi_key_defines(const cacao_key *key, char *buf, size_t buf_size) {
    if (!cacaoi_key_is_valid(key) || !buf) return 0;
    int len = snprintf(buf, buf_size,
                       "#define CACAO_GLSL 1\n#define CACAO_PASS %u\n#define CACAO_VARIANT %u\n"
                       "#define CACAO_DOWNSAMPLED %u\n#define CACAO_BLUR_PASSES %u\n"
                       "#define CACAO_FP16 %u\n",
                       key->pass, key->variant, key->downsampled, key->blur_passes, key->fp16);
    return (len > 0 && (size_t)len < buf_size) ? (size_t)len : 0;
}

/* ---- Variant selection (spec: README "Quality levels") ---- */

unsigned cacaoi_depths_variant_for_quality(unsigned quality) {
    /* MEDIUM builds no mips: its generate pass (Q1) never reads them ([quirk] MIPS-AT-MEDIUM). */
    if (quality == CACAO_KEY_QUALITY_LOWEST) return CACAO_DEPTHS_HALF;
    return quality >= CACAO_KEY_QUALITY_HIGH ? CACAO_DEPTHS_MIPS : CACAO_DEPTHS_FULL;
}

unsigned cacaoi_generate_variant_for_quality(unsigned quality) {
    return quality == 0 ? CACAO_GENERATE_Q0 : quality - 1; /* q = max(0, quality - 1) */
}

unsigned cacaoi_output_variant_for_quality(unsigned quality, bool downsampled) {
    if (quality == CACAO_KEY_QUALITY_LOWEST) return CACAO_OUTPUT_HALF;
    if (quality == CACAO_KEY_QUALITY_LOW) return CACAO_OUTPUT_NON_SMART;
    if (quality == CACAO_KEY_QUALITY_MEDIUM)
        return downsampled ? CACAO_OUTPUT_NON_SMART : CACAO_OUTPUT_SMART;
    return CACAO_OUTPUT_SMART;
}

unsigned cacaoi_slice_count_for_quality(unsigned quality) {
    return quality == CACAO_KEY_QUALITY_LOWEST ? 2 : 4;
}

/* The horizon-slice estimators: full resolution, fp32, normals prepared once, denoise passes. */
static size_t slice_keys_for_config(const cacao_key_config *c, cacao_key out[CACAO_KEY_CONFIG_MAX]) {
    if (c->downsampled) return 0; /* full resolution only */
    size_t n = 0;
    const bool direct = c->blur_passes == 0;
    const unsigned main_variant = (c->estimator == CACAO_KEY_ESTIMATOR_GTAO ? CACAO_SLICE_GTAO : CACAO_SLICE_BITMASK) +
                                  (direct ? CACAO_SLICE_GTAO_DIRECT : 0);
    out[n++] = (cacao_key){CACAO_PASS_SLICE_PREPARE,
                           c->normals_from_input ? CACAO_SLICE_NORMALS_INPUT : CACAO_SLICE_NORMALS_DEPTH, 0, 0, 0};
    out[n++] = (cacao_key){CACAO_PASS_SLICE_MAIN, (uint8_t)main_variant, 0, 0, 0};
    if (c->blur_passes > 1) out[n++] = (cacao_key){CACAO_PASS_SLICE_DENOISE, CACAO_DENOISE_INTERMEDIATE, 0, 0, 0};
    if (c->blur_passes > 0) out[n++] = (cacao_key){CACAO_PASS_SLICE_DENOISE, CACAO_DENOISE_FINAL, 0, 0, 0};
    return n;
}

size_t cacaoi_keys_for_config(const cacao_key_config *c, cacao_key out[CACAO_KEY_CONFIG_MAX]) {
    if (c->estimator != CACAO_KEY_ESTIMATOR_CACAO) return slice_keys_for_config(c, out);
    size_t n = 0;
    const uint8_t ds = c->downsampled ? 1 : 0, fp = c->fp16 ? 1 : 0;
    out[n++] = (cacao_key){CACAO_PASS_PREPARE_DEPTHS, (uint8_t)cacaoi_depths_variant_for_quality(c->quality), ds, 0, 0};
    out[n++] = (cacao_key){CACAO_PASS_PREPARE_NORMALS, c->normals_from_input ? 1 : 0, ds, 0, 0};
    if (c->quality == CACAO_KEY_QUALITY_HIGHEST) {
        out[n++] = (cacao_key){CACAO_PASS_GENERATE, CACAO_GENERATE_Q3_BASE, 0, 0, 0};
        out[n++] = (cacao_key){CACAO_PASS_IMPORTANCE, 0, 0, 0, 0};
        out[n++] = (cacao_key){CACAO_PASS_IMPORTANCE_A, 0, 0, 0, 0};
        out[n++] = (cacao_key){CACAO_PASS_IMPORTANCE_B, 0, 0, 0, 0};
    }
    out[n++] = (cacao_key){CACAO_PASS_GENERATE, (uint8_t)cacaoi_generate_variant_for_quality(c->quality), 0, 0, 0};
    if (c->blur_passes > 0)
        out[n++] = (cacao_key){CACAO_PASS_BLUR, 0, 0, (uint8_t)c->blur_passes, fp};
    out[n++] = (cacao_key){c->downsampled ? CACAO_PASS_UPSAMPLE : CACAO_PASS_APPLY,
                           (uint8_t)cacaoi_output_variant_for_quality(c->quality, c->downsampled), 0, 0, fp};
    return n;
}

bool cacaoi_key_in_subset(const cacao_key *key, const cacao_key_subset *subset) {
    for (unsigned q = 0; q < CACAO_KEY_QUALITY_COUNT; ++q) {
        if (!(subset->quality_mask & (1u << q))) continue;
        for (unsigned ds = 0; ds < 2; ++ds) {
            if (!(subset->resolution_mask & (1u << ds))) continue;
            for (unsigned fp = 0; fp < 2; ++fp) {
                if (!(subset->precision_mask & (1u << fp))) continue;
                for (unsigned ni = 0; ni < 2; ++ni)
                    for (unsigned blur = 0; blur <= CACAO_KEY_MAX_BLUR_PASSES; ++blur)
                        for (unsigned est = 0; est < CACAO_KEY_ESTIMATOR_COUNT; ++est) {
                            cacao_key_config c = {q, ds != 0, fp != 0, ni != 0, blur, est};
                            cacao_key keys[CACAO_KEY_CONFIG_MAX];
                            size_t n = cacaoi_keys_for_config(&c, keys);
                            for (size_t i = 0; i < n; ++i)
                                if (cacaoi_key_compare(&keys[i], key) == 0) return true;
                        }
            }
        }
    }
    return false;
}

/* Parses a ';' or ',' separated list of words into a bit mask using `words[0..count)`. */
static bool parse_mask(const char *list, const char *const *words, unsigned count, unsigned *mask) {
    unsigned m = 0;
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ";, ");
        if (len > 0) {
            unsigned i = 0;
            while (i < count && !(strlen(words[i]) == len && strncmp(words[i], p, len) == 0)) ++i;
            if (i == count) return false;
            m |= 1u << i;
        }
        p += len;
        if (*p) ++p;
    }
    if (m == 0) return false;
    *mask = m;
    return true;
}

const char *const cacaoi_quality_names[CACAO_KEY_QUALITY_COUNT] = {"lowest", "low", "medium", "high", "highest"};

bool cacaoi_key_subset_parse(const char *qualities, const char *downsample, const char *precision,
                            cacao_key_subset *subset) {
    cacao_key_subset s = CACAO_KEY_SUBSET_ALL;
    if (qualities && *qualities && strcmp(qualities, "all") != 0 &&
        !parse_mask(qualities, cacaoi_quality_names, CACAO_KEY_QUALITY_COUNT, &s.quality_mask))
        return false;
    if (downsample && *downsample) {
        if (strcmp(downsample, "OFF") == 0 || strcmp(downsample, "native") == 0) s.resolution_mask = 1;
        else if (strcmp(downsample, "ONLY") == 0) s.resolution_mask = 2;
        else if (strcmp(downsample, "downsampled") == 0) s.resolution_mask = 2;
        else if (strcmp(downsample, "ON") == 0 || strcmp(downsample, "all") == 0) s.resolution_mask = 3;
        else return false;
    }
    if (precision && *precision && strcmp(precision, "all") != 0 &&
        !parse_mask(precision, precision_names, 2, &s.precision_mask))
        return false;
    *subset = s;
    return true;
}
