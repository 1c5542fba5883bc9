/* cacao_names.h - the words of the settings enums, each list written once (cacao_names.c), indexed
 * by the cacao.h value - 1 (no "default"): quality "lowest" .. "highest" (also the key quality),
 * precision "fp32", "fp16" (also a key's fp16), estimator "cacao", "gtao", "bitmask", visibility
 * "falloff", "binary", shader forms "cpu", "gpu". The key space names its keys and parses its subsets with them (shadergen,
 * CACAO_QUALITIES), and cacao.h's cacao_*_name functions return them (runtime/src/settings.c).
 * Depends on cacao.h only, so a program that only parses settings (the fuzz harnesses) can take
 * cacao_names.c alone. */
#ifndef CACAO_NAMES_H
#define CACAO_NAMES_H

#include "cacao.h"

extern const char *const cacaoi_quality_names[CACAO_QUALITY_HIGHEST];
extern const char *const cacaoi_precision_names[CACAO_PRECISION_FP16];
extern const char *const cacaoi_estimator_names[CACAO_ESTIMATOR_BITMASK];
extern const char *const cacaoi_visibility_names[CACAO_VISIBILITY_BINARY];
extern const char *const cacaoi_shader_forms_names[CACAO_SHADER_FORMS_GPU];

#endif /* CACAO_NAMES_H */
