/* scene.c - analytic ray casting of the procedural test scene (see scene.h).
 * spec: shared/scenes/README.md, "Conventions" (pixel rays, depth, normals, matrices). */
#include "scene.h"

#include "camera_json.h"

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846 /* M_PI is not in strict C11 */

typedef struct vec3 {
    double x, y, z;
} vec3;

static vec3 v3(const double p[3]) { return (vec3){p[0], p[1], p[2]}; }
static vec3 add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static vec3 sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static vec3 scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
static double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vec3 cross(vec3 a, vec3 b) {
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static vec3 normalize(vec3 a) { return scale(a, 1.0 / sqrt(dot(a, a))); }
static double component(vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }

/* ---- Camera ------------------------------------------------------------------------------- */

/* The camera's orthonormal world-space basis and half-extents of the image at unit distance. */
typedef struct camera_frame {
    vec3 right, up, back; /* view +x, +y, +z in world space */
    double tan_half_x, tan_half_y;
} camera_frame;

static camera_frame camera_frame_of(const cacao_camera *cam) {
    camera_frame frame;
    frame.back = normalize(sub(v3(cam->eye), v3(cam->target)));
    frame.right = normalize(cross(v3(cam->up), frame.back));
    frame.up = cross(frame.back, frame.right);
    frame.tan_half_y = tan(cam->fov_y_deg * (PI / 360.0));
    frame.tan_half_x = frame.tan_half_y * ((double)cam->width / (double)cam->height);
    return frame;
}

void cacao_camera_projection(const cacao_camera *cam, bool reversed, float out[16]) {
    const cacao_lens centred = {0};
    cacao_camera_projection_lens(cam, &centred, reversed, out);
}

void cacao_camera_projection_lens(const cacao_camera *cam, const cacao_lens *lens, bool reversed, float out[16]) {
    double aspect = (double)cam->width / (double)cam->height;
    double n = cam->near_z, f = cam->far_z;
    for (int i = 0; i < 16; i++) out[i] = 0.0f;
    if (lens->ortho_half_height > 0.0) { /* right-handed: z_view = -distance */
        out[0] = (float)(1.0 / (aspect * lens->ortho_half_height));
        out[5] = (float)(1.0 / lens->ortho_half_height);
        out[3] = (float)lens->jitter_ndc[0];
        out[7] = (float)lens->jitter_ndc[1];
        out[10] = (float)(reversed ? 1.0 / (f - n) : -1.0 / (f - n));
        out[11] = (float)(reversed ? f / (f - n) : -n / (f - n));
        out[15] = 1.0f;
        return;
    }
    cacao_perspective(cam->fov_y_deg, aspect, n, f, reversed, out);
    out[2] = (float)-lens->jitter_ndc[0]; /* clip w = -z_view */
    out[6] = (float)-lens->jitter_ndc[1];
}

void cacao_camera_view_from_world(const cacao_camera *cam, float out[16]) {
    camera_frame frame = camera_frame_of(cam);
    vec3 eye = v3(cam->eye);
    const vec3 rows[3] = {frame.right, frame.up, frame.back};
    for (int r = 0; r < 3; r++) {
        out[4 * r + 0] = (float)rows[r].x;
        out[4 * r + 1] = (float)rows[r].y;
        out[4 * r + 2] = (float)rows[r].z;
        out[4 * r + 3] = (float)-dot(rows[r], eye);
    }
    out[12] = out[13] = out[14] = 0.0f;
    out[15] = 1.0f;
}

/* ---- Intersections ------------------------------------------------------------------------ */

/* Rays are origin + t * dir with dir's view-space z = -1, so t is the view distance z itself.
 * Each function reports the smallest surface crossing with t_min <= t < t_max (entry or exit:
 * a solid cut open by the near plane shows its far side, as a rasteriser would draw it). */
typedef struct hit {
    double t;
    vec3 normal; /* world space, any length, either orientation */
} hit;

static bool intersect_plane(const cacao_prim *p, vec3 origin, vec3 dir, double t_min,
                            double t_max, hit *out) {
    vec3 normal = v3(p->b);
    double facing = dot(normal, dir);
    if (facing == 0.0) return false;
    double t = dot(normal, sub(v3(p->a), origin)) / facing;
    if (!(t >= t_min && t < t_max)) return false;
    *out = (hit){t, normal};
    return true;
}

static bool intersect_sphere(const cacao_prim *p, vec3 origin, vec3 dir, double t_min,
                             double t_max, hit *out) {
    /* Quadratic in the stable form of Ray Tracing Gems ch. 7: the discriminant from the
     * ray's closest approach, and the two roots without cancellation. */
    vec3 centre = v3(p->a);
    vec3 to_origin = sub(origin, centre);
    double a = dot(dir, dir);
    double b = dot(to_origin, dir);
    vec3 closest = sub(to_origin, scale(dir, b / a));
    double disc = a * (p->r * p->r - dot(closest, closest));
    if (disc < 0.0) return false;
    double c = dot(to_origin, to_origin) - p->r * p->r;
    double q = -b - copysign(sqrt(disc), b);
    double roots[2] = {q != 0.0 ? c / q : 0.0, q / a};
    if (roots[0] > roots[1]) {
        double swap = roots[0];
        roots[0] = roots[1];
        roots[1] = swap;
    }
    for (int i = 0; i < 2; i++) {
        if (roots[i] >= t_min && roots[i] < t_max) {
            *out = (hit){roots[i], sub(add(origin, scale(dir, roots[i])), centre)};
            return true;
        }
    }
    return false;
}

static bool intersect_box(const cacao_prim *p, vec3 origin, vec3 dir, double t_min, double t_max,
                          hit *out) {
    vec3 lo = v3(p->a), hi = v3(p->b);
    double t_enter = -INFINITY, t_exit = INFINITY;
    int enter_axis = -1, exit_axis = -1;
    for (int axis = 0; axis < 3; axis++) {
        double o = component(origin, axis), d = component(dir, axis);
        double lo_a = component(lo, axis), hi_a = component(hi, axis);
        if (d == 0.0) {
            if (o < lo_a || o > hi_a) return false;
            continue;
        }
        double t0 = (lo_a - o) / d, t1 = (hi_a - o) / d;
        if (t0 > t1) {
            double swap = t0;
            t0 = t1;
            t1 = swap;
        }
        if (t0 > t_enter) t_enter = t0, enter_axis = axis;
        if (t1 < t_exit) t_exit = t1, exit_axis = axis;
    }
    if (t_enter > t_exit) return false;
    const double candidates[2] = {t_enter, t_exit};
    const int axes[2] = {enter_axis, exit_axis};
    for (int i = 0; i < 2; i++) {
        if (axes[i] >= 0 && candidates[i] >= t_min && candidates[i] < t_max) {
            vec3 normal = {axes[i] == 0, axes[i] == 1, axes[i] == 2};
            *out = (hit){candidates[i], normal};
            return true;
        }
    }
    return false;
}

static bool intersect(const cacao_prim *p, vec3 origin, vec3 dir, double t_min, double t_max,
                      hit *out) {
    switch (p->kind) {
    case CACAO_PRIM_PLANE: return intersect_plane(p, origin, dir, t_min, t_max, out);
    case CACAO_PRIM_BOX: return intersect_box(p, origin, dir, t_min, t_max, out);
    case CACAO_PRIM_SPHERE: return intersect_sphere(p, origin, dir, t_min, t_max, out);
    }
    return false;
}

/* ---- Rendering ---------------------------------------------------------------------------- */

void cacao_scene_render(const cacao_scene *scene, float *depth, float *depth_reversed,
                        float *normals) {
    const cacao_lens centred = {0};
    cacao_scene_render_lens(scene, &centred, depth, depth_reversed, normals);
}

void cacao_scene_render_lens(const cacao_scene *scene, const cacao_lens *lens, float *depth, float *depth_reversed,
                             float *normals) {
    const cacao_camera *cam = &scene->camera;
    camera_frame frame = camera_frame_of(cam);
    vec3 eye = v3(cam->eye);
    double n = cam->near_z, f = cam->far_z;
    const bool ortho = lens->ortho_half_height > 0.0;
    const double sy = ortho ? lens->ortho_half_height : frame.tan_half_y;
    const double sx = sy * ((double)cam->width / (double)cam->height);
    for (uint32_t y = 0; y < cam->height; y++) {
        double view_y = (1.0 - 2.0 * ((y + 0.5) / cam->height) - lens->jitter_ndc[1]) * sy;
        for (uint32_t x = 0; x < cam->width; x++) {
            double view_x = (2.0 * ((x + 0.5) / cam->width) - 1.0 - lens->jitter_ndc[0]) * sx;
            vec3 across = add(scale(frame.right, view_x), scale(frame.up, view_y));
            vec3 origin = ortho ? add(eye, across) : eye;
            vec3 dir = ortho ? scale(frame.back, -1.0) : sub(across, frame.back);

            /* Closest hit in [near, far]; the far plane itself counts as inside. */
            hit best = {nextafter(f, INFINITY), {0, 0, 0}};
            bool any = false;
            for (uint32_t i = 0; i < scene->prim_count; i++) {
                hit h;
                if (intersect(&scene->prims[i], origin, dir, n, best.t, &h)) best = h, any = true;
            }

            size_t pixel = (size_t)y * cam->width + x;
            double z = best.t;
            depth[pixel] = !any ? 1.0f : ortho ? (float)((z - n) / (f - n)) : (float)(f * (z - n) / (z * (f - n)));
            if (depth_reversed)
                depth_reversed[pixel] =
                    !any ? 0.0f : ortho ? (float)((f - z) / (f - n)) : (float)(n * (f - z) / (z * (f - n)));
            if (normals) {
                vec3 view_normal = {0, 0, 0};
                if (any) {
                    vec3 world = normalize(best.normal);
                    if (dot(world, dir) > 0.0) world = scale(world, -1.0);
                    view_normal = normalize((vec3){dot(world, frame.right), dot(world, frame.up),
                                                   dot(world, frame.back)});
                }
                normals[3 * pixel + 0] = (float)view_normal.x;
                normals[3 * pixel + 1] = (float)view_normal.y;
                normals[3 * pixel + 2] = (float)view_normal.z;
            }
        }
    }
}

/* ---- The default scene -------------------------------------------------------------------- */

#define BOX(x0, y0, z0, x1, y1, z1) {CACAO_PRIM_BOX, {x0, y0, z0}, {x1, y1, z1}, 0.0}
#define SPHERE(x, y, z, radius) {CACAO_PRIM_SPHERE, {x, y, z}, {0, 0, 0}, radius}
/* A step of the flight: solid from the floor up to its tread at height 0.18*k, running back to
 * the back wall, so each riser meets the tread below in an inner corner. */
#define STEP(k) BOX(-3.2, 0.0, -9.0, -1.2, 0.18 * (k), -9.0 + 0.3 * (9 - (k)))

/* Room: floor y = 0 (an infinite plane, so it reaches the far plane), walls 3.5 m high on the
 * left (x = -5) and at the back (z = -9), open to the right (x > 3.5) and with no roof. */
static const cacao_prim default_prims[] = {
    {CACAO_PRIM_PLANE, {0, 0, 0}, {0, 1, 0}, 0.0}, /* floor */
    BOX(-5.3, 0.0, -9.3, -5.0, 3.5, 3.0),          /* left wall */
    BOX(-5.3, 0.0, -9.3, 3.5, 3.5, -9.0),          /* back wall */
    BOX(3.2, 0.0, -9.0, 3.5, 3.5, -7.5),           /* return of the back wall at the open side */
    /* Columns */
    BOX(-2.75, 0.0, -3.75, -2.25, 3.5, -3.25),
    BOX(0.75, 0.0, -3.75, 1.25, 3.5, -3.25),
    BOX(0.75, 0.0, -7.25, 1.25, 3.5, -6.75),
    BOX(-5.0, 0.0, -6.0, -4.7, 3.5, -5.4), /* pilaster on the left wall */
    /* Stairs up to the back wall, with a landing */
    STEP(1), STEP(2), STEP(3), STEP(4), STEP(5), STEP(6), STEP(7), STEP(8),
    BOX(-3.2, 0.0, -9.0, -1.2, 1.62, -8.7),
    /* Spheres: on the open floor, against the left wall, in the back corner, touching a column
     * and touching the back wall */
    SPHERE(-0.4, 0.5, -1.6, 0.5),
    SPHERE(-4.4, 0.6, -2.0, 0.6),
    SPHERE(-4.65, 0.35, -8.65, 0.35),
    SPHERE(1.55, 0.3, -7.0, 0.3),
    SPHERE(2.6, 0.4, -8.6, 0.4),
    SPHERE(2.4, 0.35, -1.2, 0.35),
    /* A low block and a bench against the back wall */
    BOX(-1.0, 0.0, -5.6, 0.0, 0.4, -4.6),
    BOX(-0.6, 0.0, -9.0, 0.6, 0.45, -8.5),
};

static const cacao_scene default_scene = {
    .prims = default_prims,
    .prim_count = sizeof(default_prims) / sizeof(default_prims[0]),
    .camera =
        {
            .fov_y_deg = 60.0,
            .near_z = 0.1,
            .far_z = 500.0,
            .eye = {3.0, 1.6, 2.2},
            .target = {-1.0, 0.9, -5.5},
            .up = {0.0, 1.0, 0.0},
        },
    .ao_radius_world = 0.5,
};

cacao_scene cacao_default_scene(uint32_t width, uint32_t height) {
    cacao_scene scene = default_scene;
    scene.camera.width = width ? width : 1280;
    scene.camera.height = height ? height : 720;
    return scene;
}
