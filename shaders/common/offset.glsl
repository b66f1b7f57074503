// Where secondary rays start (chapters 06 on). A hit point computed in float
// lies slightly above or below the true surface; a ray started there can hit
// the surface it leaves ("shadow acne"). How far off it can be depends on
// that hit alone: on the size of the numbers that made it, not on the scene
// around it. The closest-hit shader bounds the point's error from those
// numbers (hit_error.glsl); here the ray's origin moves that far along the
// geometric normal, then one float further in each coordinate so that the
// rounding of the move cannot undo it (PBRT-v4, section 6.8.6; Wächter and
// Binder, Ray Tracing Gems ch. 6, move by units in the last place too).
#ifndef OFFSET_GLSL
#define OFFSET_GLSL
// [region offset_ray]
// The float after x toward the sign of direction (x itself for 0).
float nextFloatAway(float x, float direction) {
    if (direction == 0.0) return x;
    if (x == 0.0) return direction > 0.0 ? 1.4e-45 : -1.4e-45;
    int bits = floatBitsToInt(x);
    return intBitsToFloat((x > 0.0) == (direction > 0.0) ? bits + 1 : bits - 1);
}

// p: the hit point; error: how far it may be from the surface (along n);
// n: the unit geometric normal on the side the new ray leaves from.
vec3 offsetRay(vec3 p, float error, vec3 n) {
    vec3 moved = p + error * n;
    return vec3(nextFloatAway(moved.x, n.x),
                nextFloatAway(moved.y, n.y),
                nextFloatAway(moved.z, n.z));
}
// [end]

// The start of a secondary ray leaving the surface on the side of `n`:
// chapter 06's --fixed-epsilon experiment replaces the bounded offset by
// p + epsilon * n.
vec3 secondaryOrigin(vec3 p, float error, vec3 n) {
    return push.epsilon > 0.0 ? p + push.epsilon * n : offsetRay(p, error, n);
}
#endif
