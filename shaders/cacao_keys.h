/* cacao_keys.h - the permutation key space: one struct, its enumerations (in cacao_shared.h), and
 * the functions that list every valid key, name it, parse it, and give the shader defines that
 * specialise the source for it (cacao_table.h finds a key in a generated table). Compiled into both the generator
 * and the runtime, so both agree on it. Which keys a configuration of settings needs is the
 * policy's (cacao_policy.h).
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

#include "cacao_names.h"
#include "cacao_passes.h"

#define CACAO_KEY_MAX_BLUR_PASSES 8

typedef struct cacao_key {
    uint8_t pass;        /* CACAO_PASS_* */
    uint8_t variant;     /* prepare_depths, prepare: CACAO_DEPTHS_*;
                            generate: CACAO_GENERATE_*; apply/upsample: CACAO_OUTPUT_*; else 0 */
    uint8_t downsampled; /* prepare passes only: 0 native, 1 downsampled */
    uint8_t blur_passes; /* blur only: 1..8 */
    uint8_t fp16;        /* blur, apply, upsample only: 0 fp32, 1 fp16 */
} cacao_key;

/* Longest key name, including the terminating zero: the plan's (cacao_plan_step.key_name). Every
 * key's name fits (test_keys). */
#define CACAO_KEY_NAME_MAX CACAO_PLAN_KEY_NAME_MAX

/* Longest text cacaoi_key_defines writes, including the terminating zero. */
#define CACAO_KEY_DEFINES_MAX 2048

/* The words of the resolution axis in key names (and in build subsets); the precision axis's are
 * cacaoi_precision_names (cacao_names.h). */
extern const char *const cacaoi_resolution_names[2]; /* "native", "downsampled" */

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

/* Parses a name written by cacaoi_key_name (any key of the key space). Returns false for
 * anything else. */
bool cacaoi_key_parse(const char *name, cacao_key *out);

/* What the compiled module of a key must declare (its pass row's rule for its variant); false
 * for an invalid key. */
bool cacaoi_key_expect(const cacao_key *key, cacaoi_module_expect *out);

/* The preprocessor defines that specialise the shader source for this key, one "#define X v\n"
 * per line: the key's axes (CACAO_PASS, CACAO_VARIANT, ...), the tile list it dispatches from,
 * and per binding slot its row declares CACAO_BIND_<slot> 1, for storage images and buffers
 * CACAO_ACCESS_<slot> (readonly, writeonly, or nothing for a written buffer) and for storage
 * images with a format CACAO_FORMAT_<slot>. Returns the length written, or 0 (and an empty buf)
 * for an invalid key or a buf too small. */
size_t cacaoi_key_defines(const cacao_key *key, char *buf, size_t buf_size);

/* Pass name as used in key names ("generate", "blur", ...), or NULL for an unknown pass. */
const char *cacaoi_pass_name(unsigned pass);

#endif /* CACAO_KEYS_H */
