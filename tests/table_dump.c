/* table_dump - prints the embedded permutation table (used by the subset-build, spirv-val and
 * inspect tests).
 * usage: table_dump                    list "name module words" per permutation
 *        table_dump --write DIR        write every unique module as DIR/<first name>.spv
 *        table_dump --find NAME        exit 0 if the key is embedded, 1 with a message if not
 *        table_dump --embedded-count   the number of permutations embedded in this build
 *        table_dump --key-count [PASS] the number of keys of the key space (cacaoi_key_list, not
 *                                      the embedded table), or of one pass's keys */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cacao_table.h"

/* Keys of the key space, all or those of the pass named pass; -1 for an unknown pass name. */
static long key_count(const char *pass) {
    const size_t n = cacaoi_key_list(NULL, 0);
    if (!pass) return (long)n;
    cacao_key *keys = malloc(n * sizeof *keys);
    if (!keys) return -1;
    cacaoi_key_list(keys, n);
    long count = -1;
    for (size_t i = 0; i < n; ++i)
        if (strcmp(cacaoi_pass_name(keys[i].pass), pass) == 0) count = count < 0 ? 1 : count + 1;
    free(keys);
    return count;
}

int main(int argc, char **argv) {
    const cacao_table *t = &cacaoi_embedded_table;
    if (argc == 2 && strcmp(argv[1], "--embedded-count") == 0) {
        printf("%u\n", t->permutation_count);
        return 0;
    }
    if ((argc == 2 || argc == 3) && strcmp(argv[1], "--key-count") == 0) {
        const long count = key_count(argc == 3 ? argv[2] : NULL);
        if (count < 0) {
            fprintf(stderr, "table_dump: no keys for pass '%s'\n", argv[2]);
            return 2;
        }
        printf("%ld\n", count);
        return 0;
    }
    if (argc == 3 && strcmp(argv[1], "--find") == 0) {
        cacao_key key;
        if (!cacaoi_key_parse(argv[2], &key)) {
            fprintf(stderr, "table_dump: '%s' is not a permutation key\n", argv[2]);
            return 2;
        }
        if (!cacaoi_table_find(t, &key)) {
            fprintf(stderr, "table_dump: permutation '%s' is not embedded in this build (subset %s)\n", argv[2],
                    t->subset);
            return 1;
        }
        return 0;
    }
    if (argc == 3 && strcmp(argv[1], "--write") == 0) {
        for (uint32_t m = 0; m < t->module_count; ++m) {
            const char *name = NULL;
            for (uint32_t i = 0; i < t->permutation_count && !name; ++i)
                if (t->permutations[i].module == m) name = t->permutations[i].name;
            char path[4096];
            snprintf(path, sizeof path, "%s/%s.spv", argv[2], name ? name : "unused");
            FILE *f = fopen(path, "wb");
            if (!f || fwrite(t->modules[m].words, 4, t->modules[m].word_count, f) != t->modules[m].word_count) {
                fprintf(stderr, "table_dump: cannot write '%s'\n", path);
                if (f) fclose(f);
                return 1;
            }
            fclose(f);
        }
        return 0;
    }
    if (argc != 1) {
        fprintf(stderr, "usage: table_dump [--write DIR | --find NAME | --embedded-count | --key-count [PASS]]\n");
        return 2;
    }
    printf("subset %s\n", t->subset);
    for (uint32_t i = 0; i < t->permutation_count; ++i)
        printf("%s %u %u\n", t->permutations[i].name, t->permutations[i].module,
               t->modules[t->permutations[i].module].word_count);
    return 0;
}
