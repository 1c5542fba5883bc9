/* compile.c - GLSL specialisation, glslang C API compilation and SPIRV-Tools validation. */
#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <glslang/build_info.h>
#include <spirv-tools/libspirv.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shadergen.h"
#include "text_file.h"

#define STR2(x) #x
#define STR(x) STR2(x)

const char *sg_glslang_version(void) {
    return "glslang " STR(GLSLANG_VERSION_MAJOR) "." STR(GLSLANG_VERSION_MINOR) "." STR(
        GLSLANG_VERSION_PATCH) GLSLANG_VERSION_FLAVOR;
}

const char *sg_spirv_tools_version(void) {
    static char version[64];
    snprintf(version, sizeof version, "SPIRV-Tools %s", spvSoftwareVersionString());
    return version;
}

char *sg_read_file(const char *path) {
    char err[512];
    char *text = cacao_read_whole_file(path, 64u << 20, err, sizeof err);
    if (!text) fprintf(stderr, "shadergen: %s\n", err);
    return text;
}

/* Appends text to a growing buffer. */
typedef struct sg_buf {
    char *data;
    size_t len, cap;
} sg_buf;

static void buf_append(sg_buf *b, const char *text, size_t len) {
    if (b->len + len + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + len + 1) cap *= 2;
        char *data = realloc(b->data, cap);
        if (!data) {
            fprintf(stderr, "shadergen: out of memory\n");
            exit(1);
        }
        b->data = data;
        b->cap = cap;
    }
    memcpy(b->data + b->len, text, len);
    b->len += len;
    b->data[b->len] = '\0';
}

static void buf_printf(sg_buf *b, const char *fmt, unsigned value, const char *s) {
    char tmp[256];
    int n = snprintf(tmp, sizeof tmp, fmt, value, s);
    buf_append(b, tmp, (size_t)n);
}

char *sg_specialise(const char *source, const char *shared_header, const cacao_key *key) {
    static const char include_line[] = "#include \"cacao_shared.h\"";
    char defines[CACAO_KEY_DEFINES_MAX];
    if (!cacaoi_key_defines(key, defines, sizeof defines)) return NULL;
    sg_buf b = {0};
    unsigned line = 1;
    const char *p = source;
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (line == 1 && strncmp(p, "#version", 8) == 0) {
            /* Keep #version first, then the key's defines, then resume line numbering. */
            buf_append(&b, p, len);
            buf_append(&b, "\n#extension GL_GOOGLE_cpp_style_line_directive : enable\n", 56);
            buf_append(&b, defines, strlen(defines));
            buf_printf(&b, "#line %u \"%s\"\n", line + 1, "cacao.comp");
        } else if (strncmp(p, include_line, sizeof include_line - 1) == 0) {
            buf_append(&b, "#line 1 \"cacao_shared.h\"\n", 25);
            buf_append(&b, shared_header, strlen(shared_header));
            buf_printf(&b, "\n#line %u \"%s\"\n", line + 1, "cacao.comp");
        } else {
            buf_append(&b, p, len);
            buf_append(&b, "\n", 1);
        }
        ++line;
        p += len + (end ? 1 : 0);
    }
    return b.data;
}

static glslang_input_t compute_input(const char *text) {
    return (glslang_input_t){
        .language = GLSLANG_SOURCE_GLSL,
        .stage = GLSLANG_STAGE_COMPUTE,
        .client = GLSLANG_CLIENT_VULKAN,
        .client_version = GLSLANG_TARGET_VULKAN_1_1,
        .target_language = GLSLANG_TARGET_SPV,
        .target_language_version = GLSLANG_TARGET_SPV_1_3,
        .code = text,
        .default_version = 450,
        .default_profile = GLSLANG_NO_PROFILE,
        .messages = GLSLANG_MSG_DEFAULT_BIT | GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT,
        .resource = glslang_default_resource(),
    };
}

char *sg_preprocess(const char *text, const char *key_name) {
    const glslang_input_t input = compute_input(text);
    glslang_shader_t *shader = glslang_shader_create(&input);
    char *out = NULL;
    if (glslang_shader_preprocess(shader, &input)) {
        const char *code = glslang_shader_get_preprocessed_code(shader);
        size_t len = strlen(code);
        out = malloc(len + 1);
        if (out) memcpy(out, code, len + 1);
    } else {
        fprintf(stderr, "%s: preprocessing failed:\n%s", key_name, glslang_shader_get_info_log(shader));
    }
    glslang_shader_delete(shader);
    return out;
}

bool sg_compile(const char *text, const char *key_name, const sg_options *options, uint32_t **words,
                size_t *word_count) {
    const glslang_input_t input = compute_input(text);
    bool ok = false;
    glslang_shader_t *shader = glslang_shader_create(&input);
    glslang_program_t *program = NULL;
    if (!glslang_shader_preprocess(shader, &input) || !glslang_shader_parse(shader, &input)) {
        fprintf(stderr, "shadergen: %s: GLSL compilation failed:\n%s%s", key_name,
                glslang_shader_get_info_log(shader), glslang_shader_get_info_debug_log(shader));
        goto done;
    }
    program = glslang_program_create();
    glslang_program_add_shader(program, shader);
    if (!glslang_program_link(program, input.messages)) {
        fprintf(stderr, "shadergen: %s: link failed:\n%s", key_name, glslang_program_get_info_log(program));
        goto done;
    }
    glslang_spv_options_t spv = {
        .disable_optimizer = !options->optimize,
        .optimize_size = options->optimize,
    };
    glslang_program_SPIRV_generate_with_options(program, GLSLANG_STAGE_COMPUTE, &spv);
    const char *messages = glslang_program_SPIRV_get_messages(program);
    if (messages && *messages) {
        fprintf(stderr, "shadergen: %s: SPIR-V generation reported:\n%s", key_name, messages);
        goto done;
    }
    *word_count = glslang_program_SPIRV_get_size(program);
    *words = malloc(*word_count * sizeof(uint32_t));
    if (!*words) goto done;
    glslang_program_SPIRV_get(program, *words);
    ok = true;
done:
    if (program) glslang_program_delete(program);
    glslang_shader_delete(shader);
    return ok;
}

bool sg_validate(const uint32_t *words, size_t word_count, const char *key_name) {
    spv_context context = spvContextCreate(SPV_ENV_VULKAN_1_1);
    spv_const_binary_t binary = {words, word_count};
    spv_diagnostic diagnostic = NULL;
    spv_result_t result = spvValidate(context, &binary, &diagnostic);
    if (result != SPV_SUCCESS) {
        fprintf(stderr, "shadergen: %s: spvValidate failed: %s\n", key_name,
                diagnostic && diagnostic->error ? diagnostic->error : "(no diagnostic)");
    }
    spvDiagnosticDestroy(diagnostic);
    spvContextDestroy(context);
    return result == SPV_SUCCESS;
}

char *sg_disassemble(const uint32_t *words, size_t word_count) {
    spv_context context = spvContextCreate(SPV_ENV_VULKAN_1_1);
    spv_text text = NULL;
    spv_diagnostic diagnostic = NULL;
    char *out = NULL;
    if (spvBinaryToText(context, words, word_count,
                        SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES | SPV_BINARY_TO_TEXT_OPTION_INDENT, &text,
                        &diagnostic) == SPV_SUCCESS &&
        (out = malloc(text->length + 1))) {
        memcpy(out, text->str, text->length);
        out[text->length] = '\0';
    }
    spvTextDestroy(text);
    spvDiagnosticDestroy(diagnostic);
    spvContextDestroy(context);
    return out;
}
