/* cacao_table.c - lookups in the generated permutation table. */
#include "cacao_table.h"

const cacao_permutation *cacaoi_table_find(const cacao_table *table, const cacao_key *key) {
    if (!table || !key) return NULL;
    uint32_t lo = 0, hi = table->permutation_count;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        int c = cacaoi_key_compare(&table->permutations[mid].key, key);
        if (c == 0) return &table->permutations[mid];
        if (c < 0) lo = mid + 1;
        else hi = mid;
    }
    return NULL;
}
