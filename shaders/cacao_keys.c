/* cacao_keys.c - the permutation key space (see cacao_keys.h). */
#include "cacao_keys.h"

#include "cacao_passes.h"

#include <stdio.h>
#include <string.h>

static const char *const resolution_names[] = {"native", "downsampled"};

const char *cacaoi_pass_name(unsigned pass) {
    return pass < CACAO_PASS_COUNT ? cacaoi_passes[pass].name : NULL;
}

bool cacaoi_key_is_valid(const cacao_key *key) {
    if (!key || key->pass >= CACAO_PASS_COUNT) return false;
    const cacaoi_pass_row *a = &cacaoi_passes[key->pass];
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
        const cacaoi_pass_row *a = &cacaoi_passes[pass];
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

size_t cacaoi_key_name(const cacao_key *key, char *buf, size_t buf_size) {
    if (!cacaoi_key_is_valid(key) || !buf || buf_size == 0) return 0;
    const cacaoi_pass_row *a = &cacaoi_passes[key->pass];
    char tmp[CACAO_KEY_NAME_MAX];
    int len = snprintf(tmp, sizeof tmp, "%s", a->name);
    const char *variant = a->variant_names[key->variant];
    if (variant) len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", variant);
    if (a->has_blur) len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%u", key->blur_passes);
    if (a->has_resolution)
        len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", resolution_names[key->downsampled]);
    if (a->has_precision)
        len += snprintf(tmp + len, sizeof tmp - (size_t)len, ".%s", cacaoi_precision_names[key->fp16]);
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
    cacaoi_module_expect expect;
    if (!cacaoi_pass_expect(key, &expect) || !buf) return 0;
    int len = snprintf(buf, buf_size,
                       "#define CACAO_GLSL 1\n#define CACAO_PASS %u\n#define CACAO_VARIANT %u\n"
                       "#define CACAO_DOWNSAMPLED %u\n#define CACAO_BLUR_PASSES %u\n"
                       "#define CACAO_FP16 %u\n#define CACAO_LIST %u\n",
                       key->pass, key->variant, key->downsampled, key->blur_passes, key->fp16,
                       cacaoi_passes[key->pass].lists[key->variant]);
    /* The format qualifier of each storage image the pass row binds, from its resource's row. */
    for (unsigned slot = 0; len > 0 && (size_t)len < buf_size && slot < CACAO_BINDING_COUNT; ++slot) {
        const char *format = cacaoi_resources[expect.resource[slot]].glsl_format;
        if (expect.descriptor[slot] != CACAO_RESOURCE_STORAGE_IMAGE || !*format) continue;
        len += snprintf(buf + len, buf_size - (size_t)len, "#define CACAO_FORMAT_%s %s\n", cacaoi_slots[slot].name,
                        format);
    }
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

/* The keys of the configuration's steps (cacaoi_sequence), each once, in first-dispatch order. */
size_t cacaoi_keys_for_config(const cacao_key_config *c, cacao_key out[CACAO_KEY_CONFIG_MAX]) {
    cacaoi_step steps[CACAOI_SEQUENCE_MAX];
    const size_t count = cacaoi_sequence(c, steps);
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        size_t j = 0;
        while (j < n && cacaoi_key_compare(&out[j], &steps[i].key) != 0) ++j;
        if (j == n) out[n++] = steps[i].key;
    }
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
        !parse_mask(precision, cacaoi_precision_names, 2, &s.precision_mask))
        return false;
    *subset = s;
    return true;
}
