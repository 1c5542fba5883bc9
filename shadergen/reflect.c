/* reflect.c - per-module facts from SPIRV-Cross reflection (C API), and duplicate removal. */
#include <spirv_cross/spirv_cross_c.h>
#include <stdio.h>
#include <string.h>

#include "shadergen.h"

typedef struct resource_kind {
    spvc_resource_type type;
    uint8_t kind;
} resource_kind;

static const resource_kind kinds[] = {
    {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, CACAO_RESOURCE_UNIFORM_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, CACAO_RESOURCE_STORAGE_BUFFER},
    {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, CACAO_RESOURCE_SAMPLED_IMAGE},
    {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, CACAO_RESOURCE_STORAGE_IMAGE},
};

static void report(void *userdata, const char *error) {
    fprintf(stderr, "shadergen: %s: SPIRV-Cross: %s\n", (const char *)userdata, error);
}

bool sg_reflect(sg_module *m) {
    spvc_context context = NULL;
    spvc_parsed_ir ir = NULL;
    spvc_compiler compiler = NULL;
    spvc_resources resources = NULL;
    bool ok = false;
    if (spvc_context_create(&context) != SPVC_SUCCESS) return false;
    spvc_context_set_error_callback(context, report, m->name);
    if (spvc_context_parse_spirv(context, m->words, m->word_count, &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(context, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &compiler) != SPVC_SUCCESS ||
        spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS)
        goto done;

    for (unsigned i = 0; i < 3; ++i)
        m->workgroup_size[i] =
            spvc_compiler_get_execution_mode_argument_by_index(compiler, SpvExecutionModeLocalSize, i);
    memset(m->bindings, 0, sizeof m->bindings);
    m->uniform_size = 0;
    m->push_constant_size = 0;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
        const spvc_reflected_resource *list = NULL;
        size_t count = 0;
        if (spvc_resources_get_resource_list_for_type(resources, kinds[k].type, &list, &count) != SPVC_SUCCESS)
            goto done;
        for (size_t i = 0; i < count; ++i) {
            unsigned set = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationDescriptorSet);
            unsigned binding = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationBinding);
            if (set != 0 || binding >= CACAO_BINDING_COUNT) {
                fprintf(stderr, "shadergen: %s: resource '%s' at set %u binding %u is outside set 0's %d bindings\n",
                        m->name, list[i].name, set, binding, CACAO_BINDING_COUNT);
                goto done;
            }
            m->bindings[binding] = kinds[k].kind;
            if (kinds[k].kind == CACAO_RESOURCE_UNIFORM_BUFFER) {
                size_t size = 0;
                spvc_compiler_get_declared_struct_size(
                    compiler, spvc_compiler_get_type_handle(compiler, list[i].base_type_id), &size);
                m->uniform_size = (uint32_t)size;
            }
        }
    }
    {
        const spvc_reflected_resource *list = NULL;
        size_t count = 0;
        spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, &list, &count);
        for (size_t i = 0; i < count; ++i) {
            size_t size = 0;
            spvc_compiler_get_declared_struct_size(
                compiler, spvc_compiler_get_type_handle(compiler, list[i].base_type_id), &size);
            m->push_constant_size = (uint32_t)size;
        }
    }
    ok = true;
done:
    spvc_context_destroy(context);
    return ok;
}

uint32_t sg_dedup(sg_module *modules, size_t count) {
    uint32_t unique = 0;
    for (size_t i = 0; i < count; ++i) {
        modules[i].dedup_of = (uint32_t)i;
        modules[i].module_index = unique;
        for (size_t j = 0; j < i; ++j) {
            if (modules[j].dedup_of == j && modules[j].word_count == modules[i].word_count &&
                memcmp(modules[j].words, modules[i].words, modules[i].word_count * 4) == 0) {
                modules[i].dedup_of = (uint32_t)j;
                modules[i].module_index = modules[j].module_index;
                break;
            }
        }
        if (modules[i].dedup_of == i) ++unique;
    }
    return unique;
}
