/* sweep.c - the configurations of cacao the tools run and compile (see sweep.h). */
#include "sweep.h"

#include <fnmatch.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "image_io.h"
#include "text_file.h"

/* The blur count a configuration of this estimator has by default: CACAO 2, the horizon-slice
 * estimators 1 (their denoise passes). */
static int default_blur(cacao_estimator estimator) { return estimator == CACAO_ESTIMATOR_CACAO ? 2 : 1; }

/* Writes c->name from its fields (sweep.h's naming). */
static void name_config(sweep_config *c) {
    char estimator[16] = "", blur[16] = "";
    if (c->estimator != CACAO_ESTIMATOR_CACAO)
        snprintf(estimator, sizeof estimator, "%s_", cacao_estimator_name(c->estimator));
    if (c->blur != default_blur(c->estimator)) snprintf(blur, sizeof blur, "_blur%d", c->blur);
    snprintf(c->name, sizeof c->name, "%s%s_%s%s%s%s", estimator, cacao_quality_name(c->quality),
             c->downsample ? "downsampled" : "native", blur, c->fp16 ? "_fp16" : "",
             c->reconstruct_normals ? "_gennormals" : "");
}

/* By estimator, quality, resolution, normals, precision, then blur (the default first, then 0..8);
 * the horizon-slice estimators are fp32 only. */
uint32_t sweep_full(sweep_config out[SWEEP_FULL_SIZE]) {
    uint32_t n = 0;
    for (int e = CACAO_ESTIMATOR_CACAO; e <= CACAO_ESTIMATOR_BITMASK; ++e) {
        const int precisions = e == CACAO_ESTIMATOR_CACAO ? 2 : 1;
        for (int q = CACAO_QUALITY_LOWEST; q <= CACAO_QUALITY_HIGHEST; ++q)
            for (int ds = 0; ds < 2; ++ds)
                for (int gen = 0; gen < 2; ++gen)
                    for (int fp16 = 0; fp16 < precisions; ++fp16)
                        for (int k = -1; k <= 8; ++k) {
                            const int blur = k < 0 ? default_blur((cacao_estimator)e) : k;
                            if (k == default_blur((cacao_estimator)e)) continue; /* listed first */
                            if (e != CACAO_ESTIMATOR_CACAO && ds && blur > CACAO_HORIZON_HALF_MAX_PASSES) continue;
                            sweep_config *c = &out[n++];
                            *c = (sweep_config){.estimator = (cacao_estimator)e,
                                                .quality = (cacao_quality)q,
                                                .downsample = ds,
                                                .blur = blur,
                                                .fp16 = fp16,
                                                .reconstruct_normals = gen};
                            name_config(c);
                        }
    }
    return n;
}

bool sweep_is_default(const sweep_config *c) {
    return c->blur == default_blur(c->estimator) && !c->fp16 && !c->reconstruct_normals;
}

bool sweep_select(const char *list, bool full, sweep_config out[SWEEP_FULL_SIZE], uint32_t *count, char *err,
                  size_t err_size) {
    static sweep_config all[SWEEP_FULL_SIZE];
    const uint32_t total = sweep_full(all);
    bool chosen[SWEEP_FULL_SIZE] = {0};
    if (!list) {
        for (uint32_t i = 0; i < total; ++i) chosen[i] = full || sweep_is_default(&all[i]);
    } else { /* all of the list, however long */
        char *patterns = strdup(list);
        if (!patterns) return cacao_set_err(err, err_size, "out of memory");
        char *save = NULL;
        bool ok = true;
        for (char *p = strtok_r(patterns, ",", &save); ok && p; p = strtok_r(NULL, ",", &save)) {
            bool any = false;
            for (uint32_t i = 0; i < total; ++i)
                if (fnmatch(p, all[i].name, 0) == 0) any = chosen[i] = true;
            if (!any) {
                char shown[256];
                cacao_escape_text(p, shown, sizeof shown);
                ok = cacao_set_err(err, err_size, "'%s' matches no configuration", shown);
            }
        }
        free(patterns);
        if (!ok) return false;
    }
    *count = 0;
    for (uint32_t i = 0; i < total; ++i)
        if (chosen[i]) out[(*count)++] = all[i];
    return *count ? true : cacao_set_err(err, err_size, "empty list");
}

cacao_settings sweep_settings(const sweep_config *c, cacao_settings base) {
    base.estimator = c->estimator;
    base.quality = c->quality;
    base.downsample = c->downsample;
    base.blur_pass_count = c->blur == 0 ? CACAO_BLUR_NONE : c->blur;
    base.precision = c->fp16 ? CACAO_PRECISION_FP16 : CACAO_PRECISION_FP32;
    if (c->reconstruct_normals) base.generate_normals = true;
    return base;
}
