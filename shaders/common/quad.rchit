#version 460
// Closest-hit for quads (triangles): the unit quad's normal is +y.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_bindings.glsl"
#include "payload.glsl"
#include "hit_error.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;

// [region closest_hit]
void main() {
    payload.normal = normalize(vec3(0.0, 1.0, 0.0) * mat3(gl_WorldToObjectEXT));
    payload.t = gl_HitTEXT;
    vec3 local = gl_ObjectRayOriginEXT + gl_HitTEXT * gl_ObjectRayDirectionEXT;
    local.y = 0.0;  // exactly on the unit quad's plane
    payload.position = gl_ObjectToWorldEXT * vec4(local, 1.0);
    payload.error = hitError(
        rayPointMagnitude(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_HitTEXT),
        gl_ObjectToWorldEXT, payload.normal);
    payload.object = gl_InstanceCustomIndexEXT;
    payload.frontFace = dot(payload.normal, gl_WorldRayDirectionEXT) < 0.0 ? 1u : 0u;
    // flat or analytic: one normal, read as both where meshes need both
    if (kMeshes) payload.shading = payload.normal;
}
// [end]
