#version 450
#extension GL_GOOGLE_include_directive : enable
#extension GL_EXT_control_flow_attributes : enable
#if defined(CACAO_FP16) && CACAO_FP16 == 1
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : enable
#endif

/* cacao.comp - the one entry source of every compute pass (spec: README.md "Pass graph"), each
 * pass family in its own file under glsl/:
 *
 *   cacao_shared.h         numbers and the constant block shared with C
 *   glsl/bindings.glsl     one declaration per binding slot, guarded by the key's CACAO_BIND_<slot>
 *   glsl/common.glsl       precision, shared arithmetic, texel addressing
 *   glsl/tiles.glsl        tile lists; the classify, compact and fill passes
 *   glsl/prepare.glsl      prepare_depths, prepare_normals, prepare (fused)
 *   glsl/generate.glsl     generate (Q0..Q3, the Q3 base pass), importance_a/b
 *   glsl/blur.glsl         blur
 *   glsl/apply.glsl        apply, upsample
 *   glsl/horizon.glsl      horizon_prepare, horizon_main, horizon_denoise (GTAO, bitmask)
 *
 * The generator (shadergen) defines CACAO_GLSL, CACAO_PASS, CACAO_VARIANT, CACAO_DOWNSAMPLED,
 * CACAO_BLUR_PASSES, CACAO_FP16, CACAO_LIST, CACAO_SKIPS_BY_CLASS and CACAO_READS_CLASSES (all
 * integers) and the
 * binding guards of the key's pass row (cacaoi_key_defines), and resolves the #include lines below
 * (the GL_GOOGLE_include_directive form, relative to the including file). Each pass has its own main() under its CACAO_PASS guard.
 *
 * Out-of-bounds behaviour: AMD relies on D3D rules (an out-of-range integer load returns 0, an
 * out-of-range store is dropped). Every load and store that can leave its image is bounds-checked
 * explicitly, so nothing depends on robustImageAccess.
 */

#if !defined(CACAO_PASS) || !defined(CACAO_VARIANT) || !defined(CACAO_DOWNSAMPLED) || \
    !defined(CACAO_BLUR_PASSES) || !defined(CACAO_FP16) || !defined(CACAO_LIST) || !defined(CACAO_SKIPS_BY_CLASS) || \
    !defined(CACAO_READS_CLASSES)
#error "cacao.comp needs CACAO_PASS, CACAO_VARIANT, CACAO_DOWNSAMPLED, CACAO_BLUR_PASSES, CACAO_FP16, CACAO_LIST, CACAO_SKIPS_BY_CLASS, CACAO_READS_CLASSES"
#endif

#include "cacao_shared.h"
#include "glsl/bindings.glsl"
#include "glsl/common.glsl"
#include "glsl/tiles.glsl"
#include "glsl/prepare.glsl"
#include "glsl/generate.glsl"
#include "glsl/blur.glsl"
#include "glsl/apply.glsl"
#include "glsl/horizon.glsl"
