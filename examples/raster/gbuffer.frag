#version 450
// The G-buffer pass: unit view-space normals (right-handed, camera-facing +z), UNORM-packed as
// n * 0.5 + 0.5 into the rgb of the A2B10G10R10 attachment (cacao unpacks them with its default
// 2, -1), and the material (0..3) in its 2-bit alpha, which cacao does not read.
layout(location = 0) in vec3 normal_view;
layout(location = 1) flat in uint material;
layout(location = 0) out vec4 packed_normal;

void main() {
    packed_normal = vec4(normalize(normal_view) * 0.5 + 0.5, float(material) / 3.0);
}
