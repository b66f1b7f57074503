// How far a computed hit point can be from the true surface (chapter 06).
// The point is p = M (o + t d) + T: the object-space ray at the hit, taken
// to world space by the instance's transform (M, T). Each operation rounds
// by at most one unit in the last place of its result, so the error is a
// small multiple of the float spacing of the numbers involved: of |o|,
// |t d|, |M| times them and |T| (PBRT-v4, section 6.8: error bounds from
// the intersection computation). A sphere's far root (a ray from inside)
// is found less exactly than its near one, to about the float spacing of
// the sphere's own size: sphere.rchit adds that. The factor 16 covers those few
// roundings, the rounding of t itself, and a margin. Nothing here depends on the rest of
// the scene: a far or a huge object changes only its own hits' bounds.
#ifndef HIT_ERROR_GLSL
#define HIT_ERROR_GLSL
// [region hit_error]
const float kUnitRoundoff = 5.9604645e-8;  // 2^-24: float's relative rounding

// The magnitude of a point o + t d found by intersection: t's own error
// moves the point along d, and at grazing incidence t is found less exactly
// in just the proportion that d is closer to the surface, so the error
// along the normal is about that of |t d| in every direction.
vec3 rayPointMagnitude(vec3 o, vec3 d, float t) {
    vec3 td = abs(t * d);
    return abs(o) + vec3(max(td.x, max(td.y, td.z)));
}

// Along the unit normal n: the offset a secondary ray needs. `magnitude`:
// the size of the world-space numbers that made the point.
float hitError(vec3 magnitude, vec3 n) {
    return 16.0 * kUnitRoundoff * dot(abs(n), magnitude);
}
// The same for a point made in object space (rayPointMagnitude for a point
// on the ray) and taken to the world by the instance's transform.
float hitError(vec3 magnitude, mat4x3 objectToWorld, vec3 n) {
    return hitError(abs(objectToWorld[0]) * magnitude.x +
                        abs(objectToWorld[1]) * magnitude.y +
                        abs(objectToWorld[2]) * magnitude.z + abs(objectToWorld[3]),
                    n);
}
// [end]
#endif
