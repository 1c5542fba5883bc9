/* scene.h - a procedural scene of planes, boxes and spheres, ray-cast on the CPU into the depth
 * and normal buffers an SSAO effect takes as input (tools and tests only).
 *
 * Conventions are those of shared/scenes/README.md: view space is right-handed (+x right, +y up,
 * the camera looks down -z), the view distance of a point is z = -Z_view, pixel (x, y) with y = 0
 * the top row is the ray through the pixel centre, geometry outside [near, far] is clipped, and
 * buffers are width*height, top row first. World space has y up; units are metres.
 */
#ifndef CACAO_SCENE_H
#define CACAO_SCENE_H

#include <stdbool.h>
#include <stdint.h>

/* A pinhole camera. */
typedef struct cacao_camera {
    uint32_t width, height;  /* image size in pixels; aspect = width / height */
    double fov_y_deg;        /* full vertical field of view, degrees */
    double near_z, far_z;    /* clip distances along the view axis, 0 < near_z < far_z */
    double eye[3];           /* camera position, world space */
    double target[3];        /* a point the camera looks at, world space */
    double up[3];            /* world up hint, not parallel to target - eye */
} cacao_camera;

/* How a camera projects, beyond the plain centred perspective: all zero is that. */
typedef struct cacao_lens {
    /* > 0 makes the camera orthographic with this half height (world units; fov_y_deg unused). */
    double ortho_half_height;
    /* A frustum offset in NDC units (x right, y up), as a TAA jitter or an asymmetric frustum:
     * image content moves by jitter_ndc * size / 2 pixels, right and up. */
    double jitter_ndc[2];
} cacao_lens;

typedef enum cacao_prim_kind {
    CACAO_PRIM_PLANE,  /* infinite plane through a with normal b (any length) */
    CACAO_PRIM_BOX,    /* solid axis-aligned box from corner a (min) to corner b (max) */
    CACAO_PRIM_SPHERE, /* solid sphere with centre a and radius r */
} cacao_prim_kind;

/* One analytic primitive; which fields matter depends on kind. */
typedef struct cacao_prim {
    cacao_prim_kind kind;
    double a[3]; /* plane: a point on it; box: min corner; sphere: centre */
    double b[3]; /* plane: normal; box: max corner */
    double r;    /* sphere: radius */
} cacao_prim;

typedef struct cacao_scene {
    const cacao_prim *prims; /* prim_count primitives, not owned */
    uint32_t prim_count;
    cacao_camera camera;
    double ao_radius_world; /* the AO radius suited to the scene, world units */
} cacao_scene;

/* Ray-casts every pixel (closest hit in [near, far] over all primitives, in double precision,
 * stored as float). Each buffer holds camera.width * camera.height pixels, top row first, and is
 * allocated by the caller:
 *   depth:          standard [0,1] depth d = far*(z-near)/(z*(far-near)); background 1.0.
 *   depth_reversed: (may be NULL) d_r = near*(far-z)/(z*(far-near)); background 0.0.
 *   normals:        (may be NULL) 3 floats per pixel: the unit geometric normal in view space,
 *                   flipped to face the camera; background (0, 0, 0). */
void cacao_scene_render(const cacao_scene *scene, float *depth, float *depth_reversed,
                        float *normals);

/* The same through a lens: orthographic depth is d = (z-near)/(far-near), d_r = 1 - d. */
void cacao_scene_render_lens(const cacao_scene *scene, const cacao_lens *lens, float *depth, float *depth_reversed,
                             float *normals);

/* The README's projection (reversed = false: standard depth; true: reverse-Z), row-major 4x4
 * acting on column vectors: clip = P * (x, y, z, 1) in view space, clip.w = -Z_view. */
void cacao_camera_projection(const cacao_camera *cam, bool reversed, float out[16]);

/* The same through a lens (an orthographic one has P(3,2) = 0, P(3,3) = 1; a jitter lands in
 * P(0,2), P(1,2), or P(0,3), P(1,3) when orthographic). */
void cacao_camera_projection_lens(const cacao_camera *cam, const cacao_lens *lens, bool reversed, float out[16]);

/* World to view space, row-major 4x4 acting on column vectors: rows [right; up; back], translation
 * -R * eye, with back = normalize(eye - target), right = normalize(up_hint x back). */
void cacao_camera_view_from_world(const cacao_camera *cam, float out[16]);

/* The built-in test scene: a roofless room (sky above) with columns, a flight of stairs and
 * spheres resting on the floor and against the walls; one side is open and the floor plane runs
 * out to the far plane there. fov_y 60 degrees, near 0.1, far 500, ao_radius_world 0.5 m.
 * width/height set the camera's image size (0 means the default 1280x720).
 * Returned by value; its primitives point to constant static storage. */
cacao_scene cacao_default_scene(uint32_t width, uint32_t height);

#endif /* CACAO_SCENE_H */
