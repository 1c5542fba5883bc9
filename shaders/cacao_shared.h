/* cacao_shared.h - the one header shared by the C runtime, the generator and the GLSL source.
 *
 * Everything whose value or layout must agree between host and shader lives here exactly once:
 * the constant-buffer block, binding numbers, workgroup sizes and the numeric tables of the
 * algorithm (spec: constants.md). Which pass binds what, in which format, is the pass table's
 * (cacao_passes.h).
 *
 * It is valid C11 and valid GLSL 4.50: the GLSL side is selected by CACAO_GLSL, which the
 * generator defines in front of every shader. Keep it to #defines, the constants block and plain
 * numbers so that both languages read it the same way.
 */
#ifndef CACAO_SHARED_H
#define CACAO_SHARED_H

/* ---- Pass identifiers (the "pass" axis of the permutation key, also CACAO_PASS in GLSL) ---- */
#define CACAO_PASS_PREPARE_DEPTHS 0
#define CACAO_PASS_PREPARE_NORMALS 1
#define CACAO_PASS_GENERATE 2
#define CACAO_PASS_IMPORTANCE_A 3
#define CACAO_PASS_IMPORTANCE_B 4
#define CACAO_PASS_BLUR 5
#define CACAO_PASS_APPLY 6
#define CACAO_PASS_UPSAMPLE 7
/* Horizon-slice estimators (GTAO, visibility bitmask; spec: estimators.md), full resolution. */
#define CACAO_PASS_HORIZON_PREPARE 8        /* view z (R32F) and view normals, one texel per pixel */
#define CACAO_PASS_HORIZON_MAIN 9           /* the estimator: raw visibility per pixel */
#define CACAO_PASS_HORIZON_DENOISE 10       /* 3x3 depth/normal-aware filter (estimators.md section 5) */
/* Tile classification (docs/tiles.md): which tiles a frame computes, and the value of the rest. */
#define CACAO_PASS_CLASSIFY 11            /* one class per tile: active, faded or background */
#define CACAO_PASS_COMPACT 12             /* the tile lists and indirect dispatch commands */
#define CACAO_PASS_FILL 13                /* AO 1 where no pass computes it */
/* Prepare with normals from depth: the depths (CACAO_DEPTHS_* variants) and the normals in one
 * pass; PREPARE_DEPTHS and PREPARE_NORMALS run instead where the caller gives normals. */
#define CACAO_PASS_PREPARE 14
/* The GPU forms (cacao_shader_forms) of the blur and apply: the same arithmetic and output,
 * shaped for a GPU (shared memory and few texels per invocation, the hardware sampler). The
 * upsample has one form: one half-res position per thread cost a GPU compiler's estimate more
 * (navi21: 26.3 against 17.1 Mcycles at 1920x1080, docs/gpu.md) than the 2x2 positions of the
 * shared form. */
#define CACAO_PASS_BLUR_GPU 15
#define CACAO_PASS_APPLY_GPU 16
/* The prepare with normals from depth and the generate, as GPU forms: the same values from less
 * arithmetic per texel (docs/gpu.md "The GPU forms of prepare and generate"). */
#define CACAO_PASS_PREPARE_GPU 17
#define CACAO_PASS_GENERATE_GPU 18
/* Reuse of the previous frame (cacao_settings.reuse_unchanged, docs/tiles.md "Reusing the previous
 * frame"): which tiles' inputs changed, and which tiles' output a change can reach. */
#define CACAO_PASS_REUSE 19
/* The horizon estimators' GPU forms: the same passes on direct grids, with no classify, compact or
 * fill pass. The prepare classifies the tiles of the pixels it stores (every tile), the estimator
 * and the denoise passes run every group and store AO 1 in a group that is not needed (the CPU
 * forms: lists of the needed tiles, clears and fills for the rest; docs/tiles.md). */
#define CACAO_PASS_HORIZON_PREPARE_GPU 20
#define CACAO_PASS_HORIZON_MAIN_GPU 21
#define CACAO_PASS_HORIZON_DENOISE_GPU 22
/* CACAO's GPU forms with the caller's normals, where no prepare classifies: the tile classes from
 * the caller's depth, the texels and view z the prepare stores, dispatched before the prepare with
 * no barrier between them (docs/tiles.md). */
#define CACAO_PASS_CLASSIFY_GPU 23
/* The horizon estimators' temporal accumulation (cacao_settings.temporal_frames), after the last
 * filter pass, both forms: the frame's AO blended into the history reprojected from the last
 * frame, into the output and the next history (the two history images trade roles every frame). */
#define CACAO_PASS_HORIZON_TEMPORAL 24
#define CACAO_PASS_COUNT 25

/* Depth-prepare variants (spec: prepare.md). HALF = slices 0 and 3 only (LOWEST), FULL = four
 * slices, MIPS = four slices plus mips 1..3 (HIGH and HIGHEST; MEDIUM never reads mips) in the
 * atlas (the CPU forms); MIPS_CHAIN = the same levels as the image's mip levels (the GPU forms,
 * whose generate samples them with the sampler's level and texel choice; PREPARE_GPU's MIPS
 * variant writes the chain too). */
#define CACAO_DEPTHS_HALF 0
#define CACAO_DEPTHS_FULL 1
#define CACAO_DEPTHS_MIPS 2
#define CACAO_DEPTHS_MIPS_CHAIN 3

/* Generate variants: shader quality index q (Q0..Q3, spec: generate.md) plus the Q3 base pass. */
#define CACAO_GENERATE_Q0 0
#define CACAO_GENERATE_Q1 1
#define CACAO_GENERATE_Q2 2
#define CACAO_GENERATE_Q3 3
#define CACAO_GENERATE_Q3_BASE 4
/* Q0 and Q1 with the caller's normals (the CPU forms' generate only): they read no normal but the
 * texel's own, so generate transforms the caller's normal itself (prepare_normals' arithmetic and
 * its image's rounding) and no prepare_normals pass runs (docs/tiles.md "The normals where they
 * are read") */
#define CACAO_GENERATE_Q0_INPUT 5
#define CACAO_GENERATE_Q1_INPUT 6

/* Output variants shared by apply (native) and upsample (downsampled), spec: apply.md, upsample.md */
#define CACAO_OUTPUT_SMART 0
#define CACAO_OUTPUT_NON_SMART 1
#define CACAO_OUTPUT_HALF 2
/* The upsample's variants over compact's list of the needed tiles (CACAO_LIST_PREPARE): the CPU
 * forms without reuse, the output's other tiles filled with 1 (docs/tiles.md) */
#define CACAO_UPSAMPLE_LISTED 3 /* + CACAO_OUTPUT_*: smart_list, nonsmart_list, half_list */
/* Smart apply (native) over compact's list of the blocks of 2x2 tiles holding a needed tile
 * (CACAO_LIST_PREPARE; a group is a block): the CPU forms without reuse. The non-smart and half
 * applies (LOWEST, LOW) over compact's list of the tiles whose quads touch a needed tile (a group
 * is a tile), on frames that skip much: they run after the direct apply, whose gate compact
 * closes where it lists them (docs/tiles.md "Apply over a list where the frame skips much"). */
#define CACAO_APPLY_SMART_LIST 3
#define CACAO_APPLY_NONSMART_LIST 4
#define CACAO_APPLY_HALF_LIST 5
/* Compact lists the non-smart and half applies' groups where at most this share of the tiles is
 * active (classify's count), 2/3: below it the direct apply over every group and the fills of
 * every skipped tile cost more than the list's apply and compact's stores of the output's 1s;
 * measured on lavapipe, the two broke even at about 3/4 (docs/tiles.md "Apply over a list where
 * the frame skips much"). Either way the output is the same. */
#define CACAO_APPLY_LIST_ACTIVE_NUM 2
#define CACAO_APPLY_LIST_ACTIVE_DEN 3
/* That rule, for compact (tiles.glsl) and the tools that report its choice: active and tiles
 * unsigned (a GLSL uint, a C unsigned type) */
#define CACAO_APPLY_LISTS(active, tiles) \
    ((active) * CACAO_APPLY_LIST_ACTIVE_DEN <= (tiles) * CACAO_APPLY_LIST_ACTIVE_NUM)

/* prepare_normals' variants: every texel, or the tiles of CACAO_LIST_NORMALS (a group each) */
#define CACAO_PREPARE_NORMALS_LISTED 1

/* Slice-prepare variants: normals reconstructed from depth, or transformed from the input; or
 * (the CPU form) the view z alone, where no pass reads the normals or, with normals from depth,
 * before the normals, which the CPU form then computes from the stored view z (docs/tiles.md). */
#define CACAO_HORIZON_NORMALS_DEPTH 0
#define CACAO_HORIZON_NORMALS_INPUT 1
#define CACAO_HORIZON_VIEW_Z_ONLY 2

/* Slice-main variants: estimator (GTAO or bitmask) x destination (raw intermediate for the
 * denoiser, or the caller's output when no denoise pass runs); the _HALF variants (downsampled)
 * compute one pixel of each 2x2 block into the half-size intermediate. */
#define CACAO_HORIZON_GTAO 0
#define CACAO_HORIZON_BITMASK 1
#define CACAO_HORIZON_GTAO_DIRECT 2
#define CACAO_HORIZON_BITMASK_DIRECT 3
#define CACAO_HORIZON_GTAO_HALF 4
#define CACAO_HORIZON_BITMASK_HALF 5

/* Slice-denoise variants: into the ping-pong intermediate, or (the last pass) into the output;
 * the _UPSAMPLE variants (downsampled: always the first pass) filter the half-resolution AO up to
 * every pixel. */
#define CACAO_DENOISE_INTERMEDIATE 0
#define CACAO_DENOISE_FINAL 1
#define CACAO_DENOISE_UPSAMPLE 2
#define CACAO_DENOISE_UPSAMPLE_FINAL 3

/* The temporal pass has one variant. */
#define CACAO_TEMPORAL_RESOLVE 0

/* Classify variants (docs/tiles.md): from CACAO's deinterleaved depths, or from the horizon
 * estimators' full-resolution view z (their "slice" is the image: a tile is 8x8 pixels). */
#define CACAO_CLASSIFY_SLICES 0
#define CACAO_CLASSIFY_HORIZON 1
/* CACAO's CPU forms without reuse, first in the frame: whether any pixel of the caller's depth can
 * make a texel that is not quiet (conservatively, from the raw depth); where none can, the frame
 * is quiet: only this test runs, and it stores the output's 1s (docs/tiles.md "A quiet frame") */
#define CACAO_CLASSIFY_QUIET 2

/* Fill variants: AO 1 into the slices' AO (CACAO) or into the horizon estimators' AO intermediate;
 * or the view z (-1) and normal the horizon prepare stores for background; or CACAO's importance
 * map's 0. The slices' is a dispatch over the unneeded tiles; the others are clears of the whole
 * image before the passes that write the needed tiles (cacao_plan_step.clear). The caller's
 * output gets its 1s from compact (the unneeded tiles) or classify.quiet (a quiet frame). */
#define CACAO_FILL_SLICES 0
#define CACAO_FILL_HORIZON 1
#define CACAO_FILL_VIEW 2
#define CACAO_FILL_IMPORTANCE 3 /* a clear of the importance map to 0 (the Q3 base pass over its list) */

/* Reuse variants: compare the caller's depth (and normals) with the copy the previous frame kept,
 * per tile; sum the changed tiles along each row of tiles; mark the tiles to recompute. */
#define CACAO_REUSE_DIFF 0
#define CACAO_REUSE_DIFF_NORMALS 1
#define CACAO_REUSE_PREFIX 2
#define CACAO_REUSE_REACH 3
#define CACAO_REUSE_DIFF_GPU 4         /* the GPU forms' diffs: one invocation per 2x2 pixels, a group */
#define CACAO_REUSE_DIFF_NORMALS_GPU 5 /* per 16x16 pixels (the CPU forms: one invocation per tile) */

/* Compact variants: CACAO's lists, or the horizon estimators' (also prepare and background). */
#define CACAO_COMPACT_SLICES 0
#define CACAO_COMPACT_HORIZON 1

/* ---- Tiles (docs/tiles.md) ----
 * A tile is CACAO_TILE x CACAO_TILE slice texels (all layers). A texel is quiet when its AO is 1
 * whatever its neighbourhood: it is background (view z at the far plane or invalid) or the
 * fade-out has taken it entirely. A tile is active when some texel of it is not quiet, and
 * needed when a tile within one tile of it is active; generate runs over the needed tiles and the
 * blur over the groups that touch one; the other tiles' AO is filled with 1. One tile of margin
 * covers every blur (at most 8 iterations reach 8 texels) and the apply/upsample footprint.
 *
 * The tile buffer, in uints (the macros below are its one description, for C and GLSL):
 *   header   CACAO_TILE_HEADER uints: one VkDispatchIndirectCommand (x, y, z) per list (list l at
 *            CACAO_TILE_COMMAND(l)), the tile counts per class (CACAO_TILE_COUNT_*), and the
 *            entries per list (list l at CACAO_TILE_LIST_ENTRIES(l));
 *   classes  one uint per tile, from CACAO_TILE_CLASSES;
 *   lists    up to one entry per tile each (the blur list holds one per blur group, the blocks
 *            list one per block of 2x2 tiles: fewer); list l starts at CACAO_TILE_LIST_BASE(l, tiles);
 *   needed   a flag per tile, then one per blur group (CACAO_TILE_NEEDED, CACAO_TILE_BLUR_NEEDED);
 *   reuse    per tile: its changed flag, its least view z (as uint bits), the changed tiles of its
 *            row up to it, its recompute flag; then a recompute flag per blur group
 *            (CACAO_TILE_CHANGED .. CACAO_TILE_BLUR_RECOMPUTE: only with reuse_unchanged, which
 *            the flags' readers check);
 *   gates    one VkDispatchIndirectCommand per step (CACAO_TILE_GATE): a step that runs over the
 *            whole image whether one tile or all changed, and not at all when none did.
 * A list is dispatched as a grid x wide (tiles_x, blur_groups_x for the blur, a row of blocks
 * (tiles_x + 1) / 2 for the blocks) and as many rows as its entries fill (lavapipe runs a 1D grid
 * of the same groups slower, and the Q3 base pass's blocks 8% slower in rows tiles_x wide); group (x, y)
 * takes entry y width + x, and a group past the last entry finds CACAO_TILE_NO_ENTRY (the host
 * fills the lists with it) and returns. List entries are group coordinates x | y << 16. */
#define CACAO_TILE 8
#define CACAO_LIST_NONE 0                /* a direct dispatch */
#define CACAO_LIST_GENERATE 1            /* needed tiles (one generate group each, z = layers) */
#define CACAO_LIST_FILL_SLICES 2         /* tiles that are not needed (z 1: a group fills every layer) */
#define CACAO_LIST_PREPARE 3             /* horizon estimators: the tiles not all background where their
                                            prepare stores the view z alone (beyond two of an active
                                            tile; every one with normals from depth, before the
                                            normals' prepare, which reads it);
                                            CACAO, the CPU forms without reuse: the groups of the
                                            upsample (downsampled: the needed tiles) or of smart
                                            apply (native: blocks of 2x2 tiles holding one) */
#define CACAO_LIST_BLUR 4                /* blur groups touching a needed tile (z = layers) */
#define CACAO_LIST_BLOCKS 5              /* blocks of 2x2 tiles holding an active tile (CPU forms): a group
                                            each of CACAO's Q3 base pass (HIGHEST) and of the horizon
                                            estimators' downsampled estimator; the rest is quiet */
#define CACAO_LIST_NORMALS 6             /* tiles within two tiles of an active one (CACAO's CPU forms
                                            without reuse, the caller's normals): prepare_normals.list,
                                            a group each; generate reads the normals of the needed
                                            tiles and one texel around them. The horizon estimators'
                                            CPU forms: their prepare of the normals (the caller's:
                                            with the view z), the tiles not all background whose
                                            normals the estimator and denoise passes read */
#define CACAO_LIST_COUNT 6
#define CACAO_TILE_HEADER 32
#define CACAO_TILE_COMMAND(list) (3 * ((list) - 1)) /* header: list's indirect command (x, y, z) */
#define CACAO_TILE_COUNT_ACTIVE 18       /* header: tiles per class */
#define CACAO_TILE_COUNT_FADED 19
#define CACAO_TILE_COUNT_BACKGROUND 20
#define CACAO_TILE_LIST_ENTRIES(list) (CACAO_TILE_COUNT_BACKGROUND + (list)) /* header: entries in list */
#define CACAO_TILE_COUNT_NEEDED 27       /* header: needed tiles and blur groups (classify's flags), */
#define CACAO_TILE_COUNT_BLUR_NEEDED 28  /* counted by the GPU forms' generate and blur as they run them */
#define CACAO_TILE_COUNT_CHANGED 29      /* header, reuse: tiles whose depth (or normals) changed */
#define CACAO_TILE_COUNT_RECOMPUTE 30    /* header, reuse: tiles whose output a change can reach */
#define CACAO_TILE_NOT_QUIET 31          /* header: 1 once classify.quiet found a pixel that is not quiet */
#define CACAO_TILE_CLASSES CACAO_TILE_HEADER /* first tile class */
/* First entry of list 1..6 (tiles: tiles_x tiles_y): a tile's worth of entries each (a plan has
 * no more blur groups than tiles: cacao_plan_build checks); the uints of the whole buffer. */
#define CACAO_TILE_LIST_BASE(list, tiles) (CACAO_TILE_CLASSES + (tiles) * (list))
/* After the lists: one flag per tile and one per blur group, 0 where the lists would hold it
 * (a tile within one tile of an active one; a blur group touching such a tile), else
 * CACAO_TILE_NO_ENTRY as the host's fill left it. classify marks them from each active tile; the
 * GPU forms of generate and the blur read their group's (cacaoi_skips_by_class). */
#define CACAO_TILE_NEEDED(tiles, blur_groups) CACAO_TILE_LIST_BASE(CACAO_LIST_COUNT + 1, tiles) /* after the last list */
#define CACAO_TILE_BLUR_NEEDED(tiles, blur_groups) (CACAO_TILE_NEEDED(tiles, blur_groups) + (tiles))
#define CACAO_TILE_CHANGED(tiles, blur_groups) (CACAO_TILE_BLUR_NEEDED(tiles, blur_groups) + (blur_groups))
#define CACAO_TILE_ZMIN(tiles, blur_groups) (CACAO_TILE_CHANGED(tiles, blur_groups) + (tiles))
#define CACAO_TILE_ROW_SUM(tiles, blur_groups) (CACAO_TILE_ZMIN(tiles, blur_groups) + (tiles))
#define CACAO_TILE_RECOMPUTE(tiles, blur_groups) (CACAO_TILE_ROW_SUM(tiles, blur_groups) + (tiles))
#define CACAO_TILE_BLUR_RECOMPUTE(tiles, blur_groups) (CACAO_TILE_RECOMPUTE(tiles, blur_groups) + (tiles))
#define CACAO_TILE_GATES(tiles, blur_groups) (CACAO_TILE_BLUR_RECOMPUTE(tiles, blur_groups) + (blur_groups))
#define CACAO_TILE_GATE_MAX 18           /* gate commands (cacao.h's CACAO_PLAN_MAX_STEPS) */
/* After the gates: each gate's full grid x, which classify.quiet copies into a gate the host
 * wrote with x 0 (a frame that is not quiet opens the gates) */
#define CACAO_TILE_GATE_GRIDS(tiles, blur_groups) (CACAO_TILE_GATES(tiles, blur_groups) + 3 * CACAO_TILE_GATE_MAX)
#define CACAO_TILE_BUFFER_UINTS(tiles, blur_groups) (CACAO_TILE_GATE_GRIDS(tiles, blur_groups) + CACAO_TILE_GATE_MAX)
#define CACAO_TILE_NO_ENTRY 0xffffffffu  /* list slots past the last entry (the host fills them) */
#define CACAO_TILE_CLASS_ACTIVE 0
#define CACAO_TILE_CLASS_FADED 1
#define CACAO_TILE_CLASS_BACKGROUND 2
#define CACAO_WG_COMPACT 64
#define CACAO_WG_CLASSIFY 8              /* 8x8 tiles per group, one invocation each */

/* ---- Descriptor bindings (set 0, pushed with VK_KHR_push_descriptor) ----
 * One slot per role: each slot has one descriptor kind and one GLSL type (shaders/glsl/bindings.glsl
 * declares it once), and is named by what it holds. A content read both through a sampler and as a
 * storage image has two slots, the storage one named _IMAGE. Which pass binds which slot, to which
 * resource, reading or writing, is the pass table's (cacao_passes.c); every slot is used by some
 * pass (test_pass_table). */
#define CACAO_BINDING_CONSTANTS 0        /* uniform block cacao_constants */
#define CACAO_BINDING_LOAD_COUNTER 1     /* storage buffer, one uint (HIGHEST) */
#define CACAO_BINDING_TILES 2            /* storage buffer: tile classes, lists, indirect commands */
#define CACAO_BINDING_SRC_DEPTH 3        /* caller's depth, sampler2D, nearest */
#define CACAO_BINDING_SRC_NORMALS 4      /* caller's normals, sampler2D, nearest */
#define CACAO_BINDING_DEPTHS 5           /* deinterleaved view z, sampler2DArray, nearest */
#define CACAO_BINDING_DEPTHS_IMAGE 6     /* the same as image2DArray r16f (prepare writes, generate loads) */
#define CACAO_BINDING_NORMALS_IMAGE 7    /* deinterleaved normals, image2DArray rgba8_snorm */
#define CACAO_BINDING_SSAO 8             /* AO + packed edges, sampler2DArray, linear */
#define CACAO_BINDING_SSAO_BASE 9        /* the Q3 base pass's AO, sampler2DArray, nearest */
#define CACAO_BINDING_SSAO_IMAGE 10      /* AO + packed edges, image2DArray rg8 (written) */
#define CACAO_BINDING_IMPORTANCE_MAP 11  /* importance map, sampler2D, linear */
#define CACAO_BINDING_IMPORTANCE_MAP_IMAGE 12 /* the same as image2D r8 (written) */
#define CACAO_BINDING_VIEW_DEPTH 13      /* horizon estimators: full-res view z, image2D r32f */
#define CACAO_BINDING_VIEW_NORMALS 14    /* horizon estimators: full-res view normals, image2D rgba8_snorm */
#define CACAO_BINDING_HORIZON_AO 15      /* horizon estimators: visibility to denoise, image2D r16f (read) */
#define CACAO_BINDING_HORIZON_AO_OUT 16  /* horizon estimators: visibility, image2D r16f (written) */
#define CACAO_BINDING_OUTPUT 17          /* caller's output, image2D, written without format */
#define CACAO_BINDING_DEPTH_HISTORY 18   /* reuse: the depth the last frame read, image2D rgba32f, 2x2 pixels a texel */
#define CACAO_BINDING_NORMALS_HISTORY 19 /* reuse: the input normals it read, image2D rgba32f (read and written) */
#define CACAO_BINDING_DEPTHS_MIP1 20     /* the GPU forms' depth mip chain: level 1 of the depths, image2DArray r16f */
#define CACAO_BINDING_DEPTHS_MIP2 21     /* level 2 */
#define CACAO_BINDING_DEPTHS_MIP3 22     /* level 3 */
#define CACAO_BINDING_HISTORY 23         /* temporal: the history read, image2D rg32f */
#define CACAO_BINDING_HISTORY_OUT 24     /* temporal: the history written, image2D rg32f */
#define CACAO_BINDING_TILE_ENTRIES 25    /* the tile buffer read through an R32_UINT texel view: a list step's entries */
#define CACAO_BINDING_COUNT 26

/* ---- Workgroup sizes (x, y); z is always 1 ---- */
#define CACAO_WG_PREPARE_X 8
#define CACAO_WG_PREPARE_Y 8
#define CACAO_WG_GENERATE_X 8
#define CACAO_WG_GENERATE_Y 8
#define CACAO_WG_IMPORTANCE_X 8
#define CACAO_WG_IMPORTANCE_Y 8
#define CACAO_WG_BLUR_X 8
#define CACAO_WG_BLUR_Y 8
#define CACAO_BLUR_BLOCK_X 8             /* texels each blur thread owns, x */
#define CACAO_BLUR_BLOCK_Y 4             /* ... and y: 64x32 per group */
#define CACAO_BLUR_REGISTER_PASSES 3     /* up to this many passes, footprints in registers (blur.md in cacao.comp) */
/* Output texels per blur workgroup for N iterations: the padded tile less N on each side. */
/* Output texels of a blur group of n passes: all its blocks, or its padded tile less n each side. */
#define CACAO_BLUR_OUT_X(n) (CACAO_WG_BLUR_X * CACAO_BLUR_BLOCK_X - ((n) <= CACAO_BLUR_REGISTER_PASSES ? 0 : 2 * (n)))
#define CACAO_BLUR_OUT_Y(n) (CACAO_WG_BLUR_Y * CACAO_BLUR_BLOCK_Y - ((n) <= CACAO_BLUR_REGISTER_PASSES ? 0 : 2 * (n)))
/* The GPU form: 16x16 threads of 4x3 texels, a 64x48 padded tile in shared memory for every n. */
#define CACAO_WG_BLUR_GPU_X 16
#define CACAO_WG_BLUR_GPU_Y 16
#define CACAO_BLUR_GPU_BLOCK_X 4
#define CACAO_BLUR_GPU_BLOCK_Y 3
#define CACAO_BLUR_GPU_OUT_X(n) (CACAO_WG_BLUR_GPU_X * CACAO_BLUR_GPU_BLOCK_X - 2 * (n))
#define CACAO_BLUR_GPU_OUT_Y(n) (CACAO_WG_BLUR_GPU_Y * CACAO_BLUR_GPU_BLOCK_Y - 2 * (n))
#define CACAO_WG_APPLY_X 8
#define CACAO_WG_APPLY_Y 8
#define CACAO_WG_UPSAMPLE_X 8
#define CACAO_WG_UPSAMPLE_Y 8
#define CACAO_UPSAMPLE_BLOCK 2           /* each upsample thread filters BxB half-res positions */
#define CACAO_UPSAMPLE_SPAN_X (CACAO_WG_UPSAMPLE_X * CACAO_UPSAMPLE_BLOCK) /* half-res per group */
#define CACAO_UPSAMPLE_SPAN_Y (CACAO_WG_UPSAMPLE_Y * CACAO_UPSAMPLE_BLOCK)
#define CACAO_WG_HORIZON_X 8               /* slice prepare, main and denoise: one pixel per thread */
#define CACAO_WG_HORIZON_Y 8

/* ---- Depth mips. Intermediate formats live in the resource rows (cacao_passes.c); the shader
 * gets each storage image's qualifier as CACAO_FORMAT_<binding> from the generator. ---- */
#define CACAO_DEPTH_MIP_COUNT 4
/* Depth mip levels for a slice whose larger side is n: the full chain, at most
 * CACAO_DEPTH_MIP_COUNT (the levels a mip chain of that size has: floor(log2(n)) + 1; slices
 * narrower than 8 texels, i.e. images below 15 pixels native or 29 downsampled, get fewer). */
#define CACAO_DEPTH_MIP_LEVELS(n) ((n) >= 8 ? 4 : (n) >= 4 ? 3 : (n) >= 2 ? 2 : 1)
/* The depth atlas (HIGH, HIGHEST: the qualities whose taps read mips). Each layer holds the whole
 * chain in one single-level image: level 0 (the slice, w x h) at the origin, levels 1.. stacked
 * downwards to its right, level l at (w, y(l)) with y(1) = 0, y(l + 1) = y(l) + h(l). The atlas is
 * w + w(1) wide and max(h, y(levels)) tall. One level per image makes every tap a single-level
 * sample; the level and its texel are chosen in the shader (docs/speed-notes.md: lavapipe's
 * sampler looks up each lane's level with per-lane loads). Extent of level l of a side of n texels,
 * and the row where level l starts: */
#define CACAO_DEPTH_LEVEL_EXTENT(n, l) (((n) >> (l)) > 0 ? ((n) >> (l)) : 1)
#define CACAO_DEPTH_ATLAS_Y(h, l)                                                                  \
    (((l) >= 2 ? CACAO_DEPTH_LEVEL_EXTENT(h, 1) : 0) + ((l) >= 3 ? CACAO_DEPTH_LEVEL_EXTENT(h, 2) : 0) + \
     ((l) >= 4 ? CACAO_DEPTH_LEVEL_EXTENT(h, 3) : 0))

/* ---- Algorithm constants (spec: constants.md section 2 and 3) ---- */
#define CACAO_MAX_TAPS 32
#define CACAO_TAPS_Q0 3
#define CACAO_TAPS_Q1 5
#define CACAO_TAPS_Q2 12
#define CACAO_TAPS_Q3_BASE 5
#define CACAO_ADAPTIVE_TAP_BASE_COUNT 5
#define CACAO_ADAPTIVE_TAP_FLEXIBLE_COUNT 27
#define CACAO_BASE_WEIGHT_SCALE 20.0     /* base weight stored as sum / 20 (5 taps * 4) */
#define CACAO_HALO_AMOUNT 0.6
#define CACAO_NORMAL_EDGE_THRESHOLD 0.5
#define CACAO_MIP_OFFSET -4.3
#define CACAO_NEAR_LIMIT_SCALE 0.8
#define CACAO_NEAR_LIMIT_BIAS 0.2
#define CACAO_LOOKUP_RADIUS_FACTOR 0.85
#define CACAO_DETAIL_FALLOFF_MUL 4.0
#define CACAO_EDGE_SLOPE 1.3
#define CACAO_EDGE_DEPTH_FRACTION 0.04
#define CACAO_EDGE_FADE 0.35
#define CACAO_EDGE_PACK_SCALE 3.05
#define CACAO_NORMAL_BIAS_Z -0.0005
#define CACAO_DEPTH_PRECISION_OFFSET_MOD 0.9992
#define CACAO_STRENGTH_MULTIPLIER 4.3
#define CACAO_IMPORTANCE_POWER 0.8
#define CACAO_LOAD_COUNTER_STRIDE 3
#define CACAO_BLUR_CENTRE_WEIGHT 0.5
#define CACAO_BILATERAL_EPSILON 1e-3
#define CACAO_MAX_VIEW_Z 65504.0      /* largest half value: the view z of invalid depths */
#define CACAO_MIP_WEIGHT_FALLOFF -1.0    /* [quirk] MIP-WEIGHT-PRECEDENCE, kept: -1, not -1/R^2 */
#define CACAO_NEAR_LIMIT_RADIUS_FACTOR 1.2
#define CACAO_LOW_NEAR_LIMIT_FACTOR 1.5
#define CACAO_LOWEST_RADIUS_FACTOR 0.8

/* ---- Horizon-slice estimators (spec: estimators.md sections 2-6) ---- */
#define CACAO_HORIZON_GTAO_RADIUS_FACTOR 1.457   /* k_R of GTAO; bitmask uses R itself */
#define CACAO_HORIZON_GTAO_FALLOFF_RANGE 0.615   /* r_f, falloff visibility */
#define CACAO_HORIZON_GTAO_BINARY_FALLOFF_RANGE 0.3 /* r_f, binary visibility */
#define CACAO_HORIZON_MIN_OFFSET_PX 1.3          /* nearest sample offset: never the centre pixel */
#define CACAO_HORIZON_THICKNESS_FALLOFF 1.0      /* bitmask thickness / R, falloff visibility */
#define CACAO_HORIZON_THICKNESS_BINARY 0.5       /* bitmask thickness / R, binary visibility */
#define CACAO_HORIZON_DENOISE_SIGMA 0.02         /* tangent-plane distance / view z */
#define CACAO_HORIZON_MAX_DIRECTIONS 16
#define CACAO_HORIZON_MAX_STEPS 32

/* Sample pattern: 32 entries of (x, y, weight, mip term), spec: constants.md section 1.
 * A C initialiser for float[128]; the host copies it into the constant block (sample_pattern). */
#define CACAO_SAMPLE_PATTERN_VALUES                                                                \
    0.78488064, 0.56661671, 1.500000, -0.126083, 0.26022232, -0.29575172, 1.500000, -1.064030,     \
    0.10459357, 0.08372527, 1.110000, -2.730563, -0.68286800, 0.04963045, 1.090000, -0.498827,     \
    -0.13570161, -0.64190155, 1.250000, -0.532765, -0.26193795, -0.08205118, 0.670000, -1.783245,  \
    -0.61177456, 0.66664219, 0.710000, -0.044234, 0.43675563, 0.25119025, 0.610000, -1.167283,     \
    0.07884444, 0.86618668, 0.640000, -0.459002, -0.12790935, -0.29869005, 0.600000, -1.729424,    \
    -0.04031125, 0.02413622, 0.600000, -4.792042, 0.16201244, -0.52851415, 0.790000, -1.067055,    \
    -0.70991218, 0.47301072, 0.640000, -0.335236, 0.03277707, -0.22349690, 0.600000, -1.982384,    \
    0.68921727, 0.36800742, 0.630000, -0.266718, 0.29251814, 0.37775412, 0.610000, -1.422520,      \
    -0.12224089, 0.96582592, 0.600000, -0.426142, 0.11071457, -0.16131058, 0.600000, -2.165947,    \
    0.46562141, -0.59747696, 0.600000, -0.189760, -0.51548797, 0.11804193, 0.600000, -1.246800,    \
    0.89141309, -0.42090443, 0.600000, 0.028192, -0.32402530, -0.01591529, 0.600000, -1.543018,    \
    0.60771245, 0.41635221, 0.600000, -0.605411, 0.02379565, -0.08239821, 0.600000, -3.809046,     \
    0.48951152, -0.23657045, 0.600000, -1.189011, -0.17611565, -0.81696892, 0.600000, -0.513724,   \
    -0.33930185, -0.20732205, 0.600000, -1.698047, -0.91974425, 0.05403209, 0.600000, 0.062246,    \
    -0.15064627, -0.14949332, 0.600000, -1.896062, 0.53180975, -0.35210401, 0.600000, -0.758838,   \
    0.41487166, 0.81442589, 0.600000, -0.505648, -0.24106961, -0.32721516, 0.600000, -1.665244

/* ---- The constant block (std140). One block for every pass; per-slice values are arrays
 * indexed by slice, so one buffer serves all dispatches of a frame. ---- */
#ifdef CACAO_GLSL
#define CACAO_T_VEC2 vec2
#define CACAO_T_VEC4 vec4
#define CACAO_T_MAT4 mat4
#define CACAO_T_FLOAT float
#define CACAO_T_INT int
#define CACAO_MEMBER(type, name) CACAO_T_##type name;
#define CACAO_MEMBER_ARRAY(type, name, count) CACAO_T_##type name[count];
#else
typedef struct cacao_vec2 { float x, y; } cacao_vec2;
typedef struct cacao_vec4 { float x, y, z, w; } cacao_vec4;
typedef struct cacao_mat4 { float m[16]; } cacao_mat4; /* GLSL column-major: m[4*col + row] */
#define CACAO_T_VEC2 cacao_vec2
#define CACAO_T_VEC4 cacao_vec4
#define CACAO_T_MAT4 cacao_mat4
#define CACAO_T_FLOAT float
#define CACAO_T_INT int
#define CACAO_MEMBER(type, name) CACAO_T_##type name;
#define CACAO_MEMBER_ARRAY(type, name, count) CACAO_T_##type name[count];
#endif

/* X-list of members: M(type, name) for scalars/vectors, A(type, name, count) for arrays.
 * Order is chosen so std140 needs no padding that C would not also insert (test_shared_layout
 * compares the two layouts); every member is read by some pass. */
#define CACAO_CONSTANTS_MEMBERS(M, A)                                                              \
    M(VEC2, depth_unpack)               /* view z = (x + depth_unpack_d.x d) / (y + depth_unpack_d.y d) */ \
    M(VEC2, ndc_to_view_mul)            /* (2 tanX, -2 tanY) */                                    \
    M(VEC2, ndc_to_view_add)            /* (-tanX, tanY) */                                        \
    M(VEC2, depth_uv_to_view_mul)                                                                  \
    M(VEC2, depth_uv_to_view_add)                                                                  \
    M(VEC2, ssao_buffer_inverse_dimensions)                                                        \
    M(VEC2, depth_buffer_inverse_dimensions)                                                       \
    M(VEC2, output_buffer_inverse_dimensions)                                                      \
    M(VEC2, importance_map_inverse_dimensions)                                                     \
    M(FLOAT, effect_radius)                                                                        \
    M(FLOAT, effect_shadow_strength)                                                               \
    M(FLOAT, effect_shadow_pow)                                                                    \
    M(FLOAT, effect_shadow_clamp)                                                                  \
    M(FLOAT, effect_fade_out_mul)                                                                  \
    M(FLOAT, effect_fade_out_add)                                                                  \
    M(FLOAT, effect_horizon_angle_threshold)                                                       \
    M(FLOAT, effect_sampling_radius_near_limit_rec)                                                \
    M(FLOAT, depth_precision_offset_mod)                                                           \
    M(FLOAT, neg_rec_effect_radius)                                                                \
    M(FLOAT, load_counter_avg_div)                                                                 \
    M(FLOAT, adaptive_sample_count_limit)                                                          \
    M(FLOAT, inv_sharpness)                                                                        \
    M(INT, slice_count)                 /* 2 at LOWEST (slices 0 and 3 in layers 0 and 1), else 4 */ \
    M(FLOAT, bilateral_depth_exp2_mul)  /* upsample depth weight exp2(dz^2 x) = exp(-dz^2 / variance) */ \
    M(FLOAT, normals_unpack_mul)                                                                   \
    M(FLOAT, normals_unpack_add)                                                                   \
    M(FLOAT, detail_ao_strength)        /* 9 vec2 + 18 scalars = 144 bytes: the arrays start 16-aligned */ \
    A(VEC4, per_slice_full_res_uv_offset, 4) /* xy = (dx / Sw, dy / Sh) per slice */               \
    A(VEC4, pattern_rot_scale, 20)      /* [slice * 5 + j] = (m0, m1, m2, m3) */                   \
    A(VEC4, sample_pattern, 32)         /* CACAO_SAMPLE_PATTERN_VALUES; in the block because a */  \
                                        /* dynamically indexed GLSL const array is copied per call */ \
    A(VEC4, bilateral_axis_weight, 2)   /* [i] = exp(-(i/2)^2 / spatial variance), i = 0..5: the */ \
                                        /* upsample's spatial weight is the product for |dx|, |dy| */ \
    M(MAT4, normals_to_view)            /* n'_j = sum_i E[j][i] n_i, stored column-major */       \
    M(MAT4, view_to_previous_view)      /* temporal: this frame's view position to the last frame's */ \
    M(VEC2, depth_unpack_d)             /* (0, -1) perspective, (P(3,3), 0) orthographic */       \
    M(VEC2, view_xy_z)                  /* view xy = (ndc_to_view_mul uv + add) (x z + y) */       \
    M(VEC2, edge_depth)                 /* depth an edge is relative to = x z + y */ \
    M(FLOAT, horizon_depth_den_a)         /* slice modes: view z = (depth_unpack.x + depth_unpack_d.x d) / */ \
    M(FLOAT, horizon_depth_den_b)         /*   (a + b d + c (1 - d)): 1 - d is exact where d is near 1 */ \
    M(FLOAT, horizon_depth_den_c)                                                                    \
    M(FLOAT, horizon_far_depth)           /* raw depth of the far plane: background (2 if none) */   \
    M(FLOAT, horizon_radius)              /* effective radius (k_R R), view units */                 \
    M(FLOAT, horizon_falloff_mul)         /* GTAO: w = sat((radius - dist) falloff_mul) */            \
    M(FLOAT, horizon_thickness)           /* bitmask: constant thickness T, view units */            \
    M(FLOAT, horizon_pixel_size)          /* view units per pixel at view_xy_scale 1 */              \
    M(INT, horizon_directions)            /* slices per pixel (NS) */                                \
    M(INT, horizon_steps)                 /* steps per side (M) */                                   \
    M(INT, horizon_binary)                /* 1: binary visibility within R, 0: falloff */            \
    M(INT, horizon_noise_offset)          /* 288 (frame mod 64): decorrelates frames, 0 = frame 0 */ \
    M(INT, horizon_ortho)                 /* 1: orthographic (view rays parallel to z) */            \
    M(FLOAT, horizon_denoise_sigma)                                                                  \
    M(FLOAT, horizon_rotation_cos)        /* cos, sin of pi / slices: from one slice to the next */ \
    M(FLOAT, horizon_rotation_sin)                                                                   \
    M(FLOAT, background_z)              /* stored view z at or beyond which a texel is background */ \
    M(FLOAT, quiet_margin)              /* classification: fade argument below -margin is quiet */ \
    M(INT, tiles_all)                   /* 1: every tile active (no skipping: measurement, tests) */ \
    M(INT, needed_list)                 /* CACAO's compact lists in CACAO_LIST_PREPARE: 1 the needed tiles (the
                                           upsample), 2 the blocks of 2x2 tiles holding one (smart apply), 3 the
                                           tiles whose quads touch one (non-smart and half apply, on frames whose
                                           active tiles are at most CACAO_APPLY_LIST_ACTIVE_NUM/_DEN of all) */ \
    M(INT, needed_shift)                /* needed_list 3: bit 0, 1: the quads lie a pixel left, up (odd output) */ \
    M(INT, apply_gate)                  /* needed_list 3: the direct apply's gate (1-based), which compact closes
                                           where it lists the apply's groups */ \
    M(INT, active_blocks)               /* 1: compact lists the blocks holding an active tile (CACAO_LIST_BLOCKS) */ \
    M(INT, normals_list)                /* 1: compact lists the tiles whose normals generate reads (CACAO_LIST_NORMALS);
                                           the horizon estimators' normals from depth: 2, their view
                                           z list (CACAO_LIST_PREPARE) holds every tile not all
                                           background, the normals' prepare reads the stored z */ \
    M(INT, tile_pixels)                 /* output pixels per tile side (CACAO: 16 native, 32 downsampled;
                                           the horizon estimators 8) */ \
    M(INT, quiet_test)                  /* 1: classify.quiet opens the gates (the host writes them closed) */ \
    M(INT, quiet_zero_depth)            /* 1: the prepare reads depth 0 past the image's edge (classify.quiet) */ \
    M(INT, tiles_x)                                                                                \
    M(INT, tiles_y)                                                                                \
    M(INT, blur_groups_x)               /* the blur's full grid and output texels per group */     \
    M(INT, blur_groups_y)                                                                          \
    M(INT, blur_out_x)                                                                             \
    M(INT, blur_out_y)                                                                             \
    M(INT, slice_width)                 /* the slice (deinterleaved image, level 0) in texels */   \
    M(INT, slice_height)                                                                           \
    M(INT, reuse)                       /* 0 off; 1 reuse the previous frame's; 2, 3 full frames (record.c) */ \
    M(INT, reuse_all_or_nothing)        /* 1: any change recomputes every tile (HIGHEST's counter) */ \
    M(INT, reuse_margin)                /* slice texels a change reaches besides the taps */      \
    M(FLOAT, reuse_tap_reach)           /* farthest tap offset, in units of the lookup radius */   \
    M(FLOAT, reuse_near_k)              /* largest |view position| / z over the image's pixels */  \
    M(INT, gate_count)                  /* gate commands a frame with no change zeroes, or classify.quiet opens */ \
    M(FLOAT, temporal_min_weight)       /* temporal: 1 / temporal_frames, the blend's least weight */ \
    M(INT, temporal_history)            /* temporal: 1 where the last frame's history is valid */

#ifdef CACAO_GLSL
#ifdef CACAO_BIND_CONSTANTS /* every pass row binds it (glsl/bindings.glsl declares the other slots) */
layout(std140, set = 0, binding = CACAO_BINDING_CONSTANTS) uniform cacao_constants_block {
    CACAO_CONSTANTS_MEMBERS(CACAO_MEMBER, CACAO_MEMBER_ARRAY)
} cb;
#endif
/* The passes read the block's members other than its arrays as CB.name. In the passes below CB
 * is cc, a private copy made by hoist_constants() as the first statement of their main: lavapipe
 * loads a block value inside control flow lane by lane with a bounds check (and everything after
 * an early return, or inside a loop, is inside control flow), but once at the top of main. The
 * copy made these passes faster on lavapipe (docs/speed-notes.md); of them only generate has a
 * GPU form (the other GPU forms' modules are unchanged). Elsewhere CB is the block itself: the
 * copy made the depth mips (whose groups meet at barriers) and classify.quiet (whose invocations
 * mostly return at once) slower, left apply, the upsample and the horizon estimator as they were
 * (within this machine's noise), and costs about 9 KB of SPIR-V a module (it is not optimised
 * away). The arrays are always read from the block (their indices vary per pixel). */
#define CACAO_HOISTS_CONSTANTS                                                                         \
    (CACAO_PASS == CACAO_PASS_GENERATE || CACAO_PASS == CACAO_PASS_GENERATE_GPU ||                      \
     (CACAO_PASS == CACAO_PASS_PREPARE_NORMALS && CACAO_VARIANT == CACAO_PREPARE_NORMALS_LISTED) ||     \
     CACAO_PASS == CACAO_PASS_HORIZON_PREPARE || CACAO_PASS == CACAO_PASS_HORIZON_DENOISE ||            \
     CACAO_PASS == CACAO_PASS_HORIZON_TEMPORAL ||                                                       \
     ((CACAO_PASS == CACAO_PASS_PREPARE || CACAO_PASS == CACAO_PASS_PREPARE_DEPTHS) &&                   \
      CACAO_VARIANT != CACAO_DEPTHS_MIPS && CACAO_VARIANT != CACAO_DEPTHS_MIPS_CHAIN))
#if CACAO_HOISTS_CONSTANTS
#define CACAO_CC_MEMBER(type, name) CACAO_T_##type name;
#define CACAO_CC_COPY(type, name) cc.name = cb.name;
#define CACAO_CC_NO_ARRAY(type, name, count)
struct cacao_constants_copy {
    CACAO_CONSTANTS_MEMBERS(CACAO_CC_MEMBER, CACAO_CC_NO_ARRAY)
};
cacao_constants_copy cc;
void hoist_constants() { CACAO_CONSTANTS_MEMBERS(CACAO_CC_COPY, CACAO_CC_NO_ARRAY) }
#define CB cc
#else
#define CB cb
#endif
#else
typedef struct cacao_constants {
    CACAO_CONSTANTS_MEMBERS(CACAO_MEMBER, CACAO_MEMBER_ARRAY)
} cacao_constants;
#endif

#endif /* CACAO_SHARED_H */
