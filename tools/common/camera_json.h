/* camera_json.h - reads a scene's camera.json (layout of ../shared/scenes/README.md). */
#ifndef CACAO_CAMERA_JSON_H
#define CACAO_CAMERA_JSON_H

#include <stdbool.h>
#include <stddef.h>

typedef struct cacao_camera_file {
    int width, height; /* 0 when absent */
    double fov_y_deg, near_z, far_z;
    double ao_radius_world; /* 0 when absent */
    bool has_projection, has_projection_reversed;
    float projection[16]; /* row-major, acting on column vectors */
    float projection_reversed[16];
} cacao_camera_file;

/* Reads and checks the file; on failure writes one message naming the file and field. */
bool cacao_camera_json_read(const char *path, cacao_camera_file *out, char *err, size_t err_size);

/* Reads a JSON file of at most max_bytes that must hold exactly one object: anything after it
 * (trailing garbage) is refused naming the line and column, and so is a key given twice at the top
 * level (naming the key). Returns the parsed object (free with cJSON_Delete), or NULL with err. */
struct cJSON *cacao_json_read_object(const char *path, size_t max_bytes, char *err, size_t err_size);

/* Builds the scenes' perspective projection (row-major, column vectors) from fov/aspect/near/far. */
void cacao_perspective(double fov_y_deg, double aspect, double near_z, double far_z, bool reversed, float out[16]);

#endif
