#version 450
// The composite: a simple lit colour (albedo by the surface's world orientation, a directional
// sun and a sky term) with cacao's AO applied to the ambient light and, more gently, to the sun.
layout(set = 0, binding = 0) uniform sampler2D depth;   // raw [0,1] depth, 1 = nothing drawn
layout(set = 0, binding = 1) uniform sampler2D normals; // view-space normals, UNORM-packed
layout(set = 0, binding = 2) uniform sampler2D ao;      // cacao's output: 1 = unoccluded
layout(location = 0) out vec4 colour;

layout(push_constant) uniform Frame {
    mat4 world_from_view;
    vec4 light_view; // xyz: unit direction towards the sun
    vec2 size;       // framebuffer size in pixels
} frame;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(depth, pixel, 0).r >= 1.0) {
        float up = 1.0 - gl_FragCoord.y / frame.size.y;
        colour = vec4(mix(vec3(0.78, 0.84, 0.90), vec3(0.42, 0.60, 0.85), up), 1.0);
        return;
    }
    vec3 n = normalize(texelFetch(normals, pixel, 0).rgb * 2.0 - 1.0);
    vec3 n_world = mat3(frame.world_from_view) * n;
    vec3 albedo = n_world.y > 0.7 ? vec3(0.66, 0.55, 0.42) : abs(n_world.x) > 0.7 ? vec3(0.74, 0.76, 0.80)
                                                                                  : vec3(0.82, 0.79, 0.72);
    float visibility = texelFetch(ao, pixel, 0).r;
    float sun = max(dot(n, frame.light_view.xyz), 0.0);
    vec3 lit = albedo * (0.55 * visibility + 0.65 * sun * mix(0.5, 1.0, visibility));
    colour = vec4(pow(lit, vec3(1.0 / 2.2)), 1.0);
}
