/* shadergen - specialises shaders/cacao.comp into every permutation of the key space, compiles
 * each with glslang's C API, validates with SPIRV-Tools, reflects with SPIRV-Cross, removes
 * duplicates and writes the C sources of generated/.
 *
 * usage: shadergen --source FILE --out DIR [--qualities LIST] [--downsample ON|OFF|ONLY]
 *                  [--precision LIST] [--no-optimize]
 *
 * The source's #include lines are resolved relative to the including file (compile.c). By
 * default modules go through SPIRV-Tools' size passes (run by glslang); the summary line gives
 * the SPIR-V bytes (compare a --no-optimize run); drivers optimise again at pipeline creation.
 * (glslang 12's C API runs the optimizer only for size: asking for its performance passes gave
 * byte-identical output to no optimisation, so that choice is not offered.)
 */
#include <glslang/Include/glslang_c_interface.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cacao_policy.h"
#include "shadergen.h"

typedef struct sg_args {
    const char *source, *out;
    const char *qualities, *downsample, *precision;
    sg_options options;
} sg_args;

static int usage(const char *problem) {
    fprintf(stderr,
            "shadergen: %s\nusage: shadergen --source cacao.comp --out DIR\n"
            "       [--qualities lowest;low;medium;high;highest] [--downsample ON|OFF|ONLY]\n"
            "       [--precision fp32;fp16] [--no-optimize]\n",
            problem);
    return 2;
}

static bool parse_args(int argc, char **argv, sg_args *a) {
    *a = (sg_args){.qualities = "all", .downsample = "ON", .precision = "all", .options = {.optimize = true}};
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char **slot = NULL;
        if (strcmp(arg, "--source") == 0) slot = &a->source;
        else if (strcmp(arg, "--out") == 0) slot = &a->out;
        else if (strcmp(arg, "--qualities") == 0) slot = &a->qualities;
        else if (strcmp(arg, "--downsample") == 0) slot = &a->downsample;
        else if (strcmp(arg, "--precision") == 0) slot = &a->precision;
        else if (strcmp(arg, "--no-optimize") == 0) a->options.optimize = false;
        else {
            fprintf(stderr, "shadergen: unknown argument '%s'\n", arg);
            return false;
        }
        if (slot) {
            if (i + 1 >= argc) {
                fprintf(stderr, "shadergen: '%s' needs a value\n", arg);
                return false;
            }
            *slot = argv[++i];
        }
    }
    return a->source && a->out;
}

int main(int argc, char **argv) {
    sg_args args;
    if (!parse_args(argc, argv, &args)) return usage("missing or bad arguments");
    cacao_key_subset subset;
    if (!cacaoi_key_subset_parse(args.qualities, args.downsample, args.precision, &subset)) {
        fprintf(stderr, "shadergen: bad subset: qualities '%s', downsample '%s', precision '%s'\n",
                args.qualities, args.downsample, args.precision);
        return 2;
    }
    char subset_name[256];
    snprintf(subset_name, sizeof subset_name, "%s|%s|%s", args.qualities, args.downsample, args.precision);
    bool full = strcmp(args.qualities, "all") == 0 && strcmp(args.downsample, "ON") == 0 &&
                strcmp(args.precision, "all") == 0;

    sg_sources sources;
    if (!sg_load_sources(args.source, &sources)) return 1;

    size_t total = cacaoi_key_list(NULL, 0);
    cacao_key *keys = calloc(total, sizeof *keys);
    sg_module *modules = calloc(total, sizeof *modules);
    if (!keys || !modules) return 1;
    cacaoi_key_list(keys, total);

    glslang_initialize_process();
    size_t count = 0, words_before = 0;
    int failures = 0;
    for (size_t i = 0; i < total; ++i) {
        if (!cacaoi_key_in_subset(&keys[i], &subset)) continue;
        sg_module *m = &modules[count];
        m->key = keys[i];
        cacaoi_key_name(&keys[i], m->name, sizeof m->name);
        char *text = sg_specialise(&sources, &keys[i]);
        bool ok = text && sg_compile(text, m->name, &args.options, &m->words, &m->word_count) &&
                  sg_validate(m->words, m->word_count, m->name) && sg_reflect(m) && sg_check_row(m);
        free(text);
        if (!ok) {
            ++failures;
            continue;
        }
        words_before += m->word_count;
        ++count;
    }
    glslang_finalize_process();
    if (failures) {
        fprintf(stderr, "shadergen: %d permutation(s) failed; nothing written\n", failures);
        return 1;
    }
    uint32_t unique = sg_dedup(modules, count);
    size_t words_after = 0;
    for (size_t i = 0; i < count; ++i)
        if (modules[i].dedup_of == i) words_after += modules[i].word_count;
    if (!sg_emit(args.out, modules, count, full ? "all" : subset_name)) return 1;
    printf("shadergen: %zu permutations compiled (of %zu in the key space), %u unique modules after "
           "dedup (%zu removed); SPIR-V %zu bytes before dedup, %zu after; %s, %s%s\n",
           count, total, unique, count - unique, words_before * 4, words_after * 4,
           sg_glslang_version(), sg_spirv_tools_version(),
           args.options.optimize ? ", optimized for size" : ", not optimized");
    for (size_t i = 0; i < count; ++i) free(modules[i].words);
    free(modules);
    free(keys);
    sg_free_sources(&sources);
    return 0;
}
