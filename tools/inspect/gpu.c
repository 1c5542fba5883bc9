/* gpu.c - `cacao-inspect gpu` (see gpu.h): compiles the permutations of configurations on a device
 * whose driver reports pipeline statistics (VK_KHR_pipeline_executable_properties; RADV's null
 * device compiles with ACO for an AMD GPU that is not there), prints them, and estimates each
 * configuration's frame cost per stage from them (gpu_model.h), beside AMD's where --amd gives the
 * statistics of AMD's pipelines on the same compiler.
 *
 * Pipelines come from the runtime (cacao_context_create_pipelines with CAPTURE_STATISTICS): the
 * same SPIR-V, layouts and flags a frame uses. Every flag and the --amd file are checked before
 * the device is opened; the JSON is written only after everything was compiled. */
#include "gpu.h"

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cacao.h"
#include "cacao_policy.h"
#include "cacao_table.h"
#include "gpu_model.h"
#include "image_io.h"
#include "sweep.h"
#include "text_file.h"
#include "vkdev.h"

#define GPU_ERR 1024
#define GPU_DEFAULT_WIDTH 1920
#define GPU_DEFAULT_HEIGHT 1080

static const cacao_table *const table = &cacaoi_embedded_table;

/* One line "cacao-inspect: gpu: ..." on stderr; returns false. */
#define complain(...) cacao_error_line("cacao-inspect: gpu: ", __VA_ARGS__)

/* ---- Flags ---------------------------------------------------------------------------------- */

typedef struct gpu_options {
    const char *device, *json_path, *amd_path;
    char configs[4096]; /* the --config lists joined by commas; "" when none */
    bool all, no_spills, help;
    bool normals_from_depth;
    cacao_shader_forms forms; /* --shader-forms; DEFAULT: as a context on the device chooses */
    uint32_t width, height;
} gpu_options;

void inspect_gpu_usage(FILE *out) {
    fputs("       cacao-inspect gpu --config NAME[,NAME...] | --all [--size WxH] [--amd FILE] [--json FILE]\n"
          "                         [--device N|NAME] [--normals depth|input] [--shader-forms cpu|gpu]\n"
          "                         [--no-spills]\n"
          "                         (compiles on a device reporting pipeline statistics, e.g. RADV's null\n"
          "                         device: registers, spills, occupancy, cycles; estimated frame cost per stage)\n",
          out);
}

static const char *const help_text =
    "usage: cacao-inspect gpu --config NAME[,NAME...] | --all [options]\n"
    "Compiles permutations on a Vulkan device whose driver reports pipeline statistics\n"
    "(VK_KHR_pipeline_executable_properties) and prints per permutation VGPRs, SGPRs, spilled registers,\n"
    "scratch and LDS bytes, occupancy (subgroups per SIMD), instructions, and the compiler's latency and\n"
    "inverse throughput (cycles per wave64); then per configuration its estimated frame cost per stage:\n"
    "workgroups x wave64s per workgroup x inverse throughput, summed (a compiler's estimate, not a timing;\n"
    "the tile fill and clear steps are left out; indirect steps count their largest grid). docs/gpu.md explains it.\n"
    "  --config LIST     configurations by name or glob, comma-separated, repeatable (names as\n"
    "                    `cacao-bench --list-configs --sweep full` prints them, e.g. high_native)\n"
    "  --all             measure every embedded permutation, each read once (configurations whose keys\n"
    "                    are all measured are not compiled); the frame costs are then those of --config,\n"
    "                    or of the default sweep\n"
    "  --size WxH        frame size of the estimate (default 1920x1080)\n"
    "  --amd FILE        the JSON lines `amd_cacao_pipelines` printed on the same device family: adds AMD\n"
    "                    FidelityFX CACAO v1.2's estimate per stage and cacao/AMD (CACAO estimator only)\n"
    "  --json FILE       everything as JSON\n"
    "  --device N|NAME   the device (default: the first offering the extension), e.g. with\n"
    "                    RADV_FORCE_FAMILY=navi21 VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/radeon_icd.x86_64.json\n"
    "  --normals depth|input  normals of configurations whose name does not say (_gennormals): from\n"
    "                    depth (default, AMD's reference setting) or from an input normal buffer; AMD's\n"
    "                    estimate uses the same\n"
    "  --shader-forms cpu|gpu  the blur, apply, prepare and generate forms to compile (default:\n"
    "                    those a context on the device runs: cpu on a CPU device, gpu on others)\n"
    "  --no-spills       exit 1 naming every permutation with scratch or spilled registers\n";

static bool parse_size(const char *text, uint32_t *w, uint32_t *h) {
    char tail;
    return text && sscanf(text, "%ux%u%c", w, h, &tail) == 2 && *w >= 1 && *h >= 1 && *w <= CACAO_MAX_SIZE &&
           *h <= CACAO_MAX_SIZE;
}

static bool parse_options(int argc, char **argv, gpu_options *o) {
    *o = (gpu_options){.normals_from_depth = true, .width = GPU_DEFAULT_WIDTH, .height = GPU_DEFAULT_HEIGHT};
    for (int i = 0; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        const bool takes_value = strcmp(a, "--device") == 0 || strcmp(a, "--json") == 0 || strcmp(a, "--amd") == 0 ||
                                 strcmp(a, "--config") == 0 || strcmp(a, "--size") == 0 || strcmp(a, "--normals") == 0 ||
                                 strcmp(a, "--shader-forms") == 0;
        if (takes_value && (!v || !v[0])) return complain("%s: needs a value", a);
        if (takes_value) ++i;
        if (strcmp(a, "--device") == 0)
            o->device = v;
        else if (strcmp(a, "--json") == 0)
            o->json_path = v;
        else if (strcmp(a, "--amd") == 0)
            o->amd_path = v;
        else if (strcmp(a, "--config") == 0) {
            const size_t len = strlen(o->configs);
            if (len + strlen(v) + 2 > sizeof o->configs) return complain("--config: too many names");
            snprintf(o->configs + len, sizeof o->configs - len, "%s%s", len ? "," : "", v);
        } else if (strcmp(a, "--size") == 0) {
            if (!parse_size(v, &o->width, &o->height))
                return complain("--size %s: not WxH with each 1..%d", v, CACAO_MAX_SIZE);
        } else if (strcmp(a, "--normals") == 0) {
            if (strcmp(v, "depth") != 0 && strcmp(v, "input") != 0)
                return complain("--normals %s: use depth or input", v);
            o->normals_from_depth = strcmp(v, "depth") == 0;
        } else if (strcmp(a, "--shader-forms") == 0) {
            if (cacao_shader_forms_from_name(v, &o->forms) != CACAO_SUCCESS)
                return complain("--shader-forms %s: use cpu or gpu", cacao_shown(v).text);
        } else if (strcmp(a, "--all") == 0)
            o->all = true;
        else if (strcmp(a, "--no-spills") == 0)
            o->no_spills = true;
        else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0)
            o->help = true;
        else
            return complain("unknown argument '%s' (see cacao-inspect gpu --help)", a);
    }
    if (!o->help && !o->all && !o->configs[0]) return complain("needs --config NAME or --all (see --help)");
    return true;
}

/* ---- AMD's pipelines (--amd) ------------------------------------------------------------------ */

typedef struct amd_pipeline {
    char entry[64];
    gpu_stats stats;
} amd_pipeline;

typedef struct amd_pipelines {
    amd_pipeline *items;
    uint32_t count;
} amd_pipelines;

/* Reads one JSON line of amd_cacao_pipelines: {"entry": ..., "executable": n, "stats": {...}}. */
static bool parse_amd_line(const char *path, int line, const char *text, amd_pipeline *out, bool *first_executable) {
    cJSON *o = cJSON_Parse(text);
    const char *entry = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(o, "entry"));
    const cJSON *stats = cJSON_GetObjectItemCaseSensitive(o, "stats");
    const cJSON *executable = cJSON_GetObjectItemCaseSensitive(o, "executable");
    bool ok = entry && cJSON_IsObject(stats) && strlen(entry) < sizeof out->entry;
    if (!ok) complain("--amd %s: line %d is not {\"entry\": NAME, \"stats\": {...}}", path, line);
    if (ok) {
        snprintf(out->entry, sizeof out->entry, "%s", entry);
        out->stats = gpu_stats_none();
        *first_executable = !cJSON_IsNumber(executable) || executable->valuedouble == 0;
        const cJSON *s;
        cJSON_ArrayForEach(s, stats) {
            const gpu_stat id = gpu_stat_from_name(s->string);
            if (id < GPU_STAT_COUNT && cJSON_IsNumber(s)) out->stats.value[id] = s->valuedouble;
        }
    }
    cJSON_Delete(o);
    return ok;
}

static bool load_amd(const char *path, amd_pipelines *out) {
    char err[GPU_ERR];
    char *text = cacao_read_whole_file(path, 16u << 20, err, sizeof err);
    if (!text) return complain("--amd %s", err);
    uint32_t lines = 1;
    for (const char *c = text; *c; ++c) lines += *c == '\n';
    out->items = calloc(lines, sizeof *out->items);
    out->count = 0;
    bool ok = out->items != NULL;
    if (!ok) complain("out of memory");
    char *save = NULL;
    int line = 0;
    for (char *l = strtok_r(text, "\n", &save); ok && l; l = strtok_r(NULL, "\n", &save)) {
        ++line;
        if (strspn(l, " \t\r") == strlen(l)) continue;
        bool first = true;
        ok = parse_amd_line(path, line, l, &out->items[out->count], &first);
        if (ok && first) out->count++; /* a compute pipeline has one executable; keep the first */
    }
    free(text);
    if (ok && out->count == 0) ok = complain("--amd %s: no pipeline statistics in it", path);
    return ok;
}

static const amd_pipeline *find_amd(const amd_pipelines *amd, const char *entry) {
    for (uint32_t i = 0; i < amd->count; ++i)
        if (strcmp(amd->items[i].entry, entry) == 0) return &amd->items[i];
    return NULL;
}

/* ---- Compiling and reading statistics -------------------------------------------------------- */

/* What was measured of one embedded permutation. */
typedef struct gpu_measured {
    bool done;
    gpu_stats stats;
    char config[64]; /* the configuration it was compiled in */
} gpu_measured;

typedef struct gpu_session {
    const gpu_options *options;
    vkdev dev;
    char driver[512];
    cacao_context *ctx;
    cacao_shader_forms forms; /* CPU or GPU: what the plans and the context compile */
    bool reuse;               /* the configurations with reuse_unchanged, the horizon estimators' with
                                 temporal_frames (--all sweeps them too) */
    PFN_vkGetPipelineExecutablePropertiesKHR get_executables;
    PFN_vkGetPipelineExecutableStatisticsKHR get_statistics;
    gpu_measured *measured; /* per embedded permutation, in table order */
    uint32_t compiled, skipped;
} gpu_session;

static bool open_device(gpu_session *s) {
    char err[GPU_ERR];
    if (!vkdev_create(&(vkdev_options){.device = s->options->device, .pipeline_statistics = true}, &s->dev, err,
                      sizeof err))
        return complain("%s", err);
    vkdev_driver(&s->dev, s->driver, sizeof s->driver);
    s->get_executables = (PFN_vkGetPipelineExecutablePropertiesKHR)vkGetDeviceProcAddr(
        s->dev.device, "vkGetPipelineExecutablePropertiesKHR");
    s->get_statistics = (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(
        s->dev.device, "vkGetPipelineExecutableStatisticsKHR");
    if (!s->get_executables || !s->get_statistics)
        return complain("'%s' offers no vkGetPipelineExecutable*KHR entry points", s->dev.device_name);
    char error[256] = "";
    const cacao_context_desc desc = {.physical_device = s->dev.physical_device,
                                     .device = s->dev.device,
                                     .error = error,
                                     .error_size = sizeof error,
                                     .shader_float16_enabled = s->dev.fp16,
                                     .pipeline_create_flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR,
                                     .shader_forms = s->options->forms};
    const cacao_result r = cacao_context_create(&desc, &s->ctx);
    if (r != CACAO_SUCCESS)
        return complain("cacao_context_create on '%s': %s: %s", s->dev.device_name, cacao_result_string(r), error);
    s->forms = cacao_context_shader_forms(s->ctx); /* --shader-forms, or the device's: what plans must use */
    return true;
}

static void close_device(gpu_session *s) {
    cacao_context_destroy(s->ctx);
    s->ctx = NULL;
    vkdev_destroy(&s->dev);
}

static double statistic_value(const VkPipelineExecutableStatisticKHR *st) {
    switch (st->format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
        return st->value.b32 ? 1.0 : 0.0;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
        return (double)st->value.i64;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
        return (double)st->value.u64;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
        return st->value.f64;
    default:
        return -1.0;
    }
}

/* The statistics of the pipeline's first executable (a compute pipeline has one). */
static bool read_statistics(const gpu_session *s, VkPipeline pipeline, gpu_stats *out) {
    VkDevice device = s->dev.device;
    const VkPipelineInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = pipeline};
    VkPipelineExecutablePropertiesKHR executable = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR};
    uint32_t executables = 1;
    const VkResult vr = s->get_executables(device, &info, &executables, &executable);
    if ((vr != VK_SUCCESS && vr != VK_INCOMPLETE) || executables == 0) return false;
    *out = gpu_stats_none();
    out->subgroup_size = executable.subgroupSize;
    const VkPipelineExecutableInfoKHR which = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, .pipeline = pipeline, .executableIndex = 0};
    uint32_t count = 0;
    if (s->get_statistics(device, &which, &count, NULL) != VK_SUCCESS) return false;
    VkPipelineExecutableStatisticKHR *stats = calloc(count ? count : 1, sizeof *stats);
    if (!stats) return false;
    for (uint32_t i = 0; i < count; ++i) stats[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
    const bool ok = s->get_statistics(device, &which, &count, stats) == VK_SUCCESS;
    for (uint32_t i = 0; ok && i < count; ++i) {
        const gpu_stat id = gpu_stat_from_name(stats[i].name);
        if (id < GPU_STAT_COUNT) out->value[id] = statistic_value(&stats[i]);
    }
    free(stats);
    return ok;
}

static uint32_t permutation_index(const cacao_plan_step *step) {
    const cacao_key key = cacaoi_plan_step_key(step);
    const cacao_permutation *p = cacaoi_table_find(table, &key);
    return p ? (uint32_t)(p - table->permutations) : UINT32_MAX;
}

/* The settings a configuration compiles with: its own fields, normals from depth where its name
 * asks for reconstruction or normals_from_depth is set, and fp32 where fp16 was asked of a device
 * without shaderFloat16 (the runtime's documented fallback; *fell_back says so). */
static cacao_settings config_settings(const gpu_session *s, const sweep_config *c, bool normals_from_depth,
                                      bool *fell_back) {
    cacao_settings set = sweep_settings(c, (cacao_settings){.generate_normals = normals_from_depth,
                                                            .shader_forms = s->forms,
                                                            .reuse_unchanged = s->reuse});
    if (set.estimator != CACAO_ESTIMATOR_CACAO) { /* their second sweep: temporal accumulation instead */
        set.reuse_unchanged = false;
        set.temporal_frames = s->reuse ? 8 : 0;
    }
    *fell_back = set.precision == CACAO_PRECISION_FP16 && !s->dev.fp16 && set.estimator == CACAO_ESTIMATOR_CACAO;
    if (*fell_back) set.precision = CACAO_PRECISION_FP32;
    return set;
}

/* Compiles the configuration's pipelines unless every key it dispatches was measured, and reads
 * the statistics of those that were not. A configuration with a key this build does not embed is
 * skipped when `required` is false (--all), an error otherwise. */
static bool measure_config(gpu_session *s, const sweep_config *c, bool normals_from_depth, bool required) {
    bool fell_back;
    const cacao_settings set = config_settings(s, c, normals_from_depth, &fell_back);
    cacao_plan plan;
    char err[GPU_ERR];
    if (cacao_plan_build(&set, 64, 64, &plan, err, sizeof err) != CACAO_SUCCESS)
        return complain("%s: %s", c->name, err);
    bool wanted = false;
    for (uint32_t i = 0; i < plan.step_count; ++i) {
        if (plan.steps[i].clear) continue; /* a transfer: no pipeline */
        const uint32_t p = permutation_index(&plan.steps[i]);
        if (p == UINT32_MAX && !required) return true;
        if (p == UINT32_MAX)
            return complain("%s: permutation %s is not embedded in this build", c->name, plan.steps[i].key_name);
        wanted |= !s->measured[p].done;
    }
    if (!wanted) {
        s->skipped++;
        return true;
    }
    cacao_result r = cacao_context_set_settings(s->ctx, &set);
    if (r == CACAO_SUCCESS) r = cacao_context_create_pipelines(s->ctx, NULL);
    if (r != CACAO_SUCCESS)
        return complain("%s: creating its pipelines on '%s' failed: %s: %s", c->name, s->dev.device_name,
                        cacao_result_string(r), cacao_context_last_error(s->ctx));
    s->compiled++;
    for (uint32_t i = 0; i < plan.step_count; ++i) {
        if (plan.steps[i].clear) continue;
        gpu_measured *m = &s->measured[permutation_index(&plan.steps[i])];
        if (m->done) continue;
        const VkPipeline pipeline = cacao_context_pipeline(s->ctx, i);
        if (!pipeline || !read_statistics(s, pipeline, &m->stats))
            return complain("%s: no statistics for %s on '%s'", c->name, plan.steps[i].key_name, s->dev.device_name);
        m->done = true;
        snprintf(m->config, sizeof m->config, "%.*s", (int)sizeof m->config - 1, c->name); /* names fit: sweep.h */
    }
    return true;
}

/* ---- The estimate per configuration ------------------------------------------------------------ */

typedef struct gpu_step_estimate {
    const char *name; /* key name or AMD entry point */
    gpu_stage stage;  /* GPU_STAGE_LEFT_OUT: not counted */
    uint32_t groups[3], dispatches, threads;
    bool indirect;
    double inverse_throughput, cycles; /* cycles < 0: unknown */
} gpu_step_estimate;

typedef struct gpu_estimate {
    uint32_t step_count;
    gpu_step_estimate steps[GPU_AMD_MAX_STEPS > CACAO_PLAN_MAX_STEPS ? GPU_AMD_MAX_STEPS : CACAO_PLAN_MAX_STEPS];
    bool has_stage[GPU_STAGE_COUNT];
    double stage[GPU_STAGE_COUNT], total; /* negative: some step's cost is unknown */
} gpu_estimate;

typedef struct gpu_config_cost {
    const sweep_config *config;
    cacao_settings settings;
    bool fell_back;
    cacao_plan plan;
    gpu_estimate cacao;
    bool has_amd;
    gpu_estimate amd;
} gpu_config_cost;

static void sum_stages(gpu_estimate *e) {
    for (int g = 0; g < GPU_STAGE_COUNT; ++g) e->stage[g] = 0;
    e->total = 0;
    for (uint32_t i = 0; i < e->step_count; ++i) {
        const gpu_step_estimate *st = &e->steps[i];
        if (st->stage == GPU_STAGE_LEFT_OUT) continue;
        e->has_stage[st->stage] = true;
        if (st->cycles < 0 || e->stage[st->stage] < 0)
            e->stage[st->stage] = -1;
        else
            e->stage[st->stage] += st->cycles;
        e->total = st->cycles < 0 || e->total < 0 ? -1 : e->total + st->cycles;
    }
}

static bool estimate_cacao(const gpu_session *s, gpu_config_cost *cc) {
    gpu_estimate *e = &cc->cacao;
    e->step_count = cc->plan.step_count;
    uint32_t extra = 0; /* the classification groups of a downsampled prepare_gpu: a step of their own */
    for (uint32_t i = 0; i < cc->plan.step_count; ++i) {
        const cacao_plan_step *step = &cc->plan.steps[i];
        gpu_step_estimate *st = &e->steps[i];
        if (step->clear) { /* a transfer, left out like the tile fill: no shader to weigh */
            *st = (gpu_step_estimate){.name = step->key_name, .stage = GPU_STAGE_LEFT_OUT};
            continue;
        }
        const uint32_t p = permutation_index(step);
        gpu_stage stage;
        if (!gpu_stage_of_key(step->key_name, &stage))
            return complain("%s: no stage for %s (tools/inspect/gpu_model.c, key_stages)", cc->config->name,
                            step->key_name);
        if (p == UINT32_MAX || !s->measured[p].done)
            return complain("%s: %s was not measured", cc->config->name, step->key_name);
        const gpu_stats *stats = &s->measured[p].stats;
        const uint32_t *wg = table->permutations[p].workgroup_size;
        *st = (gpu_step_estimate){.name = step->key_name,
                                  .stage = stage,
                                  .groups = {step->dispatch[0], step->dispatch[1], step->dispatch[2]},
                                  .dispatches = 1,
                                  .threads = wg[0] * wg[1] * wg[2],
                                  /* a list's entry check, or the GPU forms' class check: both a
                                     workgroup-uniform branch around the body */
                                  .indirect = step->list != 0 || cacaoi_skips_by_class(step->key[0], step->key[1]) ||
                                              cacaoi_reads_classes(step->key[0], step->key[1]),
                                  .inverse_throughput = stats->value[GPU_STAT_INVERSE_THROUGHPUT]};
        /* A step dispatched from a tile list starts with the group's entry check (tiles.glsl,
         * group_of: the groups past the last entry return). ACO weighs the body under that
         * workgroup-uniform branch as run half the time; over the list's entries it always runs:
         * the body's full weight is twice what ACO reports (horizon_main.gtao measured 7727
         * cycles per wave as a direct dispatch and 3863 from the list, the same code otherwise). */
        if (st->indirect && st->inverse_throughput > 0) st->inverse_throughput *= 2.0;
        /* The horizon estimators' slice loop and its step loop run to the frame's budget, a
         * runtime value ACO cannot see: it weighs a loop body as run 8 times and a body nested
         * in it 32 times, i.e. 8 slices x 4 steps per side. Weighed here by the real count:
         * x (slices x steps) / 32. This scales the per-pixel and per-slice setup with the step
         * body, which dominates the figure (the step body is 2 depth reads and the sector or
         * horizon update); at LOWEST's 4 iterations the setup's share makes the weighed figure
         * an underestimate. */
        if (stage == GPU_STAGE_HORIZON_MAIN && st->inverse_throughput > 0)
            st->inverse_throughput *= (double)(cc->plan.settings.horizon_slices * cc->plan.settings.horizon_steps) / 32.0;
        st->cycles = gpu_step_cost(st->groups, 1, st->threads, st->inverse_throughput);
        /* The GPU form of the fused prepare downsampled classifies the tiles in groups of its own
         * (its dispatch's z 0: classify_from_depth, the function classify_gpu runs). ACO weighs
         * the shader's two workgroup-uniform sides, so the step's figure holds both; the
         * classification's share is weighed as classify_gpu.downsampled's pipeline over the same
         * groups and counted in the classify stage, where the classification was before it shared
         * the prepare's dispatch (and where AMD has nothing). */
        const cacao_key cls_key = {CACAO_PASS_CLASSIFY_GPU, 0, 1, 0, 0};
        const cacao_permutation *cls = cacaoi_table_find(table, &cls_key);
        const uint32_t c = cls ? (uint32_t)(cls - table->permutations) : UINT32_MAX;
        if (step->key[0] == CACAO_PASS_PREPARE_GPU && step->key[2] && step->dispatch[2] == 2 && c != UINT32_MAX &&
            s->measured[c].done && st->cycles >= 0 && e->step_count + extra < sizeof e->steps / sizeof e->steps[0]) {
            const uint32_t *cwg = cls->workgroup_size;
            gpu_step_estimate *x = &e->steps[cc->plan.step_count + extra++];
            *x = (gpu_step_estimate){.name = "classify_gpu.downsampled (prepare_gpu's groups z 0)",
                                     .stage = GPU_STAGE_CLASSIFY,
                                     .groups = {step->dispatch[0], step->dispatch[1], 1},
                                     .dispatches = 1,
                                     .threads = cwg[0] * cwg[1] * cwg[2],
                                     .inverse_throughput = s->measured[c].stats.value[GPU_STAT_INVERSE_THROUGHPUT]};
            x->cycles = gpu_step_cost(x->groups, 1, x->threads, x->inverse_throughput);
            if (x->cycles > st->cycles) x->cycles = st->cycles;
            st->cycles -= x->cycles;
        }
    }
    e->step_count += extra;
    sum_stages(e);
    return true;
}

static bool estimate_amd(const gpu_session *s, const amd_pipelines *amd, gpu_config_cost *cc) {
    static gpu_amd_step steps[GPU_AMD_MAX_STEPS];
    const cacao_settings *set = &cc->settings;
    const int blur = set->blur_pass_count == CACAO_BLUR_NONE ? 0 : set->blur_pass_count;
    gpu_estimate *e = &cc->amd;
    e->step_count = gpu_amd_steps(set->quality, set->downsample, blur, set->generate_normals, s->options->width,
                                  s->options->height, steps);
    for (uint32_t i = 0; i < e->step_count; ++i) {
        const amd_pipeline *p = find_amd(amd, steps[i].entry);
        if (!p) return complain("--amd %s: no statistics for %s", s->options->amd_path, steps[i].entry);
        gpu_step_estimate *st = &e->steps[i];
        *st = (gpu_step_estimate){.name = p->entry,
                                  .stage = steps[i].stage,
                                  .groups = {steps[i].groups[0], steps[i].groups[1], steps[i].groups[2]},
                                  .dispatches = steps[i].dispatches,
                                  .threads = steps[i].threads,
                                  .inverse_throughput = p->stats.value[GPU_STAT_INVERSE_THROUGHPUT]};
        st->cycles = gpu_step_cost(st->groups, st->dispatches, st->threads, st->inverse_throughput);
    }
    sum_stages(e);
    cc->has_amd = true;
    return true;
}

static bool estimate_config(const gpu_session *s, const amd_pipelines *amd, const sweep_config *c,
                            gpu_config_cost *cc) {
    *cc = (gpu_config_cost){.config = c};
    cc->settings = config_settings(s, c, s->options->normals_from_depth, &cc->fell_back);
    char err[GPU_ERR];
    if (cacao_plan_build(&cc->settings, s->options->width, s->options->height, &cc->plan, err, sizeof err) !=
        CACAO_SUCCESS)
        return complain("%s: %s", c->name, err);
    cc->settings = cc->plan.settings;
    if (!estimate_cacao(s, cc)) return false;
    return !amd || c->estimator != CACAO_ESTIMATOR_CACAO || estimate_amd(s, amd, cc);
}

/* ---- Text ---------------------------------------------------------------------------------- */

#define MEGA 1e6

static void print_value(double v, int width, int decimals) {
    if (v < 0)
        printf(" %*s", width, "-");
    else
        printf(" %*.*f", width, decimals, v);
}

/* A permutation of the forms this run compiles (the other forms' a context here never runs). */
static bool of_these_forms(const gpu_session *s, uint32_t p) {
    return cacaoi_key_in_forms(&table->permutations[p].key, s->forms == CACAO_SHADER_FORMS_GPU);
}

static void print_permutations(const gpu_session *s) {
    uint32_t measured = 0, of_forms = 0;
    for (uint32_t p = 0; p < table->permutation_count; ++p) {
        measured += s->measured[p].done;
        of_forms += of_these_forms(s, p);
    }
    const bool gpu = s->forms == CACAO_SHADER_FORMS_GPU;
    printf("device: %s (%s), shaderFloat16 %s, %s shader forms\n", s->dev.device_name, s->driver,
           s->dev.fp16 ? "on" : "off", cacao_shader_forms_name(s->forms));
    printf("%u of %u embedded permutations measured, those of the %s forms (%u configurations compiled, %u "
           "skipped: their keys were measured already; the %u of the %s forms: --shader-forms %s)\n\n",
           measured, of_forms, cacao_shader_forms_name(s->forms), s->compiled, s->skipped,
           table->permutation_count - of_forms, gpu ? "cpu" : "gpu", gpu ? "cpu" : "gpu");
    printf("%-34s %4s %5s", "key", "wave", "wg");
    for (int k = 0; k < GPU_STAT_COUNT; ++k) printf(" %9s", gpu_stat_columns[k]);
    printf("\n");
    for (uint32_t p = 0; p < table->permutation_count; ++p) {
        const gpu_measured *m = &s->measured[p];
        if (!m->done) continue;
        const cacao_permutation *perm = &table->permutations[p];
        char wg[16];
        snprintf(wg, sizeof wg, "%ux%u", perm->workgroup_size[0], perm->workgroup_size[1]);
        printf("%-34s %4u %5s", perm->name, m->stats.subgroup_size, wg);
        for (int k = 0; k < GPU_STAT_COUNT; ++k) print_value(m->stats.value[k], 9, 0);
        printf("\n");
    }
    int spills = 0;
    for (uint32_t p = 0; p < table->permutation_count; ++p) {
        const gpu_measured *m = &s->measured[p];
        if (!m->done || !gpu_stats_spill(&m->stats)) continue;
        if (!spills++) printf("\npermutations with scratch or spilled registers:\n");
        printf("  %-34s scratch %.0f bytes, spilled VGPRs %.0f, spilled SGPRs %.0f (VGPRs %.0f)\n",
               table->permutations[p].name, m->stats.value[GPU_STAT_SCRATCH_BYTES],
               m->stats.value[GPU_STAT_SPILLED_VGPRS], m->stats.value[GPU_STAT_SPILLED_SGPRS],
               m->stats.value[GPU_STAT_VGPRS]);
    }
    if (!spills) printf("\nno permutation uses scratch or spills registers\n");
    for (uint32_t p = 0; p < table->permutation_count; ++p)
        if (!s->measured[p].done && s->options->all && of_these_forms(s, p))
            printf("not measured: %s (no configuration of the sweep dispatches it on this device)\n",
                   table->permutations[p].name);
}

static void print_ratio(double a, double b) {
    if (a < 0 || b <= 0)
        printf(" %9s", "-");
    else
        printf(" %9.2f", a / b);
}

static void print_config(const gpu_session *s, const gpu_config_cost *cc) {
    printf("\n%s: %ux%u, normals from %s, %s%s; estimated Mcycles (wave64s x inverse throughput / 1e6)\n",
           cc->config->name, s->options->width, s->options->height, cc->settings.generate_normals ? "depth" : "input",
           cacao_precision_name(cc->settings.precision),
           cc->fell_back ? " (fp16 asked: the device lacks shaderFloat16)" : "");
    printf("  %-18s %10s %10s %9s\n", "stage", "cacao", cc->has_amd ? "AMD" : "", cc->has_amd ? "cacao/AMD" : "");
    for (int g = 0; g < GPU_STAGE_COUNT; ++g) {
        if (!cc->cacao.has_stage[g] && !(cc->has_amd && cc->amd.has_stage[g])) continue;
        printf("  %-18s", gpu_stage_names[g]);
        print_value(cc->cacao.has_stage[g] ? cc->cacao.stage[g] / MEGA : -1, 10, 3);
        if (cc->has_amd) {
            print_value(cc->amd.has_stage[g] ? cc->amd.stage[g] / MEGA : -1, 10, 3);
            print_ratio(cc->cacao.has_stage[g] ? cc->cacao.stage[g] : -1, cc->amd.has_stage[g] ? cc->amd.stage[g] : 0);
        }
        printf("\n");
    }
    printf("  %-18s", "total");
    print_value(cc->cacao.total < 0 ? -1 : cc->cacao.total / MEGA, 10, 3);
    if (cc->has_amd) {
        print_value(cc->amd.total < 0 ? -1 : cc->amd.total / MEGA, 10, 3);
        print_ratio(cc->cacao.total, cc->amd.total);
    }
    printf("\n");
}

static void print_summary(const gpu_config_cost *costs, uint32_t count, bool amd) {
    printf("\nsummary: estimated Mcycles per frame (tile fill steps left out)\n");
    printf("  %-42s %10s %10s %9s\n", "configuration", "cacao", amd ? "AMD" : "", amd ? "cacao/AMD" : "");
    for (uint32_t i = 0; i < count; ++i) {
        const gpu_config_cost *cc = &costs[i];
        printf("  %-42s", cc->config->name);
        print_value(cc->cacao.total < 0 ? -1 : cc->cacao.total / MEGA, 10, 3);
        if (amd) {
            print_value(cc->has_amd && cc->amd.total >= 0 ? cc->amd.total / MEGA : -1, 10, 3);
            print_ratio(cc->cacao.total, cc->has_amd ? cc->amd.total : 0);
        }
        printf("\n");
    }
}

/* ---- JSON ---------------------------------------------------------------------------------- */

static void add_value(cJSON *o, const char *name, double v) {
    if (v < 0)
        cJSON_AddNullToObject(o, name);
    else
        cJSON_AddNumberToObject(o, name, v);
}

static cJSON *uint_array(const uint32_t *v, int n) {
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; ++i) cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

static cJSON *stats_json(const gpu_stats *stats) {
    cJSON *o = cJSON_CreateObject();
    for (int k = 0; k < GPU_STAT_COUNT; ++k) add_value(o, gpu_stat_names[k], stats->value[k]);
    return o;
}

static cJSON *estimate_json(const gpu_estimate *e) {
    cJSON *o = cJSON_CreateObject(), *steps = cJSON_AddArrayToObject(o, "steps");
    for (uint32_t i = 0; i < e->step_count; ++i) {
        const gpu_step_estimate *st = &e->steps[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", st->name);
        cJSON_AddStringToObject(j, "stage", st->stage == GPU_STAGE_LEFT_OUT ? "left out" : gpu_stage_names[st->stage]);
        cJSON_AddItemToObject(j, "groups", uint_array(st->groups, 3));
        cJSON_AddNumberToObject(j, "dispatches", st->dispatches);
        cJSON_AddBoolToObject(j, "indirect", st->indirect);
        cJSON_AddNumberToObject(j, "threads_per_group", st->threads);
        add_value(j, "inverse_throughput", st->inverse_throughput);
        add_value(j, "cycles", st->cycles);
        cJSON_AddItemToArray(steps, j);
    }
    cJSON *stages = cJSON_AddObjectToObject(o, "stages");
    for (int g = 0; g < GPU_STAGE_COUNT; ++g)
        if (e->has_stage[g]) add_value(stages, gpu_stage_names[g], e->stage[g]);
    add_value(o, "total_cycles", e->total);
    return o;
}

static cJSON *config_json(const gpu_config_cost *cc) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", cc->config->name);
    cJSON_AddStringToObject(o, "estimator", cacao_estimator_name(cc->settings.estimator));
    cJSON_AddStringToObject(o, "quality", cacao_quality_name(cc->settings.quality));
    cJSON_AddBoolToObject(o, "downsampled", cc->settings.downsample);
    cJSON_AddNumberToObject(o, "blur",
                            cc->settings.blur_pass_count == CACAO_BLUR_NONE ? 0 : cc->settings.blur_pass_count);
    cJSON_AddStringToObject(o, "precision", cacao_precision_name(cc->settings.precision));
    cJSON_AddBoolToObject(o, "fp16_fell_back", cc->fell_back);
    cJSON_AddStringToObject(o, "normals", cc->settings.generate_normals ? "depth" : "input");
    if (cc->plan.settings.estimator != CACAO_ESTIMATOR_CACAO) { /* the budget the main pass is weighed by */
        cJSON_AddNumberToObject(o, "horizon_slices", cc->plan.settings.horizon_slices);
        cJSON_AddNumberToObject(o, "horizon_steps", cc->plan.settings.horizon_steps);
    }
    cJSON_AddItemToObject(o, "cacao", estimate_json(&cc->cacao));
    if (cc->has_amd) cJSON_AddItemToObject(o, "amd", estimate_json(&cc->amd));
    return o;
}

static bool write_json(const gpu_session *s, const gpu_config_cost *costs, uint32_t count) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "tool", "cacao-inspect gpu");
    cJSON_AddStringToObject(root, "estimate",
                            "per step: workgroups x threads per group / 64 x the compiler's Inverse Throughput "
                            "(cycles per wave64); tile fill steps left out; indirect steps at their largest grid; a "
                            "compiler's estimate, not a timing");
    cJSON_AddStringToObject(root, "device", s->dev.device_name);
    cJSON_AddStringToObject(root, "driver", s->driver);
    cJSON_AddBoolToObject(root, "shader_float16", s->dev.fp16);
    cJSON_AddItemToObject(root, "size", uint_array((const uint32_t[]){s->options->width, s->options->height}, 2));
    cJSON_AddStringToObject(root, "subset", table->subset);
    cJSON *perms = cJSON_AddArrayToObject(root, "permutations"),
          *missing = cJSON_AddArrayToObject(root, "not_measured");
    for (uint32_t p = 0; p < table->permutation_count; ++p) {
        const gpu_measured *m = &s->measured[p];
        const cacao_permutation *perm = &table->permutations[p];
        if (!m->done) {
            cJSON_AddItemToArray(missing, cJSON_CreateString(perm->name));
            continue;
        }
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "key", perm->name);
        cJSON_AddStringToObject(j, "pass", cacaoi_pass_name(perm->key.pass));
        cJSON_AddItemToObject(j, "workgroup_size", uint_array(perm->workgroup_size, 3));
        cJSON_AddNumberToObject(j, "subgroup_size", m->stats.subgroup_size);
        cJSON_AddBoolToObject(j, "spills", gpu_stats_spill(&m->stats));
        cJSON_AddStringToObject(j, "compiled_in", m->config);
        cJSON_AddItemToObject(j, "stats", stats_json(&m->stats));
        cJSON_AddItemToArray(perms, j);
    }
    cJSON *configs = cJSON_AddArrayToObject(root, "configurations");
    for (uint32_t i = 0; i < count; ++i) cJSON_AddItemToArray(configs, config_json(&costs[i]));
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp", s->options->json_path);
    FILE *f = text ? fopen(tmp, "w") : NULL;
    bool ok = f && fputs(text, f) >= 0 && fputc('\n', f) != EOF;
    ok = f && fclose(f) == 0 && ok && rename(tmp, s->options->json_path) == 0;
    free(text);
    if (!ok) remove(tmp);
    return ok ? true : complain("--json %s: cannot write it", s->options->json_path);
}

/* ---- The command --------------------------------------------------------------------------- */

static int spill_check(const gpu_session *s) {
    int spills = 0;
    for (uint32_t p = 0; p < table->permutation_count; ++p) {
        const gpu_stats *st = &s->measured[p].stats;
        if (!s->measured[p].done || !gpu_stats_spill(st)) continue;
        ++spills;
        complain("%s spills on %s: scratch %.0f bytes, %.0f VGPRs and %.0f SGPRs spilled", table->permutations[p].name,
                 s->dev.device_name, st->value[GPU_STAT_SCRATCH_BYTES], st->value[GPU_STAT_SPILLED_VGPRS],
                 st->value[GPU_STAT_SPILLED_SGPRS]);
    }
    return spills ? 1 : 0;
}

/* Measures what the options ask, then estimates and reports the configurations. */
static int run(gpu_session *s, const sweep_config *configs, uint32_t config_count, const amd_pipelines *amd) {
    for (uint32_t i = 0; i < config_count; ++i) {
        if (!measure_config(s, &configs[i], s->options->normals_from_depth, true)) return 1;
        /* classify_gpu.downsampled, which weighs a downsampled prepare_gpu's classification groups
         * (estimate_cacao): the configuration with the caller's normals dispatches it */
        bool fell_back;
        const cacao_settings set = config_settings(s, &configs[i], s->options->normals_from_depth, &fell_back);
        sweep_config given = configs[i];
        given.reconstruct_normals = false;
        if (s->forms == CACAO_SHADER_FORMS_GPU && set.estimator == CACAO_ESTIMATOR_CACAO && set.downsample &&
            set.generate_normals && !measure_config(s, &given, false, false))
            return 1;
    }
    if (s->options->all) { /* the full sweep, with normals from an input and (where it differs) from depth */
        static sweep_config sweep[SWEEP_FULL_SIZE];
        const uint32_t n = sweep_full(sweep);
        for (int from_depth = 0; from_depth < 2; ++from_depth)
            for (uint32_t i = 0; i < n; ++i)
                if (!(from_depth && sweep[i].reconstruct_normals) && !measure_config(s, &sweep[i], from_depth, false))
                    return 1;
        /* and with reuse_unchanged (its diff, prefix and reach passes; the other steps are the same),
         * the horizon estimators with temporal accumulation (its resolve pass) */
        s->reuse = true;
        for (int from_depth = 0; from_depth < 2; ++from_depth)
            for (uint32_t i = 0; i < n; ++i)
                if (!(from_depth && sweep[i].reconstruct_normals) && !measure_config(s, &sweep[i], from_depth, false))
                    return 1;
        s->reuse = false;
    }
    gpu_config_cost *costs = calloc(config_count ? config_count : 1, sizeof *costs);
    if (!costs) return !complain("out of memory");
    bool ok = true;
    for (uint32_t i = 0; ok && i < config_count; ++i)
        ok = estimate_config(s, amd->count ? amd : NULL, &configs[i], &costs[i]);
    if (ok) {
        print_permutations(s);
        for (uint32_t i = 0; i < config_count; ++i) print_config(s, &costs[i]);
        print_summary(costs, config_count, amd->count > 0);
        printf("\n(a compiler's estimate, not a timing: see docs/gpu.md for what it leaves out)\n");
    }
    if (ok && s->options->json_path) ok = write_json(s, costs, config_count);
    free(costs);
    if (!ok) return 1;
    return s->options->no_spills ? spill_check(s) : 0;
}

int inspect_gpu(int argc, char **argv) {
    gpu_options o;
    if (!parse_options(argc, argv, &o)) return 1;
    if (o.help) {
        fputs(help_text, stdout);
        return 0;
    }
    static sweep_config configs[SWEEP_FULL_SIZE];
    uint32_t config_count = 0;
    char err[GPU_ERR];
    if (!sweep_select(o.configs[0] ? o.configs : NULL, false, configs, &config_count, err, sizeof err))
        return !complain("--config: %s (see cacao-bench --list-configs --sweep full)", err);
    amd_pipelines amd = {0};
    if (o.amd_path && !load_amd(o.amd_path, &amd)) {
        free(amd.items);
        return 1;
    }
    gpu_session s = {.options = &o, .measured = calloc(table->permutation_count, sizeof(gpu_measured))};
    int rc = 1;
    if (!s.measured)
        complain("out of memory");
    else if (open_device(&s))
        rc = run(&s, configs, config_count, &amd);
    close_device(&s);
    free(s.measured);
    free(amd.items);
    return rc;
}
