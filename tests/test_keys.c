/* test_keys - the permutation key space: cacaoi_key_list lists exactly the keys cacaoi_key_is_valid
 * accepts (counted here by trying every value of every key field, not by the list's loops), every
 * valid key has a unique name that parses back to it, invalid keys are rejected, and the subset
 * filter keeps exactly the keys a hand-derived list of configurations needs (independent of
 * cacaoi_key_in_subset's enumeration). No count is written here: the pass table sets it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cacao_keys.h"
#include "cacao_passes.h"
#include "cacao_policy.h"
#include "test_util.h"

/* Every key, sized from the count the list reports; *n is that count. */
static cacao_key *all_keys(size_t *n) {
    *n = cacaoi_key_list(NULL, 0);
    cacao_key *keys = malloc(*n * sizeof *keys);
    if (!keys) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    CHECK(cacaoi_key_list(keys, *n) == *n);
    return keys;
}

/* The valid keys, counted over every value each field can hold (one past each axis's range, so a
 * key the rule lets through out of range is counted too). */
static size_t count_valid_by_trial(void) {
    size_t valid = 0;
    for (unsigned pass = 0; pass <= CACAO_PASS_COUNT; ++pass)
        for (unsigned v = 0; v <= CACAOI_MAX_VARIANTS; ++v)
            for (unsigned ds = 0; ds <= 2; ++ds)
                for (unsigned b = 0; b <= CACAO_KEY_MAX_BLUR_PASSES + 1; ++b)
                    for (unsigned fp = 0; fp <= 2; ++fp) {
                        const cacao_key k = {(uint8_t)pass, (uint8_t)v, (uint8_t)ds, (uint8_t)b, (uint8_t)fp};
                        valid += cacaoi_key_is_valid(&k);
                    }
    return valid;
}

static void test_names_round_trip(void) {
    size_t n;
    cacao_key *keys = all_keys(&n);
    printf("key space: %zu keys\n", n);
    CHECK(n > 0 && n == count_valid_by_trial());
    for (size_t i = 0; i < n; ++i) {
        char name[CACAO_KEY_NAME_MAX];
        CHECK(cacaoi_key_is_valid(&keys[i]));
        CHECK(cacaoi_key_name(&keys[i], name, sizeof name) > 0);
        cacao_key back;
        CHECK(cacaoi_key_parse(name, &back));
        CHECK(cacaoi_key_compare(&back, &keys[i]) == 0);
        if (i > 0) CHECK(cacaoi_key_compare(&keys[i - 1], &keys[i]) < 0); /* sorted, no repeats */
    }
    cacao_key k;
    CHECK(cacaoi_key_parse("generate.q2", &k) && k.pass == CACAO_PASS_GENERATE && k.variant == 2);
    CHECK(cacaoi_key_parse("blur.8.fp16", &k) && k.blur_passes == 8 && k.fp16 == 1);
    CHECK(!cacaoi_key_parse("blur.9.fp16", &k));
    CHECK(!cacaoi_key_parse("generate.q2.native", &k)); /* generate has no resolution axis */
    CHECK(!cacaoi_key_parse("", &k));
    free(keys);
}

/* A name that does not fit gives 0 and an empty buffer, never a cut name (and every name fits the
 * plan's key_name: test_names_round_trip names every key into CACAO_KEY_NAME_MAX). */
static void test_name_too_long(void) {
    cacao_key k;
    CHECK(cacaoi_key_parse("prepare_depths.mips.downsampled", &k));
    char name[CACAO_KEY_NAME_MAX];
    const size_t len = cacaoi_key_name(&k, name, sizeof name);
    CHECK(len == strlen("prepare_depths.mips.downsampled"));
    CHECK(cacaoi_key_name(&k, name, len) == 0 && name[0] == '\0');
    CHECK(cacaoi_key_name(&k, name, len + 1) == len);
}

static void test_invalid_keys(void) {
    cacao_key bad[] = {
        {CACAO_PASS_COUNT, 0, 0, 0, 0},            /* no such pass */
        {CACAO_PASS_GENERATE, 7, 0, 0, 0},         /* no such variant */
        {CACAO_PASS_GENERATE_GPU, CACAO_GENERATE_Q0_INPUT, 0, 0, 0}, /* the GPU form reads prepared normals */
        {CACAO_PASS_GENERATE, 1, 1, 0, 0},         /* generate has no resolution axis */
        {CACAO_PASS_BLUR, 0, 0, 0, 0},             /* blur needs 1..8 */
        {CACAO_PASS_BLUR, 0, 0, 9, 0},
        {CACAO_PASS_PREPARE_DEPTHS, 0, 0, 0, 1},   /* prepare has no precision axis */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char name[CACAO_KEY_NAME_MAX];
        CHECK(!cacaoi_key_is_valid(&bad[i]));
        CHECK(cacaoi_key_name(&bad[i], name, sizeof name) == 0);
    }
}

static void test_subset(void) {
    cacao_key_subset s;
    CHECK(cacaoi_key_subset_parse("medium;high", "OFF", "fp32", &s));
    /* By hand: MEDIUM native = depths without mips, Q1, apply.smart; HIGH native = depths with
     * mips, Q2, apply.smart; both: either normals source (given: prepare_depths and
     * prepare_normals, and at MEDIUM with reuse (CPU forms) Q1 reading the caller's normals; from depth: prepare,
     * both in one pass), blur 1..8 fp32. The
     * horizon-slice estimators have no quality axis (quality is their budget, a constant) and run
     * native in fp32: all their keys belong to any subset with native resolution. */
    const char *expected[] = {"prepare_depths.full.native", "prepare_depths.mips.native", "prepare_depths.mips_chain.native",
                              "prepare_normals.native", "prepare_normals.list.native", "prepare.full.native", "prepare.mips.native",
                              "generate.q1", "generate.q2", "generate.q1_input", "blur.1.fp32", "blur.2.fp32",
                              "blur.3.fp32", "blur.4.fp32", "blur.5.fp32", "blur.6.fp32",
                              "blur.7.fp32", "blur.8.fp32", "apply.smart.fp32", "apply.smart_list.fp32", "horizon_prepare.depth",
                              "horizon_prepare.input", "horizon_prepare.z", "horizon_main.gtao", "horizon_main.bitmask",
                              "horizon_main.gtao_direct", "horizon_main.bitmask_direct",
                              "horizon_denoise.intermediate", "horizon_denoise.final", "classify", "compact", "fill",
                              /* the horizon estimators' tiles (docs/tiles.md; their own images are
                               * cleared, not filled: no key) */
                              "classify.horizon", "compact.horizon",
                              /* CACAO's CPU forms without reuse: the quiet frame's test and fill */
                              "classify.quiet",
                              /* the GPU forms: a build embeds both, the device chooses (in key order) */
                              "blur_gpu.1.fp32", "blur_gpu.2.fp32", "blur_gpu.3.fp32", "blur_gpu.4.fp32",
                              "blur_gpu.5.fp32", "blur_gpu.6.fp32", "blur_gpu.7.fp32", "blur_gpu.8.fp32",
                              "apply_gpu.smart.fp32", "prepare_gpu.full.native", "prepare_gpu.mips.native",
                              "generate_gpu.q1", "generate_gpu.q2",
                              /* the GPU forms' classification from the caller's depth, where the
                               * prepare does not classify (the caller's normals; downsampled) */
                              "classify_gpu.native",
                              /* the horizon estimators' GPU forms: direct grids, no classify,
                               * compact or fill (native: the upsample serves downsampled only) */
                              "horizon_prepare_gpu.depth", "horizon_prepare_gpu.input", "horizon_main_gpu.gtao",
                              "horizon_main_gpu.bitmask", "horizon_main_gpu.gtao_direct",
                              "horizon_main_gpu.bitmask_direct", "horizon_denoise_gpu.intermediate",
                              "horizon_denoise_gpu.final",
                              /* reuse_unchanged (no axis: any CACAO configuration may ask for it) */
                              "reuse.diff", "reuse.diff_normals", "reuse.prefix", "reuse.reach", "reuse.diff_gpu",
                              "reuse.diff_normals_gpu",
                              /* temporal_frames (no axis: any horizon estimator configuration) */
                              "horizon_temporal"};
    size_t n, kept = 0;
    cacao_key *keys = all_keys(&n);
    for (size_t i = 0; i < n; ++i) {
        char name[CACAO_KEY_NAME_MAX];
        cacaoi_key_name(&keys[i], name, sizeof name);
        bool want = false;
        for (size_t j = 0; j < sizeof expected / sizeof expected[0]; ++j)
            want |= strcmp(expected[j], name) == 0;
        if (cacaoi_key_in_subset(&keys[i], &s) != want) fprintf(stderr, "subset mismatch: %s\n", name);
        CHECK(cacaoi_key_in_subset(&keys[i], &s) == want);
        kept += want;
    }
    CHECK(kept == sizeof expected / sizeof expected[0]);
    cacao_key_subset all = CACAO_KEY_SUBSET_ALL;
    for (size_t i = 0; i < n; ++i) CHECK(cacaoi_key_in_subset(&keys[i], &all)); /* no dead keys */
    /* the horizon estimators' estimator and upsample: the half-resolution variants serve the
     * downsampled configurations only, the others the native ones only */
    cacao_key_subset native, downsampled;
    CHECK(cacaoi_key_subset_parse("high", "OFF", "fp32", &native));
    CHECK(cacaoi_key_subset_parse("high", "ONLY", "fp32", &downsampled));
    unsigned half_keys = 0;
    for (size_t i = 0; i < n; ++i) {
        const bool half = (keys[i].pass == CACAO_PASS_HORIZON_MAIN && (keys[i].variant == CACAO_HORIZON_GTAO_HALF ||
                                                                     keys[i].variant == CACAO_HORIZON_BITMASK_HALF)) ||
                          (keys[i].pass == CACAO_PASS_HORIZON_DENOISE && (keys[i].variant == CACAO_DENOISE_UPSAMPLE ||
                                                                        keys[i].variant == CACAO_DENOISE_UPSAMPLE_FINAL));
        half_keys += half;
        if (keys[i].pass == CACAO_PASS_HORIZON_MAIN) {
            CHECK(cacaoi_key_in_subset(&keys[i], &downsampled) == half);
            CHECK(cacaoi_key_in_subset(&keys[i], &native) == !half);
        }
        if (half) CHECK(cacaoi_key_in_subset(&keys[i], &downsampled) && !cacaoi_key_in_subset(&keys[i], &native));
    }
    CHECK(half_keys == 4);
    free(keys);
    CHECK(!cacaoi_key_subset_parse("ultra", "OFF", "fp32", &s));
    CHECK(!cacaoi_key_subset_parse("high", "MAYBE", "fp32", &s));
    CHECK(!cacaoi_key_subset_parse("high", "OFF", "fp64", &s));
}

int main(void) {
    test_names_round_trip();
    test_invalid_keys();
    test_name_too_long();
    test_subset();
    return test_report("test_keys");
}
