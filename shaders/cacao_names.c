/* cacao_names.c - the words of the settings enums, written once (declared in cacao_keys.h). The
 * key space names its keys and parses its subsets with them (shadergen, CACAO_QUALITIES), and
 * cacao.h's cacao_*_name functions return them (runtime/src/settings.c). It depends on nothing, so
 * a program that only parses settings (the fuzz harnesses) can take it alone. */
#include "cacao_keys.h"

const char *const cacaoi_quality_names[CACAO_KEY_QUALITY_COUNT] = {"lowest", "low", "medium", "high", "highest"};
const char *const cacaoi_precision_names[2] = {"fp32", "fp16"};
const char *const cacaoi_estimator_names[3] = {"cacao", "gtao", "bitmask"};
const char *const cacaoi_visibility_names[2] = {"falloff", "binary"};
