/* scene.h - the raster example's procedural room (triangles) and its camera path. Pure
 * computation, no Vulkan.
 *
 * World space: y up, metres. View space: right-handed, x right, y up, the camera looks down -z
 * (the convention of shared/scenes/README.md and of the `cacao` command's normals.pfm). */
#ifndef RASTER_SCENE_H
#define RASTER_SCENE_H

#include <stdint.h>

#define RASTER_FOV_Y_DEG 60.0
#define RASTER_NEAR 0.1
#define RASTER_FAR 60.0
#define RASTER_AO_RADIUS 0.6 /* world units: a box's gap to the wall (5 cm) and its creases show */

/* Room, boxes, columns and a sphere: every triangle 3 vertices, normals facing out of the solid. */
#define RASTER_SCENE_MAX_VERTICES 8192

/* What a surface is made of: the composite's albedo. Four, as the normals attachment's 2-bit alpha
 * carries it (cacao reads only rgb). */
typedef enum raster_material { RASTER_FLOOR, RASTER_WALL, RASTER_FURNITURE, RASTER_CLAY } raster_material;

typedef struct raster_vertex {
    float position[3]; /* world */
    float normal[3];   /* world, unit */
    uint32_t material; /* raster_material */
} raster_vertex;

/* Writes the scene's triangles into out (RASTER_SCENE_MAX_VERTICES entries); returns the number
 * of vertices written, a multiple of 3. */
uint32_t raster_scene_build(raster_vertex *out);

/* Matrices of one frame, row-major, acting on column vectors (clip = P * v). */
typedef struct raster_camera {
    float view_from_world[16];
    float projection[16];   /* math convention for cacao: depth 0 near, 1 far; clip y up */
    float light_view[3];    /* unit direction towards the sun, view space */
} raster_camera;

/* The camera of frame `frame` of `frame_count` along a fixed path past the room's open side, for
 * an image of this aspect (width / height). */
void raster_camera_at(uint32_t frame, uint32_t frame_count, double aspect, raster_camera *out);

#endif
