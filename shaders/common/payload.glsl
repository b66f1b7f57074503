// What a traced ray brings back to the ray generation shader, which does all
// shading (bounces loop there; closest-hit shaders only describe the hit).
#ifndef PAYLOAD_GLSL
#define PAYLOAD_GLSL
// [region payload]
struct HitPayload {
    vec3 radiance;   // on a miss: the sky in the ray's direction
    float t;         // hit distance along the (unit) ray direction; < 0 on a miss
    vec3 normal;     // world-space unit geometric normal, pointing out of the shape
    uint material;
    vec3 position;   // world-space hit point: the ray's point at t
    uint frontFace;  // 1: the ray hit the outside (front) of the surface
    vec3 shading;    // world-space unit shading normal, on the side of `normal`: a mesh's
                     // interpolated vertex normal (chapter 12), else `normal` itself
    float radius;    // world-space radius of the sphere hit, 0 for other shapes (chapter 10)
    float error;     // how far `position` may be from the surface (hit_error.glsl, chapter 06)
};
// [end]
#endif
