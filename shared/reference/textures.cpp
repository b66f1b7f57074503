// The reference's textures (chapter 12): the sampler's wrap and filter, the
// values a mesh's textures give a hit (base colour, metal-roughness, normal),
// and the material made of them, written again in double.
#include "reference/reference.h"

#include <algorithm>
#include <cmath>

namespace rg {

// One level, as texture.glsl's sampleLevel: linear rgb and alpha.
static glm::dvec4 sampleLevel(const Texture& texture, const glm::dvec2& uv,
                              uint32_t level, bool nearest) {
    auto wrap = [](double u, TextureWrap mode) {  // into [0, 1]
        if (mode == TextureWrap::Clamp) return std::clamp(u, 0.0, 1.0);
        if (mode == TextureWrap::Mirror)
            return 1 - std::abs(u - 2 * std::floor(u / 2) - 1);
        return u - std::floor(u);
    };
    long w = texture.levels[level].width, h = texture.levels[level].height;
    auto texel = [&](long x, long y) {
        x = texture.wrapU == TextureWrap::Repeat ? ((x % w) + w) % w
                                                 : std::clamp(x, 0L, w - 1);
        y = texture.wrapV == TextureWrap::Repeat ? ((y % h) + h) % h
                                                 : std::clamp(y, 0L, h - 1);
        return texelValue(texture, level, uint32_t(x), uint32_t(y));
    };
    double x = wrap(uv.x, texture.wrapU) * w, y = wrap(uv.y, texture.wrapV) * h;
    if (nearest) return texel(long(std::floor(x)), long(std::floor(y)));
    x -= 0.5;
    y -= 0.5;
    double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    long ix = long(x0), iy = long(y0);
    return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), fx),
                    glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx), fy);
}

// At level of detail `lod`, as texture.glsl's sampleTexture.
static glm::dvec4 sampleRgba(const Texture& texture, const glm::dvec2& uv, double lod) {
    if (!(lod > 0)) return sampleLevel(texture, uv, 0, texture.nearest);
    bool nearest = texture.minNearest;
    double last = double(texture.levels.size() - 1);
    if (texture.mipmap == TextureMipmap::None || last == 0)
        return sampleLevel(texture, uv, 0, nearest);
    lod = std::min(lod, last);
    if (texture.mipmap == TextureMipmap::Nearest)
        return sampleLevel(texture, uv, uint32_t(std::floor(lod + 0.5)), nearest);
    uint32_t below = uint32_t(std::floor(lod));
    glm::dvec4 a = sampleLevel(texture, uv, below, nearest);
    if (below == uint32_t(last)) return a;
    return glm::mix(a, sampleLevel(texture, uv, below + 1, nearest), lod - below);
}

glm::dvec3 ReferenceRenderer::sampleTexture(const Texture& texture, const glm::dvec2& uv,
                                            double lod) {
    return glm::dvec3(sampleRgba(texture, uv, lod));
}

double ReferenceRenderer::sampleAlpha(const Texture& texture, const glm::dvec2& uv) {
    return sampleRgba(texture, uv, 0).a;  // level 0, as alpha.rahit
}

// [region reference_cone]
// mesh.rchit's coneLod in double: log2 of the cone's footprint in texture
// coordinates at the hit; texelLod adds 0.5 log2(w h) per texture.
double ReferenceRenderer::coneLod(const ReferenceHit& hit, const glm::dvec3& direction,
                                  const RayCone& cone) const {
    const Object& obj = scene_.objects[hit.object];
    const MeshData& mesh = meshes_[obj.mesh];
    const uint32_t* v = &mesh.indices[3 * hit.triangle];
    glm::dvec2 d1 = mesh.texcoords[v[1]] - mesh.texcoords[v[0]],
               d2 = mesh.texcoords[v[2]] - mesh.texcoords[v[0]];
    double uvArea = std::abs(d1.x * d2.y - d2.x * d1.y);
    glm::dmat3 toWorld(obj.transform);
    double worldArea =
        glm::length(glm::cross(toWorld * (mesh.vertices[v[1]] - mesh.vertices[v[0]]),
                               toWorld * (mesh.vertices[v[2]] - mesh.vertices[v[0]])));
    double width = cone.spread * (cone.start + hit.t);
    double cosine = std::abs(glm::dot(hit.normal, direction));
    return 0.5 * std::log2(uvArea / worldArea) + std::log2(width / cosine);
}
// [end]

static double texelLod(const Texture& texture, double footprint) {
    return footprint + 0.5 * std::log2(double(texture.width) * texture.height);
}

void ReferenceRenderer::textureAt(ReferenceHit& hit, const glm::dvec3& direction,
                                  const RayCone& cone) const {
    const Object& obj = scene_.objects[hit.object];
    if (hit.t < 0 || obj.type != ShapeType::Mesh || meshes_[obj.mesh].texcoords.empty())
        return;
    textureHit(obj, hit.triangle, hit.weights,
               rayCones_ ? coneLod(hit, direction, cone) : 0, hit);
}

void ReferenceRenderer::textureHit(const Object& obj, uint32_t triangle,
                                   const glm::dvec3& w, double footprint,
                                   ReferenceHit& hit) const {
    const MeshData& mesh = meshes_[obj.mesh];
    const Material& material = scene_.materials[obj.material];
    if (mesh.texcoords.empty()) return;
    const uint32_t* v = &mesh.indices[3 * triangle];
    glm::dvec2 uv = w.x * mesh.texcoords[v[0]] + w.y * mesh.texcoords[v[1]] +
                    w.z * mesh.texcoords[v[2]];
    auto sample = [&](int index) {
        const Texture& t = *scene_.textures[index];
        return sampleTexture(t, uv, texelLod(t, footprint));
    };
    if (material.texture >= 0) hit.tint = sample(material.texture);
    if (material.metalRough.texture >= 0) {
        glm::dvec3 mr = sample(material.metalRough.texture);
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
    glm::dvec3 texel = sample(material.normalTexture) * 2.0 - 1.0;
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
