#version 450
// The composite: a simple lit colour (albedo by material, a directional sun, ambient light) with
// cacao's AO applied to the ambient light and, more gently, to the sun.
layout(set = 0, binding = 0) uniform sampler2D depth;   // raw [0,1] depth, 1 = nothing drawn
layout(set = 0, binding = 1) uniform sampler2D normals; // view-space normal (UNORM-packed), material in alpha
layout(set = 0, binding = 2) uniform sampler2D ao;      // cacao's output: 1 = unoccluded
layout(location = 0) out vec4 colour;

layout(push_constant) uniform Frame {
    vec4 light_view; // xyz: unit direction towards the sun, view space
    vec2 size;       // framebuffer size in pixels
} frame;

const vec3 albedo[4] = vec3[4](vec3(0.76, 0.64, 0.50),  // floor
                               vec3(0.88, 0.86, 0.82),  // walls
                               vec3(0.64, 0.71, 0.80),  // furniture
                               vec3(0.86, 0.52, 0.40)); // clay

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(depth, pixel, 0).r >= 1.0) { // sky: lighter towards the horizon
        float up = 1.0 - gl_FragCoord.y / frame.size.y;
        colour = vec4(mix(vec3(0.78, 0.84, 0.90), vec3(0.42, 0.60, 0.85), up), 1.0);
        return;
    }
    vec4 g = texelFetch(normals, pixel, 0);
    vec3 n = normalize(g.rgb * 2.0 - 1.0);
    float visibility = texelFetch(ao, pixel, 0).r;
    float sun = max(dot(n, frame.light_view.xyz), 0.0);
    vec3 lit = albedo[int(round(g.a * 3.0))] * (0.8 * visibility + 0.45 * sun * mix(0.4, 1.0, visibility));
    colour = vec4(lit, 1.0); // written as display values, no tone curve: the AO shows as computed
}
