/* table_dump - prints the embedded permutation table (used by the subset-build and spirv-val tests).
 * usage: table_dump               list "name module words" per permutation
 *        table_dump --write DIR   write every unique module as DIR/<first name>.spv
 *        table_dump --find NAME   exit 0 if the key is embedded, 1 with a message if not */
#include <stdio.h>
#include <string.h>

#include "cacao_table.h"

int main(int argc, char **argv) {
    const cacao_table *t = &cacaoi_embedded_table;
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
        fprintf(stderr, "usage: table_dump [--write DIR | --find NAME]\n");
        return 2;
    }
    printf("subset %s\n", t->subset);
    for (uint32_t i = 0; i < t->permutation_count; ++i)
        printf("%s %u %u\n", t->permutations[i].name, t->permutations[i].module,
               t->modules[t->permutations[i].module].word_count);
    return 0;
}
