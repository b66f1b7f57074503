// Where secondary rays start (chapters 06 on). A hit point computed in float
// lies slightly above or below the true surface; a ray started there can hit
// the surface it leaves ("shadow acne"). How far off it can be depends on
// that hit alone: on the size of the numbers that made it, not on the scene
// around it. The closest-hit shader bounds the point's error from those
// numbers (hit_error.glsl); here the ray's origin moves that far along the
// geometric normal (PBRT-v4, section 6.8.6; Wächter and Binder, Ray Tracing
// Gems ch. 6, move by units in the last place of the coordinates instead).
#ifndef OFFSET_GLSL
#define OFFSET_GLSL
// [region offset_ray]
// p: the hit point; error: how far it may be from the surface (along n);
// n: the unit geometric normal on the side the new ray leaves from. The
// move itself rounds too, by at most one unit in the last place of each
// coordinate: that costs at most 1/16 of `error` along n (the bound counts
// 16 units of the same numbers), so the new origin stays beyond the surface.
// The floor keeps a hit at the very origin of a tiny scene off it as well.
vec3 offsetRay(vec3 p, float error, vec3 n) {
    return p + max(error, 1e-30) * n;
}
// [end]

// The start of a secondary ray leaving the surface on the side of `n`:
// chapter 06's --fixed-epsilon experiment replaces the bounded offset by
// p + epsilon * n.
vec3 secondaryOrigin(vec3 p, float error, vec3 n) {
    return push.epsilon > 0.0 ? p + push.epsilon * n : offsetRay(p, error, n);
}
#endif
