/* test_row_check - shadergen's check of a compiled module against its pass row (sg_check_row),
 * which runs on every permutation at build time: every embedded module passes it, and it fails,
 * naming the pass and binding, when module and row disagree on what the module declares (another
 * pass's module under this key, a binding missing, a storage format, layering or access changed,
 * another workgroup size). */
#include <stdlib.h>
#include <string.h>

#include "shadergen.h"
#include "test_util.h"

static bool reflect_key(const char *name, sg_module *m) {
    memset(m, 0, sizeof *m);
    if (!cacaoi_key_parse(name, &m->key)) return false;
    snprintf(m->name, sizeof m->name, "%s", name);
    const cacao_permutation *p = cacaoi_table_find(&cacaoi_embedded_table, &m->key);
    if (!p) return false;
    const cacao_module *mod = &cacaoi_embedded_table.modules[p->module];
    m->words = (uint32_t *)mod->words;
    m->word_count = mod->word_count;
    return sg_reflect(m);
}

int main(void) {
    const cacao_table *t = &cacaoi_embedded_table;
    for (uint32_t i = 0; i < t->permutation_count; ++i) {
        sg_module m;
        CHECK(reflect_key(t->permutations[i].name, &m));
        CHECK(sg_check_row(&m));
    }
    printf("%u embedded modules match their rows; the next mismatches are expected:\n", t->permutation_count);

    sg_module m;
    CHECK(reflect_key("apply.smart.fp32", &m));
    m.key.pass = CACAO_PASS_BLUR, m.key.variant = 0, m.key.blur_passes = 2; /* apply's module as blur's */
    CHECK(!sg_check_row(&m));

    CHECK(reflect_key("generate.q3", &m));
    m.bindings[CACAO_BINDING_IMPORTANCE_MAP] = CACAOI_DESCRIPTOR_NONE; /* a binding the row has, missing */
    CHECK(!sg_check_row(&m));

    CHECK(reflect_key("prepare_depths.mips.native", &m));
    m.image_format[CACAO_BINDING_DEPTHS_IMAGE] = m.image_format[CACAO_BINDING_DEPTHS_IMAGE] + 1; /* other format */
    CHECK(!sg_check_row(&m));

    CHECK(reflect_key("blur.3.fp16", &m));
    m.image_arrayed[CACAO_BINDING_SSAO_IMAGE] = false; /* a 2D image where the row's resource is layered */
    CHECK(!sg_check_row(&m));

    CHECK(reflect_key("horizon_main.gtao", &m));
    m.non_writable[CACAO_BINDING_VIEW_DEPTH] = false; /* writable where the row only reads */
    CHECK(!sg_check_row(&m));

    CHECK(reflect_key("importance_a", &m));
    m.workgroup_size[0] = 16;
    CHECK(!sg_check_row(&m));
    return test_report("row_check");
}
