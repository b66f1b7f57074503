// Exercise, chapter 08: reflection (thesis 4.1).
// replaces: 08_reflection/raygen.rgen#bounce_loop
// One ray, then a mirror's share of the light from the reflected ray:
// add throughput * (1 - mirror) * the local shading, then, while mirror >
// 0 and depth < push.maxDepth, multiply the throughput by mirror, move the
// origin off the surface (secondaryOrigin(payload.position,
// payload.error, n)) and reflect the direction about n (r = d - 2 (d . n)
// n: GLSL's reflect), and go round again. Until it is written, mirrors
// show only their own colour.
for (uint depth = 0u;; ++depth) {
    traceClosest(origin, eyeTmin(), direction);
    ++rays;
    if (payload.t < 0.0) {  // the sky
        radiance += throughput * payload.radiance;
        break;
    }
    GpuMaterial m = materials[objects[payload.object].material];
    vec3 n = facingNormal(payload.normal, direction);
    float mirror = m.params.y;  // reflectivity
    radiance += throughput * (1.0 - mirror) *
                localShading(m, payload.position, payload.error, n, -direction, rays);
    // TODO(you): follow the mirror's reflected ray
    break;
}
