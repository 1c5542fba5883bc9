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

/* ---- Sources and #include ----
 * glslang 12's C API has no include callback (glslang_input_t gained one in later releases), so
 * the generator resolves the source's #include "file" lines itself (the GL_GOOGLE_include_directive
 * form, names relative to the including file), marking each file with #line so that compile
 * errors name the right file and line. */

/* The name of an #include line ('#include "name"'), or false for another line. */
static bool include_name(const char *line, size_t len, char *name, size_t name_size) {
    static const char directive[] = "#include \"";
    if (len < sizeof directive || strncmp(line, directive, sizeof directive - 1) != 0) return false;
    const char *start = line + sizeof directive - 1;
    const char *end = memchr(start, '"', len - (sizeof directive - 1));
    if (!end || (size_t)(end - start) + 1 > name_size) return false;
    memcpy(name, start, (size_t)(end - start));
    name[end - start] = '\0';
    return true;
}

/* name relative to the folder of includer (both relative to the entry's folder). */
static void relative_to(const char *includer, const char *name, char *out, size_t out_size) {
    const char *slash = strrchr(includer, '/');
    const int dir = slash ? (int)(slash - includer) + 1 : 0;
    snprintf(out, out_size, "%.*s%s", dir, includer, name);
}

static const sg_source *find_source(const sg_sources *sources, const char *name) {
    for (size_t i = 0; i < sources->count; ++i)
        if (strcmp(sources->files[i].name, name) == 0) return &sources->files[i];
    return NULL;
}

/* Reads file `name` (relative to dir) and, recursively, every file it includes; a file that cannot
 * be read is reported with the includer and line that named it (from: NULL for the entry). */
static bool load_file(const char *dir, const char *name, unsigned depth, const char *from, unsigned from_line,
                      sg_sources *out) {
    if (find_source(out, name)) return true;
    if (depth > SG_MAX_INCLUDE_DEPTH || out->count >= SG_MAX_SOURCES) {
        fprintf(stderr, "shadergen: %s: includes nest deeper than %d or name more than %d files\n", name,
                SG_MAX_INCLUDE_DEPTH, SG_MAX_SOURCES);
        return false;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s%s", dir, name);
    char err[512];
    char *text = cacao_read_whole_file(path, 64u << 20, err, sizeof err);
    if (!text && from) fprintf(stderr, "shadergen: %s:%u: cannot include \"%s\": %s\n", from, from_line, name, err);
    if (!text && !from) fprintf(stderr, "shadergen: %s\n", err);
    char *copy = malloc(strlen(name) + 1);
    if (!text || !copy) {
        free(text);
        free(copy);
        return false;
    }
    memcpy(copy, name, strlen(name) + 1);
    out->files[out->count++] = (sg_source){copy, text};
    unsigned line = 1;
    for (const char *p = text; *p; ++line) {
        const char *end = strchr(p, '\n');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        char inc[256], rel[512];
        if (include_name(p, len, inc, sizeof inc)) {
            relative_to(name, inc, rel, sizeof rel);
            if (!load_file(dir, rel, depth + 1, copy, line, out)) return false;
        }
        p += len + (end ? 1 : 0);
    }
    return true;
}

bool sg_load_sources(const char *entry_path, sg_sources *out) {
    memset(out, 0, sizeof *out);
    const char *slash = strrchr(entry_path, '/');
    char dir[4096];
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - entry_path) + 1 : 0, entry_path);
    if (load_file(dir, slash ? slash + 1 : entry_path, 0, NULL, 0, out)) return true;
    sg_free_sources(out);
    return false;
}

void sg_free_sources(sg_sources *sources) {
    for (size_t i = 0; i < sources->count; ++i) {
        free((char *)sources->files[i].name);
        free((char *)sources->files[i].text);
    }
    memset(sources, 0, sizeof *sources);
}

static void buf_line_mark(sg_buf *b, unsigned line, const char *file) {
    char tmp[600];
    int n = snprintf(tmp, sizeof tmp, "#line %u \"%s\"\n", line, file);
    buf_append(b, tmp, (size_t)n);
}

/* Appends file `src` with its includes spliced in; false (message printed) on an unresolved one. */
static bool splice(sg_buf *b, const sg_sources *sources, const sg_source *src, const char *defines, unsigned depth) {
    unsigned line = 1;
    for (const char *p = src->text; *p; ++line) {
        const char *end = strchr(p, '\n');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        char inc[256], rel[512];
        if (depth == 0 && line == 1 && strncmp(p, "#version", 8) == 0) {
            /* Keep #version first, then the key's defines, then resume line numbering. */
            buf_append(b, p, len);
            static const char ext[] = "\n#extension GL_GOOGLE_cpp_style_line_directive : enable\n";
            buf_append(b, ext, sizeof ext - 1);
            buf_append(b, defines, strlen(defines));
            buf_line_mark(b, line + 1, src->name);
        } else if (include_name(p, len, inc, sizeof inc)) {
            relative_to(src->name, inc, rel, sizeof rel);
            const sg_source *child = find_source(sources, rel);
            if (!child || depth >= SG_MAX_INCLUDE_DEPTH) {
                fprintf(stderr, "shadergen: %s:%u: cannot include \"%s\" (%s)\n", src->name, line, inc,
                        child ? "nested too deep" : "not among the loaded sources");
                return false;
            }
            buf_line_mark(b, 1, child->name);
            if (!splice(b, sources, child, defines, depth + 1)) return false;
            buf_append(b, "\n", 1);
            buf_line_mark(b, line + 1, src->name);
        } else {
            buf_append(b, p, len);
            buf_append(b, "\n", 1);
        }
        p += len + (end ? 1 : 0);
    }
    return true;
}

char *sg_specialise(const sg_sources *sources, const cacao_key *key) {
    char defines[CACAO_KEY_DEFINES_MAX];
    if (!sources->count || !cacaoi_key_defines(key, defines, sizeof defines)) return NULL;
    sg_buf b = {0};
    if (!splice(&b, sources, &sources->files[0], defines, 0)) {
        free(b.data);
        return NULL;
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
