// Blinn-Phong shading (thesis 3), defined once for every chapter's raygen:
// ambient (3.1), diffuse with a shadow ray to each light (3.2), specular
// with the half vector (3.3). Radiance is linear; the display transform
// happens once, at the end (shared/core/display.h).
#ifndef SHADING_GLSL
#define SHADING_GLSL
#include "offset.glsl"
#include "hit_error.glsl"

layout(location = 1) rayPayloadEXT uint shadowPayload;

// a light adding less than this to a point is left out (no shadow ray)
#define MIN_LIGHT 1e-4

// [region ambient]
vec3 ambientTerm(GpuMaterial m) {
    return m.ka.rgb * camera.ambient.rgb;  // I_g = k_a I_a
}
// [end]

// Length and direction of a vector of any size: |v|^2 overflows float past
// 1.8e19 (a light seen from a sky dome of radius 1e20); then v is first
// divided by its largest component (only where the scene can be that
// large: kCarefulSizes).
float safeLength(vec3 v) {
    float vv = dot(v, v);
    if (!kCarefulSizes || vv < 1e37) return sqrt(vv);
    float m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    return m * length(v / m);
}
vec3 safeNormalize(vec3 v) {
    float vv = dot(v, v);
    return !kCarefulSizes || vv < 1e37
               ? v * inversesqrt(vv)
               : normalize(v / max(abs(v.x), max(abs(v.y), abs(v.z))));
}

// [region visible]
// True when nothing lies between `origin` (already offset from the surface)
// and the light. The ray is aimed from where it starts: aimed from the
// surface point instead, it would end beside the light, by the offset.
// It stops short of the light by the rounding of the two points (the same
// kind of bound as the offset, not a share of the distance), so a light
// inside a small closed object stays inside it. It needs no closest hit,
// only "anything at all": it stops at the first hit and runs no
// closest-hit shader; only the shadow miss shader says "lit".
bool lightVisible(vec3 origin, vec3 light) {
    vec3 toLight = light - origin;
    float distanceToLight = safeLength(toLight);
    toLight = safeNormalize(toLight);
    vec3 magnitude = max(abs(origin), abs(light));
    float shortBy =
        64.0 * kUnitRoundoff * max(magnitude.x, max(magnitude.y, magnitude.z));
    shadowPayload = 1u;  // assume blocked until the miss shader says otherwise
    traceRayEXT(tlas,
                kRayFlags | gl_RayFlagsTerminateOnFirstHitEXT |
                    gl_RayFlagsSkipClosestHitShaderEXT,
                0xFF,  // every instance can cast a shadow
                RAY_TYPE_SHADOW,  // SBT offset: the shadow hit groups
                0,  // SBT stride: one geometry per BLAS
                MISS_SHADOW,  // the shadow miss shader
                origin, 0.0,  // origin already offset from the surface
                toLight, distanceToLight - shortBy,  // stop just short of the light
                1);  // payload location 1: shadowPayload
    return shadowPayload == 0u;
}
// [end]

// [region specular_power]
// max(0, n.h)^shininess for any shininess: near the peak n.h rounds to 1
// within 6e-8, which a power of 1e6 turns into 6 % (e^(-1e6 * 6e-8)). So in
// a scene with a shininess of 1e4 or more (where that error passes 6e-4;
// kCarefulShininess) the power is taken as exp(shininess * log(cos)) with
// 1 - cos from the vectors' difference, |n - h|^2 / 2, exact where cos is
// near 1. Every material of such a scene takes that path: a branch on each
// material's shininess splits the GPU's threads (chapter 12: 1 % slower).
float specularPower(vec3 n, vec3 h, float shininess) {
    float cosine = dot(n, h);
    if (cosine <= 0.0) return 0.0;
    if (!kCarefulShininess) return pow(cosine, shininess);
    vec3 w = n - h;
    float x = 0.5 * dot(w, w);                                     // 1 - cos
    float logCosine = x < 1e-3 ? -x * (1.0 + x * (0.5 + x / 3.0))  // log(1 - x), series
                               : log(cosine);
    return exp(shininess * logCosine);
}
// [end]

// [region diffuse]
// k_d * sum over lights of I_i * max(0, l . n), for the lights this point sees.
// n faces the side the ray came from; `rays` counts the shadow rays traced.
vec3 diffuseTerm(GpuMaterial m, vec3 p, float error, vec3 n, inout uint rays) {
    vec3 sum = vec3(0.0);
    vec3 origin = secondaryOrigin(p, error, n);
    for (uint i = 0u; i < camera.counts.z; ++i) {
        vec3 l = safeNormalize(lights[i].position.xyz - p);
        float ndotl = dot(n, l);
        if (ndotl <= 0.0) continue;  // the light is behind the surface: no ray needed
        ++rays;
        if (lightVisible(origin, lights[i].position.xyz))
            sum += lights[i].intensity.rgb * ndotl;
    }
    return m.kd.rgb * sum;
}
// [end]

// [region diffuse_specular]
// Diffuse and Blinn-Phong specular together, one shadow ray per light that
// could add at least MIN_LIGHT here:
// k_d I_i max(0, l.n) + k_s I_i max(0, n.h)^shininess, h = (l + v) / |l + v|.
// Chapter 12's meshes light with their interpolated normal `ns`; shadow
// rays still leave along the surface's own normal n (ns = n before).
vec3 diffuseSpecularTerm(GpuMaterial m, vec3 p, float error, vec3 n, vec3 ns, vec3 v,
                         inout uint rays) {
    vec3 sum = vec3(0.0);
    vec3 origin = secondaryOrigin(p, error, n);
    for (uint i = 0u; i < camera.counts.z; ++i) {
        vec3 l = safeNormalize(lights[i].position.xyz - p);
        float ndotl = dot(ns, l);
        if (ndotl <= 0.0) continue;
        vec3 h = normalize(l + v);
        float specular = specularPower(ns, h, m.params.x);
        vec3 light = lights[i].intensity.rgb * (m.kd.rgb * ndotl + m.ks.rgb * specular);
        // A light that could add next to nothing here (clear glass away from its
        // glint) is not shadow-tested: the rule the ray tree prunes branches by.
        if (max(light.r, max(light.g, light.b)) < MIN_LIGHT) continue;
        ++rays;
        if (lightVisible(origin, lights[i].position.xyz)) sum += light;
    }
    return sum;
}
// [end]

vec3 diffuseSpecularTerm(GpuMaterial m, vec3 p, float error, vec3 n, vec3 v,
                         inout uint rays) {
    return diffuseSpecularTerm(m, p, error, n, n, v, rays);
}

// Chapter 07's whole local model: ambient + diffuse + specular.
vec3 localShading(GpuMaterial m, vec3 p, float error, vec3 n, vec3 ns, vec3 v,
                  inout uint rays) {
    return ambientTerm(m) + diffuseSpecularTerm(m, p, error, n, ns, v, rays);
}
vec3 localShading(GpuMaterial m, vec3 p, float error, vec3 n, vec3 v, inout uint rays) {
    return localShading(m, p, error, n, n, v, rays);
}

// [region surface_light]
// Chapter 09 on: the two parts of the local model take different shares of
// the light. Ambient and diffuse light is scattered by the surface's own
// material: it takes the share the surface keeps (`local`). The highlight
// is the light's reflection, blurred (thesis 3.3): a dielectric reflects
// the Fresnel share F of it (`highlight`), however much it refracts.
vec3 surfaceLight(GpuMaterial m, vec3 p, float error, vec3 n, vec3 ns, vec3 v,
                  float local, float highlight, inout uint rays) {
    GpuMaterial weighted = m;
    weighted.kd.rgb *= local;
    weighted.ks.rgb *= highlight;
    return local * ambientTerm(m) +
           diffuseSpecularTerm(weighted, p, error, n, ns, v, rays);
}
// [end]
#endif
