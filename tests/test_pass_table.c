/* test_pass_table - the declarative pass table (shaders/cacao_passes.c) is consistent, and what is
 * derived from it agrees everywhere, over every configuration (estimator x quality x resolution x
 * precision x normals source x blur 0..8):
 *   - the rows: a binding's slot kind fits its resource (buffers at buffer slots, images at image
 *     slots), each variant binds a slot at most once, and every resource a linear-sampler slot reads
 *     supports filtering;
 *   - the sequence: a step rebinds a slot only to a resource of the same format and layering as the
 *     row's (the GLSL qualifier is the row's), and no step reads what it writes;
 *   - the plan built from it: its steps are exactly the sequence's keys, the subset filter's keys
 *     (cacaoi_keys_for_config) are exactly the plan's distinct keys, each step binds exactly the
 *     slots its embedded module declares, with that module's workgroup size, and every resource a
 *     step touches is allocated (intermediates) or supplied by the caller;
 *   - the slots: every slot of the set layout is bound by some pass row and declared by some
 *     embedded module, and each slot has one role: every binding of it, in every row, is of one
 *     format and layering (the one GLSL declaration of glsl/bindings.glsl fits them all); no
 *     variant binds more than CACAO_PLAN_MAX_BINDINGS slots;
 *   - the GLSL defines of every key carry exactly the row's CACAO_BIND_<slot>, a CACAO_ACCESS_<slot>
 *     of the row's access for storage slots, and one CACAO_FORMAT_<slot> per formatted storage
 *     image.
 * Pure C: no device. */
#include <stdlib.h>
#include <string.h>

#include "cacao_passes.h"
#include "cacao_table.h"
#include "internal.h"
#include "test_util.h"

static bool is_buffer(cacao_resource r) {
    return cacaoi_resources[r].size == CACAOI_SIZE_BUFFER || cacaoi_resources[r].size == CACAOI_SIZE_TILES;
}

static void test_rows(void) {
    for (unsigned p = 0; p < CACAO_PASS_COUNT; ++p) {
        const cacaoi_pass_row *row = &cacaoi_passes[p];
        CHECK(row->name && row->variants >= 1 && row->variants <= CACAOI_MAX_VARIANTS);
        CHECK(row->binding_count <= CACAOI_PASS_MAX_BINDINGS);
        /* quads: only variants the row has, and only on a direct slice or output grid (the lists'
         * groups are tiles), or smart apply's listed variant (compact lists its groups, blocks of
         * 2x2 tiles: 4x4 pixels per invocation); a variant's own grid: only variants the row has, a direct one (a list's groups
         * are its entries), a grid rule that exists */
        CHECK(row->grid != CACAOI_GRID_ROW && (row->grid <= CACAOI_GRID_TILES || row->grid == CACAOI_GRID_SLICE_CLASSIFY));
        /* the slice grid with the classification's groups (z 0 downsampled): the GPU form of the
         * fused prepare only, whose groups of 2x2 texels cover 2x2 tiles */
        CHECK((row->grid == CACAOI_GRID_SLICE_CLASSIFY) == (p == CACAO_PASS_PREPARE_GPU));
        for (unsigned v = 0; v < CACAOI_MAX_VARIANTS; ++v) {
            const uint8_t grid = row->grids[v] != CACAOI_GRID_ROW ? row->grids[v] : row->grid;
            CHECK(row->quad[v] <= 4 && (v < row->variants || row->quad[v] == 0));
            if (row->quad[v] > 1)
                CHECK((grid == CACAOI_GRID_SLICE || grid == CACAOI_GRID_SLICE_CLASSIFY || grid == CACAOI_GRID_OUTPUT) &&
                      (row->lists[v] == CACAO_LIST_NONE ||
                       (p == CACAO_PASS_APPLY && v >= CACAO_APPLY_SMART_LIST && row->lists[v] == CACAO_LIST_PREPARE &&
                        row->quad[v] == row->quad[v - CACAO_APPLY_SMART_LIST + CACAO_OUTPUT_SMART])));
            CHECK(row->grids[v] <= CACAOI_GRID_TILE_ROWS && (v < row->variants || row->grids[v] == CACAOI_GRID_ROW));
            /* a list's groups are tiles (or blur groups); the exception, the blocks list, holds
             * blocks of 2x2 tiles: the groups of a grid of CACAO_TILE x CACAO_TILE invocations,
             * each 2x2 texels of the tiles' (the Q3 base pass's importance grid, the horizon
             * estimators' half-size grid) */
            if (row->grids[v] != CACAOI_GRID_ROW)
                CHECK(row->lists[v] == CACAO_LIST_NONE ||
                      (row->lists[v] == CACAO_LIST_BLOCKS &&
                       (row->grids[v] == CACAOI_GRID_IMPORTANCE || row->grids[v] == CACAOI_GRID_HALF) &&
                       row->workgroup[0] == CACAO_TILE && row->workgroup[1] == CACAO_TILE));
        }
        for (unsigned v = 0; v < row->variants; ++v) {
            /* one unnamed variant, or all named; a pass that gained variants may keep its first
             * unnamed (its keys keep their names: "classify", "classify.horizon") */
            CHECK(row->variants == 1 ? row->variant_names[v] == NULL : (v == 0 || row->variant_names[v] != NULL));
            for (unsigned u = 0; u < v; ++u)
                CHECK(!row->variant_names[u] || !row->variant_names[v] ||
                      strcmp(row->variant_names[u], row->variant_names[v]) != 0);
            unsigned seen[CACAO_BINDING_COUNT] = {0};
            for (unsigned i = 0; i < row->binding_count; ++i) {
                const cacaoi_pass_binding *b = &row->bindings[i];
                CHECK(b->slot < CACAO_BINDING_COUNT && b->resource < CACAO_RES_COUNT);
                if (!((b->variants >> v) & 1u)) continue;
                ++seen[b->slot];
                const uint8_t kind = cacaoi_slots[b->slot].descriptor;
                /* (a storage texel buffer slot holds a buffer too: the tile buffer's texel view) */
                const bool buffer_slot = kind == CACAOI_DESCRIPTOR_UNIFORM_BUFFER || kind == CACAOI_DESCRIPTOR_STORAGE_BUFFER ||
                                         kind == CACAOI_DESCRIPTOR_STORAGE_TEXEL_BUFFER;
                if (buffer_slot != is_buffer(b->resource))
                    fprintf(stderr, "%s variant %u: slot %s holds %s\n", row->name, v, cacaoi_slots[b->slot].name,
                            cacaoi_resources[b->resource].name);
                CHECK(buffer_slot == is_buffer(b->resource));
                if (cacaoi_slots[b->slot].sampler == CACAOI_SAMPLER_LINEAR) CHECK(cacaoi_resources[b->resource].filtered);
                if (kind == CACAOI_DESCRIPTOR_SAMPLED_IMAGE) CHECK(!b->write); /* sampled = read */
                /* only the depths hold levels (an atlas, or the GPU forms' chain, whose levels 1..3
                 * have their own slots), written by the prepares' mips variants */
                const bool chain_slot = b->slot >= CACAO_BINDING_DEPTHS_MIP1 && b->slot <= CACAO_BINDING_DEPTHS_MIP3;
                if (b->levels > 1)
                    CHECK(b->resource == CACAO_RES_DEPTHS && b->levels <= CACAO_DEPTH_MIP_COUNT && b->write &&
                          (b->slot == CACAO_BINDING_DEPTHS_IMAGE || chain_slot));
                if (chain_slot) CHECK(b->levels == CACAO_DEPTH_MIP_COUNT && b->resource == CACAO_RES_DEPTHS && b->write);
            }
            CHECK(seen[CACAO_BINDING_CONSTANTS] == 1); /* every pass reads the constant block */
            unsigned bound = 0;
            for (unsigned s = 0; s < CACAO_BINDING_COUNT; ++s) {
                CHECK(seen[s] <= 1);
                bound += seen[s];
            }
            unsigned native_only = 0; /* bindings the downsampled keys leave out */
            for (unsigned i = 0; i < row->binding_count; ++i)
                if (((row->bindings[i].variants >> v) & 1u) && row->bindings[i].native_only) {
                    CHECK(row->has_resolution); /* only the prepare passes have the axis */
                    ++native_only;
                }
            cacaoi_pass_binding out[CACAO_PLAN_MAX_BINDINGS];
            CHECK(bound <= CACAO_PLAN_MAX_BINDINGS && cacaoi_variant_bindings(p, v, 0, out) == bound);
            CHECK(cacaoi_variant_bindings(p, v, 1, out) == bound - native_only);
        }
    }
    /* Only the caller's images and the buffers lack a format; intermediates have a GLSL one. */
    for (unsigned r = 0; r < CACAO_RES_COUNT; ++r) {
        const cacaoi_resource_row *row = &cacaoi_resources[r];
        CHECK(strcmp(row->name, cacao_resource_name((cacao_resource)r)) == 0);
        const bool intermediate = row->size != CACAOI_SIZE_CALLER && !is_buffer((cacao_resource)r);
        CHECK(intermediate == (row->format != VK_FORMAT_UNDEFINED));
        CHECK(intermediate == (*row->glsl_format != '\0'));
        CHECK(intermediate == (row->texel_bytes > 0));
    }
}

/* Every slot has one role and is used: some row binds it, and every binding of it (any row, any
 * variant) is to a resource of one format and layering, so one GLSL declaration serves them all;
 * some embedded module declares it. */
static void test_slots(void) {
    for (unsigned s = 0; s < CACAO_BINDING_COUNT; ++s) {
        const cacaoi_resource_row *first = NULL;
        unsigned rows = 0;
        for (unsigned p = 0; p < CACAO_PASS_COUNT; ++p)
            for (unsigned i = 0; i < cacaoi_passes[p].binding_count; ++i) {
                const cacaoi_pass_binding *b = &cacaoi_passes[p].bindings[i];
                if (b->slot != s) continue;
                const cacaoi_resource_row *r = &cacaoi_resources[b->resource];
                if (!first) first = r;
                if (r->format != first->format || r->layered != first->layered)
                    fprintf(stderr, "slot %s: %s binds %s, another row %s\n", cacaoi_slots[s].name,
                            cacaoi_passes[p].name, r->name, first->name);
                /* (the size may differ: horizon_denoise reads the full-size AO_RAW or, upsampling,
                 * the half-size AO_HALF through one slot; no shader sizes a loop by that image) */
                CHECK(r->format == first->format && r->layered == first->layered);
                ++rows;
            }
        if (rows == 0) fprintf(stderr, "slot %s: no pass row binds it\n", cacaoi_slots[s].name);
        CHECK(rows > 0);
        bool declared = false;
        for (uint32_t i = 0; i < cacaoi_embedded_table.permutation_count && !declared; ++i)
            declared = cacaoi_embedded_table.permutations[i].bindings[s] == cacaoi_slots[s].descriptor;
        if (!declared) fprintf(stderr, "slot %s: no embedded module declares it\n", cacaoi_slots[s].name);
        CHECK(declared || cacaoi_embedded_table.permutation_count < cacaoi_key_list(NULL, 0)); /* a subset may lack it */
    }
}

static bool has_line(const char *text, const char *line) {
    const size_t n = strlen(line);
    for (const char *at = strstr(text, line); at; at = strstr(at + 1, line))
        if ((at == text || at[-1] == '\n') && at[n] == '\n') return true;
    return false;
}

static void test_defines(void) {
    const size_t n = cacaoi_key_list(NULL, 0);
    cacao_key *keys = calloc(n, sizeof *keys);
    CHECK(keys && cacaoi_key_list(keys, n) == n);
    for (size_t i = 0; keys && i < n; ++i) {
        char defines[CACAO_KEY_DEFINES_MAX], name[64], line[128];
        char small[16];
        CHECK(cacaoi_key_defines(&keys[i], small, sizeof small) == 0 && small[0] == '\0'); /* not a cut text */
        CHECK(cacaoi_key_defines(&keys[i], defines, sizeof defines) > 0);
        cacaoi_module_expect want;
        CHECK(cacaoi_key_expect(&keys[i], &want));
        for (unsigned s = 0; s < CACAO_BINDING_COUNT; ++s) {
            const uint8_t kind = want.descriptor[s];
            snprintf(line, sizeof line, "#define CACAO_BIND_%s 1", cacaoi_slots[s].name);
            CHECK(has_line(defines, line) == (kind != CACAOI_DESCRIPTOR_NONE));
            const bool storage = kind == CACAOI_DESCRIPTOR_STORAGE_IMAGE || kind == CACAOI_DESCRIPTOR_STORAGE_BUFFER;
            const char *access = !want.write[s] ? "readonly" : kind == CACAOI_DESCRIPTOR_STORAGE_IMAGE ? "writeonly" : "";
            snprintf(line, sizeof line, "#define CACAO_ACCESS_%s %s", cacaoi_slots[s].name, access);
            CHECK(has_line(defines, line) == storage);
            snprintf(name, sizeof name, "#define CACAO_FORMAT_%s ", cacaoi_slots[s].name);
            const bool formatted = want.descriptor[s] == CACAOI_DESCRIPTOR_STORAGE_IMAGE &&
                                   *cacaoi_resources[want.resource[s]].glsl_format;
            const char *at = strstr(defines, name);
            CHECK((at != NULL) == formatted);
            if (at) CHECK(strncmp(at + strlen(name), cacaoi_resources[want.resource[s]].glsl_format,
                                  strlen(cacaoi_resources[want.resource[s]].glsl_format)) == 0);
        }
    }
    free(keys);
}

static unsigned configs_checked;

static void check_config(const cacao_settings *s) {
    cacao_plan plan;
    char err[256];
    if (cacao_plan_build(s, 97, 61, &plan, err, sizeof err) != CACAO_SUCCESS) {
        /* the one refused combination: more filter passes than a downsampled horizon estimator runs */
        CHECK(s->estimator != CACAO_ESTIMATOR_CACAO && s->downsample && s->blur_pass_count > CACAO_HORIZON_HALF_MAX_PASSES);
        return;
    }
    ++configs_checked;
    const cacao_key_config config = cacaoi_key_config_of(&plan.settings);
    cacaoi_step steps[CACAOI_SEQUENCE_MAX];
    const size_t count = cacaoi_sequence(&config, steps);
    CHECK(count == plan.step_count);
    cacao_key keys[CACAO_KEY_CONFIG_MAX];
    const size_t key_count = cacaoi_keys_for_config(&config, keys);
    bool key_listed[CACAO_KEY_CONFIG_MAX] = {false};
    bool allocated[CACAO_RES_COUNT] = {false};
    for (uint32_t i = 0; i < plan.image_count; ++i) allocated[plan.images[i].resource] = true;
    for (uint32_t i = 0; i < plan.step_count && i < count; ++i) {
        const cacao_plan_step *st = &plan.steps[i];
        const cacao_key key = cacaoi_plan_step_key(st);
        CHECK(cacaoi_key_compare(&key, &steps[i].key) == 0);
        CHECK(st->clear == cacaoi_fill_is_clear(steps[i].key.pass, steps[i].key.variant));
        /* a step reading the tile buffer is a list dispatch, classify or compact, a GPU form that
         * skips by the classes itself (it then writes its count there), a GPU form of a prepare
         * that classifies (then no classify pass runs): the fused prepare, the horizon
         * estimators'; or a GPU form that reads the classes only */
        const bool prepare_classifies = st->key[0] == CACAO_PASS_PREPARE_GPU || st->key[0] == CACAO_PASS_HORIZON_PREPARE_GPU;
        if (prepare_classifies)
            CHECK(config.gpu_forms && (st->key[0] == CACAO_PASS_HORIZON_PREPARE_GPU || cacaoi_prepare_classifies(&config)));
        /* classify_gpu: CACAO's GPU forms where the prepare does not classify, first of the
         * frame's passes after reuse's, with no barrier before the prepare after it */
        if (st->key[0] == CACAO_PASS_CLASSIFY_GPU) {
            CHECK(config.gpu_forms && config.estimator == CACAO_KEY_ESTIMATOR_CACAO && !cacaoi_prepare_classifies(&config));
            CHECK(i + 1 < plan.step_count && !plan.steps[i + 1].barrier_before);
        }
        if (cacaoi_skips_by_class(st->key[0], st->key[1]))
            CHECK(st->list == CACAO_LIST_NONE && config.gpu_forms);
        for (uint32_t j = 0; j < st->binding_count; ++j)
            if (st->bindings[j].resource == CACAO_RES_TILES)
                CHECK(st->list != CACAO_LIST_NONE || st->key[0] == CACAO_PASS_CLASSIFY ||
                      st->key[0] == CACAO_PASS_CLASSIFY_GPU || st->key[0] == CACAO_PASS_COMPACT ||
                      cacaoi_skips_by_class(st->key[0], st->key[1]) || prepare_classifies ||
                      (cacaoi_reads_classes(st->key[0], st->key[1]) && !st->bindings[j].write));
        if (st->clear) { /* a transfer: it only writes cacao's own images, each with a clear value; no module */
            CHECK(st->dispatch[0] == 0 && st->list == CACAO_LIST_NONE && st->binding_count >= 1);
            for (uint32_t j = 0; j < st->binding_count; ++j) {
                float value[4];
                CHECK(st->bindings[j].write && allocated[st->bindings[j].resource] &&
                      cacaoi_clear_value(st->bindings[j].resource, value));
            }
            continue;
        }
        size_t k = 0;
        while (k < key_count && cacaoi_key_compare(&keys[k], &key) != 0) ++k;
        CHECK(k < key_count);
        if (k < key_count) key_listed[k] = true;

        /* Rebinding keeps the row's format and layering. */
        cacaoi_module_expect want;
        CHECK(cacaoi_key_expect(&key, &want));
        uint32_t reads = 0, writes = 0;
        bool bound[CACAO_BINDING_COUNT] = {false};
        for (uint32_t j = 0; j < st->binding_count; ++j) {
            const cacao_plan_binding *b = &st->bindings[j];
            const cacaoi_resource_row *have = &cacaoi_resources[b->resource], *row = &cacaoi_resources[want.resource[b->binding]];
            CHECK(have->format == row->format && have->layered == row->layered && have->size == row->size);
            CHECK(b->write == want.write[b->binding]);
            bound[b->binding] = true;
            /* compact writes the tile buffer and reads what the passes before it wrote there
             * through its texel view; no other step reads what it writes */
            if (b->binding != CACAO_BINDING_TILE_ENTRIES) *(b->write ? &writes : &reads) |= 1u << b->resource;
            const uint8_t size = have->size;
            CHECK(allocated[b->resource] || size == CACAOI_SIZE_CALLER || size == CACAOI_SIZE_BUFFER ||
                  (size == CACAOI_SIZE_TILES && plan.uses_tiles && plan.tile_buffer_bytes > 0));
        }
        CHECK((reads & writes) == 0);

        /* The embedded module declares exactly the bound slots, at the row's workgroup size. */
        const cacao_permutation *perm = cacaoi_table_find(&cacaoi_embedded_table, &key);
        CHECK(perm != NULL);
        if (!perm) continue;
        for (unsigned b = 0; b < CACAO_BINDING_COUNT; ++b) {
            if ((perm->bindings[b] != CACAOI_DESCRIPTOR_NONE) != bound[b])
                fprintf(stderr, "%s: slot %s bound %d, module %d\n", st->key_name, cacaoi_slots[b].name, bound[b],
                        perm->bindings[b]);
            CHECK((perm->bindings[b] != CACAOI_DESCRIPTOR_NONE) == bound[b]);
            if (bound[b]) CHECK(perm->bindings[b] == cacaoi_slots[b].descriptor);
        }
        CHECK(memcmp(perm->workgroup_size, want.workgroup, sizeof want.workgroup) == 0);
    }
    for (size_t k = 0; k < key_count; ++k) CHECK(key_listed[k]); /* no key the plan does not dispatch */
}

static void test_every_configuration(void) {
    for (int est = CACAO_ESTIMATOR_CACAO; est <= CACAO_ESTIMATOR_BITMASK; ++est)
        for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
            for (int ds = 0; ds < 2; ++ds)
                for (int fp = CACAO_PRECISION_FP32; fp <= CACAO_PRECISION_FP16; ++fp)
                    for (int gen = 0; gen < 2; ++gen)
                        for (int blur = 0; blur <= 8; ++blur)
                        for (int forms = CACAO_SHADER_FORMS_CPU; forms <= CACAO_SHADER_FORMS_GPU; ++forms) {
                            const cacao_settings s = {.estimator = (cacao_estimator)est,
                                                      .shader_forms = (cacao_shader_forms)forms,
                                                      .quality = (cacao_quality)q,
                                                      .downsample = ds != 0,
                                                      .precision = (cacao_precision)fp,
                                                      .generate_normals = gen != 0,
                                                      .blur_pass_count = blur ? blur : CACAO_BLUR_NONE};
                            check_config(&s);
                        }
    /* 5 qualities x 2 x 2 x 2 x 9 for CACAO; for each horizon estimator 5 x 2 x 2 x 9 native and
     * 5 x 2 x 2 x 7 downsampled (blur none to 6); each with the CPU and the GPU shader forms */
    printf("%u configurations checked\n", configs_checked);
    CHECK(configs_checked == 2000); /* 2 x (360 + 2 x (180 + 140)) */
}

/* The tile buffer gives the blur list a tile's worth of entries (cacao_shared.h): a blur group
 * outputs at least a tile each way, in both forms, at every pass count, so a plan never has more
 * blur groups than tiles. */
static void test_blur_groups_fit(void) {
    for (unsigned n = 1; n <= CACAO_KEY_MAX_BLUR_PASSES; ++n)
        for (int gpu = 0; gpu < 2; ++gpu) {
            uint32_t out[2];
            cacaoi_blur_out(gpu ? CACAO_PASS_BLUR_GPU : CACAO_PASS_BLUR, n, out);
            CHECK(out[0] >= CACAO_TILE && out[1] >= CACAO_TILE);
        }
}

int main(void) {
    test_blur_groups_fit();
    test_rows();
    test_slots();
    test_defines();
    test_every_configuration();
    return test_report("pass_table");
}
