/* blur.glsl - the edge-aware blur, all its iterations in one dispatch. */

/* ============================== BLUR ============================== */
#if CACAO_PASS == CACAO_PASS_BLUR || CACAO_PASS == CACAO_PASS_BLUR_GPU
/* spec: blur.md (padded-domain formulation, N Jacobi iterations in one dispatch), two ways:
 * - up to CACAO_BLUR_REGISTER_PASSES passes, each thread computes a block of BX x BY output
 *   texels from its footprint, the block and N more texels on every side, held in registers:
 *   iteration it is right at the texels at least it from the footprint's edge, so after N the
 *   block is exact. The footprints overlap (each texel is loaded and updated by several threads),
 *   but no texel goes through shared memory: on lavapipe, whose shared loads run lane by lane and
 *   whose barriers switch between all the group's invocations, that exchange was 2/3 of the blur
 *   (docs/speed-notes.md). Its fully unrolled code grows with N x footprint: past 3 passes
 *   lavapipe's compile time grows to seconds (7.9 s at 4, 26 s at 6), so
 * - beyond, a group owns a padded tile of BX x BY blocks, one per thread, whose values and edge
 *   weights stay in registers for all N iterations; shared memory carries only the values the
 *   neighbours need (one barrier per iteration, double-buffered). The inner
 *   (WG BX - 2N) x (WG BY - 2N) texels are exact: values at distance d from the padded border
 *   are wrong after d iterations at most, and the inner region is N away from it. */
/* The GPU form (CACAO_PASS_BLUR_GPU) is the shared-memory way for every N, with 4x3-texel blocks
 * of 16x16 threads (a 64x48 padded tile, AMD's): a GPU keeps the registers such a block needs
 * (the 8x4 register block spills), and its shared memory and barriers are cheap. It reads every
 * neighbour from shared memory, takes its edge weights from a shared table of the 256 edge codes
 * and tests the stores per row and column (docs/gpu.md, "The GPU forms", has what each saved).
 * Both forms compute every texel from the same neighbourhood with the same arithmetic: the same
 * output. */
#define BLUR_N CACAO_BLUR_PASSES
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
layout(local_size_x = CACAO_WG_BLUR_GPU_X, local_size_y = CACAO_WG_BLUR_GPU_Y) in;
#define BX CACAO_BLUR_GPU_BLOCK_X
#define BY CACAO_BLUR_GPU_BLOCK_Y
#define BLUR_OUT ivec2(CACAO_BLUR_GPU_OUT_X(BLUR_N), CACAO_BLUR_GPU_OUT_Y(BLUR_N))
#define BLUR_PX (CACAO_WG_BLUR_GPU_X * BX) /* padded tile width */
#define BLUR_PY (CACAO_WG_BLUR_GPU_Y * BY) /* padded tile height */
#else
layout(local_size_x = CACAO_WG_BLUR_X, local_size_y = CACAO_WG_BLUR_Y) in;
#define BX CACAO_BLUR_BLOCK_X
#define BY CACAO_BLUR_BLOCK_Y
#define BLUR_OUT ivec2(CACAO_BLUR_OUT_X(BLUR_N), CACAO_BLUR_OUT_Y(BLUR_N))
#define BLUR_PX (CACAO_WG_BLUR_X * BX)
#define BLUR_PY (CACAO_WG_BLUR_Y * BY)
#endif

rfloat blur_store_value(float v)
{
#if CACAO_FP16 == 1
    return rfloat(v);
#else
    return round_to_half(v); /* AMD keeps the values as half between iterations */
#endif
}

/* Sum of a texel's blur weights: the centre's and its four edges'. */
rfloat blur_weight_sum(rvec4 e) { return rfloat(CACAO_BLUR_CENTRE_WEIGHT) + e.x + e.y + e.z + e.w; }

/* One Jacobi update of a texel: its value c and its neighbours' (left, right, top, bottom),
 * weighted by its edges w, over their sum wsum; stored as the iterations keep it. */
rfloat blur_update(rfloat c, rfloat l, rfloat r, rfloat t, rfloat b, rvec4 w, rfloat wsum)
{
    rfloat sum = rfloat(CACAO_BLUR_CENTRE_WEIGHT) * c + w.x * l + w.y * r + w.z * t + w.w * b;
    return blur_store_value(float(sum / wsum));
}

/* Value (r) and packed edges (g) of padded-domain texels c .. c + 1 (2x2), mirrored at the
 * slice's edges ([quirk] BLUR-BORDER-EDGES), from one gather per channel: the mirrored
 * coordinates m0, m1 of a pair differ by at most 1 (mirroring and its clamp are continuous), so
 * they lie in lo = min(m0, m1), lo + 1 (clamped by the sampler at the last texel), which one gather
 * at the corner between them reads; each texel then takes its own of the two. Out: [y][x]. */
void load_blur_piece(ivec2 c, ivec2 s, int layer, out vec2 ae[2][2])
{
    ivec2 m0 = mirror_coord(c, s), m1 = mirror_coord(c + 1, s);
    ivec2 lo = min(m0, m1);
    vec3 at = vec3(vec2(lo + 1) / vec2(s), float(layer));
    /* gather order: x = (lo.x, lo.y + 1), y = (lo.x + 1, lo.y + 1), z = (lo.x + 1, lo.y), w = (lo.x, lo.y) */
    vec4 ga = textureGather(ssao, at, 0);
    vec4 ge = textureGather(ssao, at, 1);
    [[unroll]] for (int j = 0; j < 2; ++j) {
        [[unroll]] for (int i = 0; i < 2; ++i) {
            bool first_x = (i == 0 ? m0.x : m1.x) == lo.x;
            bool first_y = (j == 0 ? m0.y : m1.y) == lo.y;
            ae[j][i] = first_y ? (first_x ? vec2(ga.w, ge.w) : vec2(ga.z, ge.z))
                               : (first_x ? vec2(ga.x, ge.x) : vec2(ga.y, ge.y));
        }
    }
}

#if CACAO_PASS == CACAO_PASS_BLUR && BLUR_N <= CACAO_BLUR_REGISTER_PASSES
#define FX (BX + 2 * BLUR_N) /* the footprint */
#define FY (BY + 2 * BLUR_N)
#if FX % 2 != 0 || FY % 2 != 0
#error "the blur loads its footprint in 2x2 pieces"
#endif

void main()
{
    ivec2 group;
    if (!group_of(group)) return;
    ivec2 s = textureSize(ssao, 0).xy;
    int layer = int(gl_WorkGroupID.z);
    ivec2 out0 = group * BLUR_OUT + ivec2(gl_LocalInvocationID.xy) * ivec2(BX, BY);

    rfloat v[FY][FX];
    float packed[FY][FX];
    [[unroll]] for (int py = 0; py < FY; py += 2) {
        [[unroll]] for (int px = 0; px < FX; px += 2) {
            vec2 ae[2][2];
            load_blur_piece(out0 - BLUR_N + ivec2(px, py), s, layer, ae);
            [[unroll]] for (int j = 0; j < 2; ++j) {
                [[unroll]] for (int i = 0; i < 2; ++i) {
                    v[py + j][px + i] = blur_store_value(ae[j][i].r);
                    packed[py + j][px + i] = ae[j][i].g;
                }
            }
        }
    }
    /* edge weights of the texels the iterations update: all but the footprint's outer ring */
    rvec4 e[FY][FX];
    rfloat wsum[FY][FX];
    [[unroll]] for (int y = 1; y < FY - 1; ++y) {
        [[unroll]] for (int x = 1; x < FX - 1; ++x) {
            e[y][x] = unpack_edges(packed[y][x]);
            wsum[y][x] = blur_weight_sum(e[y][x]);
        }
    }
    /* Every iteration updates the whole inner region (constant bounds: shrinking it by one per
     * iteration made the loops too irregular for the driver to unroll, and the arrays went to
     * memory, several times slower: docs/speed-notes.md); what it gets wrong near the edge no block
     * texel depends on. */
    [[unroll]] for (int it = 0; it < BLUR_N; ++it) {
        rfloat nv[FY][FX] = v;
        [[unroll]] for (int y = 1; y < FY - 1; ++y) {
            [[unroll]] for (int x = 1; x < FX - 1; ++x) {
                nv[y][x] = blur_update(v[y][x], v[y][x - 1], v[y][x + 1], v[y - 1][x], v[y + 1][x], e[y][x], wsum[y][x]);
            }
        }
        v = nv;
    }

    /* the block: (blurred AO, original packed edges) */
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 p = out0 + ivec2(x, y);
            if (in_rect(p, s))
                imageStore(ssao_image, ivec3(p, layer),
                           vec4(float(v[BLUR_N + y][BLUR_N + x]), packed[BLUR_N + y][BLUR_N + x], 0.0, 0.0));
        }
    }
}
#else
/* 2 x 2048 values: 16 KiB (fp32), 8 KiB (fp16); the GPU form 2 x 3072. */
shared rfloat blur_values[2][BLUR_PY][BLUR_PX];
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
/* The GPU form's edge weights and their sum for each 8-bit edge code, one entry per invocation,
 * written before the first iteration's barrier: a texel then reads its weights (two shared loads)
 * instead of unpacking them (18 instructions on navi21, a quarter of the shader). */
#if CACAO_WG_BLUR_GPU_X * CACAO_WG_BLUR_GPU_Y != 256
#error "the GPU blur's invocations write its 256 edge codes' weights"
#endif
shared rvec4 blur_edge_weights[256];
shared rfloat blur_edge_sums[256];
#endif

void main()
{
    ivec2 group;
    if (!group_of(group)) return; /* the whole group: before any barrier */
    ivec2 s = textureSize(ssao, 0).xy;
    int layer = int(gl_WorkGroupID.z);
    ivec2 tile_origin = group * BLUR_OUT;
    ivec2 b0 = ivec2(gl_LocalInvocationID.xy) * ivec2(BX, BY); /* block origin in the padded tile */

    /* the block: value and edges both from the mirrored texel ([quirk] BLUR-BORDER-EDGES) */
    rfloat v[BY][BX];
    rvec4 e[BY][BX];
    rfloat wsum[BY][BX];
    float packed[BY][BX];
#if CACAO_SKIPS_BY_CLASS
    /* compact's test for the blur list (classify's flag), the same for the whole group (so are
     * the barriers under it): a group the list would leave out stores AO 1 and edges 1 (the
     * value the CPU forms' clear leaves there) where it stores, and computes nothing */
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            v[y][x] = rfloat(1.0);
            packed[y][x] = 1.0;
        }
    }
    int work = group_work(group); /* reuse: a group it keeps stores nothing (below) */
    if (work == GROUP_COMPUTE) {
#endif
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 c = mirror_coord(tile_origin - BLUR_N + b0 + ivec2(x, y), s);
            vec2 ae = texelFetch(ssao, ivec3(c, layer), 0).rg;
            v[y][x] = blur_store_value(ae.r);
            packed[y][x] = ae.g;
#if CACAO_PASS != CACAO_PASS_BLUR_GPU
            e[y][x] = unpack_edges(ae.g);
            wsum[y][x] = blur_weight_sum(e[y][x]);
#endif
        }
    }
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
    {
        uint code = gl_LocalInvocationIndex;
        rvec4 w = unpack_edge_bits(code);
        blur_edge_weights[code] = w;
        blur_edge_sums[code] = blur_weight_sum(w);
    }
#endif

    /* neighbours outside the block; reads past the padded tile clamp to it */
    int xl = max(b0.x - 1, 0), xr = min(b0.x + BX, BLUR_PX - 1);
    int yt = max(b0.y - 1, 0), yb = min(b0.y + BY, BLUR_PY - 1);
    /* A neighbour clamped to the block is the block's own texel, which shared memory holds too:
     * lavapipe takes it from the register (its shared loads run lane by lane), a GPU reads shared
     * memory unconditionally (a branch per read costs it more than the read). */
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
#define BLUR_NEIGHBOUR(own_cond, own, shared_value) (shared_value)
#else
#define BLUR_NEIGHBOUR(own_cond, own, shared_value) ((own_cond) ? (own) : (shared_value))
#endif

    [[unroll]] for (int it = 0; it < BLUR_N; ++it) {
        int buf = it & 1;
        [[unroll]] for (int y = 0; y < BY; ++y)
            [[unroll]] for (int x = 0; x < BX; ++x) blur_values[buf][b0.y + y][b0.x + x] = v[y][x];
        barrier();
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
        if (it == 0) {
            [[unroll]] for (int y = 0; y < BY; ++y) {
                [[unroll]] for (int x = 0; x < BX; ++x) {
                    uint code = edges_bits(packed[y][x]);
                    e[y][x] = blur_edge_weights[code];
                    wsum[y][x] = blur_edge_sums[code];
                }
            }
        }
#endif
        rfloat left[BY], right[BY], top[BX], bottom[BX];
        [[unroll]] for (int y = 0; y < BY; ++y) {
            left[y] = BLUR_NEIGHBOUR(xl == b0.x, v[y][0], blur_values[buf][b0.y + y][xl]);
            right[y] = BLUR_NEIGHBOUR(xr == b0.x + BX - 1, v[y][BX - 1], blur_values[buf][b0.y + y][xr]);
        }
        [[unroll]] for (int x = 0; x < BX; ++x) {
            top[x] = BLUR_NEIGHBOUR(yt == b0.y, v[0][x], blur_values[buf][yt][b0.x + x]);
            bottom[x] = BLUR_NEIGHBOUR(yb == b0.y + BY - 1, v[BY - 1][x], blur_values[buf][yb][b0.x + x]);
        }
        rfloat nv[BY][BX];
        [[unroll]] for (int y = 0; y < BY; ++y) {
            [[unroll]] for (int x = 0; x < BX; ++x) {
                rfloat al = x > 0 ? v[y][x - 1] : left[y];
                rfloat ar = x < BX - 1 ? v[y][x + 1] : right[y];
                rfloat at = y > 0 ? v[y - 1][x] : top[x];
                rfloat ab = y < BY - 1 ? v[y + 1][x] : bottom[x];
                nv[y][x] = blur_update(v[y][x], al, ar, at, ab, e[y][x], wsum[y][x]);
            }
        }
        v = nv;
        /* no second barrier: the next iteration writes the other buffer, and the one after
         * this buffer again only after that iteration's barrier */
    }
#if CACAO_SKIPS_BY_CLASS
    }
    if (work == GROUP_KEEP) return;
#endif

    /* inner texels: (blurred AO, original packed edges) */
#if CACAO_PASS == CACAO_PASS_BLUR_GPU
    /* the same test per column and per row, each once (p >= 0 as tile_origin, o >= 0) */
    bool column_in[BX], row_in[BY];
    [[unroll]] for (int x = 0; x < BX; ++x) {
        int o = b0.x + x - BLUR_N;
        column_in[x] = o >= 0 && o < BLUR_OUT.x && tile_origin.x + o < s.x;
    }
    [[unroll]] for (int y = 0; y < BY; ++y) {
        int o = b0.y + y - BLUR_N;
        row_in[y] = o >= 0 && o < BLUR_OUT.y && tile_origin.y + o < s.y;
    }
#define BLUR_STORES(o, p, x, y) (row_in[y] && column_in[x])
#else
#define BLUR_STORES(o, p, x, y) (in_rect(o, BLUR_OUT) && in_rect(p, s))
#endif
    [[unroll]] for (int y = 0; y < BY; ++y) {
        [[unroll]] for (int x = 0; x < BX; ++x) {
            ivec2 o = b0 + ivec2(x, y) - BLUR_N;
            ivec2 p = tile_origin + o;
            if (BLUR_STORES(o, p, x, y))
                imageStore(ssao_image, ivec3(p, layer), vec4(float(v[y][x]), packed[y][x], 0.0, 0.0));
        }
    }
}
#endif /* register or shared-memory blur */
#endif /* BLUR */
