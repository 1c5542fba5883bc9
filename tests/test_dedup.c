/* test_dedup - duplicate removal: the same permutation compiled twice is stored once, different
 * permutations stay apart, and in the embedded table permutations share a module only when their
 * SPIR-V would be byte-identical (distinct modules really differ). Prints counts before/after. */
#include <glslang/Include/glslang_c_interface.h>
#include <stdlib.h>
#include <string.h>

#include "shadergen.h"
#include "test_util.h"

static bool compile_key(const sg_sources *sources, const char *name, sg_module *m) {
    memset(m, 0, sizeof *m);
    if (!cacaoi_key_parse(name, &m->key)) return false;
    snprintf(m->name, sizeof m->name, "%s", name);
    char *text = sg_specialise(sources, &m->key);
    sg_options options = {.optimize = true};
    bool ok = text && sg_compile(text, name, &options, &m->words, &m->word_count) &&
              sg_validate(m->words, m->word_count, name);
    free(text);
    return ok;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: test_dedup cacao.comp\n");
        return 2;
    }
    sg_sources sources;
    const bool loaded = sg_load_sources(argv[1], &sources);
    CHECK(loaded);
    if (!loaded) return 1;
    glslang_initialize_process();
    sg_module m[3];
    CHECK(compile_key(&sources, "generate.q2", &m[0]));
    CHECK(compile_key(&sources, "blur.3.fp32", &m[1]));
    CHECK(compile_key(&sources, "generate.q2", &m[2])); /* the same key again */
    glslang_finalize_process();
    uint32_t unique = sg_dedup(m, 3);
    printf("synthetic: 3 modules before dedup, %u after\n", unique);
    CHECK(unique == 2);
    CHECK(m[2].dedup_of == 0 && m[2].module_index == m[0].module_index);
    CHECK(m[1].dedup_of == 1 && m[1].module_index != m[0].module_index);
    for (int i = 0; i < 3; ++i) free(m[i].words);

    /* The committed table: shared modules are identical by construction; distinct ones differ. */
    const cacao_table *t = &cacaoi_embedded_table;
    for (uint32_t a = 0; a < t->module_count; ++a)
        for (uint32_t b = a + 1; b < t->module_count; ++b)
            CHECK(t->modules[a].word_count != t->modules[b].word_count ||
                  memcmp(t->modules[a].words, t->modules[b].words, t->modules[a].word_count * 4) != 0);
    for (uint32_t i = 0; i < t->permutation_count; ++i) CHECK(t->permutations[i].module < t->module_count);
    printf("embedded table: %u permutations, %u unique modules\n", t->permutation_count, t->module_count);
    sg_free_sources(&sources);
    return test_report("test_dedup");
}
