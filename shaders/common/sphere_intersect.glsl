// Ray / sphere intersection for any radius and any distance. Plain GLSL that
// also compiles as C++ with GLM (tests/test_sphere_intersection.cpp runs this
// exact code in float on hard rays against double precision), hence the
// RG_OUT and RG_PRECISE macros. kCarefulSizes comes from rt_bindings.glsl
// (tests/glsl_as_cpp.h in C++).
#ifndef RG_OUT
#define RG_OUT(T) out T
#endif
#ifndef RG_PRECISE
#define RG_PRECISE precise  // computed as written: no fused or reordered operations
#endif

// [region two_sum]
// Error-free transformations: a + b and a * b as their rounded float plus
// the exact rounding error (Knuth's TwoSum; Dekker's product, with
// Veltkamp's split of each factor into halves of 12 bits whose products are
// exact). Enough for |f|^2 - r^2 to be nearly exact when the two are huge
// and almost equal: a ray starting just off a big sphere. Plain adds and
// multiplies, which Vulkan rounds correctly, and no fma(): a driver may
// split that into a multiply and an add (lavapipe does), which loses the
// very error it is meant to return.
vec2 twoSum(float a, float b) {
    RG_PRECISE float s = a + b;
    RG_PRECISE float bb = s - a;
    RG_PRECISE float e = (a - (s - bb)) + (b - bb);
    return vec2(s, e);
}
vec2 split(float a) {
    RG_PRECISE float c = 4097.0f * a;  // 2^12 + 1
    RG_PRECISE float high = c - (c - a);
    RG_PRECISE float low = a - high;
    return vec2(high, low);
}
vec2 twoProduct(float a, float b) {
    vec2 x = split(a), y = split(b);
    RG_PRECISE float p = a * b;
    RG_PRECISE float e = ((x.x * y.x - p) + x.x * y.y + x.y * y.x) + x.y * y.y;
    return vec2(p, e);
}
// [end]

// (hi, lo) + p, where p = (value, error) is exact.
vec2 accumulate(vec2 sum, vec2 p) {
    vec2 s = twoSum(sum.x, p.x);
    return vec2(s.x, sum.y + s.y + p.y);
}

// |o - centre|^2 - r^2 to a few units in the last place even where the
// two terms are huge and nearly equal (the origin near a big sphere): the
// difference o - centre as an exact sum of two floats, each square and r^2
// as exact products, added without losing their low parts.
float exactSquaredDistanceMinusRadius(vec3 o, vec3 centre, float r) {
    vec2 x = twoSum(o.x, -centre.x), y = twoSum(o.y, -centre.y),
         z = twoSum(o.z, -centre.z);
    vec2 c = twoProduct(-r, r);
    c = accumulate(c, twoProduct(x.x, x.x));
    c = accumulate(c, twoProduct(y.x, y.x));
    c = accumulate(c, twoProduct(z.x, z.x));
    c.y += 2.0f * (x.x * x.y + y.x * y.y + z.x * z.y);
    return c.x + c.y;
}

float maxAbs(vec3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }

// [region sphere_roots]
// Roots t.x <= t.y of |o + t d - centre| = r along any direction d (not
// unit: object space gives it scaled), in d's own units; false when the
// ray's line misses. With f = o - centre, b = -(f . d), c = |f|^2 - r^2 the
// roots are (b +- sqrt(b^2 - |d|^2 c)) / |d|^2. Two places lose digits:
// - far from a small sphere, b^2 and |d|^2 c are huge and nearly equal:
//   Haines et al., Ray Tracing Gems ch. 7, take the discriminant from the
//   centre's distance to the line instead, and the nearer root as c / q;
// - near the surface of a big one, c itself is the difference of two huge
//   and nearly equal numbers: there it is computed exactly, unless the ray
//   surely leaves (a ray from this sphere's own surface, whose offset puts
//   it well beyond c's rounding: outside and moving away, no root ahead;
//   inside and moving in, the root ahead is q / |d|^2, exact anyway).
// Sizes whose squares would over- or underflow (a sky dome of radius 1e20)
// are first scaled by powers of two, which is exact. Without
// kCarefulSizes (a scene that needs neither, rt_scene.h) only Haines's
// form is left.
bool intersectSphere(vec3 o, vec3 d, vec3 centre, float r, RG_OUT(vec2) t) {
    vec3 f = o - centre;
    float a = dot(d, d), ff = dot(f, f), rr = r * r, m = max(ff, rr);
    float unit = 1.0f;                            // t in d's units per t found below
    if (kCarefulSizes && !(a > 1e-18f && a < 1e18f && m > 1e-18f && m < 1e18f)) {
        int e, ed;
        frexp(max(r, maxAbs(f)), e);
        frexp(maxAbs(d), ed);
        float k = ldexp(1.0f, -e), kd = ldexp(1.0f, -ed);
        o *= k; centre *= k; r *= k; f *= k; d *= kd;
        a = dot(d, d); ff = dot(f, f); rr = r * r;
        unit = kd / k;
    }
    float b = -dot(f, d), c = ff - rr, discriminant;
    float rounding = 4.0f * 5.9604645e-8f * ff;   // c's own rounding
    bool near = kCarefulSizes && abs(c) < 0.125f * ff;
    if (near && c > rounding && b <= 0.0f) return false;
    if (!near || (c < -rounding && b > 0.0f)) {   // Haines's form
        vec3 l = f + (b / a) * d;                 // centre -> closest point of the line
        discriminant = a * (rr - dot(l, l));      // = b^2 - a c, without cancellation
    } else {                                      // near the surface: c exactly
        c = exactSquaredDistanceMinusRadius(o, centre, r);
        discriminant = b * b - a * c;
    }
    if (discriminant < 0.0f) return false;
    float q = b + (b >= 0.0f ? 1.0f : -1.0f) * sqrt(discriminant);
    // tangent through the closest point: one double root
    if (q == 0.0f) {
        t = vec2(0.0f);
        return c == 0.0f;
    }
    float t0 = c / q, t1 = q / a;                 // no subtraction of near-equal numbers
    t = vec2(min(t0, t1), max(t0, t1)) * unit;
    return true;
}
// [end]
