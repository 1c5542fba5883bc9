/* projections.h - test-side builders of every projection convention engines use, written from
 * the definition of clip space (clip = P * v, depth = clip.z / clip.w, ndc x right, y up), not
 * from the library's math. Header-only, tests only. */
#ifndef CACAO_TEST_PROJECTIONS_H
#define CACAO_TEST_PROJECTIONS_H

#include <stdbool.h>
#include <string.h>

typedef enum proj_kind {
    PROJ_STANDARD,
    PROJ_REVERSED,
    PROJ_INFINITE,
    PROJ_INFINITE_REVERSED,
    PROJ_ORTHO,
    PROJ_ORTHO_REVERSED,
    PROJ_KIND_COUNT
} proj_kind;

static const char *const proj_kind_names[PROJ_KIND_COUNT] = {
    "standard", "reversed", "infinite-far", "infinite-far reversed", "orthographic", "orthographic reversed"};

static inline bool proj_is_ortho(proj_kind k) { return k == PROJ_ORTHO || k == PROJ_ORTHO_REVERSED; }
static inline bool proj_is_reversed(proj_kind k) {
    return k == PROJ_REVERSED || k == PROJ_INFINITE_REVERSED || k == PROJ_ORTHO_REVERSED;
}

/* Row-major math-convention matrix. The view looks down +z (left-handed) or -z (right-handed);
 * at distance f a point (x, y) lands at ndc (x / (f sx) + jx, y / (f sy) + jy) for perspective
 * (sx, sy = tan of the half angles) and at (x / sx + jx, y / sy + jy) for orthographic (sx, sy =
 * half extents); depth maps near..far to 0..1, or 1..0 when reversed. */
static inline void proj_build(proj_kind k, bool left_handed, double sx, double sy, double n, double f, double jx,
                              double jy, float out[16]) {
    const double h = left_handed ? 1.0 : -1.0;
    memset(out, 0, 16 * sizeof(float));
    out[0] = (float)(1.0 / sx);
    out[5] = (float)(1.0 / sy);
    if (proj_is_ortho(k)) {
        out[3] = (float)jx;
        out[7] = (float)jy;
        out[10] = (float)(k == PROJ_ORTHO ? h / (f - n) : -h / (f - n));
        out[11] = (float)(k == PROJ_ORTHO ? -n / (f - n) : f / (f - n));
        out[15] = 1.0f;
        return;
    }
    out[2] = (float)(h * jx);
    out[6] = (float)(h * jy);
    out[14] = (float)h;
    switch (k) {
    case PROJ_STANDARD:
        out[10] = (float)(h * f / (f - n)), out[11] = (float)(-f * n / (f - n));
        break;
    case PROJ_REVERSED:
        out[10] = (float)(-h * n / (f - n)), out[11] = (float)(f * n / (f - n));
        break;
    case PROJ_INFINITE:
        out[10] = (float)h, out[11] = (float)(-n);
        break;
    default:
        out[10] = 0.0f, out[11] = (float)n;
        break; /* infinite reversed: d = n / z */
    }
}

/* Depth the projection writes for a point at distance z (> 0) in front of the camera. */
static inline double proj_depth(proj_kind k, double n, double f, double z) {
    switch (k) {
    case PROJ_STANDARD:
        return f * (z - n) / (z * (f - n));
    case PROJ_REVERSED:
        return n * (f - z) / (z * (f - n));
    case PROJ_INFINITE:
        return 1.0 - n / z;
    case PROJ_INFINITE_REVERSED:
        return n / z;
    case PROJ_ORTHO:
        return (z - n) / (f - n);
    default:
        return (f - z) / (f - n);
    }
}

static inline void proj_transpose(const float in[16], float out[16]) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[c * 4 + r] = in[r * 4 + c];
}

#endif /* CACAO_TEST_PROJECTIONS_H */
