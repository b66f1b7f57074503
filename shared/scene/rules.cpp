// The scene's rules and checks (chapters 03, 06, 12, 13): what a transform
// stretches, where camera rays start, and what a chapter cannot draw.
#include "scene/scene.h"

#include "core/files.h"

#include <algorithm>
#include <cmath>

namespace rg {

double largestStretch(const glm::dmat4& m) {
    return std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                     glm::length(glm::dvec3(m[2]))});
}

double smallestStretch(const glm::dmat4& m) {
    return std::min({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                     glm::length(glm::dvec3(m[2]))});
}

// [region metal_roughness]
// glTF's metal-roughness material (glTF 2.0, 3.9.2) in RayGlass's terms:
// the base colour is diffuse where the surface is neither metal nor glass;
// metal is an untinted mirror of that strength, rough by its roughness (ch
// 11); glass is rough by its roughness too (KHR_materials_transmission:
// the same microfacets reflect and transmit; ch 15's frosted glass); the
// highlight narrows as the roughness falls (Blinn-Phong's exponent
// 2 / alpha^2 - 2 for GGX's alpha = roughness^2).
void applyMetalRoughness(Material& m, const glm::dvec3& baseColor, double metallic,
                         double roughness, double transmission) {
    double dielectric = (1 - metallic) * (1 - transmission);
    m.kd = baseColor * dielectric;
    m.ka = m.kd;
    double alpha = std::max(roughness * roughness, 1e-3);
    m.shininess = std::min(1e6, std::max(1.0, 2 / (alpha * alpha) - 2));
    m.ks = glm::dvec3(0.04 * (1 - roughness));
    m.reflectivity = metallic * (1 - transmission);
    // rough: metal, and glass (not a dielectric's diffuse base)
    m.roughness = transmission > 0 ? roughness : roughness * metallic;
}
// [end]

// [region eye_tmin]
// Rule 1 of docs/scene-format.md: camera rays ignore hits closer to the eye
// than this. It is 0 unless the eye lies on a surface within that
// surface's float rounding (an eye placed exactly on a sphere lands, once in
// float, a hair inside or outside it); then a reach a little beyond that
// rounding, so that the eye sees what a ray leaving the surface would. Each
// surface's rounding grows with its own size and distance, so the value
// depends on the surfaces at the eye alone, not on the rest of the scene.
double eyeTmin(const Scene& s) {
    // 8 units of float's relative rounding, 2^-24
    constexpr double kRounding = 8.0 / 16777216.0;
    constexpr double kReach = 1.0 / 16384.0;          // 2^-14 of the surface's size
    double tMin = 0;
    for (const Object& o : s.objects) {
        if (o.hidden) continue;
        const glm::dmat4& m = o.transform;
        double scale = largestStretch(m);
        double size = glm::length(glm::dvec3(m[3]) - s.camera.position) + scale;
        // the eye, in object space
        glm::dvec3 q = glm::dvec3(glm::inverse(m) * glm::dvec4(s.camera.position, 1.0));
        // in object units
        double rounding = kRounding * size / scale;
        bool onSurface =
            o.type == ShapeType::Sphere ? std::abs(glm::length(q) - 1.0) <= rounding
            : o.type == ShapeType::Quad
                ? std::abs(q.y) <= rounding && std::abs(q.x) <= 1 + rounding &&
                      std::abs(q.z) <= 1 + rounding
                // a mesh: an eye on one of its triangles is not looked for
                : false;
        if (onSurface) tMin = std::max(tMin, kReach * size);
    }
    return tMin;
}
// [end]

void refuseUnstackableMedia(const Scene& scene) {
    for (size_t i = 255; i < scene.materials.size(); ++i)
        if (scene.materials[i].transmission > 0)
            throw InputError(scene.path + ": materials." + scene.materials[i].name +
                             ": a medium must be among the first 255 materials (chapter "
                             "13's stack keeps 8 bits an entry)");
}

void refuseMeshes(const Scene& scene) {
    for (const Object& o : scene.objects)
        if (o.type == ShapeType::Mesh)
            throw InputError(
                scene.path + ": " + scene.meshes[o.mesh]->name +
                ": triangle meshes come in chapter 12; run 12_triangle_meshes");
}

void refusePhysicalLights(const Scene& scene) {
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].kind != PointLight::Kind::Thesis)
            throw InputError(scene.path + ": lights[" + std::to_string(i) +
                             "]: lights in physical units (power, irradiance) come in "
                             "chapter 14; run 14_caustics");
}

void refuseSunDiscInReference(const Scene& scene) {
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].angularRadius > 0)
            throw InputError(scene.path + ": lights[" + std::to_string(i) +
                             "].angular_radius_deg: the CPU reference (--reference) "
                             "takes the sun as a point; leave out one or the other");
}

void requirePhysicalLights(const Scene& scene) {
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].kind == PointLight::Kind::Thesis)
            throw InputError(scene.path + ": lights[" + std::to_string(i) +
                             "]: chapters 14-15 need lights in physical units: a point "
                             "light's \"power\" in watts, or a directional light");
}

}  // namespace rg
