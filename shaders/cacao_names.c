/* cacao_names.c - the words of the settings enums (see cacao_names.h). */
#include "cacao_names.h"

const char *const cacaoi_quality_names[CACAO_QUALITY_HIGHEST] = {"lowest", "low", "medium", "high", "highest"};
const char *const cacaoi_precision_names[CACAO_PRECISION_FP16] = {"fp32", "fp16"};
const char *const cacaoi_estimator_names[CACAO_ESTIMATOR_BITMASK] = {"cacao", "gtao", "bitmask"};
const char *const cacaoi_visibility_names[CACAO_VISIBILITY_BINARY] = {"falloff", "binary"};
const char *const cacaoi_shader_forms_names[CACAO_SHADER_FORMS_GPU] = {"cpu", "gpu"};
