#version 460
// Miss shader (thesis 2.2.3): nothing was hit, the ray sees the sky.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_bindings.glsl"
#include "payload.glsl"
#include "sky.glsl"

// [region miss]
layout(location = 0) rayPayloadInEXT HitPayload payload;

void main() {
    payload.radiance = skyRadiance(gl_WorldRayDirectionEXT);
    payload.t = -1.0;
}
// [end]
