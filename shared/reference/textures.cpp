// The reference's textures (chapter 12): the sampler's wrap and filter, the
// values a mesh's textures give a hit (base colour, metal-roughness, normal),
// and the material made of them, written again in double.
#include "reference/reference.h"

#include <algorithm>
#include <cmath>

namespace rg {

// Linear rgb and alpha, as texture.glsl's sampleTexture.
static glm::dvec4 sampleRgba(const Texture& texture, const glm::dvec2& uv) {
    auto wrap = [](double u, TextureWrap mode) {  // into [0, 1]
        if (mode == TextureWrap::Clamp) return std::clamp(u, 0.0, 1.0);
        if (mode == TextureWrap::Mirror)
            return 1 - std::abs(u - 2 * std::floor(u / 2) - 1);
        return u - std::floor(u);
    };
    auto texel = [&](long x, long y) {
        long w = texture.width, h = texture.height;
        x = texture.wrapU == TextureWrap::Repeat ? ((x % w) + w) % w
                                                 : std::clamp(x, 0L, w - 1);
        y = texture.wrapV == TextureWrap::Repeat ? ((y % h) + h) % h
                                                 : std::clamp(y, 0L, h - 1);
        size_t i = size_t(y) * w + x;
        return glm::dvec4(glm::dvec3(texture.texels[i]),
                          texture.alpha.empty() ? 1.0 : texture.alpha[i]);
    };
    double x = wrap(uv.x, texture.wrapU) * texture.width,
           y = wrap(uv.y, texture.wrapV) * texture.height;
    if (texture.nearest) return texel(long(std::floor(x)), long(std::floor(y)));
    x -= 0.5;
    y -= 0.5;
    double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    long ix = long(x0), iy = long(y0);
    return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), fx),
                    glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx), fy);
}

glm::dvec3 ReferenceRenderer::sampleTexture(const Texture& texture,
                                            const glm::dvec2& uv) {
    return glm::dvec3(sampleRgba(texture, uv));
}

double ReferenceRenderer::sampleAlpha(const Texture& texture, const glm::dvec2& uv) {
    return sampleRgba(texture, uv).a;
}

void ReferenceRenderer::textureHit(const Object& obj, uint32_t triangle,
                                   const glm::dvec3& w, ReferenceHit& hit) const {
    const MeshData& mesh = meshes_[obj.mesh];
    const Material& material = scene_.materials[obj.material];
    if (mesh.texcoords.empty()) return;
    const uint32_t* v = &mesh.indices[3 * triangle];
    glm::dvec2 uv = w.x * mesh.texcoords[v[0]] + w.y * mesh.texcoords[v[1]] +
                    w.z * mesh.texcoords[v[2]];
    auto texture = [&](int index) -> const Texture& { return *scene_.textures[index]; };
    if (material.texture >= 0) hit.tint = sampleTexture(texture(material.texture), uv);
    if (material.metalRough.texture >= 0) {
        glm::dvec3 mr = sampleTexture(texture(material.metalRough.texture), uv);
        hit.roughnessTexel = mr.g;
        hit.metalnessTexel = mr.b;
    }
    if (material.normalTexture < 0) return;
    // mesh.rchit's normalFromTexture: the tangent frame of the triangle's
    // texture coordinates, about the shading normal
    glm::dvec2 d1 = mesh.texcoords[v[1]] - mesh.texcoords[v[0]],
               d2 = mesh.texcoords[v[2]] - mesh.texcoords[v[0]];
    double det = d1.x * d2.y - d2.x * d1.y;
    if (det == 0) return;
    glm::dvec3 e1 = mesh.vertices[v[1]] - mesh.vertices[v[0]],
               e2 = mesh.vertices[v[2]] - mesh.vertices[v[0]];
    glm::dmat3 toWorld(obj.transform);
    glm::dvec3 dpdu = toWorld * ((e1 * d2.y - e2 * d1.y) / det),
               dpdv = toWorld * ((e2 * d1.x - e1 * d2.x) / det);
    glm::dvec3 n = hit.shading, t = dpdu - n * glm::dot(n, dpdu);
    if (glm::dot(t, t) == 0) return;
    t = glm::normalize(t);
    glm::dvec3 b = glm::cross(n, t);
    if (glm::dot(b, -dpdv) < 0) b = -b;  // mirrored texture coordinates
    glm::dvec3 texel = sampleTexture(texture(material.normalTexture), uv) * 2.0 - 1.0;
    texel.x *= material.normalScale;
    texel.y *= material.normalScale;
    glm::dvec3 mapped = texel.x * t + texel.y * b + texel.z * n;
    if (glm::dot(mapped, mapped) > 0) hit.shading = glm::normalize(mapped);
}

Material ReferenceRenderer::hitMaterial(const ReferenceHit& hit) const {
    Material m = scene_.materials[scene_.objects[hit.object].material];
    if (m.metalRough.texture >= 0) {  // raygen_common.glsl's hitMaterial
        applyMetalRoughness(m, m.metalRough.baseColor * hit.tint,
                            m.metalRough.metallic * hit.metalnessTexel,
                            m.metalRough.roughness * hit.roughnessTexel, m.transmission);
        return m;
    }
    m.ka *= hit.tint;
    m.kd *= hit.tint;
    return m;
}

}  // namespace rg
