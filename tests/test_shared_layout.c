/* test_shared_layout - the constant block's C layout (offsetof/sizeof of cacao_constants) equals
 * the std140 layout SPIRV-Cross reflects from every embedded module that uses the block. The
 * shaders and the runtime include the same header, but C and std140 pack differently (vec2
 * alignment, array strides, mat4), so only reflection of the compiled SPIR-V proves agreement. */
#include <spirv_cross/spirv_cross_c.h>
#include <stddef.h>
#include <string.h>

#include "cacao_table.h"
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
    spvc_context ctx = NULL;
    spvc_parsed_ir ir = NULL;
    spvc_compiler comp = NULL;
    spvc_resources res = NULL;
    const spvc_reflected_resource *list = NULL;
    size_t count = 0;
    CHECK(spvc_context_create(&ctx) == SPVC_SUCCESS);
    CHECK(spvc_context_parse_spirv(ctx, m->words, m->word_count, &ir) == SPVC_SUCCESS);
    CHECK(spvc_context_create_compiler(ctx, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &comp) ==
          SPVC_SUCCESS);
    CHECK(spvc_compiler_create_shader_resources(comp, &res) == SPVC_SUCCESS);
    CHECK(spvc_resources_get_resource_list_for_type(res, SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, &list, &count) ==
          SPVC_SUCCESS);
    CHECK(count == 1);
    for (size_t r = 0; r < count; ++r) {
        spvc_type type = spvc_compiler_get_type_handle(comp, list[r].base_type_id);
        size_t struct_size = 0;
        spvc_compiler_get_declared_struct_size(comp, type, &struct_size);
        CHECK(struct_size == sizeof(cacao_constants));
        CHECK(p->uniform_size == sizeof(cacao_constants));
        unsigned members = spvc_type_get_num_member_types(type);
        CHECK(members == C_MEMBER_COUNT);
        for (unsigned i = 0; i < members && i < C_MEMBER_COUNT; ++i) {
            const char *name = spvc_compiler_get_member_name(comp, list[r].base_type_id, i);
            unsigned offset = 0;
            size_t size = 0;
            spvc_compiler_type_struct_member_offset(comp, type, i, &offset);
            spvc_compiler_get_declared_struct_member_size(comp, type, i, &size);
            if (strcmp(name, c_members[i].name) != 0 || offset != c_members[i].offset || size != c_members[i].size) {
                fprintf(stderr, "%s: member %u: SPIR-V '%s' at %u (%zu bytes), C '%s' at %zu (%zu bytes)\n", p->name,
                        i, name, offset, size, c_members[i].name, c_members[i].offset, c_members[i].size);
                ++test_failures;
            }
        }
    }
    spvc_context_destroy(ctx);
}

int main(void) {
    unsigned checked = 0;
    for (uint32_t i = 0; i < cacaoi_embedded_table.permutation_count; ++i) {
        const cacao_permutation *p = &cacaoi_embedded_table.permutations[i];
        if (p->bindings[CACAO_BINDING_CONSTANTS] != CACAO_RESOURCE_UNIFORM_BUFFER) continue;
        check_module(p);
        ++checked;
    }
    printf("checked the constant block of %u modules against sizeof %zu, %zu members\n", checked,
           sizeof(cacao_constants), C_MEMBER_COUNT);
    CHECK(checked > 0);
    return test_report("test_shared_layout");
}
