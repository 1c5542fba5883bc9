#version 450
// The G-buffer pass: unit view-space normals (right-handed, camera-facing +z), UNORM-packed as
// n * 0.5 + 0.5 into the A2B10G10R10 attachment; cacao unpacks them with its default 2, -1.
layout(location = 0) in vec3 normal_view;
layout(location = 0) out vec4 packed_normal;

void main() {
    packed_normal = vec4(normalize(normal_view) * 0.5 + 0.5, 1.0);
}
