// Chapter 15: microfacet.glsl's model where the ray tree (ray_tree.glsl)
// and the photons (photon_trace.glsl) meet a rough surface: one visible
// normal drawn per branch, the reflected and refracted directions about it
// with their shares, and the glints of the lights.
#ifndef ROUGH_SURFACE_GLSL
#define ROUGH_SURFACE_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "fresnel.glsl"
#include "microfacet.glsl"

// The albedo table (chapter 15's main.cpp uploads it) by device address.
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer AlbedoTable {
    float entries[];
};
#define ALBEDO_TABLE(i) AlbedoTable(push.albedoTable).entries[i]
#include "albedo_table.glsl"

// glTF's convention (and PBRT's RoughnessToAlpha): alpha = roughness^2, so
// that roughness looks even from 0 to 1. Thin walls stay smooth.
float roughAlpha(GpuMaterial m) {
    bool thin = kThinWalls && (m.flags & MATERIAL_THIN) != 0u;
    return thin ? 0.0 : m.extra.y * m.extra.y;
}

// [region compensation]
// Single scattering loses the light that leaves a facet toward another
// facet; really it scatters on and leaves (Kulla and Conty 2017). Turquin's
// compensation (2019) returns it in the lobe's own shape: the dielectric's
// lobe over its albedo E(cos_o) keeps all the light, as a clear dielectric
// must; a mirror of reflectivity R keeps 1 + R (1 - E) / E times its lobe
// (each further bounce takes R again). --multiple-scattering off: 1.
struct Compensation {
    float dielectric, mirror;
};
Compensation compensation(GpuMaterial m, float alpha, float n1, float n2, float cosO) {
    if (push.multipleScattering == 0u) return Compensation(1.0, 1.0);
    float roughness = sqrt(alpha);
    float kept = max(dielectricAlbedo(cosO, roughness, n1, n2), 0.05);
    float keptMirror = max(mirrorAlbedo(cosO, roughness), 0.05);
    return Compensation(1.0 / kept, 1.0 + m.params.y * (1.0 - keptMirror) / keptMirror);
}
// [end]

// [region rough_split]
struct RoughSplit {
    vec3 reflected, refracted;  // world directions
    float reflectedShare, refractedShare;
};

// Where a ray going `direction` meets a rough surface (facing normals n,
// ns) between indices n1 and n2: the material's dielectric part
// (transmission) divides by Fresnel at the microfacet, its mirror part
// (reflectivity) reflects about the same microfacet; u: the sample point.
RoughSplit coneSplit(GpuMaterial m, float alpha, float n1, float n2, vec3 n, vec3 ns,
                     vec3 direction, vec2 u);
RoughSplit roughSplit(GpuMaterial m, float alpha, float n1, float n2, vec3 n, vec3 ns,
                      vec3 direction, vec2 u) {
    if (push.facetSampling == FACETS_CONE)  // the comparison below
        return coneSplit(m, alpha, n1, n2, n, ns, direction, u);
    mat3 frame = basisAround(ns);  // the frame of ns, as the reference builds it
    vec3 t = frame[0], b = frame[1];
    vec3 wo = normalize(
        vec3(dot(-direction, t), dot(-direction, b), max(dot(-direction, ns), 1e-6)));
    vec3 facet = sampleVisibleNormal(wo, alpha, u);
    MicrofacetSplit s =
        microfacetSplit(wo, facet, alpha, n1, n2, push.fresnelMode, m.extra.x);
    float transmission = m.params.z, mirror = (1.0 - transmission) * m.params.y;
    Compensation c = compensation(m, alpha, n1, n2, wo.z);
    RoughSplit r;
    r.reflected = s.reflected.x * t + s.reflected.y * b + s.reflected.z * ns;
    r.refracted = s.refracted.x * t + s.refracted.y * b + s.refracted.z * ns;
    // the mirror part: no Fresnel, the same masking (G2 / G1)
    float masking = s.reflected.z > 0.0 ? smithG2(wo, s.reflected, alpha) /
                                              smithG1(wo, alpha)
                                        : 0.0;
    r.reflectedShare =
        transmission * c.dielectric * s.reflectedShare + mirror * c.mirror * masking;
    r.refractedShare = transmission * c.dielectric * s.refractedShare;
    // a mesh's flat triangle (n) decides the sides, as ray_tree.glsl's sides
    if (dot(r.reflected, n) <= 0.0) r.reflectedShare = 0.0;
    if (dot(r.refracted, n) >= 0.0) r.refractedShare = 0.0;
    return r;
}
// [end]

// The material's microfacet lobe toward wi (local; BSDF times |cos|): its
// dielectric part both ways, its mirror part F D G2 / (4 cos_o) on the
// viewer's side, with no Fresnel; each compensated as its branches are
// (c: compensation's factors for wo, looked up once a hit).
float roughLobe(GpuMaterial m, float alpha, float n1, float n2, vec3 wo, vec3 wi,
                Compensation c) {
    float transmission = m.params.z, mirror = (1.0 - transmission) * m.params.y;
    float f = transmission * c.dielectric *
              dielectricCosBsdf(wo, wi, alpha, n1, n2, push.fresnelMode, m.extra.x);
    if (wi.z > 0.0 && mirror > 0.0)
        f += mirror * c.mirror * ggxD(normalize(wo + wi), alpha) *
             smithG2(wo, wi, alpha) / (4.0 * wo.z);
    return f;
}

// [region cone_split]
// --sampling cone, for the comparison on page 15: microfacet.glsl's mixture
// of chapter 11's cone and visible normals; each branch carries the lobe
// times cos over the mixture's density.
RoughSplit coneSplit(GpuMaterial m, float alpha, float n1, float n2, vec3 n, vec3 ns,
                     vec3 direction, vec2 u) {
    mat3 frame = basisAround(ns);  // the frame of ns, as the reference builds it
    vec3 t = frame[0], b = frame[1];
    vec3 wo = normalize(
        vec3(dot(-direction, t), dot(-direction, b), max(dot(-direction, ns), 1e-6)));
    Compensation c = compensation(m, alpha, n1, n2, wo.z);
    ConeMixtureSample s = sampleConeMixture(wo, alpha, n1, n2, u);
    RoughSplit r;
    r.reflected = s.reflected.x * t + s.reflected.y * b + s.reflected.z * ns;
    r.refracted = s.refracted.x * t + s.refracted.y * b + s.refracted.z * ns;
    float reflected = roughLobe(m, alpha, n1, n2, wo, s.reflected, c),
          refracted = roughLobe(m, alpha, n1, n2, wo, s.refracted, c);
    r.reflectedShare = s.reflectedDensity > 0.0 ? reflected / s.reflectedDensity : 0.0;
    r.refractedShare = s.refractedDensity > 0.0 ? refracted / s.refractedDensity : 0.0;
    if (dot(r.reflected, n) <= 0.0) r.reflectedShare = 0.0;
    if (dot(r.refracted, n) >= 0.0) r.refractedShare = 0.0;
    return r;
}
// [end]

// [region rough_glint]
// The lights at a rough surface, seen from v: the microfacet lobe
// evaluated toward each light (it cannot be sampled: a point light or the
// sun is hit by no ray), and the local model's part (directLight's). On
// the viewer's side the reflection, F D G2 / (4 cos_o), of the dielectric
// and the mirror parts; behind the surface the transmission (a frosted
// pane glows where the sun is behind it), its shadow ray leaving from the
// far side. A glint that would add less than MIN_LIGHT to the pixel
// (`throughput`: the branch's share of it) is left out, as a weak branch
// is not traced (performance page: 9 % of chapter 15's camera rays' time).
// The two parts share one shadow ray per light: on the GPU one call site
// instead of two (performance page: 15 % of chapter 15's frame).
vec3 roughLight(GpuMaterial m, float alpha, float n1, float n2, vec3 p, float error,
                vec3 n, vec3 ns, vec3 v, float local, float highlight, vec3 throughput,
                inout uint rays) {
    mat3 frame = basisAround(ns);  // the frame of ns, as the reference builds it
    vec3 t = frame[0], b = frame[1];
    vec3 wo = normalize(vec3(dot(v, t), dot(v, b), max(dot(v, ns), 1e-6)));
    // for every light; alpha = 0: a smooth surface, no lobe
    Compensation c = alpha > 0.0 ? compensation(m, alpha, n1, n2, wo.z)
                                 : Compensation(1.0, 1.0);
    vec3 sum = local * ambientTerm(m);  // ambient: 0 unless the scene gives it
    for (uint i = 0u; i < camera.counts.z; ++i) {
        vec3 l = towardLight(lights[i], p), irradiance = irradianceFrom(i, p);
        vec3 wi = vec3(dot(l, t), dot(l, b), dot(l, ns));
        // n: a mesh's flat triangle. Between it and ns the lobe has no side,
        // and the local part is lit from the front.
        bool below = dot(l, n) < 0.0, behind = below && wi.z < 0.0;
        vec3 light = vec3(0.0);
        if (alpha > 0.0 && below == (wi.z < 0.0)) {
            vec3 glint = roughLobe(m, alpha, n1, n2, wo, wi, c) * irradiance;
            vec3 seen = glint * throughput;
            if (max(seen.r, max(seen.g, seen.b)) >= MIN_LIGHT) light += glint;
        }
        vec3 direct = localLight(m, ns, v, l, irradiance, local, highlight);
        if (max(direct.r, max(direct.g, direct.b)) >= MIN_LIGHT) light += direct;
        if (light == vec3(0.0)) continue;
        ++rays;
        sum += light * lightArriving(i, secondaryOrigin(p, error, behind ? -n : n), l);
    }
    return sum;
}
// [end]
#endif
