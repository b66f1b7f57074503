// Where secondary rays start (chapters 06 on). A hit point computed in float
// lies slightly above or below the true surface; a ray started there can hit
// the surface it leaves ("shadow acne"). A fixed epsilon works at one scene
// scale only. Wächter and Binder ("A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems, ch. 6) move the point along the
// normal by a fixed number of units in the last place of each coordinate, so
// the offset grows with the coordinates' own rounding error. Their two
// absolute constants assume a scene of size 1; here they are multiplied by
// the scene's scale (camera.scale.x), so a scene of size 1e-3 works too.
#ifndef OFFSET_GLSL
#define OFFSET_GLSL
// [region offset_ray]
vec3 offsetRay(vec3 p, vec3 n) {
    const float intScale = 256.0;                      // ULPs to move away from the surface
    float nearOrigin = camera.scale.x / 32.0;          // below this, ULPs are too small:
    float floatScale = camera.scale.x / 65536.0;       //   move by a fixed fraction of the scene
    ivec3 ofI = ivec3(intScale * n);
    vec3 pI = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -ofI.x : ofI.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -ofI.y : ofI.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -ofI.z : ofI.z)));
    return vec3(abs(p.x) < nearOrigin ? p.x + floatScale * n.x : pI.x,
                abs(p.y) < nearOrigin ? p.y + floatScale * n.y : pI.y,
                abs(p.z) < nearOrigin ? p.z + floatScale * n.z : pI.z);
}
// [end]

// The start of a secondary ray leaving the surface on the side of `n`:
// chapter 06's --fixed-epsilon experiment replaces the robust offset by
// p + epsilon * n.
vec3 secondaryOrigin(vec3 p, vec3 n) {
    return push.epsilon > 0.0 ? p + push.epsilon * n : offsetRay(p, n);
}
#endif
