/* internal.h - declarations shared by the runtime's source files (not installed). */
#ifndef CACAO_INTERNAL_H
#define CACAO_INTERNAL_H

#include <stdarg.h>

#include "cacao.h"
#include "cacao_keys.h"
#include "cacao_passes.h"
#include "cacao_policy.h"
#include "cacao_shared.h"
#include "cacao_table.h"

/* printf-style error message into a caller buffer (NULL-safe); the one formatter of the runtime's
 * messages (cacaoi_fail writes the context's last error through it). */
void cacaoi_set_error(char *error, size_t error_size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void cacaoi_set_error_v(char *error, size_t error_size, const char *fmt, va_list ap)
    __attribute__((format(printf, 3, 0)));

/* The literal values of resolved settings: CACAO_ZERO -> 0.0f, CACAO_BLUR_NONE -> 0 blur passes.
 * Resolved settings keep those encodings so that resolving them again is the identity. */
void cacaoi_settings_literal(const cacao_settings *resolved, cacao_settings *out);

/* The key-space axes of resolved settings (what cacaoi_sequence takes). */
cacao_key_config cacaoi_key_config_of(const cacao_settings *resolved);

/* Checks the projection (finite, P(1,1) > 0, P(0,0) > 0, usable depth mapping). */
cacao_result cacaoi_check_projection(const cacao_inputs *inputs, char *error, size_t error_size);

/* spec: constants.md section 8 - fills the constant block from the plan and the frame's matrices.
 * Pure; the inputs are assumed checked by cacaoi_check_projection. */
void cacaoi_fill_constants(const cacao_plan *plan, const cacao_inputs *inputs, cacao_constants *out);

#endif
