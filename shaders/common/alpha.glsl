// Chapter 12's alpha test (glTF's alphaMode MASK), for any-hit shaders: a
// candidate hit on a mesh whose base colour's alpha there is below its
// material's alphaCutoff is no hit at all (alpha.rahit; chapter 14's
// transmitted shadows too).
#ifndef ALPHA_GLSL
#define ALPHA_GLSL
#include "rt_bindings.glsl"
#include "mesh_buffers.glsl"
#include "texture.glsl"

// [region cut_out]
// True where the mesh hit at `barycentrics` (of its triangle's second and
// third vertex) is cut out.
bool cutOut(vec2 barycentrics) {
    GpuObject object = objects[gl_InstanceCustomIndexEXT];
    GpuMaterial m = materials[object.material];
    float alpha = m.alpha;
    GpuMesh mesh = meshes[object.mesh];
    if (m.texture.z != 0u && mesh.texcoords != uvec2(0u)) {
        vec3 w = vec3(1.0 - barycentrics.x - barycentrics.y, barycentrics);
        vec2 uv = texcoordAt(mesh, triangleAt(mesh, gl_PrimitiveID), w);
        // level 0: coverage decided at the texture's own resolution
        alpha *= sampleTexture(m.texture, uv, 0.0).a;
    }
    return alpha < m.alphaCutoff;
}
// [end]
#endif
