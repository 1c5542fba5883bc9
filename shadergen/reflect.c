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
    {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, CACAOI_DESCRIPTOR_UNIFORM_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, CACAOI_DESCRIPTOR_STORAGE_BUFFER},
    {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, CACAOI_DESCRIPTOR_SAMPLED_IMAGE},
    {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, CACAOI_DESCRIPTOR_STORAGE_IMAGE},
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
            if (kinds[k].kind == CACAOI_DESCRIPTOR_SAMPLED_IMAGE || kinds[k].kind == CACAOI_DESCRIPTOR_STORAGE_IMAGE) {
                spvc_type type = spvc_compiler_get_type_handle(compiler, list[i].type_id);
                /* a storage image of dimension Buffer is a storage texel buffer */
                if (kinds[k].kind == CACAOI_DESCRIPTOR_STORAGE_IMAGE && spvc_type_get_image_dimension(type) == SpvDimBuffer)
                    m->bindings[binding] = CACAOI_DESCRIPTOR_STORAGE_TEXEL_BUFFER;
                m->image_format[binding] = (uint32_t)spvc_type_get_image_storage_format(type);
                m->image_arrayed[binding] = spvc_type_get_image_arrayed(type);
                m->non_writable[binding] = spvc_compiler_has_decoration(compiler, list[i].id, SpvDecorationNonWritable);
            }
            if (kinds[k].kind == CACAOI_DESCRIPTOR_UNIFORM_BUFFER) {
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

bool sg_uniform_block(const uint32_t *words, size_t word_count, sg_block *block) {
    spvc_context context = NULL;
    spvc_parsed_ir ir = NULL;
    spvc_compiler compiler = NULL;
    spvc_resources resources = NULL;
    const spvc_reflected_resource *list = NULL;
    size_t count = 0;
    bool ok = false;
    if (spvc_context_create(&context) != SPVC_SUCCESS) return false;
    spvc_context_set_error_callback(context, report, (void *)"uniform block");
    if (spvc_context_parse_spirv(context, words, word_count, &ir) == SPVC_SUCCESS &&
        spvc_context_create_compiler(context, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler) ==
            SPVC_SUCCESS &&
        spvc_compiler_create_shader_resources(compiler, &resources) == SPVC_SUCCESS &&
        spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, &list, &count) ==
            SPVC_SUCCESS &&
        count == 1) {
        spvc_type type = spvc_compiler_get_type_handle(compiler, list[0].base_type_id);
        snprintf(block->name, sizeof block->name, "%s", list[0].name);
        block->binding = spvc_compiler_get_decoration(compiler, list[0].id, SpvDecorationBinding);
        spvc_compiler_get_declared_struct_size(compiler, type, &block->size);
        const unsigned n = spvc_type_get_num_member_types(type);
        block->member_count = n;
        sg_member *members = block->members;
        for (unsigned i = 0; i < n && i < SG_BLOCK_MAX_MEMBERS; ++i) {
            unsigned offset = 0;
            size_t member_size = 0;
            spvc_compiler_type_struct_member_offset(compiler, type, i, &offset);
            spvc_compiler_get_declared_struct_member_size(compiler, type, i, &member_size);
            snprintf(members[i].name, sizeof members[i].name, "%s",
                     spvc_compiler_get_member_name(compiler, list[0].base_type_id, i));
            members[i].offset = offset;
            members[i].size = (uint32_t)member_size;
        }
        ok = true;
    }
    spvc_context_destroy(context);
    return ok;
}

/* SPIR-V image format of a GLSL storage-image qualifier used by the resource rows. */
static SpvImageFormat spv_format(const char *glsl) {
    static const struct {
        const char *glsl;
        SpvImageFormat spv;
    } formats[] = {
        {"r16f", SpvImageFormatR16f}, {"r32f", SpvImageFormatR32f}, {"rgba8_snorm", SpvImageFormatRgba8Snorm},
        {"rg8", SpvImageFormatRg8},   {"r8", SpvImageFormatR8}, {"rgba32f", SpvImageFormatRgba32f},
        {"rg32f", SpvImageFormatRg32f},
    };
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; ++i)
        if (strcmp(formats[i].glsl, glsl) == 0) return formats[i].spv;
    return SpvImageFormatUnknown;
}


bool sg_check_row(const sg_module *m) {
    cacaoi_module_expect want;
    if (!cacaoi_key_expect(&m->key, &want)) {
        fprintf(stderr, "shadergen: %s: no pass row for this key\n", m->name);
        return false;
    }
    bool ok = true;
    const char *pass = cacaoi_pass_name(m->key.pass);
    if (memcmp(m->workgroup_size, want.workgroup, sizeof want.workgroup) != 0) {
        fprintf(stderr, "shadergen: %s: pass %s: workgroup %ux%ux%u, its row says %ux%ux%u\n", m->name, pass,
                m->workgroup_size[0], m->workgroup_size[1], m->workgroup_size[2], want.workgroup[0],
                want.workgroup[1], want.workgroup[2]);
        ok = false;
    }
    for (unsigned b = 0; b < CACAO_BINDING_COUNT; ++b) {
        const char *slot = cacaoi_slots[b].name;
        if (m->bindings[b] != want.descriptor[b]) {
            fprintf(stderr, "shadergen: %s: pass %s, binding %s (%u): the module declares %s, its row %s\n", m->name,
                    pass, slot, b, cacaoi_descriptor_names[m->bindings[b]], cacaoi_descriptor_names[want.descriptor[b]]);
            ok = false;
            continue;
        }
        const bool image = want.descriptor[b] == CACAOI_DESCRIPTOR_SAMPLED_IMAGE ||
                           want.descriptor[b] == CACAOI_DESCRIPTOR_STORAGE_IMAGE;
        if (!image) continue;
        const cacaoi_resource_row *res = &cacaoi_resources[want.resource[b]];
        if (m->image_arrayed[b] != res->layered) {
            fprintf(stderr, "shadergen: %s: pass %s, binding %s (%u): the module declares %s image, resource %s is %s\n",
                    m->name, pass, slot, b, m->image_arrayed[b] ? "an array" : "a 2D", res->name,
                    res->layered ? "layered" : "one layer");
            ok = false;
        }
        if (want.descriptor[b] != CACAOI_DESCRIPTOR_STORAGE_IMAGE) continue;
        if (m->image_format[b] != (uint32_t)spv_format(res->glsl_format)) {
            fprintf(stderr, "shadergen: %s: pass %s, binding %s (%u): declared format %u, resource %s has '%s'\n",
                    m->name, pass, slot, b, m->image_format[b], res->name,
                    *res->glsl_format ? res->glsl_format : "none (the view's format)");
            ok = false;
        }
        if (m->non_writable[b] == want.write[b]) {
            fprintf(stderr, "shadergen: %s: pass %s, binding %s (%u): the module %s it, its row says %s\n", m->name,
                    pass, slot, b, m->non_writable[b] ? "only reads" : "may write", want.write[b] ? "write" : "read");
            ok = false;
        }
    }
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
