#version 460
// Closest-hit for spheres: describe the hit; raygen shades it.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_bindings.glsl"
#include "payload.glsl"
#include "hit_error.glsl"

// [region closest_hit]
layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec3 objectNormal;

void main() {
    // Box k of an instance is object customIndex + k (one box per instance
    // of the unit sphere; many in a sphere group, chapter 03).
    uint index = gl_InstanceCustomIndexEXT + gl_PrimitiveID;
    vec4 s = objects[index].sphere;
    // Normals transform with the inverse transpose: n * M^-1 = (M^-T) n.
    payload.normal = normalize(objectNormal * mat3(gl_WorldToObjectEXT));
    payload.t = gl_HitTEXT;
    // The hit point from the ray (not as centre + radius * normal, whose
    // error grows with the centre's distance: a floor of radius 1e5).
    vec3 local = gl_ObjectRayOriginEXT + gl_HitTEXT * gl_ObjectRayDirectionEXT;
    payload.position = gl_ObjectToWorldEXT * vec4(local, 1.0);
    vec3 magnitude =
        rayPointMagnitude(gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_HitTEXT);
    // the far root: from inside
    if (gl_HitKindEXT == 1u) magnitude += abs(gl_ObjectRayOriginEXT - s.xyz) + s.w;
    payload.error = hitError(magnitude, gl_ObjectToWorldEXT, payload.normal);
    payload.object = index;
    payload.frontFace = gl_HitKindEXT == 0u ? 1u : 0u;
    payload.shading = payload.normal;  // flat or analytic: one normal
}
// [end]
