// The camera ray of thesis 2.2.2, through the pixel's centre.
#ifndef CAMERA_GLSL
#define CAMERA_GLSL
// [region eye_tmin]
// Camera rays ignore hits closer to the eye than this: 0, unless the eye
// lies exactly on a surface; then a little more than that surface's
// rounding, so that the eye sees what a ray leaving that surface would: the
// outside above its tangent plane, the inside below (the rule and its value
// are in docs/scene-format.md and Scene::eyeTmin; the CPU reference follows
// it).
float eyeTmin() { return camera.eye.x; }
// [end]

// [region camera_ray]
void cameraRay(uvec2 pixel, uvec2 size, out vec3 origin, out vec3 direction) {
    vec2 pixelCenter = vec2(pixel) + 0.5;                     // not the corner
    vec2 ndc = pixelCenter / vec2(size) * 2.0 - 1.0;          // -1..1; y = -1 is the top row
    origin = (camera.viewInverse * vec4(0, 0, 0, 1)).xyz;
    vec4 target = camera.projInverse * vec4(ndc.x, ndc.y, 1, 1);  // Vulkan clip space: y down
    direction = (camera.viewInverse * vec4(normalize(target.xyz), 0)).xyz;
}
// [end]
#endif
