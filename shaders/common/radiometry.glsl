// Chapter 14: direct light in physical units. A point light of power P
// radiates P / 4pi watts per steradian (its intensity I); a surface at
// distance r, turned by theta from it, receives the irradiance
// E = I cos(theta) / r^2 (W/m^2). A sun gives E = E_sun cos(theta), the
// same everywhere. A diffuse surface of albedo kd reflects the radiance
// kd / pi E (Lambert: the 1/pi makes the light it sends out over the
// hemisphere kd E, never more than arrived).
#ifndef RADIOMETRY_GLSL
#define RADIOMETRY_GLSL
#include "sampling.glsl"

// --caustics transmit: the shadow ray's payload, what the glass on its way
// lets through (transmit.glsl)
layout(location = 2) rayPayloadEXT vec4 shadowTransmittance;  // rgb; w: tMax

// [region transmitted]
// What reaches `origin` from `tMax` along l through the glass in between:
// the traversal runs the shadow hit groups' any-hit shaders at every hit
// (no opaque shortcut), which multiply in each glass and stop at anything
// else; the miss shader leaves what is left.
vec3 transmittedLight(vec3 origin, vec3 l, float tMax) {
    shadowTransmittance = vec4(1.0, 1.0, 1.0, tMax);
    traceRayEXT(tlas, gl_RayFlagsNoOpaqueEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF,
                RAY_TYPE_SHADOW, 0, MISS_TRANSMIT, origin, 0.0, l, tMax, 2);
    return shadowTransmittance.rgb;
}
// [end]

// Nothing between `origin` and the sun in direction l (a shadow ray to infinity).
bool sunVisible(vec3 origin, vec3 l) {
    shadowPayload = 1u;
    traceRayEXT(tlas,
                kRayFlags | gl_RayFlagsTerminateOnFirstHitEXT |
                    gl_RayFlagsSkipClosestHitShaderEXT,
                0xFF, RAY_TYPE_SHADOW, 0, MISS_SHADOW, origin, 0.0, l, kInfinity, 1);
    return shadowPayload == 0u;
}

// [region sun_disc]
// Toward a light from p. A sun with a disc (its angular radius in
// intensity.w; the real one's is 0.27 degrees) is a direction drawn
// uniformly over the disc's solid angle, a new one each frame at each
// point: a point in the penumbra sees part of the disc, and the frames'
// average is that part (a soft shadow's edge). The disc's radiance times
// its solid angle is the sun's irradiance, so E stays as it was.
vec3 towardSun(GpuLight sun, vec2 u) {  // u in [0,1)^2
    vec3 axis = -sun.position.xyz;
    float cosine = 1.0 - u.x * (1.0 - cos(sun.intensity.w));
    float sine = sqrt(max(0.0, 1.0 - cosine * cosine)), phi = 2.0 * kPi * u.y;
    mat3 frame = basisAround(axis);
    return normalize(cosine * axis + sine * (cos(phi) * frame[0] + sin(phi) * frame[1]));
}
vec3 towardLight(GpuLight light, vec3 p) {
    if (light.position.w != LIGHT_DIRECTIONAL)
        return safeNormalize(light.position.xyz - p);
    if (!kSunDiscs || light.intensity.w <= 0.0) return -light.position.xyz;
    uvec3 bits = floatBitsToUint(p);  // the point and the frame choose
    uint h = pcgHash(bits.x ^ pcgHash(bits.y ^ pcgHash(bits.z ^ pcgHash(push.frame))));
    return towardSun(light, vec2(toUnit(h), toUnit(pcgHash(h))));
}
// [end]

// [region direct]
// The local model of chapter 09 (the shares `local` and `highlight`), in
// radiometric terms: Lambert's kd / pi, and Blinn-Phong's lobe normalized
// so that it reflects at most ks of the light, (s + 8) / (8 pi) (n.h)^s
// (Akenine-Moller et al., Real-Time Rendering, 9.8), each times E; 0 for a
// light behind the surface.
vec3 localLight(GpuMaterial m, vec3 ns, vec3 v, vec3 l, vec3 irradiance, float local,
                float highlight) {
    float cosine = dot(ns, l), s = m.params.x;
    if (cosine <= 0.0) return vec3(0.0);
    vec3 brdf = local * m.kd.rgb / kPi +
                highlight * m.ks.rgb * (s + 8.0) / (8.0 * kPi) *
                    specularPower(ns, normalize(l + v), s);
    return brdf * irradiance * cosine;
}

// E on a surface facing light i from p: I / r^2, or the sun's.
vec3 irradianceFrom(uint i, vec3 p) {
    vec3 toLight = lights[i].position.xyz - p;
    return lights[i].position.w == LIGHT_DIRECTIONAL
               ? lights[i].intensity.rgb
               : lights[i].intensity.rgb / dot(toLight, toLight);
}

// What of light i reaches `origin` from direction l: 1 or 0 by a shadow
// ray, or with --caustics transmit what the glass on the way lets through.
vec3 lightArriving(uint i, vec3 origin, vec3 l) {
    bool sun = lights[i].position.w == LIGHT_DIRECTIONAL;
    if (push.caustics == CAUSTICS_TRANSMIT) {  // shadow rays through glass
        vec3 toLight = lights[i].position.xyz - origin;
        float tMax = sun ? kInfinity : safeLength(toLight) * (1.0 - 1e-5);
        return transmittedLight(origin, sun ? l : safeNormalize(toLight), tMax);
    }
    bool visible =
        sun ? sunVisible(origin, l) : lightVisible(origin, lights[i].position.xyz);
    return vec3(visible ? 1.0 : 0.0);
}

vec3 directLight(GpuMaterial m, vec3 p, float error, vec3 n, vec3 ns, vec3 v,
                 float local, float highlight, inout uint rays) {
    vec3 sum = local * ambientTerm(m);  // ambient: 0 unless the scene gives it
    vec3 origin = secondaryOrigin(p, error, n);
    for (uint i = 0u; i < camera.counts.z; ++i) {
        vec3 l = towardLight(lights[i], p);
        vec3 light = localLight(m, ns, v, l, irradianceFrom(i, p), local, highlight);
        if (max(light.r, max(light.g, light.b)) < MIN_LIGHT) continue;
        ++rays;
        sum += light * lightArriving(i, origin, l);
    }
    return sum;
}
// [end]
#endif
