// Ray / sphere intersection for any radius and any distance. Plain GLSL that
// also compiles as C++ with GLM (tests/test_sphere_intersection.cpp runs this
// exact code in float on hard rays against double precision), hence the
// RG_OUT and RG_PRECISE macros.
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

// Near the surface (|f| close to r), b = -(f . d), c = |f|^2 - r^2 and the
// discriminant b^2 - c all lose their digits to cancellation. Here they come
// from the exact difference f = o - centre (fHi + fLo), exact products and
// exact sums, to a few units in the last place of each result: a ray that
// starts just off a big sphere, or grazes it, finds the right root (Ray
// Tracing Gems ch. 7 removes the cancellation in the discriminant for rays
// from far away; this removes it for rays from close by). d: unit length.
vec3 nearSurfaceTerms(vec3 o, vec3 centre, float r, vec3 d) {
    vec2 x = twoSum(o.x, -centre.x), y = twoSum(o.y, -centre.y), z = twoSum(o.z, -centre.z);
    vec2 c = twoProduct(x.x, x.x);
    c = accumulate(c, twoProduct(y.x, y.x));
    c = accumulate(c, twoProduct(z.x, z.x));
    c = accumulate(c, twoProduct(-r, r));
    c.y += 2.0f * (x.x * x.y + y.x * y.y + z.x * z.y);
    vec2 b = twoProduct(-x.x, d.x);
    b = accumulate(b, twoProduct(-y.x, d.y));
    b = accumulate(b, twoProduct(-z.x, d.z));
    b.y -= x.y * d.x + y.y * d.y + z.y * d.z;
    vec2 discriminant = twoProduct(b.x, b.x);
    discriminant = accumulate(discriminant, vec2(-c.x, -c.y));
    discriminant.y += 2.0f * b.x * b.y;
    return vec3(b.x + b.y, c.x + c.y, discriminant.x + discriminant.y);
}

// [region sphere_roots]
// Roots t.x <= t.y of |o + t d - centre| = r along any direction d (not
// unit: object space gives it scaled), in d's own units; false when the
// ray's line misses. Haines et al., Ray Tracing Gems ch. 7: the
// discriminant from the centre's distance to the line, the nearer root as
// c / q. Where the sizes would overflow or underflow when squared,
// everything is first scaled by a power of two (exact) so that the largest
// of |f| and r is about 1: a sky dome of radius 1e20 squares to 1e40, past
// float's range, and its object-space direction (1e-20) to an underflow. When the origin is near the surface (c much smaller than
// |f|^2: a ray leaving this sphere, an eye near a big one), the terms are
// computed nearly exactly.
bool intersectSphere(vec3 o, vec3 d, vec3 centre, float r, RG_OUT(vec2) t) {
    float dd = dot(d, d);
    float perUnit;                                // t in d's units per unit length
    vec3 dn;
    if (dd > 1e-30f && dd < 1e30f) {              // the usual case: |d|^2 is a normal float
        perUnit = inversesqrt(dd);
        dn = d * perUnit;
    } else {                                      // scaled first, or |d|^2 under- or overflows
        float m = max(abs(d.x), max(abs(d.y), abs(d.z)));
        dn = normalize(d / m);
        perUnit = 1.0f / (m * length(d / m));
    }
    vec3 f = o - centre;
    float size = max(r, max(abs(f.x), max(abs(f.y), abs(f.z))));
    float k = 1.0f;                               // squares of up to 1e30 fit a float
    if (size > 1e15f || size < 1e-15f) {
        int e;
        frexp(size, e);
        k = ldexp(1.0f, -e);                      // 2^-e: exact scaling
    }
    vec3 fk = f * k;
    float rk = r * k;
    float ff = dot(fk, fk);
    float b = -dot(fk, dn), c = ff - rk * rk, discriminant;
    // Near the surface c loses its digits, and the root c / q with them,
    // unless the ray leaves for sure: it starts outside beyond c's own
    // rounding and moves away (no root ahead: a shadow ray from this
    // sphere), or starts inside and moves in (the root ahead is q, exact).
    float rounding = 4.0f * 5.9604645e-8f * ff;
    bool near = abs(c) < 0.125f * ff;
    if (near && c > rounding && b <= 0.0f) return false;
    if (!near || (c < -rounding && b > 0.0f)) {   // Haines's form
        vec3 l = fk + b * dn;                     // centre -> closest point of the line
        float ll = length(l);
        discriminant = (rk - ll) * (rk + ll);     // rk^2 - |l|^2 without cancellation
    } else {                                      // the exact terms
        vec3 terms = nearSurfaceTerms(o * k, centre * k, rk, dn);
        b = terms.x;
        c = terms.y;
        discriminant = terms.z;
    }
    if (discriminant < 0.0f) return false;
    float q = b + (b >= 0.0f ? 1.0f : -1.0f) * sqrt(discriminant);
    if (q == 0.0f) {                              // tangent through the closest point: one double root
        t = vec2(0.0f);
        return c == 0.0f;
    }
    float t0 = c / q, t1 = q;                     // no subtraction of near-equal numbers
    float scale = perUnit / k;
    t = vec2(min(t0, t1), max(t0, t1)) * scale;
    return true;
}
// [end]
