/* test_settings_roundtrip - one settings encoding: cacao_settings_resolve is idempotent and
 * cacao_plan_build(&plan.settings, w, h) rebuilds exactly the same plan, over every quality,
 * resolution mode, blur count (default, none, 1..8), precision, normals source and every explicit
 * zero (CACAO_ZERO in each field that accepts it). An explicit zero must still mean zero after
 * resolving twice: the constant block built from the rebuilt plan carries the literal 0. */
#include <string.h>

#include "internal.h"
#include "test_util.h"

static bool settings_equal(const cacao_settings *a, const cacao_settings *b) {
    return a->radius == b->radius && a->shadow_multiplier == b->shadow_multiplier &&
           a->shadow_power == b->shadow_power && a->shadow_clamp == b->shadow_clamp &&
           a->horizon_angle_threshold == b->horizon_angle_threshold && a->fade_out_from == b->fade_out_from &&
           a->fade_out_to == b->fade_out_to && a->sharpness == b->sharpness &&
           a->detail_shadow_strength == b->detail_shadow_strength &&
           a->adaptive_quality_limit == b->adaptive_quality_limit &&
           a->bilateral_sigma_squared == b->bilateral_sigma_squared &&
           a->bilateral_similarity_distance_sigma == b->bilateral_similarity_distance_sigma &&
           a->blur_pass_count == b->blur_pass_count && a->quality == b->quality && a->precision == b->precision &&
           a->generate_normals == b->generate_normals && a->downsample == b->downsample &&
           a->estimator == b->estimator && a->visibility == b->visibility && a->thickness == b->thickness &&
           a->horizon_slices == b->horizon_slices && a->horizon_steps == b->horizon_steps;
}

static bool plans_equal(const cacao_plan *a, const cacao_plan *b) {
    if (!settings_equal(&a->settings, &b->settings) || a->width != b->width || a->height != b->height ||
        a->slice_width != b->slice_width || a->slice_height != b->slice_height ||
        a->importance_width != b->importance_width || a->importance_height != b->importance_height ||
        a->slice_count != b->slice_count || a->step_count != b->step_count || a->image_count != b->image_count ||
        a->uses_load_counter != b->uses_load_counter || a->total_bytes != b->total_bytes)
        return false;
    for (uint32_t i = 0; i < a->step_count; ++i) {
        const cacao_plan_step *x = &a->steps[i], *y = &b->steps[i];
        if (strcmp(x->key_name, y->key_name) != 0 || memcmp(x->key, y->key, sizeof x->key) != 0 ||
            memcmp(x->dispatch, y->dispatch, sizeof x->dispatch) != 0 || x->binding_count != y->binding_count ||
            x->barrier_before != y->barrier_before || x->barrier_resources != y->barrier_resources)
            return false;
        for (uint32_t j = 0; j < x->binding_count; ++j)
            if (memcmp(&x->bindings[j], &y->bindings[j], sizeof x->bindings[j]) != 0) return false;
    }
    for (uint32_t i = 0; i < a->image_count; ++i) {
        const cacao_plan_image *x = &a->images[i], *y = &b->images[i];
        if (x->resource != y->resource || x->format != y->format || x->width != y->width || x->height != y->height ||
            x->layers != y->layers || x->mips != y->mips || x->bytes != y->bytes)
            return false;
    }
    return true;
}

static unsigned blur_steps(const cacao_plan *p) {
    unsigned n = 0;
    for (uint32_t i = 0; i < p->step_count; ++i)
        n += strncmp(p->steps[i].key_name, "blur.", 5) == 0 || strncmp(p->steps[i].key_name, "horizon_denoise.", 14) == 0;
    return n;
}

/* The float fields whose 0 means "default" and which accept CACAO_ZERO. */
static const size_t zero_fields[] = {
    offsetof(cacao_settings, horizon_angle_threshold),
    offsetof(cacao_settings, fade_out_from),
    offsetof(cacao_settings, sharpness),
    offsetof(cacao_settings, detail_shadow_strength),
    offsetof(cacao_settings, adaptive_quality_limit),
};
#define ZERO_FIELDS (sizeof zero_fields / sizeof zero_fields[0])

static unsigned checked;

static void check_one(const cacao_settings *in, uint32_t w, uint32_t h) {
    char err[256];
    cacao_settings r1, r2;
    CHECK(cacao_settings_resolve(in, &r1, err, sizeof err) == CACAO_SUCCESS);
    CHECK(cacao_settings_resolve(&r1, &r2, err, sizeof err) == CACAO_SUCCESS);
    if (!settings_equal(&r1, &r2))
        fprintf(stderr, "resolve not idempotent: quality %d blur %d\n", (int)in->quality, in->blur_pass_count);
    CHECK(settings_equal(&r1, &r2));

    cacao_plan p1, p2;
    CHECK(cacao_plan_build(in, w, h, &p1, err, sizeof err) == CACAO_SUCCESS);
    CHECK(cacao_plan_build(&p1.settings, w, h, &p2, err, sizeof err) == CACAO_SUCCESS);
    if (!plans_equal(&p1, &p2))
        fprintf(stderr, "plan not reproduced: quality %d blur %d (%u vs %u steps)\n", (int)in->quality,
                in->blur_pass_count, p1.step_count, p2.step_count);
    CHECK(plans_equal(&p1, &p2));
    CHECK(settings_equal(&p1.settings, &r1));

    /* The blur count the caller asked for, in both plans (CACAO: one step of N iterations, default
     * 2; the slice estimators: N denoise steps, default 1, downsampled N filter steps counting
     * the upsample, which always runs). */
    const bool slice = in->estimator == CACAO_ESTIMATOR_GTAO || in->estimator == CACAO_ESTIMATOR_BITMASK;
    const unsigned want_blur = in->blur_pass_count == CACAO_BLUR_NONE ? 0
                               : in->blur_pass_count == 0             ? (slice ? 1 : 2)
                                                                      : (unsigned)in->blur_pass_count;
    const unsigned want_steps = !slice ? want_blur > 0 : in->downsample && want_blur == 0 ? 1 : want_blur;
    CHECK(blur_steps(&p2) == want_steps);
    if (slice) { /* the budget: the quality level's unless given */
        /* docs/estimators.md: {slices, steps} per quality, GTAO then bitmask */
        static const int budget[2][5][2] = {{{1, 4}, {2, 4}, {2, 6}, {3, 8}, {6, 8}},
                                            {{1, 4}, {1, 6}, {2, 8}, {2, 12}, {2, 16}}};
        const int q = in->quality ? (int)in->quality - 1 : 4, e = in->estimator == CACAO_ESTIMATOR_BITMASK;
        CHECK(p2.settings.horizon_slices == (in->horizon_slices ? in->horizon_slices : budget[e][q][0]));
        CHECK(p2.settings.horizon_steps == (in->horizon_steps ? in->horizon_steps : budget[e][q][1]));
        CHECK(p2.settings.precision == CACAO_PRECISION_FP32);
    }
    for (uint32_t i = 0; i < p2.step_count; ++i)
        if (strncmp(p2.steps[i].key_name, "blur.", 5) == 0) CHECK(p2.steps[i].key[3] == want_blur);

    /* Explicit zeros are still zeros in the constant block of the rebuilt plan. */
    cacao_inputs inputs = {.projection = {1.2f, 0, 0, 0, 0, 2.1f, 0, 0, 0, 0, -1.0f, -1.0f, 0, 0, -0.1f, 0}};
    CHECK(cacaoi_check_projection(&inputs, err, sizeof err) == CACAO_SUCCESS);
    cacao_constants c;
    cacaoi_fill_constants(&p2, &inputs, &c);
    if (in->horizon_angle_threshold == CACAO_ZERO) CHECK(c.effect_horizon_angle_threshold == 0.0f);
    if (in->sharpness == CACAO_ZERO) CHECK(c.inv_sharpness == 1.0f);
    if (in->detail_shadow_strength == CACAO_ZERO) CHECK(c.detail_ao_strength == 0.0f);
    if (in->adaptive_quality_limit == CACAO_ZERO) CHECK(c.adaptive_sample_count_limit == 0.0f);
    if (in->fade_out_from == CACAO_ZERO) CHECK(c.effect_fade_out_add == 1.0f);
    ++checked;
}

int main(void) {
    const int blurs[] = {0, CACAO_BLUR_NONE, 1, 2, 3, 4, 5, 6, 7, 8};
    for (int e = 0; e <= CACAO_ESTIMATOR_BITMASK; ++e)
    for (int q = 0; q <= CACAO_QUALITY_HIGHEST; ++q)
        for (int ds = 0; ds < 2; ++ds)
            for (size_t b = 0; b < sizeof blurs / sizeof blurs[0]; ++b)
                for (int prec = 0; prec <= CACAO_PRECISION_FP16; ++prec)
                    for (int gn = 0; gn < 2; ++gn) /* zero mask: none, each field alone, all of them */
                        for (unsigned m = 0; m <= ZERO_FIELDS + 1; ++m) {
                            cacao_settings s = {.estimator = (cacao_estimator)e,
                                                .horizon_slices = m == 1 ? 5 : 0, /* an explicit budget */
                                                .horizon_steps = m == 1 ? 7 : 0,
                                                .quality = (cacao_quality)q,
                                                .downsample = ds,
                                                .blur_pass_count = blurs[b],
                                                .precision = (cacao_precision)prec,
                                                .generate_normals = gn,
                                                .radius = 0.5f + 0.25f * (float)m};
                            for (size_t f = 0; f < ZERO_FIELDS; ++f)
                                if (m == ZERO_FIELDS + 1 || m == f + 1)
                                    *(float *)((char *)&s + zero_fields[f]) = CACAO_ZERO;
                            if (e >= CACAO_ESTIMATOR_GTAO && ds && blurs[b] > CACAO_HORIZON_HALF_MAX_PASSES) {
                                cacao_settings r; /* more filter passes than downsampled runs */
                                CHECK(cacao_settings_resolve(&s, &r, NULL, 0) == CACAO_ERROR_INVALID_ARGUMENT);
                                continue;
                            }
                            check_one(&s, 97 + 13 * (uint32_t)m, 61 + 7 * (uint32_t)b);
                        }
    /* The cases the issue names: resolved once, blur none stays none and horizon 0 stays 0. */
    cacao_settings none = {.blur_pass_count = CACAO_BLUR_NONE, .horizon_angle_threshold = CACAO_ZERO}, r;
    CHECK(cacao_settings_resolve(&none, &r, NULL, 0) == CACAO_SUCCESS);
    CHECK(cacao_settings_resolve(&r, &r, NULL, 0) == CACAO_SUCCESS);
    CHECK(r.blur_pass_count == CACAO_BLUR_NONE && r.horizon_angle_threshold == CACAO_ZERO);
    printf("%u settings checked\n", checked);
    return test_report("test_settings_roundtrip");
}
