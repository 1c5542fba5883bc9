#version 450
// The G-buffer pass: world-space triangles to clip space, normals to view space.
layout(location = 0) in vec3 position_world;
layout(location = 1) in vec3 normal_world;
layout(location = 2) in uint material;
layout(location = 0) out vec3 normal_view;
layout(location = 1) flat out uint material_out;

layout(push_constant) uniform Frame {
    mat4 clip_from_world; // the projection cacao gets, with clip y negated: Vulkan's framebuffer y points down
    mat4 view_from_world; // rigid: its 3x3 maps normals too
} frame;

void main() {
    gl_Position = frame.clip_from_world * vec4(position_world, 1.0);
    normal_view = mat3(frame.view_from_world) * normal_world;
    material_out = material;
}
