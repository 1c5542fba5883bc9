/* test_shared_layout - the constant block's C layout (offsetof/sizeof of cacao_constants) equals
 * the std140 layout SPIRV-Cross reflects from every embedded module that uses the block. The
 * shaders and the runtime include the same header, but C and std140 pack differently (vec2
 * alignment, array strides, mat4), so only reflection of the compiled SPIR-V proves agreement. */
#include <stddef.h>
#include <string.h>

#include "shadergen.h"
#include "test_util.h"

typedef struct c_member {
    const char *name;
    size_t offset, size;
} c_member;

#define MEMBER(type, name) {#name, offsetof(cacao_constants, name), sizeof(((cacao_constants *)0)->name)},
#define MEMBER_ARRAY(type, name, count) MEMBER(type, name)
static const c_member c_members[] = {CACAO_CONSTANTS_MEMBERS(MEMBER, MEMBER_ARRAY)};
#define C_MEMBER_COUNT (sizeof c_members / sizeof c_members[0])

static void check_module(const cacao_permutation *p) {
    const cacao_module *m = &cacaoi_embedded_table.modules[p->module];
    static sg_block block;
    CHECK(sg_uniform_block(m->words, m->word_count, &block));
    CHECK(block.binding == CACAO_BINDING_CONSTANTS);
    CHECK(block.size == sizeof(cacao_constants));
    CHECK(p->uniform_size == sizeof(cacao_constants));
    CHECK(block.member_count == C_MEMBER_COUNT);
    for (size_t i = 0; i < block.member_count && i < C_MEMBER_COUNT; ++i) {
        const sg_member *got = &block.members[i];
        if (strcmp(got->name, c_members[i].name) != 0 || got->offset != c_members[i].offset ||
            got->size != c_members[i].size) {
            fprintf(stderr, "%s: member %zu: SPIR-V '%s' at %u (%u bytes), C '%s' at %zu (%zu bytes)\n", p->name, i,
                    got->name, got->offset, got->size, c_members[i].name, c_members[i].offset, c_members[i].size);
            ++test_failures;
        }
    }
}

int main(void) {
    unsigned checked = 0;
    for (uint32_t i = 0; i < cacaoi_embedded_table.permutation_count; ++i) {
        const cacao_permutation *p = &cacaoi_embedded_table.permutations[i];
        if (p->bindings[CACAO_BINDING_CONSTANTS] != CACAOI_DESCRIPTOR_UNIFORM_BUFFER) continue;
        check_module(p);
        ++checked;
    }
    printf("checked the constant block of %u modules against sizeof %zu, %zu members\n", checked,
           sizeof(cacao_constants), C_MEMBER_COUNT);
    CHECK(checked > 0);
    return test_report("test_shared_layout");
}
