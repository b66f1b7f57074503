// The camera ray of thesis 2.2.2, through a point of the pixel: its centre,
// or with --antialias a new point each frame (chapter 04's antialiasing).
#ifndef CAMERA_GLSL
#define CAMERA_GLSL
#include "sampling.glsl"
// [region eye_tmin]
// Camera rays ignore hits closer to the eye than this: 0, unless the eye
// lies exactly on a surface; then a little more than that surface's
// rounding, so that the eye sees what a ray leaving that surface would: the
// outside above its tangent plane, the inside below (the rule and its value
// are in docs/scene-format.md and Scene::eyeTmin; the CPU reference follows
// it).
float eyeTmin() { return camera.eyeTmin; }
// [end]

// [region camera_ray]
// `offset`: where in the pixel the ray passes, (0.5, 0.5) at its centre.
void cameraRay(uvec2 pixel, uvec2 size, vec2 offset, out vec3 origin,
               out vec3 direction) {
    // -1..1; y = -1: the top row
    vec2 ndc = (vec2(pixel) + offset) / vec2(size) * 2.0 - 1.0;
    origin = (camera.viewInverse * vec4(0, 0, 0, 1)).xyz;
    // Vulkan clip space: y down
    vec4 target = camera.projInverse * vec4(ndc.x, ndc.y, 1, 1);
    direction = (camera.viewInverse * vec4(normalize(target.xyz), 0)).xyz;
}
// [end]

// [region pixel_offset]
// Antialiasing: a pixel is a small square, and its colour the mean over it.
// Frame k of an accumulation (push.accumulated) samples point k of the
// pixel's own scrambled Sobol sequence (sampling.glsl): after 2^m frames one
// point in each of 2^m equal parts of the square. The seed is the pixel's
// alone, so a window that rested for N frames shows what a headless run of
// N frames writes. Without --antialias: the centre.
vec2 pixelOffset(uvec2 pixel) {
    return kAverages && push.antialias != 0u ? pixelJitter(pixel, push.accumulated)
                                             : vec2(0.5);
}
// [end]
#endif
