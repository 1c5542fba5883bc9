/* cacao_keys.c - the permutation key space (see cacao_keys.h). */
#include "cacao_keys.h"

#include <stdio.h>
#include <string.h>

_Static_assert(CACAO_PLAN_KEY_NAME_MAX >= 32, "key names need room");

const char *const cacaoi_resolution_names[2] = {"native", "downsampled"};

const char *cacaoi_pass_name(unsigned pass) {
    return pass < CACAO_PASS_COUNT ? cacaoi_passes[pass].name : NULL;
}

/* The highest value of each axis a pass's keys take (the lowest: 1 for the blur's passes, else 0). */
static unsigned max_downsampled(const cacaoi_pass_row *a) { return a->has_resolution ? 1u : 0u; }
static unsigned min_blur(const cacaoi_pass_row *a) { return a->has_blur ? 1u : 0u; }
static unsigned max_blur(const cacaoi_pass_row *a) { return a->has_blur ? (unsigned)CACAO_KEY_MAX_BLUR_PASSES : 0u; }
static unsigned max_fp16(const cacaoi_pass_row *a) { return a->has_precision ? 1u : 0u; }

bool cacaoi_key_is_valid(const cacao_key *key) {
    if (!key || key->pass >= CACAO_PASS_COUNT) return false;
    const cacaoi_pass_row *a = &cacaoi_passes[key->pass];
    return key->variant < a->variants && !cacaoi_fill_is_clear(key->pass, key->variant) &&
           key->downsampled <= max_downsampled(a) && key->blur_passes >= min_blur(a) && key->blur_passes <= max_blur(a) &&
           key->fp16 <= max_fp16(a);
}

/* The first key of the key space (*key zeroed) or the one after *key, in canonical order; false
 * past the last. The axes vary fastest from the last: fp16, blur passes, resolution, variant, pass. */
static bool key_step(cacao_key *k, bool first);
static bool key_next(cacao_key *k, bool first) { /* the fills that are clears have no module: no key */
    bool more = key_step(k, first);
    while (more && cacaoi_fill_is_clear(k->pass, k->variant)) more = key_step(k, false);
    return more;
}

static bool key_step(cacao_key *k, bool first) {
    if (first) {
        *k = (cacao_key){0, 0, 0, (uint8_t)min_blur(&cacaoi_passes[0]), 0};
        return true;
    }
    const cacaoi_pass_row *a = &cacaoi_passes[k->pass];
    if (k->fp16 < max_fp16(a)) return ++k->fp16, true;
    k->fp16 = 0;
    if (k->blur_passes < max_blur(a)) return ++k->blur_passes, true;
    k->blur_passes = (uint8_t)min_blur(a);
    if (k->downsampled < max_downsampled(a)) return ++k->downsampled, true;
    k->downsampled = 0;
    if (k->variant + 1u < a->variants) return ++k->variant, true;
    if (k->pass + 1u >= CACAO_PASS_COUNT) return false;
    *k = (cacao_key){(uint8_t)(k->pass + 1), 0, 0, (uint8_t)min_blur(&cacaoi_passes[k->pass + 1]), 0};
    return true;
}

size_t cacaoi_key_list(cacao_key *out, size_t cap) {
    size_t n = 0;
    cacao_key k;
    for (bool more = key_next(&k, true); more; more = key_next(&k, false)) {
        if (n < cap) out[n] = k;
        ++n;
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

/* Appends printf(fmt, word) or printf(fmt, number) to buf; false when it does not fit. */
static bool appended(int n, size_t size, size_t *len) {
    if (n < 0 || (size_t)n >= size - *len) return false;
    *len += (size_t)n;
    return true;
}
static bool append(char *buf, size_t size, size_t *len, const char *fmt, const char *word) {
    return appended(snprintf(buf + *len, size - *len, fmt, word), size, len);
}
static bool append_number(char *buf, size_t size, size_t *len, const char *fmt, unsigned number) {
    return appended(snprintf(buf + *len, size - *len, fmt, number), size, len);
}

size_t cacaoi_key_name(const cacao_key *key, char *buf, size_t buf_size) {
    if (!cacaoi_key_is_valid(key) || !buf || buf_size == 0) return 0;
    const cacaoi_pass_row *a = &cacaoi_passes[key->pass];
    size_t len = 0;
    const char *variant = a->variant_names[key->variant];
    const bool ok = append(buf, buf_size, &len, "%s", a->name) &&
                    (!variant || append(buf, buf_size, &len, ".%s", variant)) &&
                    (!a->has_blur || append_number(buf, buf_size, &len, ".%u", key->blur_passes)) &&
                    (!a->has_resolution ||
                     append(buf, buf_size, &len, ".%s", cacaoi_resolution_names[key->downsampled])) &&
                    (!a->has_precision || append(buf, buf_size, &len, ".%s", cacaoi_precision_names[key->fp16]));
    if (!ok) {
        buf[0] = '\0';
        return 0;
    }
    return len;
}

bool cacaoi_key_parse(const char *name, cacao_key *out) {
    if (!name || !out) return false;
    cacao_key k;
    for (bool more = key_next(&k, true); more; more = key_next(&k, false)) {
        char buf[CACAO_KEY_NAME_MAX];
        if (cacaoi_key_name(&k, buf, sizeof buf) && strcmp(buf, name) == 0) {
            *out = k;
            return true;
        }
    }
    return false;
}

bool cacaoi_key_expect(const cacao_key *key, cacaoi_module_expect *out) {
    return cacaoi_key_is_valid(key) && cacaoi_pass_expect(key->pass, key->variant, key->downsampled, out);
}

/* How the GLSL declares a slot's access: storage images read or write only; a written storage
 * buffer is also read (the tile lists are built in place), a read one is read only. */
static const char *access_qualifier(uint8_t descriptor, bool write) {
    if (!write) return "readonly";
    return descriptor == CACAOI_DESCRIPTOR_STORAGE_IMAGE ? "writeonly" : "";
}

size_t cacaoi_key_defines(const cacao_key *key, char *buf, size_t buf_size) {
    cacaoi_module_expect expect;
    if (!cacaoi_key_expect(key, &expect) || !buf || buf_size == 0) return 0;
    size_t len = 0;
    bool ok = append_number(buf, buf_size, &len, "#define CACAO_GLSL 1\n#define CACAO_PASS %u\n", key->pass) &&
              append_number(buf, buf_size, &len, "#define CACAO_VARIANT %u\n", key->variant) &&
              append_number(buf, buf_size, &len, "#define CACAO_DOWNSAMPLED %u\n", key->downsampled) &&
              append_number(buf, buf_size, &len, "#define CACAO_BLUR_PASSES %u\n", key->blur_passes) &&
              append_number(buf, buf_size, &len, "#define CACAO_FP16 %u\n", key->fp16) &&
              append_number(buf, buf_size, &len, "#define CACAO_LIST %u\n", cacaoi_passes[key->pass].lists[key->variant]) &&
              append_number(buf, buf_size, &len, "#define CACAO_SKIPS_BY_CLASS %u\n",
                            cacaoi_skips_by_class(key->pass, key->variant) ? 1u : 0u) &&
              append_number(buf, buf_size, &len, "#define CACAO_READS_CLASSES %u\n",
                            cacaoi_reads_classes(key->pass, key->variant) ? 1u : 0u);
    /* The slots the row binds: the GLSL declares exactly these (shaders/glsl/bindings.glsl). */
    for (unsigned slot = 0; ok && slot < CACAO_BINDING_COUNT; ++slot) {
        const uint8_t descriptor = expect.descriptor[slot];
        if (descriptor == CACAOI_DESCRIPTOR_NONE) continue;
        const char *name = cacaoi_slots[slot].name;
        ok = append(buf, buf_size, &len, "#define CACAO_BIND_%s 1\n", name);
        if (ok && (descriptor == CACAOI_DESCRIPTOR_STORAGE_IMAGE || descriptor == CACAOI_DESCRIPTOR_STORAGE_BUFFER))
            ok = append(buf, buf_size, &len, "#define CACAO_ACCESS_%s", name) &&
                 append(buf, buf_size, &len, " %s\n", access_qualifier(descriptor, expect.write[slot]));
        /* the format qualifier of a storage image, from its resource's row */
        const char *format = cacaoi_resources[expect.resource[slot]].glsl_format;
        if (ok && descriptor == CACAOI_DESCRIPTOR_STORAGE_IMAGE && *format)
            ok = append(buf, buf_size, &len, "#define CACAO_FORMAT_%s", name) &&
                 append(buf, buf_size, &len, " %s\n", format);
    }
    if (!ok) buf[0] = '\0'; /* never a cut text */
    return ok ? len : 0;
}
