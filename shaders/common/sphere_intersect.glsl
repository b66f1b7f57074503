// Ray / unit-sphere intersection. Plain GLSL that also compiles as C++ with
// GLM (tests/test_sphere_intersection.cpp runs this exact code in float on
// hard rays against double precision), hence the RG_OUT macro.
#ifndef RG_OUT
#define RG_OUT(T) out T
#endif

// [region haines]
// Roots t.x <= t.y of |o + t d| = 1 (unit sphere at the origin); false when
// the ray's line misses. Haines et al., Ray Tracing Gems ch. 7, eqs. 7.5-7.8.
bool intersectUnitSphere(vec3 o, vec3 d, RG_OUT(vec2) t) {
    float a = dot(d, d);
    float b = -dot(o, d);                          // b' = -(f . d), f = o - centre
    vec3 l = o + (b / a) * d;                      // centre -> closest point of the line
    float discriminant = a * (1.0f - dot(l, l));   // = b'^2 - a c, without cancellation
    if (discriminant < 0.0f) return false;
    float c = dot(o, o) - 1.0f;
    float q = b + (b >= 0.0f ? 1.0f : -1.0f) * sqrt(discriminant);
    if (q == 0.0f) {                               // tangent through the closest point: one double root
        t = vec2(0.0f);
        return c == 0.0f;
    }
    float t0 = c / q, t1 = q / a;                  // no subtraction of near-equal numbers
    t = vec2(min(t0, t1), max(t0, t1));
    return true;
}
// [end]
