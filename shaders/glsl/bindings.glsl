/* bindings.glsl - the one declaration of every binding slot (cacao_shared.h), each under the guard
 * the generator defines from the key's pass row: CACAO_BIND_<slot> where the row binds the slot,
 * CACAO_ACCESS_<slot> (readonly / writeonly) from its read or write, CACAO_FORMAT_<slot> from its
 * resource's format (cacaoi_key_defines). A pass's GLSL body says nothing else about its
 * resources; shadergen checks every module's reflection against its row. */

/* The constant block is declared in cacao_shared.h under CACAO_BIND_CONSTANTS (its layout is
 * shared with C). */

#ifdef CACAO_BIND_LOAD_COUNTER
layout(std430, set = 0, binding = CACAO_BINDING_LOAD_COUNTER) CACAO_ACCESS_LOAD_COUNTER buffer cacao_load_counter
{
    uint load_counter;
};
#endif

#ifdef CACAO_BIND_TILES
/* Header, classes and lists (tiles.glsl; layout in cacao_shared.h). */
layout(std430, set = 0, binding = CACAO_BINDING_TILES) CACAO_ACCESS_TILES buffer cacao_tiles { uint tiles[]; };
#endif

#ifdef CACAO_BIND_TILE_ENTRIES
/* The same buffer as the list steps read it, their entries: a texel load, which lavapipe runs per
 * invocation at a fraction of a storage buffer load's cost (tiles.glsl, group_of). */
layout(set = 0, binding = CACAO_BINDING_TILE_ENTRIES, r32ui) uniform readonly uimageBuffer tile_entries;
#endif

#ifdef CACAO_BIND_SRC_DEPTH
layout(set = 0, binding = CACAO_BINDING_SRC_DEPTH) uniform sampler2D src_depth;
#endif

#ifdef CACAO_BIND_SRC_NORMALS
layout(set = 0, binding = CACAO_BINDING_SRC_NORMALS) uniform sampler2D src_normals;
#endif

#ifdef CACAO_BIND_DEPTHS
layout(set = 0, binding = CACAO_BINDING_DEPTHS) uniform sampler2DArray depths;
#endif

#ifdef CACAO_BIND_DEPTHS_IMAGE
/* The slices' depths; with mips (CACAO_DEPTHS_MIPS, the CPU forms) the atlas of levels 0..3
 * (cacao_shared.h); in the GPU forms level 0 of the mip chain.
 * Generate loads single texels through it: on lavapipe an imageLoad costs less than the sampling
 * function a nearest textureLod calls (docs/speed-notes.md). */
layout(set = 0, binding = CACAO_BINDING_DEPTHS_IMAGE, CACAO_FORMAT_DEPTHS_IMAGE) uniform CACAO_ACCESS_DEPTHS_IMAGE
    image2DArray depths_image;
#endif

/* The GPU forms' depth mips 1..3: views of one level each of the depths' mip chain, which the
 * prepare writes and generate samples through `depths` (the CPU forms: the atlas above). */
#ifdef CACAO_BIND_DEPTHS_MIP1 /* the pass rows bind the three together (W_CHAIN, cacao_passes.c) */
#define DEPTHS_MIP_IMAGE(l)                                                                        \
    layout(set = 0, binding = CACAO_BINDING_DEPTHS_MIP##l, CACAO_FORMAT_DEPTHS_MIP##l)               \
        uniform CACAO_ACCESS_DEPTHS_MIP##l image2DArray depths_mip##l
DEPTHS_MIP_IMAGE(1);
DEPTHS_MIP_IMAGE(2);
DEPTHS_MIP_IMAGE(3);
#endif

#ifdef CACAO_BIND_NORMALS_IMAGE
layout(set = 0, binding = CACAO_BINDING_NORMALS_IMAGE, CACAO_FORMAT_NORMALS_IMAGE) uniform CACAO_ACCESS_NORMALS_IMAGE
    image2DArray normals_image;
#endif

#ifdef CACAO_BIND_SSAO
layout(set = 0, binding = CACAO_BINDING_SSAO) uniform sampler2DArray ssao;
#endif

#ifdef CACAO_BIND_SSAO_BASE
layout(set = 0, binding = CACAO_BINDING_SSAO_BASE) uniform sampler2DArray ssao_base;
#endif

#ifdef CACAO_BIND_SSAO_IMAGE
layout(set = 0, binding = CACAO_BINDING_SSAO_IMAGE, CACAO_FORMAT_SSAO_IMAGE) uniform CACAO_ACCESS_SSAO_IMAGE
    image2DArray ssao_image;
#endif

#ifdef CACAO_BIND_IMPORTANCE_MAP
layout(set = 0, binding = CACAO_BINDING_IMPORTANCE_MAP) uniform sampler2D importance_map;
#endif

#ifdef CACAO_BIND_IMPORTANCE_MAP_IMAGE
layout(set = 0, binding = CACAO_BINDING_IMPORTANCE_MAP_IMAGE, CACAO_FORMAT_IMPORTANCE_MAP_IMAGE) uniform
    CACAO_ACCESS_IMPORTANCE_MAP_IMAGE image2D importance_map_image;
#endif

/* The horizon estimators' full-resolution intermediates are storage images, also where they are
 * read: lavapipe loads those at a fraction of the cost of a sampled fetch (docs/speed-notes.md). */
#ifdef CACAO_BIND_VIEW_DEPTH
layout(set = 0, binding = CACAO_BINDING_VIEW_DEPTH, CACAO_FORMAT_VIEW_DEPTH) uniform CACAO_ACCESS_VIEW_DEPTH
    image2D view_depth;
#endif

#ifdef CACAO_BIND_VIEW_NORMALS
layout(set = 0, binding = CACAO_BINDING_VIEW_NORMALS, CACAO_FORMAT_VIEW_NORMALS) uniform CACAO_ACCESS_VIEW_NORMALS
    image2D view_normals;
#endif

#ifdef CACAO_BIND_HORIZON_AO
layout(set = 0, binding = CACAO_BINDING_HORIZON_AO, CACAO_FORMAT_HORIZON_AO) uniform CACAO_ACCESS_HORIZON_AO
    image2D horizon_ao;
#endif

#ifdef CACAO_BIND_HORIZON_AO_OUT
layout(set = 0, binding = CACAO_BINDING_HORIZON_AO_OUT, CACAO_FORMAT_HORIZON_AO_OUT) uniform
    CACAO_ACCESS_HORIZON_AO_OUT image2D horizon_ao_out;
#endif

#ifdef CACAO_BIND_HISTORY
layout(set = 0, binding = CACAO_BINDING_HISTORY, CACAO_FORMAT_HISTORY) uniform CACAO_ACCESS_HISTORY image2D history;
#endif

#ifdef CACAO_BIND_HISTORY_OUT
layout(set = 0, binding = CACAO_BINDING_HISTORY_OUT, CACAO_FORMAT_HISTORY_OUT) uniform CACAO_ACCESS_HISTORY_OUT
    image2D history_out;
#endif

#ifdef CACAO_BIND_OUTPUT
/* No format qualifier: the caller's image format (shaderStorageImageWriteWithoutFormat). */
layout(set = 0, binding = CACAO_BINDING_OUTPUT) uniform CACAO_ACCESS_OUTPUT image2D output_image;
#endif
/* Reuse (tiles.glsl): the copies the diff compares with and updates, so read and written through
 * one declaration (no access qualifier; CACAO_ACCESS_ is not used). */
#ifdef CACAO_BIND_DEPTH_HISTORY
layout(set = 0, binding = CACAO_BINDING_DEPTH_HISTORY, CACAO_FORMAT_DEPTH_HISTORY) uniform image2D depth_history;
#endif
#ifdef CACAO_BIND_NORMALS_HISTORY
layout(set = 0, binding = CACAO_BINDING_NORMALS_HISTORY, CACAO_FORMAT_NORMALS_HISTORY) uniform image2D normals_history;
#endif
