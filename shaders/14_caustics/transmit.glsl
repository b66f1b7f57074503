// Chapter 14's --caustics transmit: what real-time engines do with glass in
// a shadow ray's way. The ray is not bent: each glass surface it crosses
// passes the Fresnel share 1 - F (from air into the glass, at the line's own
// angle, as at both faces of a pane), the glass between absorbs
// (Beer-Lambert), and anything else stops it. Cheap, and right for a clear
// pane (a coloured one only facing the light: at an angle the straight
// chord is longer than the refracted one); but nothing is focused, so a
// ball's shadow is a dim disc where the photons make a bright spot
// (docs/14_caustics.md).
#ifndef TRANSMIT_GLSL
#define TRANSMIT_GLSL
#include "rt_bindings.glsl"
#include "fresnel.glsl"

// The shadow ray's transmittance so far (rgb, from 1: radiometry.glsl),
// and where the ray ends (w): any-hit shaders see only the candidate's t
// as gl_RayTmaxEXT.
layout(location = 2) rayPayloadInEXT vec4 transmittance;

// [region cross]
// `surfaces` glass surfaces crossed at `cosine` to their normal, and the
// glass's absorption over `inside` (negative where the ray enters: the
// leaving surface's exp(-sigma t_out) completes it to the length between).
void crossGlass(GpuMaterial m, float cosine, float surfaces, float inside) {
    if (m.params.z <= 0.0) {  // opaque: the light is blocked
        transmittance.rgb = vec3(0.0);
        terminateRayEXT;
    }
    float F = fresnel(push.fresnelMode, m.extra.x, abs(cosine), 1.0, m.params.w);
    // clamped so that exp(+sigma t) cannot overflow before its partner comes
    transmittance.rgb *= pow(m.params.z * (1.0 - F), surfaces) *
                         exp(clamp(-m.medium.rgb * inside, -80.0, 80.0));
    ignoreIntersectionEXT;  // on through the glass
}
// [end]
#endif
