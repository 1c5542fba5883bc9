/* scene.c - the raster example's room and camera path (see scene.h). */
#include "scene.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct mesh {
    raster_vertex *vertices;
    uint32_t count;
    raster_material material; /* of the vertices added next */
} mesh;

typedef struct vec3 {
    double x, y, z;
} vec3;

static vec3 v3(double x, double y, double z) { return (vec3){x, y, z}; }
static vec3 add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static vec3 sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static vec3 scale(vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vec3 cross(vec3 a, vec3 b) { return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
static vec3 normalize(vec3 a) { return scale(a, 1.0 / sqrt(dot(a, a))); }

static void vertex(mesh *m, vec3 p, vec3 n) {
    if (m->count >= RASTER_SCENE_MAX_VERTICES) return; /* cannot happen with the scene below */
    m->vertices[m->count++] = (raster_vertex){{(float)p.x, (float)p.y, (float)p.z}, {(float)n.x, (float)n.y, (float)n.z},
                                               m->material};
}

/* Two triangles a-b-c, a-c-d with a normal at each corner (culling is off: winding is free). */
static void quad(mesh *m, const vec3 p[4], const vec3 n[4]) {
    static const int corners[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; ++i) vertex(m, p[corners[i]], n[corners[i]]);
}

static void flat_quad(mesh *m, vec3 a, vec3 b, vec3 c, vec3 d, vec3 normal) {
    quad(m, (const vec3[4]){a, b, c, d}, (const vec3[4]){normal, normal, normal, normal});
}

/* A solid axis-aligned box from lo to hi, all six faces. */
static void box(mesh *m, vec3 lo, vec3 hi) {
    const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
    flat_quad(m, v3(x0, y0, z0), v3(x0, y1, z0), v3(x0, y1, z1), v3(x0, y0, z1), v3(-1, 0, 0));
    flat_quad(m, v3(x1, y0, z0), v3(x1, y1, z0), v3(x1, y1, z1), v3(x1, y0, z1), v3(1, 0, 0));
    flat_quad(m, v3(x0, y0, z0), v3(x1, y0, z0), v3(x1, y0, z1), v3(x0, y0, z1), v3(0, -1, 0));
    flat_quad(m, v3(x0, y1, z0), v3(x1, y1, z0), v3(x1, y1, z1), v3(x0, y1, z1), v3(0, 1, 0));
    flat_quad(m, v3(x0, y0, z0), v3(x1, y0, z0), v3(x1, y1, z0), v3(x0, y1, z0), v3(0, 0, -1));
    flat_quad(m, v3(x0, y0, z1), v3(x1, y0, z1), v3(x1, y1, z1), v3(x0, y1, z1), v3(0, 0, 1));
}

/* A column standing on the floor: a smooth side of `segments` quads and a flat top. */
static void column(mesh *m, double x, double z, double radius, double height, int segments) {
    const vec3 top = v3(x, height, z), up = v3(0, 1, 0);
    for (int i = 0; i < segments; ++i) {
        const double a0 = 2 * PI * i / segments, a1 = 2 * PI * (i + 1) / segments;
        const vec3 n0 = v3(cos(a0), 0, sin(a0)), n1 = v3(cos(a1), 0, sin(a1));
        const vec3 b0 = add(v3(x, 0, z), scale(n0, radius)), b1 = add(v3(x, 0, z), scale(n1, radius));
        const vec3 t0 = add(b0, v3(0, height, 0)), t1 = add(b1, v3(0, height, 0));
        quad(m, (const vec3[4]){b0, b1, t1, t0}, (const vec3[4]){n0, n1, n1, n0});
        vertex(m, top, up);
        vertex(m, t0, up);
        vertex(m, t1, up);
    }
}

/* A sphere of stacks x slices quads with smooth normals. */
static void sphere(mesh *m, vec3 centre, double radius, int stacks, int slices) {
    for (int s = 0; s < stacks; ++s)
        for (int i = 0; i < slices; ++i) {
            vec3 p[4], n[4];
            for (int k = 0; k < 4; ++k) {
                const double polar = PI * (s + (k >= 2)) / stacks;
                const double azimuth = 2 * PI * (i + (k == 1 || k == 2)) / slices;
                n[k] = v3(sin(polar) * cos(azimuth), cos(polar), sin(polar) * sin(azimuth));
                p[k] = add(centre, scale(n[k], radius));
            }
            quad(m, p, n);
        }
}

uint32_t raster_scene_build(raster_vertex *out) {
    mesh m = {out, 0, RASTER_FLOOR};
    box(&m, v3(-8, -0.2, -8), v3(8, 0, 8));           /* floor slab; beyond it, sky */
    m.material = RASTER_WALL;
    box(&m, v3(-5, 0, -4.2), v3(5, 3, -4));           /* back wall */
    box(&m, v3(-5.2, 0, -4.2), v3(-5, 3, 4));         /* left wall: a corner with the back wall */
    m.material = RASTER_FURNITURE;
    box(&m, v3(-2, 0, -3.95), v3(-0.8, 0.9, -3.1));   /* a chest 5 cm from the back wall */
    box(&m, v3(-1.8, 0.9, -3.8), v3(-1.2, 1.3, -3.3)); /* a box on top of it */
    box(&m, v3(-5, 0, -4), v3(-4, 1.6, -2.8));        /* a cupboard in the corner */
    box(&m, v3(0.5, 0, -1), v3(1.5, 0.5, 0.2));       /* a low crate in the open */
    box(&m, v3(1.8, 0.95, -3.95), v3(3.8, 1.0, -3.5)); /* a thin shelf, 5 cm off the wall */
    column(&m, 2.8, -2.4, 0.25, 3, 24);
    column(&m, -3.6, 1.2, 0.25, 3, 24);
    column(&m, 3.4, 1.4, 0.2, 2.2, 24);
    m.material = RASTER_CLAY;
    sphere(&m, v3(-1.3, 0.6, -0.6), 0.6, 16, 24);     /* resting on the floor */
    return m.count;
}

/* Row-major 4x4 from the rows of a rotation and a translation. */
static void rigid(vec3 r0, vec3 r1, vec3 r2, vec3 t, float out[16]) {
    const vec3 rows[3] = {r0, r1, r2};
    const double tr[3] = {t.x, t.y, t.z};
    memset(out, 0, 16 * sizeof(float));
    for (int i = 0; i < 3; ++i) {
        out[4 * i + 0] = (float)rows[i].x;
        out[4 * i + 1] = (float)rows[i].y;
        out[4 * i + 2] = (float)rows[i].z;
        out[4 * i + 3] = (float)tr[i];
    }
    out[15] = 1.0f;
}

void raster_camera_at(uint32_t frame, uint32_t frame_count, double aspect, raster_camera *out) {
    const double t = frame_count > 1 ? (double)frame / (frame_count - 1) : 0.0;
    const vec3 eye = v3(4.5 - 5.0 * t, 3.4 - 0.6 * t, 6.5 - 0.8 * t), target = v3(-1.5, 0.6, -1.8);
    const vec3 forward = normalize(sub(target, eye));
    const vec3 right = normalize(cross(forward, v3(0, 1, 0))), up = cross(right, forward), back = scale(forward, -1);
    rigid(right, up, back, v3(-dot(right, eye), -dot(up, eye), -dot(back, eye)), out->view_from_world);
    /* The perspective of shared/scenes/README.md: clip.w = -z_view, depth = far(z-near)/(z(far-near)). */
    const double f = 1.0 / tan(RASTER_FOV_Y_DEG * PI / 360.0), n = RASTER_NEAR, fz = RASTER_FAR;
    memset(out->projection, 0, sizeof out->projection);
    out->projection[0] = (float)(f / aspect);
    out->projection[5] = (float)f;
    out->projection[10] = (float)(-fz / (fz - n));
    out->projection[11] = (float)(-fz * n / (fz - n));
    out->projection[14] = -1.0f;
    const vec3 sun = normalize(v3(-0.5, 0.8, 0.35));
    out->light_view[0] = (float)dot(right, sun);
    out->light_view[1] = (float)dot(up, sun);
    out->light_view[2] = (float)dot(back, sun);
}
