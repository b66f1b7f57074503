// Chapter 15, rough surfaces as microfacets: the GGX (Trowbridge-Reitz)
// distribution of normals, Smith's height-correlated masking-shadowing and
// the sampling of visible normals; a rough dielectric's reflection and
// transmission (Walter, Marschner, Li and Torrance 2007) and a rough
// mirror. Plain GLSL that also compiles as C++ (tests/test_microfacet.cpp).
//
// Everything here works in the local frame of the surface: z is the
// macro-surface normal on the side the ray comes from, `wo` points back
// along the ray (wo.z > 0), `wi` is the direction the light arrives from
// (above: reflected, below: transmitted). alpha = roughness^2 (glTF's
// convention): alpha = 0 is chapter 13's smooth surface.
#ifndef MICROFACET_GLSL
#define MICROFACET_GLSL

// [region distribution]
// D(m): the density of microfacet normals m per unit of the macro-surface's
// projected area, normalized so that the integral of D(m) m.z over the
// hemisphere is 1 (Walter et al. 2007, eq. 33).
float ggxD(vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    float a2 = alpha * alpha;
    float t = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
    return 1.0f / (kPi * a2 * t * t);
}

// Smith's Lambda for GGX: how much of the surface a direction w sees
// masked, Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2 (Heitz 2014, eq. 72).
// Either side of the surface: it depends on w.z^2 only.
float smithLambda(vec3 w, float alpha) {
    float z2 = w.z * w.z;
    if (z2 <= 0.0f) return 1e30f;  // grazing: all masked
    float tan2 = max(0.0f, 1.0f - z2) / z2;
    return 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * tan2));
}
// The share of the microfacets facing w that w sees.
float smithG1(vec3 w, float alpha) { return 1.0f / (1.0f + smithLambda(w, alpha)); }
// The share visible from both wo and wi, their heights correlated (Heitz
// 2014, eq. 99); for transmission too, as PBRT-v4 does.
float smithG2(vec3 wo, vec3 wi, float alpha) {
    return 1.0f / (1.0f + smithLambda(wo, alpha) + smithLambda(wi, alpha));
}
// [end]

// [region visible_normals]
// A microfacet normal drawn with the density of the normals wo sees,
// D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z (Heitz 2018), by Dupuy and
// Benyoub's spherical caps (2023): stretch the view to alpha = 1, where the
// visible normals of a hemisphere are a uniform point on a spherical cap
// plus wo, and unstretch. u in [0,1)^2; wo.z > 0.
vec3 sampleVisibleNormal(vec3 wo, float alpha, vec2 u) {
    vec3 stretched = normalize(vec3(wo.x * alpha, wo.y * alpha, wo.z));
    float phi = 2.0f * kPi * u.x;
    float z = (1.0f - u.y) * (1.0f + stretched.z) - stretched.z;
    float s = sqrt(clamp(1.0f - z * z, 0.0f, 1.0f));
    vec3 h = vec3(s * cos(phi), s * sin(phi), z) + stretched;
    return normalize(vec3(h.x * alpha, h.y * alpha, max(h.z, 0.0f)));
}
float visibleNormalPdf(vec3 wo, vec3 m, float alpha) {
    return smithG1(wo, alpha) * max(0.0f, dot(wo, m)) * ggxD(m, alpha) / wo.z;
}
// [end]

// [region dielectric]
// A rough dielectric where the ray meets index n2 from index n1: the BSDF
// value for light arriving from wi, times |wi.z| (what the light integral
// sums), for reflection and transmission alike. F: the Fresnel reflectance
// at the microfacet (fresnel.glsl's; 1 under total internal reflection).
// Reflection (Walter et al. eq. 20): F D G2 / (4 |wo.z| |wi.z|), m the half
// vector of wo and wi. Transmission (eq. 21): m = -(n1 wo + n2 wi),
// normalized, and (1 - F) D G2 |wo.m| |wi.m| n2^2 / (|wo.z| |wi.z| (n1 wo.m
// + n2 wi.m)^2). Radiance is not rescaled by (n1/n2)^2 where it crosses:
// as chapter 13's smooth glass, whose rays leave every glass they enter.
//
// The facet normal that turns wo into wi: the half vector of a reflection
// or of a refraction, on the side of z; vec3(0) where no facet can (wo or
// wi on the wrong side of it).
vec3 halfVector(vec3 wo, vec3 wi, float n1, float n2) {
    bool reflected = wi.z > 0.0f;
    vec3 m = reflected ? wo + wi : -(n1 * wo + n2 * wi);
    if (dot(m, m) == 0.0f) return vec3(0.0f);
    m = normalize(m);
    if (m.z < 0.0f) m = -m;
    float om = dot(wo, m), im = dot(wi, m);
    // each side of the microfacet as the macro-surface says
    if (om <= 0.0f || (reflected ? im <= 0.0f : im >= 0.0f)) return vec3(0.0f);
    return m;
}
float dielectricCosBsdf(vec3 wo, vec3 wi, float alpha, float n1, float n2,
                        uint fresnelMode, float f0) {
    bool reflected = wi.z > 0.0f;
    vec3 m = halfVector(wo, wi, n1, n2);
    if (m == vec3(0.0f)) return 0.0f;
    float om = dot(wo, m), im = dot(wi, m);
    float F = fresnel(fresnelMode, f0, om, n1, n2);
    float DG = ggxD(m, alpha) * smithG2(wo, wi, alpha);
    if (reflected) return F * DG / (4.0f * wo.z);
    float denominator = n1 * om + n2 * im;
    return (1.0f - F) * DG * om * abs(im) * n2 * n2 /
           (wo.z * denominator * denominator);
}

// The density with which one visible normal m (sampleVisibleNormal) makes
// wi, as a reflection about m or as a refraction through it (the Jacobians
// of Walter et al. eqs. 14 and 17).
float dielectricPdf(vec3 wo, vec3 wi, float alpha, float n1, float n2) {
    bool reflected = wi.z > 0.0f;
    vec3 m = halfVector(wo, wi, n1, n2);
    if (m == vec3(0.0f)) return 0.0f;
    float om = dot(wo, m), im = dot(wi, m);
    float pm = visibleNormalPdf(wo, m, alpha);
    if (reflected) return pm / (4.0f * om);
    float denominator = n1 * om + n2 * im;
    return pm * n2 * n2 * abs(im) / (denominator * denominator);
}
// [end]

// [region split]
// How a rough surface divides the light for one visible normal m: the
// reflected and refracted directions and the share of the light each
// carries. Each share is the BSDF times cos over the density above, which
// for a visible normal is F G2 / G1(wo) and (1 - F) G2 / G1(wo): never
// above 1, and exactly chapter 13's F and 1 - F where alpha -> 0 (m = z,
// G = 1). A direction on the wrong side of the macro-surface carries
// nothing: the light single scattering loses (multiple scattering between
// the microfacets would bring part of it back).
struct MicrofacetSplit {
    vec3 reflected, refracted;  // local directions (refracted: 0 under TIR)
    float reflectedShare, refractedShare;
};
MicrofacetSplit microfacetSplit(vec3 wo, vec3 m, float alpha, float n1, float n2,
                                uint fresnelMode, float f0) {
    MicrofacetSplit s;
    float om = dot(wo, m);
    float F = fresnel(fresnelMode, f0, om, n1, n2);
    float g1 = smithG1(wo, alpha);
    s.reflected = 2.0f * om * m - wo;
    s.reflectedShare =
        s.reflected.z > 0.0f ? F * smithG2(wo, s.reflected, alpha) / g1 : 0.0f;
    s.refracted = vec3(0.0f);
    s.refractedShare = 0.0f;
    float eta = n1 / n2, k = 1.0f - eta * eta * (1.0f - om * om);
    if (k > 0.0f) {  // GLSL's refract(-wo, m, eta)
        s.refracted = -eta * wo + (eta * om - sqrt(k)) * m;
        if (s.refracted.z < 0.0f)
            s.refractedShare = (1.0f - F) * smithG2(wo, s.refracted, alpha) / g1;
    }
    return s;
}
// [end]

// [region cone_mixture]
// Chapter 11's cone as a sampler for this model (page 15's comparison): a
// direction uniform in the cone of half-angle roughness x 90 degrees about
// the smooth mirror (refracted) direction. Alone it carries the BSDF times
// cos times the cone's solid angle: up to D's peak, 1 / (pi alpha^2), times
// that angle, so the rare direction that finds the lobe's peak carries a
// hundred times its share and more (a firefly), and none leaves the cone. Half
// the samples draw a visible normal instead and each branch's density is
// the mixture's (defensive importance sampling, Hesterberg 1995; Veach's
// one-sample MIS with the balance heuristic, thesis 9.2.4): a share is then
// at most twice a visible normal's, and no direction is left out.
struct ConeMixtureSample {
    vec3 reflected, refracted;  // refracted: 0 where none
    float reflectedDensity, refractedDensity;  // per solid angle; 0: carries nothing
};
float coneDensity(vec3 axis, vec3 wi, float cosMax) {
    return dot(axis, wi) >= cosMax ? 1.0f / (2.0f * kPi * (1.0f - cosMax)) : 0.0f;
}
ConeMixtureSample sampleConeMixture(vec3 wo, float alpha, float n1, float n2, vec2 u) {
    float roughness = sqrt(alpha), cosMax = cos(roughness * 0.5f * kPi);
    vec3 mirror = vec3(-wo.x, -wo.y, wo.z);
    vec3 through = refract(-wo, vec3(0.0f, 0.0f, 1.0f), n1 / n2);
    ConeMixtureSample c;
    if (u.x < 0.5f) {  // the cone's half, u.x stretched back to [0, 1)
        vec2 v = vec2(2.0f * u.x, u.y);
        c.reflected = lobeDirection(mirror, roughness, v);
        c.refracted =
            through == vec3(0.0f) ? through : lobeDirection(through, roughness, v);
    } else {  // the visible normals' half
        vec3 m = sampleVisibleNormal(wo, alpha, vec2(2.0f * u.x - 1.0f, u.y));
        MicrofacetSplit s = microfacetSplit(wo, m, alpha, n1, n2, 0u, 0.0f);
        c.reflected = s.reflected, c.refracted = s.refracted;
    }
    c.reflectedDensity = 0.5f * coneDensity(mirror, c.reflected, cosMax) +
                         0.5f * dielectricPdf(wo, c.reflected, alpha, n1, n2);
    c.refractedDensity = 0.5f * dielectricPdf(wo, c.refracted, alpha, n1, n2);
    if (through != vec3(0.0f))
        c.refractedDensity += 0.5f * coneDensity(through, c.refracted, cosMax);
    if (c.reflected.z <= 0.0f) c.reflectedDensity = 0.0f;
    if (c.refracted.z >= 0.0f) c.refractedDensity = 0.0f;
    return c;
}
// [end]
#endif
