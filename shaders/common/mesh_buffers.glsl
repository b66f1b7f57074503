// A mesh's vertex and index buffers, read by device address (chapter 12):
// the closest-hit shader (mesh.rchit) and the watertight triangle test
// (triangle.rint) read the same ones.
#ifndef MESH_BUFFERS_GLSL
#define MESH_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "rt_bindings.glsl"

// [region buffers]
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Floats {
    float f[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Indices {
    uint i[];
};
layout(binding = RT_BINDING_MESHES, std430) readonly buffer Meshes { GpuMesh meshes[]; };

vec3 vec3At(Floats data, uint vertex) {
    return vec3(data.f[3u * vertex], data.f[3u * vertex + 1u], data.f[3u * vertex + 2u]);
}
vec2 vec2At(Floats data, uint vertex) {
    return vec2(data.f[2u * vertex], data.f[2u * vertex + 1u]);
}
// [end]

// The texture coordinates of triangle v's three vertices, one a column.
mat3x2 texcoordsOf(GpuMesh mesh, uvec3 v) {
    Floats uvs = Floats(mesh.texcoords);
    return mat3x2(vec2At(uvs, v.x), vec2At(uvs, v.y), vec2At(uvs, v.z));
}
// The texture coordinate at barycentric weights w between the three.
vec2 texcoordAt(mat3x2 t, vec3 w) { return w.x * t[0] + w.y * t[1] + w.z * t[2]; }
vec2 texcoordAt(GpuMesh mesh, uvec3 v, vec3 w) {
    return texcoordAt(texcoordsOf(mesh, v), w);
}

// The three vertex indices of triangle `triangle` of `mesh`.
uvec3 triangleAt(GpuMesh mesh, uint triangle) {
    Indices indices = Indices(mesh.indices);
    return uvec3(indices.i[3u * triangle], indices.i[3u * triangle + 1u],
                 indices.i[3u * triangle + 2u]);
}

// --triangles watertight: the hit kind triangle.rint reports for a ray that
// meets a triangle's front (counter-clockwise) side; the driver's own test
// reports gl_HitKindFrontFacingTriangleEXT (custom kinds must be 0-127).
const uint kHitKindFrontBox = 0u;
#endif
