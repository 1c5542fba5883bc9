/* apply.glsl - apply (native) and upsample (downsampled): the slices' AO into the output. */

/* ============================== APPLY / UPSAMPLE shared ============================== */
#if CACAO_PASS == CACAO_PASS_APPLY || CACAO_PASS == CACAO_PASS_UPSAMPLE || CACAO_PASS == CACAO_PASS_APPLY_GPU

/* Bilinear read of one layer of the AO texture (LinearClamp). */
rfloat ao_bilinear(vec2 uv, int layer) { return rfloat(textureLod(ssao, vec3(uv, float(layer)), 0.0).r); }

/* The edge-aware interleave of the 2S-sized re-interleaved image at integer position p (spec:
 * apply.md "Apply", integer p as written: [quirk] APPLY-HALF-PIXEL) from the pixel's edges e:
 * where it reads its three neighbour layers (uv of the horizontal, vertical and diagonal ones). */
void smart_apply_taps(ivec2 p, rvec4 e, out vec2 uvh, out vec2 uvv, out vec2 uvd)
{
    int mx = p.x & 1, my = p.y & 1;
    float sx = float(e.y - e.x); /* push samples away from edges */
    float sy = float(e.w - e.z);
    vec2 pf = vec2(p);
    vec2 inv_s = CB.ssao_buffer_inverse_dimensions;
    uvh = (pf + vec2(float(mx) + sx - 0.5, 0.5 - float(my))) * 0.5 * inv_s;
    uvv = (pf + vec2(0.5 - float(mx), float(my) - 0.5 + sy)) * 0.5 * inv_s;
    uvd = (pf + vec2(float(mx) - 0.5 + sx, float(my) - 0.5 + sy)) * 0.5 * inv_s;
}

/* ... and the pixel's value from its own texel's AO and the three reads. */
rfloat smart_apply_mix(rfloat ao, rvec4 e, rfloat ah, rfloat av, rfloat ad)
{
    rfloat wh = (e.x + e.y) * rfloat(0.5);
    rfloat wv = (e.z + e.w) * rfloat(0.5);
    rfloat wd = (wh + wv) * rfloat(0.5);
    return (ao + wh * ah + wv * av + wd * ad) / (rfloat(1.0) + wh + wv + wd);
}

rfloat smart_apply(ivec2 p)
{
    int mx = p.x & 1, my = p.y & 1;
    int ic = mx + 2 * my;
    int ih = (1 - mx) + 2 * my;
    int iv = mx + 2 * (1 - my);
    int id = (1 - mx) + 2 * (1 - my);
    vec2 ae = texelFetch(ssao, ivec3(p >> 1, ic), 0).rg;
    rvec4 e = unpack_edges(ae.g);
    vec2 uvh, uvv, uvd;
    smart_apply_taps(p, e, uvh, uvv, uvd);
    return smart_apply_mix(rfloat(ae.r), e, ao_bilinear(uvh, ih), ao_bilinear(uvv, iv), ao_bilinear(uvd, id));
}
#endif

/* ============================== APPLY ============================== */
#if CACAO_PASS == CACAO_PASS_APPLY
/* spec: apply.md (Apply, NonSmartApply, NonSmartHalfApply) */
layout(local_size_x = CACAO_WG_APPLY_X, local_size_y = CACAO_WG_APPLY_Y) in;

/* One axis of the linear sampler's filter on 8-bit texels: a weight of f / 256 (8 fractional
 * coordinate bits), the product rounded, a + round(f (b - a) / 256). */
int lerp_texel8(int f, int a, int b) { return a + ((f * (b - a) + 128) >> 8); }

/* The 8-bit texels of unorm values as gathered. */
int texel8(float v) { return int(v * 255.0 + 0.5); }
ivec4 texel8(vec4 v) { return ivec4(v * 255.0 + 0.5); }

#if CACAO_VARIANT == CACAO_OUTPUT_SMART || CACAO_VARIANT == CACAO_APPLY_SMART_LIST
/* The sampler's bilinear read, to the bit, from a 4x4 window w of one layer's texels (window
 * texel 0 at slice texel base) at sampler coordinate uv. Along an axis the read starts at window
 * texel lo, or (shift: where the edges can move it by one) at lo or lo + 1. */
int window_read(float w[4][4], ivec2 base, vec2 uv, vec2 fixed_size, ivec2 lo, bvec2 shift)
{
    ivec2 c = ivec2(roundEven(uv * fixed_size)) - 128; /* 8.8 fixed point, less half a texel */
    ivec2 f = c & 255;
    bvec2 hi = bvec2(shift.x && (c.x >> 8) - base.x != lo.x, shift.y && (c.y >> 8) - base.y != lo.y);
    int row[3];
    [[unroll]] for (int k = 0; k < 3; ++k) {
        int y = min(lo.y + k, 3);
        int v0 = texel8(w[y][lo.x]), v1 = texel8(w[y][min(lo.x + 1, 3)]), v2 = texel8(w[y][min(lo.x + 2, 3)]);
        row[k] = lerp_texel8(f.x, hi.x ? v1 : v0, hi.x ? v2 : v1);
    }
    return lerp_texel8(f.y, hi.y ? row[1] : row[0], hi.y ? row[2] : row[1]);
}

/* One invocation computes 4x4 output pixels, those of slice texels Q, Q + 1 (x and y). Their reads
 * of a layer with parity (lx, ly) all lie in the 4x4 texels from Q - 1 - (lx, ly): where the edges
 * push a pixel's read, it moves by at most half a texel, towards the texels that pixel's parity
 * leaves room for. So 4 gathers per layer and one of the edges give every texel the 16 pixels read
 * (20 sampler operations, against 64), and the shader filters as the sampler does on 8-bit texels
 * (as the non-smart apply below). */
void main()
{
    ivec2 g; /* listed: a block of 2x2 tiles (the group's 16x16 slice texels) */
    if (!group_of(g)) return;
    ivec2 Q = 2 * texel_of(g);
    ivec2 osize = imageSize(output_image);
    ivec2 ssize = textureSize(ssao, 0).xy;
    if (!in_rect(2 * Q, osize)) return;
    const vec2 fixed_size = vec2(ssize * 256);
    float w[4][4][4]; /* layer, y, x */
    [[unroll]] for (int l = 0; l < 4; ++l) {
        ivec2 base = Q - 1 - ivec2(l & 1, l >> 1);
        [[unroll]] for (int gy = 0; gy < 2; ++gy) {
            [[unroll]] for (int gx = 0; gx < 2; ++gx) {
                /* x: (x0, y1), y: (x1, y1), z: (x1, y0), w: (x0, y0) */
                vec4 g = textureGather(ssao, vec3(vec2(base + 1 + 2 * ivec2(gx, gy)) / vec2(ssize), float(l)), 0);
                w[l][2 * gy][2 * gx] = g.w;
                w[l][2 * gy][2 * gx + 1] = g.z;
                w[l][2 * gy + 1][2 * gx] = g.x;
                w[l][2 * gy + 1][2 * gx + 1] = g.y;
            }
        }
    }
    vec4 edges[4]; /* per layer, the packed edges of texels Q .. Q + 1, in gather order */
    [[unroll]] for (int l = 0; l < 4; ++l)
        edges[l] = textureGather(ssao, vec3(vec2(Q + 1) / vec2(ssize), float(l)), 1);
    [[unroll]] for (int i = 0; i < 16; ++i) {
        ivec2 d = ivec2((i >> 1) & 1, i >> 3);  /* texel Q + d */
        ivec2 m = ivec2(i & 1, (i >> 2) & 1);   /* parity */
        ivec2 p = 2 * (Q + d) + m;
        int ic = m.x + 2 * m.y, ih = (1 - m.x) + 2 * m.y, iv = m.x + 2 * (1 - m.y), id = (1 - m.x) + 2 * (1 - m.y);
        int gather_index = d.y == 0 ? 3 - d.x : d.x; /* (0,0) w, (1,0) z, (0,1) x, (1,1) y */
        rvec4 e = unpack_edges(edges[ic][gather_index]);
        vec2 uvh, uvv, uvd;
        smart_apply_taps(p, e, uvh, uvv, uvd);
        /* window texel of slice texel t in a layer of parity l: t - Q + 1 + l; an axis the edges
         * shift starts at t + m - 2 (window d + m - 1 + l), a fixed one at t - 1 (d + l) */
        ivec2 lh = ivec2(1 - m.x, m.y), lv = ivec2(m.x, 1 - m.y), ld = 1 - m;
        int ah = window_read(w[ih], Q - 1 - lh, uvh, fixed_size, ivec2(d.x + m.x - 1 + lh.x, d.y + lh.y), bvec2(true, false));
        int av = window_read(w[iv], Q - 1 - lv, uvv, fixed_size, ivec2(d.x + lv.x, d.y + m.y - 1 + lv.y), bvec2(false, true));
        int ad = window_read(w[id], Q - 1 - ld, uvd, fixed_size, d + m - 1 + ld, bvec2(true, true));
        rfloat ao = rfloat(w[ic][d.y + 1 + m.y][d.x + 1 + m.x]);
        rfloat v = smart_apply_mix(ao, e, rfloat(float(ah) * (1.0 / 255.0)), rfloat(float(av) * (1.0 / 255.0)),
                                   rfloat(float(ad) * (1.0 / 255.0)));
        if (in_rect(p, osize))
            imageStore(output_image, p, vec4(float(v), 0.0, 0.0, 0.0));
    }
}
#else
/* Non-smart and half: the mean of the layers (all four, or slices 0 and 3) read bilinearly at
 * uv = p / output size (no +0.5, as AMD). One invocation computes a 2x2 quad of output pixels. */
#if CACAO_VARIANT == CACAO_OUTPUT_NON_SMART || CACAO_VARIANT == CACAO_APPLY_NONSMART_LIST
#define APPLY_LAYERS 4
#else
#define APPLY_LAYERS 2 /* layers 0,1 = slices 0,3 */
#endif

void main()
{
    /* Quad q holds the output pixels o .. o + 1, o = 2q (even size) or 2q - 1 (odd): in either
     * case both of them read, per axis, between slice texels q - 1 and q (p / O in a slice of
     * S = ceil(O / 2) texels, less half a texel, lies in [q - 1, q] for those p). So one gather
     * per layer at the corner between those texels reads the four texels of all four pixels, and
     * the filter is done here as the sampler does it on 8-bit texels, to the bit, with a quarter of
     * its reads. Listed: the group is a tile's 8x8 quads, whose pixels lie a pixel left (up) of
     * the tile's where the output's width (height) is odd. */
    ivec2 g;
    if (!group_of(g)) return;
    ivec2 q = texel_of(g);
    ivec2 osize = imageSize(output_image);
    ivec2 ssize = textureSize(ssao, 0).xy;
    vec2 inv_o = CB.output_buffer_inverse_dimensions;
    if (!in_rect(q, ssize)) return;
    ivec2 o = 2 * q - (osize & 1);
    /* each pixel's weight of texel q, in 256ths: its coordinate in 8.8 fixed point, rounded as
     * the sampler rounds it, less the half texel, relative to texel q - 1 (0 < weight <= 256) */
    const vec2 fixed_size = vec2(ssize * 256);
    ivec2 w[2];
    [[unroll]] for (int i = 0; i < 2; ++i)
        w[i] = ivec2(roundEven(vec2(o + i) * inv_o * fixed_size)) - 128 - 256 * (q - 1);
    /* precise: otherwise the compiler factors the 1/255 out of the sum and the last bit moves;
     * and the sampler converts an 8-bit value v to v * (1/255), not v / 255 */
    precise rfloat sum[4] = rfloat[4](rfloat(0.0), rfloat(0.0), rfloat(0.0), rfloat(0.0));
    vec2 corner = vec2(q) / vec2(ssize);
    [[unroll]] for (int l = 0; l < APPLY_LAYERS; ++l) {
        /* x: (q-1, q), y: (q, q), z: (q, q-1), w: (q-1, q-1) */
        ivec4 t = texel8(textureGather(ssao, vec3(corner, float(l)), 0));
        [[unroll]] for (int i = 0; i < 4; ++i) {
            int fx = w[i & 1].x, fy = w[i >> 1].y;
            int v = lerp_texel8(fy, lerp_texel8(fx, t.w, t.z), lerp_texel8(fx, t.x, t.y));
            sum[i] += rfloat(float(v) * (1.0 / 255.0));
        }
    }
    [[unroll]] for (int i = 0; i < 4; ++i) {
        ivec2 p = o + ivec2(i & 1, i >> 1);
        if (all(greaterThanEqual(p, ivec2(0))))
            imageStore(output_image, p, vec4(float(sum[i] / rfloat(APPLY_LAYERS)), 0.0, 0.0, 0.0));
    }
}
#endif
#endif /* APPLY */

/* ============================== APPLY, GPU form ============================== */
#if CACAO_PASS == CACAO_PASS_APPLY_GPU
/* spec: apply.md. A 2x2 quad of output pixels per invocation, each pixel's reads through the
 * hardware sampler: the arithmetic the CPU form above reproduces by hand from gathers (which on
 * lavapipe saves sampler calls, and on a GPU costs registers and instructions the sampler does for
 * free). Four pixels per invocation, a quarter of the workgroups of one each: measured faster on
 * a GPU (docs/gpu.md, "Measured on a real GPU"). */
layout(local_size_x = CACAO_WG_APPLY_X, local_size_y = CACAO_WG_APPLY_Y) in;

void main()
{
    ivec2 q = 2 * ivec2(gl_GlobalInvocationID.xy);
    ivec2 osize = imageSize(output_image);
    if (!in_rect(q, osize)) return;
    [[unroll]] for (int i = 0; i < 4; ++i) {
        ivec2 p = q + ivec2(i & 1, i >> 1);
#if CACAO_VARIANT == CACAO_OUTPUT_SMART
        rfloat ao = smart_apply(p);
#elif CACAO_VARIANT == CACAO_OUTPUT_NON_SMART
        vec2 uv = vec2(p) * CB.output_buffer_inverse_dimensions; /* no +0.5, as AMD */
        rfloat ao = (ao_bilinear(uv, 0) + ao_bilinear(uv, 1) + ao_bilinear(uv, 2) + ao_bilinear(uv, 3)) / rfloat(4.0);
#else
        vec2 uv = vec2(p) * CB.output_buffer_inverse_dimensions;
        rfloat ao = (ao_bilinear(uv, 0) + ao_bilinear(uv, 1)) / rfloat(2.0); /* layers 0,1 = slices 0,3 */
#endif
        if (in_rect(p, osize)) imageStore(output_image, p, vec4(float(ao), 0.0, 0.0, 0.0));
    }
}
#endif /* APPLY_GPU */

/* ============================== UPSAMPLE ============================== */
#if CACAO_PASS == CACAO_PASS_UPSAMPLE
/* spec: upsample.md (bilateral 5x5, Smart / NonSmart / Half). One form for CPUs and GPUs: one
 * half-res position per thread cost a GPU compiler's estimate more than 2x2 (cacao_shared.h). */
layout(local_size_x = CACAO_WG_UPSAMPLE_X, local_size_y = CACAO_WG_UPSAMPLE_Y) in;
#define UP_KIND (CACAO_VARIANT % CACAO_UPSAMPLE_LISTED) /* CACAO_OUTPUT_*, listed or not */
#define UP_B CACAO_UPSAMPLE_BLOCK
#define UP_THREADS (CACAO_WG_UPSAMPLE_X * CACAO_WG_UPSAMPLE_Y)
#define UP_TABLE_X (CACAO_UPSAMPLE_SPAN_X + 4) /* the group's half-res positions + 2 apron each side */
#define UP_TABLE_Y (CACAO_UPSAMPLE_SPAN_Y + 4)
#define UP_WIN (UP_B + 4)                       /* one thread's window of table entries */
#define UP_NO_DEPTH -1.0e30 /* marks an entry outside the Q image: weight 0 (step 2) */

shared rfloat up_value[UP_TABLE_X * UP_TABLE_Y];
shared float up_depth[UP_TABLE_X * UP_TABLE_Y];

/* Deinterleaved depth (mip 0) at slice texel c of a layer; OOB -> 0 (D3D load rule). */
float load_depth_or_zero(ivec2 c, int layer)
{
    return in_rect(c, slice_size()) ? texelFetch(depths, ivec3(c, layer), 0).r : 0.0;
}

rfloat table_value(float v)
{
#if CACAO_FP16 == 1
    return rfloat(v);
#else
    return round_to_half(v); /* AMD stores the table as half */
#endif
}

void main()
{
    /* The block values step 2 uses in its 5x5 loop, read as main's first statements: on lavapipe
     * a block load after step 1's loop is made lane by lane with a bounds check, at every use
     * (docs/speed-notes.md, which has what this copy saves). */
    float axis_weight[6]; /* exp(-(i/2)^2 / spatial variance) for i = 0..5 */
    [[unroll]] for (int i = 0; i < 6; ++i) axis_weight[i] = cb.bilateral_axis_weight[i >> 2][i & 3];
    const float depth_exp2_mul = CB.bilateral_depth_exp2_mul;
    ivec2 s = textureSize(ssao, 0).xy;
    ivec2 qsize = 2 * s;
    ivec2 g; /* listed: a tile (the group's span is a tile's 16x16 half-res positions) */
    if (!group_of(g)) return;
    vec2 inv_s = CB.ssao_buffer_inverse_dimensions;

    /* Step 1: (value, depth) of Q-positions g*SPAN - 2 .. g*SPAN + SPAN + 1, filled by all
     * threads. Entries outside [0, 2S) get weight 0 ([quirk] BILATERAL-LEFT-BORDER fixed). */
    const ivec2 span = ivec2(CACAO_UPSAMPLE_SPAN_X, CACAO_UPSAMPLE_SPAN_Y);
    for (int i = int(gl_LocalInvocationIndex); i < UP_TABLE_X * UP_TABLE_Y; i += UP_THREADS) {
        ivec2 q = g * span + ivec2(i % UP_TABLE_X, i / UP_TABLE_X) - 2;
        float value = 0.0;
        float depth = UP_NO_DEPTH;
        if (in_rect(q, qsize)) {
            int cx = q.x & 1, cy = q.y & 1;
            ivec2 c = q >> 1;
#if UP_KIND == CACAO_OUTPUT_SMART
            value = float(smart_apply(q));
            /* depth from ((qx+1)/2, qy/2) ([quirk] BILATERAL-DEPTH-SHIFT kept; OOB -> 0) */
            depth = load_depth_or_zero(ivec2((q.x + 1) >> 1, c.y), cx + 2 * cy);
#elif UP_KIND == CACAO_OUTPUT_NON_SMART
            /* 3x3 tent: bilinear reads at +-1/2 texel around the slice texel centre */
            vec2 cc = vec2(c) + 0.5;
            float sum = 0.0;
            for (int k = 0; k < 4; ++k) {
                vec2 delta = 0.5 * vec2(cx - (k & 1), cy - (k >> 1));
                sum += textureLod(ssao, vec3((cc + delta) * inv_s, float(k)), 0.0).r;
            }
            value = sum / 4.0;
            depth = load_depth_or_zero(c, cx + 2 * cy);
#else
            /* slices 0 and 3 only (layers 0 and 1) */
            vec2 cc = vec2(c) + 0.5;
            float s0 = textureLod(ssao, vec3((cc + 0.5 * vec2(cx, cy)) * inv_s, 0.0), 0.0).r;
            float s3 = textureLod(ssao, vec3((cc + 0.5 * vec2(cx - 1, cy - 1)) * inv_s, 1.0), 0.0).r;
            value = (s0 + s3) / 2.0;
            depth = load_depth_or_zero(c, cy); /* layer 0 (slice 0) on even rows, 1 (slice 3) on odd */
#endif
        }
        up_value[i] = table_value(value);
        up_depth[i] = depth;
    }
    barrier();

    /* Step 2: bilateral filter for the 2x2 full-res pixels of each of this thread's BxB
     * half-res positions. The thread's (B+4)^2 window of the table is read once into registers:
     * with B = 2 that is 36 shared-memory reads for 4 positions instead of 100, which is most of
     * this pass's time on a CPU device (every such read is a gather). */
    ivec2 l = ivec2(gl_LocalInvocationID.xy) * UP_B;
    ivec2 t0 = g * span + l;
    rfloat win_v[UP_WIN][UP_WIN];
    float win_z[UP_WIN][UP_WIN];
    [[unroll]] for (int y = 0; y < UP_WIN; ++y) {
        [[unroll]] for (int x = 0; x < UP_WIN; ++x) {
            int idx = (l.y + y) * UP_TABLE_X + l.x + x;
            win_v[y][x] = up_value[idx];
            win_z[y][x] = up_depth[idx];
        }
    }

    ivec2 out_size = imageSize(output_image);
    [[unroll]] for (int by = 0; by < UP_B; ++by) {
        [[unroll]] for (int bx = 0; bx < UP_B; ++bx) {
            ivec2 t = t0 + ivec2(bx, by);
            float zf[4];
            [[unroll]] for (int o = 0; o < 4; ++o) zf[o] = view_z(load_src_depth_or_zero(2 * t + ivec2(o & 1, o >> 1)));

            rfloat centre = win_v[by + 2][bx + 2];
            rfloat tot[4], wsum[4];
            [[unroll]] for (int o = 0; o < 4; ++o) {
                tot[o] = rfloat(CACAO_BILATERAL_EPSILON) * centre;
                wsum[o] = rfloat(CACAO_BILATERAL_EPSILON);
            }
            /* fully unrolled: tot[] and wsum[] stay in registers */
            [[unroll]] for (int y = -2; y <= 2; ++y) {
                [[unroll]] for (int x = -2; x <= 2; ++x) {
                    rfloat v = win_v[by + 2 + y][bx + 2 + x];
                    float zq = win_z[by + 2 + y][bx + 2 + x];
                    [[unroll]] for (int o = 0; o < 4; ++o) {
                        /* |dx|, |dy| in half texels: x - (o & 1) / 2 and y - (o >> 1) / 2 */
                        float ws = axis_weight[abs(2 * x - (o & 1))] * axis_weight[abs(2 * y - (o >> 1))];
                        float dz = zf[o] - zq; /* sigma is used as a variance, as AMD does */
                        /* An entry outside the image (UP_NO_DEPTH) weighs exactly 0 with no test: zf
                         * is a finite view z (at most CACAO_MAX_VIEW_Z), so its difference squares to
                         * +inf, times the multiplier (negative: constants.c keeps it below -FLT_MIN)
                         * -inf, whose exp2 is 0. A select per weight cost a GPU compiler's estimate
                         * 10% of the pass (docs/gpu.md). */
                        float wz = exp2(dz * dz * depth_exp2_mul);
                        rfloat w = rfloat(ws * wz);
                        tot[o] += v * w;
                        wsum[o] += w;
                    }
                }
            }
            [[unroll]] for (int o = 0; o < 4; ++o) {
                ivec2 p = 2 * t + ivec2(o & 1, o >> 1);
                if (in_rect(p, out_size)) imageStore(output_image, p, vec4(float(tot[o] / wsum[o]), 0.0, 0.0, 0.0));
            }
        }
    }
}
#endif /* UPSAMPLE */
