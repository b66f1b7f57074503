#version 460
// Closest-hit for triangle meshes (chapter 12) and the tessellated sphere
// (--sphere-mesh). Triangles need no intersection shader: the traversal
// finds the hit itself and hands over two barycentrics (with --triangles
// watertight, triangle.rint finds it and hands over the same two).
// This shader reads the triangle's vertices by device address, and
// describes the hit: the geometric normal of the flat triangle (offsets and
// sides), the interpolated vertex normal (shading), and the side the ray
// came from, from the hit kind (the winding), never from a normal.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_bindings.glsl"
#include "mesh_buffers.glsl"
#include "payload.glsl"
#include "hit_error.glsl"
#include "texture.glsl"

layout(location = 0) rayPayloadInEXT HitPayload payload;
hitAttributeEXT vec2 barycentrics;  // weights of the triangle's second and third vertex

// [region normal_texture]
// glTF's normal texture (3.9.3): a normal in the tangent space of the
// surface, x along the texture's u, y toward the image's top (-v), z the
// shading normal. Without TANGENT attributes (not read) the tangent is the
// triangle's own direction of growing u, made perpendicular to the shading
// normal; the bitangent's sign follows the texture's handedness (mirrored
// coordinates flip it).
// `uvs`: the triangle's three texture coordinates, `uv` the hit's.
vec3 normalFromTexture(GpuMaterial material, vec3 a, vec3 b, vec3 c, mat3x2 uvs,
                       vec2 uv, float footprint) {
    vec2 d1 = uvs[1] - uvs[0], d2 = uvs[2] - uvs[0];
    float det = d1.x * d2.y - d2.x * d1.y;
    if (det == 0.0) return payload.shading;  // no texture space on this triangle
    vec3 e1 = b - a, e2 = c - a;
    // dP/du and dP/dv in object space, then world (tangents go as points do)
    vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det, dpdv = (e2 * d1.x - e1 * d2.x) / det;
    dpdu = mat3(gl_ObjectToWorldEXT) * dpdu;
    dpdv = mat3(gl_ObjectToWorldEXT) * dpdv;
    vec3 n = payload.shading;
    vec3 t = dpdu - n * dot(n, dpdu);
    if (dot(t, t) == 0.0) return n;
    t = normalize(t);
    vec3 bt = cross(n, t);
    if (dot(bt, -dpdv) < 0.0) bt = -bt;  // mirrored texture coordinates
    uvec4 map = material.normalTexture;
    vec3 texel = sampleTexture(map, uv, texelLod(map, footprint)).rgb * 2.0 - 1.0;
    texel.xy *= material.factors.y;  // the normal texture's scale
    vec3 mapped = texel.x * t + texel.y * bt + texel.z * n;
    return dot(mapped, mapped) > 0.0 ? normalize(mapped) : n;
}
// [end]

// [region ray_cone]
// Which mip level (Akenine-Moller et al., Ray Tracing Gems 2019, ch. 20):
// a pixel's rays fill a cone that widens by the angle one pixel spans
// (`cone.y`, raygen_common.glsl) per unit of distance, here `cone.x + t`
// from the eye. Where it meets the triangle at an angle its footprint is
// 1/|n.d| longer, and the triangle stretches its texture coordinates' area
// over its world area; log2 of the footprint in texture coordinates:
//   0.5 log2(uv area / world area) + log2(width / |n.d|).
// texelLod adds 0.5 log2(w h) for a texture of w x h texels.
float coneLod(vec2 cone, vec3 a, vec3 b, vec3 c, mat3x2 uvs) {
    if (!kRayCones) return 0.0;  // no mip levels, or --mips off: level 0
    vec2 d1 = uvs[1] - uvs[0], d2 = uvs[2] - uvs[0];
    float uvArea = abs(d1.x * d2.y - d2.x * d1.y);
    mat3 toWorld = mat3(gl_ObjectToWorldEXT);
    float worldArea = length(cross(toWorld * (b - a), toWorld * (c - a)));
    float width = cone.y * (cone.x + gl_HitTEXT);
    float cosine = abs(dot(payload.normal, gl_WorldRayDirectionEXT));
    // a zero or infinite term gives -inf, +inf or NaN: sampleTexture reads
    // level 0 for all but +inf (the last level)
    return 0.5 * log2(uvArea / worldArea) + log2(width / cosine);
}
// [end]

// [region closest_hit]
void main() {
    vec2 cone = payload.radiance.xy;  // the ray's cone, as traceClosest left it
    GpuObject object = objects[gl_InstanceCustomIndexEXT];
    GpuMesh mesh = meshes[object.mesh];
    uvec3 v = triangleAt(mesh, gl_PrimitiveID);
    Floats positions = Floats(mesh.vertices);
    vec3 a = vec3At(positions, v.x), b = vec3At(positions, v.y),
         c = vec3At(positions, v.z);
    vec3 w = vec3(1.0 - barycentrics.x - barycentrics.y, barycentrics.x, barycentrics.y);
    vec3 local = w.x * a + w.y * b + w.z * c;  // on the flat triangle
    // Counter-clockwise seen from outside: b - a, c - a, and their cross
    // product points out. Normals go to world space with the inverse transpose.
    payload.normal = normalize(cross(b - a, c - a) * mat3(gl_WorldToObjectEXT));
    payload.shading = payload.normal;
    if (mesh.normals != uvec2(0u)) {  // smooth: the vertex normals, interpolated
        Floats normals = Floats(mesh.normals);
        vec3 n = w.x * vec3At(normals, v.x) + w.y * vec3At(normals, v.y) +
                 w.z * vec3At(normals, v.z);
        vec3 world = n * mat3(gl_WorldToObjectEXT);
        if (dot(world, world) > 0.0) payload.shading = normalize(world);
    }
    // The traversal's own verdict from the winding: no normal can get it
    // wrong (or triangle.rint's, with --triangles watertight).
    bool front = gl_HitKindEXT == gl_HitKindFrontFacingTriangleEXT ||
                 gl_HitKindEXT == kHitKindFrontBox;
    payload.frontFace = front ? 1u : 0u;
    payload.t = gl_HitTEXT;
    payload.position = gl_ObjectToWorldEXT * vec4(local, 1.0);
    // The point comes from the vertices, but the next ray's test against
    // this triangle shears it into that ray's frame (Woop et al. 2013), which
    // mixes the coordinates: it rounds with the largest of them, whichever
    // way the triangle faces. Per axis, a floor at y = 0 would get a bound
    // from its y = 0 alone, and on NVIDIA shadow rays near its diagonal hit it again.
    vec3 corner = max(abs(a), max(abs(b), abs(c)));
    vec3 magnitude = vec3(max(corner.x, max(corner.y, corner.z)));
    payload.error = hitError(magnitude, gl_ObjectToWorldEXT, payload.normal);
    payload.object = gl_InstanceCustomIndexEXT;
    // [region base_colour]
    // On a hit the payload's radiance is free: it brings the textures'
    // values back (payload.glsl), and hitMaterial (raygen_common.glsl) makes
    // the hit's material of them.
    HitTextures h = HitTextures(vec3(1.0), 1.0, 1.0);
    GpuMaterial material = materials[object.material];
    if (mesh.texcoords != uvec2(0u)) {
        mat3x2 uvs = texcoordsOf(mesh, v);  // read once: the normal texture's too
        vec2 uv = texcoordAt(uvs, w);
        float footprint = coneLod(cone, a, b, c, uvs);
        uvec4 color = material.texture, mrTexture = material.metalRoughTexture;
        if (color.z != 0u)
            h.baseColor = sampleTexture(color, uv, texelLod(color, footprint)).rgb;
        if (mrTexture.z != 0u) {
            vec4 mr = sampleTexture(mrTexture, uv, texelLod(mrTexture, footprint));
            h.roughness = mr.g;
            h.metalness = mr.b;
        }
        if (material.normalTexture.z != 0u)
            payload.shading = normalFromTexture(material, a, b, c, uvs, uv, footprint);
    }
    payload.radiance = packHitTextures(h);
    // [end]
}
// [end]
