/* cacao_table.h - the schema of the generated permutation table (generated/cacao_table.c).
 *
 * Written by shadergen, read by the runtime and the tools. Every per-permutation fact here comes
 * from reflection of the compiled module (SPIRV-Cross), not from a hand-kept list.
 */
#ifndef CACAO_TABLE_H
#define CACAO_TABLE_H

#include <stdint.h>

#include "cacao_keys.h"
#include "cacao_passes.h"

typedef struct cacao_module {
    const uint32_t *words; /* SPIR-V */
    uint32_t word_count;
} cacao_module;

typedef struct cacao_permutation {
    cacao_key key;
    const char *name;          /* cacaoi_key_name(key) */
    uint32_t module;           /* index into cacao_table.modules (shared by identical modules) */
    uint32_t workgroup_size[3];
    uint32_t uniform_size;     /* bytes of the constant block, 0 if unused */
    uint32_t push_constant_size;
    uint8_t bindings[CACAO_BINDING_COUNT]; /* CACAOI_DESCRIPTOR_* per binding of set 0 */
} cacao_permutation;

typedef struct cacao_table {
    const cacao_permutation *permutations; /* sorted by cacaoi_key_compare */
    uint32_t permutation_count;
    const cacao_module *modules;
    uint32_t module_count;
    const char *entry_point;
    const char *glslang_version;
    const char *spirv_tools_version;
    const char *subset;        /* "all" or the build's subset, e.g. "medium;high|OFF|fp32" */
} cacao_table;

/* The table linked into this build (the committed full set, or a build-tree subset). */
extern const cacao_table cacaoi_embedded_table;

/* Binary search by key; NULL when the key is not embedded in this build. */
static inline const cacao_permutation *cacaoi_table_find(const cacao_table *table, const cacao_key *key) {
    if (!table || !key) return NULL;
    uint32_t lo = 0, hi = table->permutation_count;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        const int c = cacaoi_key_compare(&table->permutations[mid].key, key);
        if (c == 0) return &table->permutations[mid];
        if (c < 0) lo = mid + 1;
        else hi = mid;
    }
    return NULL;
}

#endif /* CACAO_TABLE_H */
