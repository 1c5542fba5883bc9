/* sweep.h - the named configurations of cacao the tools run (cacao-bench) and compile
 * (cacao-inspect gpu): one list in one order, one naming, one way of selecting them by name.
 *
 * A name is [gtao_|bitmask_]<quality>_<native|downsampled>[_blurN][_fp16][_gennormals]: the CACAO
 * estimator at every quality, resolution, blur 0..8, precision and normals source, then the
 * horizon-slice estimators (native, fp32) at every quality, normals source and denoise passes.
 * The default sweep is the configurations at the default blur (CACAO 2, the horizon estimators
 * 1), fp32, normals as the inputs give them. */
#ifndef CACAO_SWEEP_H
#define CACAO_SWEEP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cacao.h"

/* One configuration: what differs between the rows of a sweep. blur is literal (0 = none). */
typedef struct sweep_config {
    char name[64];
    cacao_estimator estimator;
    cacao_quality quality;
    bool downsample;
    int blur;
    bool fp16;
    bool reconstruct_normals; /* forces reconstruction; otherwise as the inputs and flags say */
} sweep_config;

/* Configurations of the full sweep. */
#define SWEEP_FULL_SIZE (5 * 2 * 2 * 2 * 9 + 2 * 5 * 2 * (9 + 9 - 2))

/* Writes the full sweep in its order; returns SWEEP_FULL_SIZE. */
uint32_t sweep_full(sweep_config out[SWEEP_FULL_SIZE]);

/* True for a configuration of the default sweep. */
bool sweep_is_default(const sweep_config *config);

/* The configurations a comma list of names or globs (fnmatch) selects, in sweep order, each once;
 * list NULL selects the default sweep, or the full one when full is true. On error (a pattern that
 * matches nothing, an empty list) writes one line naming it into err and returns false. */
bool sweep_select(const char *list, bool full, sweep_config out[SWEEP_FULL_SIZE], uint32_t *count, char *err,
                  size_t err_size);

/* base with the configuration's own fields (estimator, quality, resolution, blur, precision, and
 * normals reconstruction where it forces it). */
cacao_settings sweep_settings(const sweep_config *config, cacao_settings base);

#endif /* CACAO_SWEEP_H */
