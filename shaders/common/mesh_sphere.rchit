#version 460
// Closest-hit for a tessellated sphere (--sphere-mesh): the normal is
// interpolated from the vertices (on the unit sphere, a vertex's normal is
// its position), as meshes are usually shaded; the hit point lies on the
// flat triangle. Compare with the analytic sphere in docs/performance.md.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_bindings.glsl"
#include "payload.glsl"
#include "hit_error.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;
layout(binding = RT_BINDING_MESH_VERTICES, std430) readonly buffer MeshVertices { float meshVertices[]; };
layout(binding = RT_BINDING_MESH_INDICES, std430) readonly buffer MeshIndices { uint meshIndices[]; };
hitAttributeEXT vec2 barycentrics;

vec3 vertex(uint i) {
    uint v = meshIndices[3u * gl_PrimitiveID + i];
    return vec3(meshVertices[3u * v], meshVertices[3u * v + 1u], meshVertices[3u * v + 2u]);
}

void main() {
    vec3 a = vertex(0u), b = vertex(1u), c = vertex(2u);
    vec3 w = vec3(1.0 - barycentrics.x - barycentrics.y, barycentrics.x, barycentrics.y);
    vec3 local = w.x * a + w.y * b + w.z * c;  // on the triangle
    vec3 smoothNormal = normalize(local);      // the sphere's normal there
    vec3 faceNormal = cross(b - a, c - a);     // outward: counter-clockwise from outside
    payload.normal = normalize(smoothNormal * mat3(gl_WorldToObjectEXT));
    payload.t = gl_HitTEXT;
    payload.position = gl_ObjectToWorldEXT * vec4(local, 1.0);
    payload.error = hitError(abs(local), gl_ObjectToWorldEXT, payload.normal);  // interpolated from the vertices
    payload.material = objects[gl_InstanceCustomIndexEXT].material;
    payload.frontFace = dot(faceNormal, gl_ObjectRayDirectionEXT) < 0.0 ? 1u : 0u;
    payload.radius = 0.0;  // no bound: interpolated normals can refract a ray out of the mesh
}
