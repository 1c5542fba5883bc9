/* shadergen.h - internal interface of the build-time shader generator. */
#ifndef SHADERGEN_H
#define SHADERGEN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao_table.h"

/* One compiled permutation. */
typedef struct sg_module {
    cacao_key key;
    char name[CACAO_KEY_NAME_MAX];
    uint32_t *words;
    size_t word_count;
    uint32_t dedup_of;         /* index of the first permutation with identical words, or itself */
    uint32_t module_index;     /* index among unique modules */
    uint32_t workgroup_size[3];
    uint32_t uniform_size;
    uint32_t push_constant_size;
    uint8_t bindings[CACAO_BINDING_COUNT];
    /* Image bindings only: declared format (SpvImageFormat), arrayed, decorated NonWritable. */
    uint32_t image_format[CACAO_BINDING_COUNT];
    bool image_arrayed[CACAO_BINDING_COUNT];
    bool non_writable[CACAO_BINDING_COUNT];
} sg_module;

typedef struct sg_options {
    bool optimize; /* run glslang's SPIRV-Tools optimizer; its C API offers the size passes only */
} sg_options;

/* The shader's source files: the entry (cacao.comp) first, then every file it includes, each
 * named relative to the entry's folder ("cacao_shared.h", "glsl/blur.glsl"). */
typedef struct sg_source {
    const char *name;
    const char *text;
} sg_source;
#define SG_MAX_SOURCES 32
#define SG_MAX_INCLUDE_DEPTH 8
typedef struct sg_sources {
    sg_source files[SG_MAX_SOURCES];
    size_t count;
} sg_sources;

/* Reads the entry source and, recursively, every file its #include "name" lines name (relative to
 * the including file). False (message naming the file) when one cannot be read. */
bool sg_load_sources(const char *entry_path, sg_sources *out);
void sg_free_sources(sg_sources *sources);

/* Builds the full shader text for a key: #version line, the key's defines, every #include
 * spliced in place, with #line directives so errors name the right file and line. NULL (message
 * printed) for an invalid key or an include not among the sources. The caller frees it. */
char *sg_specialise(const sg_sources *sources, const cacao_key *key);

/* Compiles GLSL text to SPIR-V 1.3 (Vulkan 1.1). On failure prints the key and log, returns false. */
bool sg_compile(const char *text, const char *key_name, const sg_options *options, uint32_t **words,
                size_t *word_count);

/* Preprocesses GLSL text (defines expanded, comments gone) for inspection; NULL on failure
 * (message printed). The caller frees the result. */
char *sg_preprocess(const char *text, const char *key_name);

/* Runs spvValidate (Vulkan 1.1 rules). On failure prints the key and diagnostic. */
bool sg_validate(const uint32_t *words, size_t word_count, const char *key_name);

/* SPIR-V disassembly with friendly names, or NULL; the caller frees it. */
char *sg_disassemble(const uint32_t *words, size_t word_count);

/* Fills workgroup size, bindings, uniform and push-constant sizes from SPIRV-Cross reflection. */
bool sg_reflect(sg_module *module);

/* One member of a module's uniform block, as SPIRV-Cross lays it out (std140). */
typedef struct sg_member {
    char name[64];
    uint32_t offset;
    uint32_t size;
} sg_member;

typedef struct sg_block {
    char name[64];
    uint32_t binding;
    size_t size;         /* declared size, bytes */
    size_t member_count; /* all members; members[] holds the first SG_BLOCK_MAX_MEMBERS */
    sg_member members[128];
} sg_block;
#define SG_BLOCK_MAX_MEMBERS 128

/* The module's one uniform block. False when it has none (or several) or reflection fails. */
bool sg_uniform_block(const uint32_t *words, size_t word_count, sg_block *block);

/* Checks a reflected module against its pass row (cacaoi_pass_expect): workgroup size, and per
 * binding slot the descriptor kind, image layering, storage format and access. Prints every
 * mismatch naming the pass and the binding; false if there was one. */
bool sg_check_row(const sg_module *module);

/* Marks identical modules (dedup_of, module_index); returns the number of unique modules. */
uint32_t sg_dedup(sg_module *modules, size_t count);

/* Writes cacao_spirv.c, cacao_table.c and VERSIONS into dir. */
bool sg_emit(const char *dir, const sg_module *modules, size_t count, const char *subset);

/* Versions of the compilers, as recorded in generated/VERSIONS. */
const char *sg_glslang_version(void);
const char *sg_spirv_tools_version(void);


#endif /* SHADERGEN_H */
