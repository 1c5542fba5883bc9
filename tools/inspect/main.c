/* cacao-inspect - see and trust every shader permutation this build embeds.
 *
 *   cacao-inspect list [--pass NAME] [--quality Q] [--json] [--costs BENCH.json]
 *                                                             every permutation, one per line (with
 *                                                             its measured cost from a cacao-bench run)
 *   cacao-inspect show KEY                                    defines, preprocessed GLSL, reflection, SPIR-V
 *   cacao-inspect plan --size WxH [settings flags]            the pass plan cacao_record would walk
 *   cacao-inspect plan --scene DIR [settings flags]           the same for one frame of a scene, run on
 *                                                             the device, with its tiles and the work
 *                                                             each step skipped (also --depth/--camera)
 *   cacao-inspect stats                                       counts, dedup, bytes per pass
 *   cacao-inspect facts                                       the counts and limits the docs state, as JSON
 *   cacao-inspect verify                                      re-validate modules, check plan keys are embedded
 *   cacao-inspect gpu --config NAME | --all [--amd FILE]      a GPU compiler's statistics of the permutations
 *                                                             and configurations' estimated frame cost (gpu.c)
 *
 * Everything comes from the embedded table (generated/), reflection of the modules (SPIRV-Cross)
 * and the runtime's own cacao_plan_build: no second copy of any of that logic. The command line
 * and the --costs JSON are checked first, in inspect_args.c. */
#include <cjson/cJSON.h>
#include <glslang/Include/glslang_c_interface.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cacao.h"
#include "cacao_policy.h"
#include "cacao_shared.h"
#include "gpu.h"
#include "inputs.h"
#include "inspect_args.h"
#include "options.h"
#include "shadergen.h"
#include "text_file.h"

extern const sg_source cacao_inspect_sources[]; /* the shader's source files, entry first (embed.cmake) */
extern const size_t cacao_inspect_source_count;

static const cacao_table *table = &cacaoi_embedded_table;

static int fail(const char *fmt, const char *arg) {
    fprintf(stderr, "cacao-inspect: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n");
    return 1;
}

/* Keys that share a module with permutation i, as "name, name". */
static void dedup_group(uint32_t i, char *out, size_t n) {
    out[0] = '\0';
    size_t len = 0;
    for (uint32_t j = 0; j < table->permutation_count; ++j)
        if (j != i && table->permutations[j].module == table->permutations[i].module && len + 50 < n)
            len += (size_t)snprintf(out + len, n - len, "%s%s", len ? "," : "", table->permutations[j].name);
}

/* What one permutation cost in a cacao-bench run: the median of its per-run median times, and the
 * configurations it served ("a,b", each once, however many). */
typedef struct perm_cost {
    double *ms;
    uint32_t runs;
    char *served;
} perm_cost;

static int compare_doubles(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *v, uint32_t n) {
    qsort(v, n, sizeof *v, compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Adds one run of a permutation; false when out of memory. */
static bool add_cost(perm_cost *c, double ms, const char *config) {
    double *grown = realloc(c->ms, (c->runs + 1) * sizeof *grown);
    if (!grown) return false;
    c->ms = grown;
    c->ms[c->runs++] = ms;
    const size_t len = c->served ? strlen(c->served) : 0, config_len = strlen(config);
    for (const char *at = c->served ? strstr(c->served, config) : NULL; at; at = strstr(at + 1, config))
        if ((at == c->served || at[-1] == ',') && (at[config_len] == ',' || at[config_len] == 0)) return true;
    char *served = realloc(c->served, len + config_len + 2);
    if (!served) return false;
    snprintf(served + len, config_len + 2, "%s%s", len ? "," : "", config);
    c->served = served;
    return true;
}

/* Reads a cacao-bench --json file (checked by inspect_read_costs) into costs[permutation]. */
static int load_costs(const char *path, perm_cost *costs) {
    char err[1024];
    cJSON *root = inspect_read_costs(path, err, sizeof err);
    if (!root) return fail("%s", err);
    const cJSON *r;
    bool ok = true;
    cJSON_ArrayForEach(r, cJSON_GetObjectItemCaseSensitive(root, "results")) {
        const char *config = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(r, "config"));
        const cJSON *p;
        cJSON_ArrayForEach(p, cJSON_GetObjectItemCaseSensitive(r, "passes")) {
            const char *name = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(p, "name"));
            const double ms = cJSON_GetObjectItemCaseSensitive(p, "time_ms")->valuedouble;
            for (uint32_t i = 0; ok && i < table->permutation_count; ++i)
                if (strcmp(table->permutations[i].name, name) == 0) ok = add_cost(&costs[i], ms, config);
        }
    }
    cJSON_Delete(root);
    return ok ? 0 : fail("--costs %s: out of memory", path);
}

static void free_costs(perm_cost *costs) {
    for (uint32_t i = 0; costs && i < table->permutation_count; ++i) {
        free(costs[i].ms);
        free(costs[i].served);
    }
    free(costs);
}

static int cmd_list(const inspect_args *a) {
    const char *pass = a->pass;
    const int quality = a->quality;
    const bool json = a->json;
    perm_cost *costs = a->costs_path ? calloc(table->permutation_count, sizeof *costs) : NULL;
    if (a->costs_path && (!costs || load_costs(a->costs_path, costs) != 0)) {
        free_costs(costs);
        return 1;
    }
    cJSON *array = json ? cJSON_CreateArray() : NULL;
    if (!json && costs) {
        printf("%-34s %9s %5s  %s\n", "key", "median_ms", "runs", "configurations served");
    } else if (!json) {
        printf("%-34s %-8s %-5s %-10s %5s %-8s %9s  %s\n", "key", "entry", "blur", "precision", "wg", "module", "bytes",
               "shares module with");
    }
    for (uint32_t i = 0; i < table->permutation_count; ++i) {
        const cacao_permutation *p = &table->permutations[i];
        if (pass && strcmp(pass, cacaoi_pass_name(p->key.pass)) != 0) continue;
        if (quality >= 0) {
            const cacao_key_subset s = {1u << quality, 3, 3};
            if (!cacaoi_key_in_subset(&p->key, &s)) continue;
        }
        char group[1024], wg[32];
        dedup_group(i, group, sizeof group);
        snprintf(wg, sizeof wg, "%ux%u", p->workgroup_size[0], p->workgroup_size[1]);
        const uint32_t bytes = table->modules[p->module].word_count * 4;
        if (json) {
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "key", p->name);
            cJSON_AddStringToObject(o, "pass", cacaoi_pass_name(p->key.pass));
            cJSON_AddNumberToObject(o, "variant", p->key.variant);
            cJSON_AddBoolToObject(o, "downsampled", p->key.downsampled);
            cJSON_AddNumberToObject(o, "blur_passes", p->key.blur_passes);
            cJSON_AddStringToObject(o, "precision", p->key.fp16 ? "fp16" : "fp32");
            cJSON_AddStringToObject(o, "entry_point", table->entry_point);
            cJSON_AddNumberToObject(o, "spirv_bytes", bytes);
            cJSON_AddNumberToObject(o, "module", p->module);
            cJSON_AddStringToObject(o, "shares_module_with", group);
            cJSON *w = cJSON_AddArrayToObject(o, "workgroup_size");
            for (int k = 0; k < 3; ++k) cJSON_AddItemToArray(w, cJSON_CreateNumber(p->workgroup_size[k]));
            if (costs && costs[i].runs) {
                cJSON *cost = cJSON_AddObjectToObject(o, "cost");
                cJSON_AddNumberToObject(cost, "median_ms", median_of(costs[i].ms, costs[i].runs));
                cJSON_AddNumberToObject(cost, "runs", costs[i].runs);
                cJSON_AddStringToObject(cost, "configurations", costs[i].served);
            }
            cJSON_AddItemToArray(array, o);
        } else if (costs) {
            if (costs[i].runs)
                printf("%-34s %9.3f %5u  %s\n", p->name, median_of(costs[i].ms, costs[i].runs), costs[i].runs,
                       costs[i].served);
            else printf("%-34s %9s %5u  %s\n", p->name, "-", 0u, "(not run by this bench)");
        } else {
            printf("%-34s %-8s %-5u %-10s %5s %-8u %9u  %s\n", p->name, table->entry_point, p->key.blur_passes,
                   p->key.fp16 ? "fp16" : "fp32", wg, p->module, bytes, group[0] ? group : "-");
        }
    }
    if (json) {
        char *text = cJSON_Print(array);
        printf("%s\n", text);
        free(text);
        cJSON_Delete(array);
    }
    free_costs(costs);
    return 0;
}

/* Uniform block members and sizes as SPIRV-Cross reflects them from the module. */
static void print_reflection(const cacao_module *m) {
    static sg_block block;
    if (!sg_uniform_block(m->words, m->word_count, &block)) return;
    printf("uniform block '%s' (binding %u), %zu bytes, std140:\n", block.name, block.binding, block.size);
    for (size_t i = 0; i < block.member_count && i < SG_BLOCK_MAX_MEMBERS; ++i)
        printf("  %4u  %-40s %3u bytes\n", block.members[i].offset, block.members[i].name, block.members[i].size);
}

static int cmd_show(const char *key_name) {
    cacao_key key;
    cacaoi_key_parse(key_name, &key); /* checked by inspect_parse_args */
    const cacao_permutation *p = cacaoi_table_find(table, &key);
    if (!p) return fail("show: '%s' is not embedded in this build", key_name);
    const cacao_module *m = &table->modules[p->module];
    char defines[CACAO_KEY_DEFINES_MAX];
    cacaoi_key_defines(&key, defines, sizeof defines);
    printf("== %s\nSPIR-V: %u bytes (module %u), entry point '%s', workgroup %ux%ux%u\n\n== defines\n%s\n", p->name,
           m->word_count * 4, p->module, table->entry_point, p->workgroup_size[0], p->workgroup_size[1],
           p->workgroup_size[2], defines);
    printf("== descriptor bindings (set 0, from reflection)\n");
    for (int b = 0; b < CACAO_BINDING_COUNT; ++b)
        if (p->bindings[b]) printf("  binding %2d: %s\n", b, cacaoi_descriptor_names[p->bindings[b]]);
    printf("push constants: %u bytes\n", p->push_constant_size);
    print_reflection(m);

    glslang_initialize_process();
    sg_sources sources = {.count = cacao_inspect_source_count};
    for (size_t i = 0; i < sources.count && i < SG_MAX_SOURCES; ++i) sources.files[i] = cacao_inspect_sources[i];
    char *text = sg_specialise(&sources, &key);
    char *pre = text ? sg_preprocess(text, p->name) : NULL;
    glslang_finalize_process();
    printf("\n== preprocessed GLSL\n%s\n", pre ? pre : "(preprocessing failed)");
    free(pre);
    free(text);

    char *dis = sg_disassemble(m->words, m->word_count);
    printf("== SPIR-V disassembly\n%s", dis ? dis : "(disassembly failed)\n");
    free(dis);
    return 0;
}

static double percent(uint32_t part, uint32_t whole) { return whole ? 100.0 * part / whole : 0.0; }

/* The half and non-smart applies' listed step (LOWEST, LOW native, the CPU forms without reuse),
 * which runs after their direct step, and compact's choice between them on a frame with counts c
 * (CACAO_APPLY_LISTS, compact's rule: at most CACAO_APPLY_LIST_ACTIVE_NUM/_DEN of the tiles
 * active; docs/tiles.md "Apply over a list where the frame skips much"). */
static bool listed_apply_step(const cacao_plan_step *st) {
    return st->key[0] == CACAO_PASS_APPLY && (st->key[1] == CACAO_APPLY_NONSMART_LIST || st->key[1] == CACAO_APPLY_HALF_LIST);
}
static bool apply_listed(const cacao_tile_counts *c) {
    return CACAO_APPLY_LISTS((uint64_t)c->active, (uint64_t)c->tiles);
}
static bool has_listed_apply(const cacao_plan *plan) {
    for (uint32_t i = 0; i < plan->step_count; ++i)
        if (listed_apply_step(&plan->steps[i])) return true;
    return false;
}

/* Whether the plan's compact stores the AO 1 of the output's skipped tiles (the horizon
 * estimators' CPU forms; CACAO's where the upsample or smart apply runs over a list). */
static bool compact_fills_output(const cacao_plan *plan, const cacao_tile_counts *c) {
    for (uint32_t i = 0; i < plan->step_count; ++i) {
        const cacao_plan_step *st = &plan->steps[i];
        if ((st->key[0] == CACAO_PASS_COMPACT && st->key[1] == CACAO_COMPACT_HORIZON) ||
            (st->list == CACAO_LIST_PREPARE && plan->settings.estimator == CACAO_ESTIMATOR_CACAO &&
             (!listed_apply_step(st) || apply_listed(c))))
            return true;
    }
    return false;
}

/* Whether the plan's horizon prepare stores the view z of every tile first (normals from depth,
 * the CPU forms: the normals' prepare reads it). */
static bool horizon_z_first(const cacao_plan *plan) {
    for (uint32_t i = 0; i < plan->step_count; ++i)
        if (plan->steps[i].key[0] == CACAO_PASS_HORIZON_PREPARE && plan->steps[i].key[1] == CACAO_HORIZON_NORMALS_DEPTH)
            return true;
    return false;
}

/* What each step of the plan did on the frame whose tile counts are c. */
static void print_skipped_work(const cacao_plan *plan, const cacao_tile_counts *c, bool output_kept) {
    const bool reuse = plan->settings.reuse_unchanged, nothing_changed = reuse && c->changed == 0;
    if (nothing_changed)
        printf("tiles: %u (%ux%u of 8x8 slice texels): classify did not run (nothing changed)\n", c->tiles,
               plan->tiles_x, plan->tiles_y);
    else if (c->quiet)
        printf("tiles: %u (%ux%u of 8x8 slice texels): a quiet frame (no pixel can be occluded), classify did not run\n",
               c->tiles, plan->tiles_x, plan->tiles_y);
    else
        printf("tiles: %u (%ux%u of 8x8 slice texels): %u active (%.1f%%), %u faded (%.1f%%), %u background (%.1f%%)\n",
               c->tiles, plan->tiles_x, plan->tiles_y, c->active, percent(c->active, c->tiles), c->faded,
               percent(c->faded, c->tiles), c->background, percent(c->background, c->tiles));
    if (reuse)
        printf("reuse: %u tiles changed since the last frame (%.1f%%); a change can reach %u (%.1f%%); %u (%.1f%%) keep the "
               "last frame's AO\n", c->changed, percent(c->changed, c->tiles), c->recomputed,
               percent(c->recomputed, c->tiles), c->tiles - c->recomputed, percent(c->tiles - c->recomputed, c->tiles));
    printf("work each step skips on this frame:\n");
    const uint32_t generate_skipped = c->generate_total - c->generate_run, blur_skipped = c->blur_total - c->blur_run;
    for (uint32_t i = 0; i < plan->step_count; ++i) {
        const cacao_plan_step *st = &plan->steps[i];
        printf("  %2u %-34s ", i, st->key_name);
        if (st->key[0] == CACAO_PASS_CLASSIFY && st->key[1] == CACAO_CLASSIFY_QUIET) {
            printf(c->quiet ? "found no pixel that can be occluded: the frame is quiet; wrote AO 1 into every output "
                              "pixel (the frame's one pass)\n"
                            : "found a pixel that can be occluded: the frame is not quiet\n");
            continue;
        }
        if (c->quiet && !(st->clear && st->bindings[0].resource == CACAO_RES_IMPORTANCE)) {
            printf("%s: the frame is quiet, dispatches nothing\n", st->list ? "its list is empty" : "gated");
            continue;
        }
        if (st->list == CACAO_LIST_NORMALS) {
            printf(plan->settings.estimator == CACAO_ESTIMATOR_CACAO
                       ? "transforms the normals of the tiles within two of an active tile (generate's reads)\n"
                   : st->key[1] == CACAO_HORIZON_NORMALS_DEPTH
                       ? "normals from the stored view z, of the tiles within two of an active tile (the "
                         "estimator's and the denoise's reads)\n"
                       : "view z and normals of the tiles within two of an active tile (the estimator's and the "
                         "denoise's reads)\n");
            continue;
        }
        if (st->clear && st->bindings[0].resource == CACAO_RES_IMPORTANCE) {
            printf("clears the importance map to 0; the %u blocks the base pass skips keep it (%.1f%%)\n",
                   c->blocks_total - c->blocks_run, percent(c->blocks_total - c->blocks_run, c->blocks_total));
            continue;
        }
        if (st->clear) {
            const bool view = st->bindings[0].resource == CACAO_RES_VIEW_DEPTH;
            printf(view ? "clears view z and normals; the %u background tiles keep them (%.1f%% of the tiles)\n"
                        : "clears to AO 1; the %u skipped tiles keep it (%.1f%% of the tiles)\n",
                   view ? c->background : generate_skipped, percent(view ? c->background : generate_skipped, c->tiles));
            continue;
        }
        /* the GPU forms of generate and the blur skip the groups the lists leave out themselves */
        const unsigned list = !cacaoi_skips_by_class(st->key[0], st->key[1]) ? st->list
                              : st->key[0] == CACAO_PASS_BLUR_GPU        ? CACAO_LIST_BLUR
                                                                         : CACAO_LIST_GENERATE;
        if (st->list == CACAO_LIST_BLOCKS ||
            (st->key[0] == CACAO_PASS_GENERATE_GPU && st->key[1] == CACAO_GENERATE_Q3_BASE)) {
            printf("runs %u of %u %s, skips %u (%.1f%%: no active tile, %s)\n", c->blocks_run, c->blocks_total,
                   st->list ? "blocks of 2x2 tiles" : "tiles", c->blocks_total - c->blocks_run,
                   percent(c->blocks_total - c->blocks_run, c->blocks_total),
                   st->key[0] == CACAO_PASS_HORIZON_MAIN ? "AO 1" : "importance 0");
            continue;
        }
        switch (list) {
        case CACAO_LIST_GENERATE:
            printf("runs %u of %u tiles, skips %u (%.1f%%)\n", c->generate_run, c->generate_total, generate_skipped,
                   percent(generate_skipped, c->generate_total));
            break;
        case CACAO_LIST_FILL_SLICES:
            if (reuse)
                printf("writes AO 1 into the skipped tiles a change reaches (at most %u)\n", c->recomputed);
            else
                printf("writes AO 1 into the %u of the %u skipped tiles that a later pass reads (%.1f%% of the tiles)\n",
                       c->fill_run, generate_skipped, percent(c->fill_run, c->generate_total));
            break;
        case CACAO_LIST_PREPARE:
            if (listed_apply_step(st)) {
                if (apply_listed(c))
                    printf("runs over the tiles whose quads touch one of the %u needed tiles (at most %d/%d of the tiles "
                           "active: compact listed them; skips the %u others, %.1f%% of the tiles)\n",
                           c->generate_run, CACAO_APPLY_LIST_ACTIVE_NUM, CACAO_APPLY_LIST_ACTIVE_DEN, generate_skipped,
                           percent(generate_skipped, c->generate_total));
                else
                    printf("its list is empty: more than %d/%d of the tiles are active, the apply before ran over "
                           "everything\n",
                           CACAO_APPLY_LIST_ACTIVE_NUM, CACAO_APPLY_LIST_ACTIVE_DEN);
                break;
            }
            if (plan->settings.estimator == CACAO_ESTIMATOR_CACAO) {
                printf(plan->settings.downsample ? "runs over the %u needed tiles, skips %u (%.1f%%)\n"
                                                 : "runs over the blocks of 2x2 tiles holding one of the %u needed tiles "
                                                   "(skips the blocks of the %u others, %.1f%% of the tiles)\n",
                       c->generate_run, generate_skipped, percent(generate_skipped, c->generate_total));
                break;
            }
            if (horizon_z_first(plan))
                printf("view z of the tiles not all background (the normals' prepare reads it), skips the %u "
                       "background ones (%.1f%%)\n",
                       c->background, percent(c->background, c->tiles));
            else
                printf("view z alone of the other tiles not all background, skips the %u background ones (%.1f%%)\n",
                       c->background, percent(c->background, c->tiles));
            break;
        case CACAO_LIST_BLUR:
            printf("runs %u of %u groups, skips %u (%.1f%%)\n", c->blur_run, c->blur_total, blur_skipped,
                   percent(blur_skipped, c->blur_total));
            break;
        default:
            if (st->key[0] == CACAO_PASS_COMPACT && compact_fills_output(plan, c))
                printf("runs over everything; writes AO 1 into the output of the %u skipped tiles (%.1f%% of the "
                       "tiles)\n",
                       generate_skipped, percent(generate_skipped, c->generate_total));
            else if (st->key[0] == CACAO_PASS_REUSE)
                printf("reuse's bookkeeping (full frames record only the diff, or nothing)\n");
            else if (st->gate && nothing_changed && (i + 1 < plan->step_count || output_kept))
                printf("gated: nothing changed, dispatches nothing\n");
            else if (st->key[0] == CACAO_PASS_APPLY && has_listed_apply(plan) && apply_listed(c))
                printf("gated: at most %d/%d of the tiles are active, compact listed the groups the next step runs; "
                       "dispatches nothing\n",
                       CACAO_APPLY_LIST_ACTIVE_NUM, CACAO_APPLY_LIST_ACTIVE_DEN);
            else
                printf("runs over everything, skips 0%%\n");
        }
        if (reuse && (list == CACAO_LIST_GENERATE || list == CACAO_LIST_BLUR))
            printf("  %2s %-34s (background, faded, and the %u tiles no change reaches)\n", "", "", c->tiles - c->recomputed);
    }
}

/* Runs one frame of the inputs on the device (cacao's --device, default lavapipe) for its tile
 * counts, then prints them beside the plan that ran. */
static int plan_on_scene(const cli_options *options) {
    char err[1024];
    cli_inputs in;
    if (!cli_inputs_load(options, &in, err, sizeof err)) return fail("plan: %s", err);
    const cacao_settings s = cli_inputs_settings(options, &in);
    int rc = 0;
    cacao_plan plan;
    vkdev_frame frame = cli_inputs_frame(&in, &s, options->frame_index);
    frame.plan_out = &plan;
    float *moved = NULL;
    if (!cli_inputs_reuse_frame(options, &in, &frame, &moved, err, sizeof err)) {
        cli_inputs_free(&in);
        return fail("plan: %s", err);
    }
    float *ao = malloc(sizeof(float) * in.depth.width * in.depth.height);
    vkdev dev;
    cacao_timings timings = {0};
    if (!ao)
        rc = fail("plan: out of memory for the frame of %s",
                  options->scene_dir ? options->scene_dir : options->depth_path);
    else if (!vkdev_create(&(vkdev_options){.validation = options->validate, .device = options->device}, &dev, err,
                           sizeof err))
        rc = fail("plan: %s", err);
    else {
        /* with reuse, the second of two frames: the first is a full one (--move-box: the second moved) */
        const cacao_result r = vkdev_run(&dev, &s, &frame, s.reuse_unchanged ? 2 : 1, ao, &timings, err, sizeof err);
        if (r != CACAO_SUCCESS) {
            fprintf(stderr, "cacao-inspect: plan: %s: %s\n", cacao_result_string(r), err);
            rc = 1;
        } else {
            cacao_plan_print(&plan, stdout);
            printf("frame: %s%s, on %s\n", options->scene_dir ? options->scene_dir : options->depth_path,
                   s.reuse_unchanged ? " (the second of two frames)" : "", dev.device_name);
            if (timings.has_tiles)
                print_skipped_work(&plan, &timings.tiles, options->keep_output);
            else
                printf("no tile counts for this frame: every step runs over everything\n");
        }
        vkdev_destroy(&dev);
        if (rc == 0 && dev.validation_messages) {
            char count[32];
            snprintf(count, sizeof count, "%u", dev.validation_messages);
            rc = fail("plan: --validate: the validation layer reported %s message(s)", count);
        }
    }
    free(ao);
    free(moved);
    cli_inputs_free(&in);
    return rc;
}

/* `plan` takes --size WxH and the settings flags of the cacao command (the same flag table), or
 * instead of --size the cacao command's inputs (--scene DIR, or --depth FILE --camera FILE ...);
 * inspect_parse_args has checked which. */
static int cmd_plan(const inspect_args *a) {
    const cli_options *options = &a->options;
    if (options->scene_dir || options->depth_path) return plan_on_scene(options);
    cacao_plan plan;
    char err[256];
    if (cacao_plan_build(&options->settings, a->width, a->height, &plan, err, sizeof err) != CACAO_SUCCESS)
        return fail("plan: %s", err);
    cacao_plan_print(&plan, stdout);
    int missing = 0;
    for (uint32_t i = 0; i < plan.step_count; ++i) {
        const cacao_key key = cacaoi_plan_step_key(&plan.steps[i]);
        if (!plan.steps[i].clear && !cacaoi_table_find(table, &key)) missing += fprintf(stderr, "note: %s is not embedded in this build\n",
                                                               plan.steps[i].key_name) > 0;
    }
    return missing ? 1 : 0;
}

/* Keys and SPIR-V bytes per pass of the embedded table, each module counted once. */
typedef struct table_totals {
    uint32_t keys[CACAO_PASS_COUNT];
    uint64_t bytes[CACAO_PASS_COUNT], total_bytes;
} table_totals;

static void count_table(table_totals *t) {
    memset(t, 0, sizeof *t);
    bool counted[1024] = {false};
    for (uint32_t i = 0; i < table->permutation_count; ++i) {
        const cacao_permutation *p = &table->permutations[i];
        t->keys[p->key.pass]++;
        if (p->module < 1024 && !counted[p->module]) {
            counted[p->module] = true;
            t->bytes[p->key.pass] += table->modules[p->module].word_count * 4u;
            t->total_bytes += table->modules[p->module].word_count * 4u;
        }
    }
}

static int cmd_stats(void) {
    table_totals t;
    count_table(&t);
    printf("subset: %s\ncompilers: %s, %s\n", table->subset, table->glslang_version, table->spirv_tools_version);
    printf("permutations: %u before dedup, %u unique modules after (%u removed)\n", table->permutation_count,
           table->module_count, table->permutation_count - table->module_count);
    printf("embedded SPIR-V: %llu bytes\n%-16s %6s %10s\n", (unsigned long long)t.total_bytes, "pass", "keys", "bytes");
    for (unsigned p = 0; p < CACAO_PASS_COUNT; ++p)
        if (t.keys[p]) printf("%-16s %6u %10llu\n", cacaoi_pass_name(p), t.keys[p], (unsigned long long)t.bytes[p]);
    return 0;
}

/* The counts and limits the documentation states, as JSON (tools/refresh-docs.py writes them into
 * README.md and docs/): the embedded table, the rows of the pass table, the API's limits. Keys and
 * bytes per pass or key: `list --json`. */
static int cmd_facts(void) {
    table_totals t;
    count_table(&t);
    unsigned caller_resources = 0;
    for (unsigned r = 0; r < CACAO_RES_COUNT; ++r) caller_resources += cacaoi_resources[r].size == CACAOI_SIZE_CALLER;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "subset", table->subset);
    cJSON_AddNumberToObject(o, "key_space", (double)cacaoi_key_list(NULL, 0));
    cJSON_AddNumberToObject(o, "permutations", table->permutation_count);
    cJSON_AddNumberToObject(o, "modules", table->module_count);
    cJSON_AddNumberToObject(o, "duplicates_removed", table->permutation_count - table->module_count);
    cJSON_AddNumberToObject(o, "spirv_bytes", (double)t.total_bytes);
    cJSON_AddNumberToObject(o, "passes", CACAO_PASS_COUNT);
    cJSON_AddNumberToObject(o, "resources", CACAO_RES_COUNT);
    cJSON_AddNumberToObject(o, "caller_resources", caller_resources);
    cJSON_AddNumberToObject(o, "binding_slots", CACAO_BINDING_COUNT);
    cJSON_AddNumberToObject(o, "max_size", CACAO_MAX_SIZE);
    cJSON_AddNumberToObject(o, "tile_texels", CACAO_TILE);
    cJSON *blur = cJSON_AddArrayToObject(o, "blur_group_texels"); /* output of a group, fewest passes */
    cJSON_AddItemToArray(blur, cJSON_CreateNumber(CACAO_BLUR_OUT_X(1)));
    cJSON_AddItemToArray(blur, cJSON_CreateNumber(CACAO_BLUR_OUT_Y(1)));
    char *text = cJSON_Print(o);
    printf("%s\n", text);
    free(text);
    cJSON_Delete(o);
    return 0;
}

/* Parses the table's subset string ("all" or "qualities|downsample|precision"). */
static bool table_subset(cacao_key_subset *s) {
    if (strcmp(table->subset, "all") == 0) {
        *s = CACAO_KEY_SUBSET_ALL;
        return true;
    }
    char q[128], d[32], p[64];
    if (sscanf(table->subset, "%127[^|]|%31[^|]|%63s", q, d, p) != 3) return false;
    return cacaoi_key_subset_parse(q, d, p, s);
}

static int cmd_verify(void) {
    int errors = 0;
    for (uint32_t m = 0; m < table->module_count; ++m) {
        char name[32];
        snprintf(name, sizeof name, "module %u", m);
        errors += !sg_validate(table->modules[m].words, table->modules[m].word_count, name);
    }
    printf("%u modules re-validated with SPIRV-Tools (Vulkan 1.1): %s\n", table->module_count,
           errors ? "FAILED" : "all valid");
    cacao_key_subset subset;
    if (!table_subset(&subset)) return fail("cannot parse the table's subset '%s'", table->subset);
    unsigned configs = 0, missing = 0;
    for (int e = CACAO_ESTIMATOR_CACAO; e <= CACAO_ESTIMATOR_BITMASK; ++e)
    for (unsigned q = 0; q < 5; ++q)
        for (unsigned ds = 0; ds < 2; ++ds)
            for (unsigned fp = 0; fp < 2; ++fp)
                for (unsigned gen = 0; gen < 2; ++gen)
                    for (int blur = 0; blur <= 8; ++blur) {
                        if (!(subset.quality_mask >> q & 1) || !(subset.resolution_mask >> ds & 1) ||
                            !(subset.precision_mask >> fp & 1))
                            continue;
                        if (e != CACAO_ESTIMATOR_CACAO && (ds || fp)) continue; /* native fp32 only */
                        const cacao_settings s = {.estimator = (cacao_estimator)e,
                                                  .quality = (cacao_quality)(q + 1), .downsample = ds,
                                                  .precision = fp ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32,
                                                  .generate_normals = gen,
                                                  .blur_pass_count = blur ? blur : CACAO_BLUR_NONE};
                        cacao_plan plan;
                        char err[256];
                        if (cacao_plan_build(&s, 1920, 1080, &plan, err, sizeof err) != CACAO_SUCCESS) {
                            fprintf(stderr, "plan failed: %s\n", err);
                            ++errors;
                            continue;
                        }
                        ++configs;
                        for (uint32_t i = 0; i < plan.step_count; ++i) {
                            const cacao_key key = cacaoi_plan_step_key(&plan.steps[i]);
                            if (!plan.steps[i].clear && !cacaoi_table_find(table, &key)) {
                                fprintf(stderr, "missing: %s (quality %s)\n", plan.steps[i].key_name,
                                        cacao_quality_name(s.quality));
                                ++missing;
                            }
                        }
                    }
    printf("%u configurations of subset '%s' planned: %s\n", configs, table->subset,
           missing ? "some keys are NOT embedded" : "every key they dispatch is embedded");
    return errors || missing ? 1 : 0;
}

static void usage(FILE *out) {
    fprintf(out, "usage: cacao-inspect list [--pass NAME] [--quality LEVEL] [--json] [--costs BENCH.json]\n"
                 "       cacao-inspect show KEY\n"
                 "       cacao-inspect plan --size WxH [settings flags of the cacao command, e.g.\n"
                 "                          --quality LEVEL --downsample --blur N --precision fp16 --no-normals]\n"
                 "       cacao-inspect plan --scene DIR | --depth FILE --camera FILE [settings flags]\n"
                 "                          (runs one frame on --device, default lavapipe: tiles and skipped work)\n"
                 "       cacao-inspect stats\n"
                 "       cacao-inspect facts   (the counts and limits the docs state, as JSON)\n"
                 "       cacao-inspect verify\n");
    inspect_gpu_usage(out);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    /* gpu parses its own arguments (gpu.c) */
    if (strcmp(argv[1], "gpu") == 0) return inspect_gpu(argc - 2, argv + 2);
    static inspect_args args; /* holds the cacao command's options: kept off the stack */
    char err[1024];
    if (!inspect_parse_args(argc, argv, &args, err, sizeof err)) return fail("%s", err);
    switch (args.command) {
    case INSPECT_LIST:
        return cmd_list(&args);
    case INSPECT_SHOW:
        return cmd_show(args.key);
    case INSPECT_PLAN:
        return cmd_plan(&args);
    case INSPECT_STATS:
        return cmd_stats();
    case INSPECT_VERIFY:
        return cmd_verify();
    case INSPECT_FACTS:
        return cmd_facts();
    default:
        usage(stdout);
        return 0;
    }
}
