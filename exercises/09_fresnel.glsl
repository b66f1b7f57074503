// Exercise, chapter 09: Fresnel (thesis 4.2).
// replaces: 09_fresnel/raygen.rgen#fresnel_weight
// How much a surface reflects: for glass (transmission > 0) Fresnel's F,
// from fresnel(push.fresnelMode, m.extra.x, cos i, n1, n2) with n1 and n2
// the indices on the two sides (air 1 outside; which side from
// payload.frontFace); for the rest, its reflectivity m.params.y. The
// highlight is reflected light too: glass's share of it is F. Until it is
// written, glass reflects as a fixed mirror of its reflectivity.
float ior = m.params.w, transmission = m.params.z;
// TODO(you): F, and glass's reflected share and highlight from it
float reflected = m.params.y;
float highlight = 1.0 - m.params.y;
