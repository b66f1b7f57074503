// What a traced ray brings back to the ray generation shader, which does all
// shading (bounces loop there; closest-hit shaders only describe the hit).
#ifndef PAYLOAD_GLSL
#define PAYLOAD_GLSL
// [region payload]
// 16 scalars: a 17th costs chapter 09 13 % on an H200 (docs/12_triangle_meshes.md).
struct HitPayload {
    vec3 radiance;   // on a miss: the sky in the ray's direction
    float t;         // hit distance along the (unit) ray direction; < 0 on a miss
    vec3 normal;     // world-space unit geometric normal, pointing out of the shape
    // index into objects[]: the material, the radius (chapter 10) of what was hit
    uint object;
    vec3 position;   // world-space hit point: the ray's point at t
    uint frontFace;  // 1: the ray hit the outside (front) of the surface
    vec3 shading;    // world-space unit shading normal, on the side of `normal`: a mesh's
                     // interpolated vertex normal (chapter 12), else `normal` itself
    // how far `position` may be from the surface (hit_error.glsl, chapter 06)
    float error;
};
// [end]
#endif
