/* cacao_keys.h - the permutation key space: one struct, its enumerations (in cacao_shared.h), and
 * the functions that list every valid key, name it, parse it, and say which keys one configuration
 * of settings needs. Compiled into both the generator and the runtime, so both agree on it.
 *
 * A key names only the axes its pass depends on: a generate key has a quality variant but no
 * resolution mode (generate does the same math at either resolution), a blur key has a pass count
 * and a precision but no quality. The key space therefore has no redundant entries by construction.
 */
#ifndef CACAO_KEYS_H
#define CACAO_KEYS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao_shared.h"

/* Key-space quality levels, 0-based. The public cacao_quality is 1-based (0 there means "default"):
 * key quality = cacao_quality - 1 (cacaoi_key_quality). */
#define CACAO_KEY_QUALITY_LOWEST 0
#define CACAO_KEY_QUALITY_LOW 1
#define CACAO_KEY_QUALITY_MEDIUM 2
#define CACAO_KEY_QUALITY_HIGH 3
#define CACAO_KEY_QUALITY_HIGHEST 4
#define CACAO_KEY_QUALITY_COUNT 5

/* The words of the settings enums, each list written once (cacao_names.c); cacao.h's
 * cacao_*_name return them. Quality by key quality ("lowest" .. "highest"), precision by the key's
 * fp16 ("fp32", "fp16"), estimator and visibility by their cacao.h value - 1. */
extern const char *const cacaoi_quality_names[CACAO_KEY_QUALITY_COUNT];
extern const char *const cacaoi_precision_names[2];
extern const char *const cacaoi_estimator_names[3];
extern const char *const cacaoi_visibility_names[2];
/* Key quality of a public (1-based) cacao_quality value. */
#define cacaoi_key_quality(api_quality) ((unsigned)(api_quality) - 1u)
#define CACAO_KEY_MAX_BLUR_PASSES 8

typedef struct cacao_key {
    uint8_t pass;        /* CACAO_PASS_* */
    uint8_t variant;     /* prepare_depths, prepare: CACAO_DEPTHS_*;
                            generate: CACAO_GENERATE_*; apply/upsample: CACAO_OUTPUT_*; else 0 */
    uint8_t downsampled; /* prepare passes only: 0 native, 1 downsampled */
    uint8_t blur_passes; /* blur only: 1..8 */
    uint8_t fp16;        /* blur, apply, upsample only: 0 fp32, 1 fp16 */
} cacao_key;

/* Longest key name, including the terminating zero. */
#define CACAO_KEY_NAME_MAX 48

/* Longest text cacaoi_key_defines writes, including the terminating zero. */
#define CACAO_KEY_DEFINES_MAX 1024

/* Writes every valid key, in canonical (sorted) order, into out[0..cap) and returns the total
 * number of valid keys (which may exceed cap; pass out = NULL, cap = 0 to count). */
size_t cacaoi_key_list(cacao_key *out, size_t cap);

/* True when the key is one of the keys cacaoi_key_list produces. */
bool cacaoi_key_is_valid(const cacao_key *key);

/* Total order used for sorting and binary search of tables. */
int cacaoi_key_compare(const cacao_key *a, const cacao_key *b);

/* Stable short name, e.g. "generate.q2", "blur.4.fp16", "prepare_depths.mips.downsampled".
 * Returns the name length, or 0 if the key is invalid or buf too small. */
size_t cacaoi_key_name(const cacao_key *key, char *buf, size_t buf_size);

/* Parses a name written by cacaoi_key_name. Returns false for anything else. */
bool cacaoi_key_parse(const char *name, cacao_key *out);

/* The preprocessor defines that specialise the shader source for this key, one "#define X v\n"
 * per line. Returns the length written, or 0 if buf is too small. */
size_t cacaoi_key_defines(const cacao_key *key, char *buf, size_t buf_size);

/* Pass name as used in key names ("generate", "blur", ...), or NULL for an unknown pass. */
const char *cacaoi_pass_name(unsigned pass);

/* ---- Which variant each setting selects (spec: README "Quality levels"); the plan and the
 * subset filter both use these, so the choice is made in one place. ---- */
unsigned cacaoi_depths_variant_for_quality(unsigned quality);
unsigned cacaoi_generate_variant_for_quality(unsigned quality); /* Q3 for HIGHEST (+ Q3 base) */
unsigned cacaoi_output_variant_for_quality(unsigned quality, bool downsampled);
unsigned cacaoi_slice_count_for_quality(unsigned quality);

/* Estimators (the public cacao_estimator less one: 0-based, no "default"). */
#define CACAO_KEY_ESTIMATOR_CACAO 0
#define CACAO_KEY_ESTIMATOR_GTAO 1
#define CACAO_KEY_ESTIMATOR_BITMASK 2
#define CACAO_KEY_ESTIMATOR_COUNT 3

/* One configuration's axes, as far as they select shader keys. */
typedef struct cacao_key_config {
    unsigned quality;      /* CACAO_KEY_QUALITY_* */
    bool downsampled;      /* CACAO estimator only: the slice estimators have no downsampled keys */
    bool fp16;
    bool normals_from_input;
    unsigned blur_passes;  /* 0..8 (slice estimators: denoise passes) */
    unsigned estimator;    /* CACAO_KEY_ESTIMATOR_* */
} cacao_key_config;

/* Keys one configuration dispatches, in dispatch order (at most CACAO_KEY_CONFIG_MAX). */
#define CACAO_KEY_CONFIG_MAX 16
size_t cacaoi_keys_for_config(const cacao_key_config *config, cacao_key out[CACAO_KEY_CONFIG_MAX]);

/* A build-time subset of the configuration space (bit masks; bit i = quality i, bit 0/1 =
 * native/downsampled, bit 0/1 = fp32/fp16). */
typedef struct cacao_key_subset {
    unsigned quality_mask;
    unsigned resolution_mask;
    unsigned precision_mask;
} cacao_key_subset;

#define CACAO_KEY_SUBSET_ALL ((cacao_key_subset){0x1f, 0x3, 0x3})

/* True when some configuration inside the subset dispatches this key. */
bool cacaoi_key_in_subset(const cacao_key *key, const cacao_key_subset *subset);

/* Parses the CMake-style lists used by the build: qualities "medium;high" (or "all"), downsample
 * "ON" (native and downsampled), "OFF" (native only) or "ONLY" (downsampled only), precision
 * "fp32;fp16". Return false and leave *subset unchanged on an unknown word. */
bool cacaoi_key_subset_parse(const char *qualities, const char *downsample, const char *precision,
                            cacao_key_subset *subset);

#endif /* CACAO_KEYS_H */
