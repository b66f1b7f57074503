// Exercise, chapter 10: refraction (thesis 4.4).
// replaces: common/ray_tree.glsl#refract
// The share tr = throughput * s.refracted goes on through the surface:
// where it is at least MIN_THROUGHPUT, push a branch (tree.stack[tree.top++]
// = Branch(origin, depth, direction, tMax, tr, beyond)) whose direction is
// refractedDirection(b.direction, n, ns, s.eta) (a thin wall's: b.direction
// unbent), whose origin is moved to the far side (secondaryOrigin(p, e,
// -n)), at depth (b.depth + 1u) | spectral, with tMax insideReach(o, p,
// radius) when entering a sphere (else kInfinity). No refracted direction
// (vec3(0)): add tr to the reflected share rf. Until it is written, glass
// shows only what it reflects.
if (maxComponent(tr) >= MIN_THROUGHPUT) {
    // TODO(you): the refracted branch
}
