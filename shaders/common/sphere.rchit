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
    payload.t = gl_HitTEXT;
    if (s == vec4(0.0, 0.0, 0.0, 1.0)) {
        // An instance of the unit sphere: the point the intersection shader
        // found (refined where the origin is far: a squashed sphere), moved
        // back onto the sphere along its radius (PBRT-v4 6.8.5). Its error is
        // then that of its own coordinates, axis by axis, however inexactly t
        // was found (a far root, a ray from inside): a sphere squashed to a
        // plate has small numbers along its thin axis, and its bound along
        // the normal stays within its thickness (docs/06_diffuse.md).
        vec3 local = normalize(objectNormal);
        // Normals transform with the inverse transpose: n * M^-1 = (M^-T) n.
        payload.normal = normalize(objectNormal * mat3(gl_WorldToObjectEXT));
        payload.position = gl_ObjectToWorldEXT * vec4(local, 1.0);
        payload.error = hitError(abs(local), gl_ObjectToWorldEXT, payload.normal);
    } else {
        // A sphere of a group (chapter 03), whose one instance has the
        // identity transform: object space is world space, and no matrix is
        // needed. The point from the ray, not as centre + radius * normal,
        // whose error grows with the centre's distance (a floor of radius
        // 1e5). A group's spheres are round: the largest number in every
        // axis bounds it.
        vec3 o = gl_WorldRayOriginEXT, d = gl_WorldRayDirectionEXT;
        payload.normal = normalize(objectNormal);
        payload.position = o + gl_HitTEXT * d;
        vec3 magnitude = rayPointMagnitude(o, d, gl_HitTEXT);
        // the far root: from inside
        if (gl_HitKindEXT == 1u) magnitude += abs(o - s.xyz) + s.w;
        payload.error = hitError(magnitude, payload.normal);
    }
    payload.object = index;
    payload.frontFace = gl_HitKindEXT == 0u ? 1u : 0u;
    // flat or analytic: one normal, read as both where meshes need both
    if (kMeshes) payload.shading = payload.normal;
}
// [end]
