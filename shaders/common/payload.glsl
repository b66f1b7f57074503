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

// [region hit_textures]
// On a hit the payload's radiance is free (the ray generation shader
// gathers a hit's light itself): a mesh's closest-hit shader brings its
// textures' values at the hit back in it, five numbers in [0, 1] as three
// pairs of 16-bit fixed point (2^-16 is far below a display's 1/255): the
// base colour texture's rgb, the metal-roughness texture's roughness (G)
// and metalness (B). Only arithmetic may flush or alter a float's bits, not
// a copy (VK_KHR_shader_float_controls, issue 1), so the bits arrive intact.
struct HitTextures {
    vec3 baseColor;   // 1 where the mesh has no base colour texture
    float roughness;  // the metal-roughness texture's: 1 where there is none
    float metalness;
};
vec3 packHitTextures(HitTextures h) {
    return uintBitsToFloat(uvec3(packUnorm2x16(h.baseColor.rg),
                                 packUnorm2x16(vec2(h.baseColor.b, h.roughness)),
                                 packUnorm2x16(vec2(h.metalness, 0.0))));
}
HitTextures unpackHitTextures(vec3 packed) {
    uvec3 bits = floatBitsToUint(packed);
    vec2 rg = unpackUnorm2x16(bits.x), br = unpackUnorm2x16(bits.y);
    return HitTextures(vec3(rg, br.x), br.y, unpackUnorm2x16(bits.z).x);
}
// [end]
#endif
