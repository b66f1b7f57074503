// Chapter 15's rough surfaces in the reference, in double, written again
// from page 15's formulas (not from microfacet.glsl): GGX, Smith's
// height-correlated masking, the visible normals by spherical caps, how one
// facet divides the light, and the lights' glints. The compensation of
// multiple scattering reads the build's albedo table with the GPU's own
// interpolation (albedo_table.glsl as C++): the table is the rule, and
// test_microfacet and the white furnace check it against physics.
#include "reference/ray_tree.h"
#include "reference/sampling.h"
#include "scene/microfacet_albedo.h"

#include <algorithm>
#include <cmath>

namespace shader {
namespace {
using namespace glm;
using uint = std::uint32_t;
#define ALBEDO_TABLE(i) rg::kMicrofacetAlbedo[i]
#include "albedo_table.glsl"
#undef ALBEDO_TABLE
}  // namespace
}  // namespace shader

namespace rg::ref {
namespace {

constexpr double kPi = 3.14159265358979323846;

double lambda(double cosine, double alpha) {
    double c2 = cosine * cosine;
    if (c2 <= 0) return 1e300;
    return 0.5 * (-1 + std::sqrt(1 + alpha * alpha * std::max(0.0, 1 - c2) / c2));
}

double ggx(double cosine, double alpha) {
    if (cosine <= 0) return 0;
    double a2 = alpha * alpha, c2 = cosine * cosine;
    double t = (1 - c2) / a2 + c2;
    return 1 / (kPi * a2 * t * t);
}

// The frame of the facing shading normal, (t, b, ns), built as the GPU
// builds it (Duff et al. 2017): the sample points turn the same way.
void frameOf(const glm::dvec3& ns, glm::dvec3& t, glm::dvec3& b) {
    double s = ns.z >= 0 ? 1 : -1;
    double a = -1 / (s + ns.z), c = ns.x * ns.y * a;
    t = glm::dvec3(1 + s * ns.x * ns.x * a, s * c, -s * ns.x);
    b = glm::dvec3(c, s + ns.y * ns.y * a, -ns.y);
}

// Turquin's (2019) factors on the dielectric's and the mirror's lobes
// (rough_surface.glsl's compensation): 1 / E and 1 + R (1 - E) / E.
struct Compensation {
    double dielectric = 1, mirror = 1;
};
Compensation compensation(const ReferenceSettings& settings, const Material& m,
                          double alpha, double n1, double n2, double cosO) {
    if (!settings.multipleScattering) return {};
    float roughness = float(std::sqrt(alpha));
    double kept = std::max<double>(
        shader::dielectricAlbedo(float(cosO), roughness, float(n1), float(n2)), 0.05);
    double keptMirror =
        std::max<double>(shader::mirrorAlbedo(float(cosO), roughness), 0.05);
    return {1 / kept, 1 + m.reflectivity * (1 - keptMirror) / keptMirror};
}

// the branch's own Sobol sequence (ray_tree.glsl's branchSequence)
uint32_t branchSequence(uint32_t seed, uint32_t depth, uint32_t path) {
    return shader::pcgHash(seed ^ shader::pcgHash(gpu::branchName(depth, path)));
}

}  // namespace

glm::dvec2 branchSample(uint32_t seed, uint32_t accumulated, uint32_t depth,
                        uint32_t path) {
    // the GPU's points (sampling.glsl compiled as C++), as the page names them
    glm::vec2 u = shader::sobolPoint(accumulated, branchSequence(seed, depth, path));
    return glm::dvec2(u);
}

glm::dvec2 rouletteSample(uint32_t seed, uint32_t accumulated, uint32_t depth,
                          uint32_t path) {
    constexpr uint32_t kRouletteSalt = 0x0B0E7712u;  // ROULETTE_SALT
    uint32_t sequence = branchSequence(seed, depth, path) ^ kRouletteSalt;
    return glm::dvec2(shader::sobolPoint(accumulated, sequence));
}

RoughBranches roughBranches(const ReferenceSettings& settings, const Material& m,
                            double alpha, double n1, double n2, const glm::dvec3& n,
                            const glm::dvec3& ns, const glm::dvec3& direction,
                            glm::dvec2 u) {
    glm::dvec3 t, b;
    frameOf(ns, t, b);
    glm::dvec3 v = -direction;
    double cosO = std::max(glm::dot(v, ns), 1e-6);
    // wo in the frame, stretched to alpha = 1: the visible normals there are a
    // uniform point on the cap above -wo, plus wo (Dupuy and Benyoub 2023)
    glm::dvec3 wo = glm::normalize(glm::dvec3(glm::dot(v, t), glm::dot(v, b), cosO));
    glm::dvec3 stretched = glm::normalize(glm::dvec3(alpha * wo.x, alpha * wo.y, wo.z));
    double phi = 2 * kPi * u.x, z = (1 - u.y) * (1 + stretched.z) - stretched.z;
    double s = std::sqrt(std::clamp(1 - z * z, 0.0, 1.0));
    glm::dvec3 h = glm::dvec3(s * std::cos(phi), s * std::sin(phi), z) + stretched;
    glm::dvec3 facet =
        glm::normalize(glm::dvec3(alpha * h.x, alpha * h.y, std::max(h.z, 0.0)));
    glm::dvec3 mw = facet.x * t + facet.y * b + facet.z * ns;  // in the world
    double om = glm::dot(v, mw);
    double F = referenceFresnel(settings.fresnelMode, m.f0, om, n1, n2);
    double g1 = 1 / (1 + lambda(wo.z, alpha));
    RoughBranches r;
    r.reflected = 2 * om * mw - v;
    double cosR = glm::dot(r.reflected, ns);
    double masking =
        cosR > 0 ? (1 / (1 + lambda(wo.z, alpha) + lambda(cosR, alpha))) / g1 : 0;
    Compensation c = compensation(settings, m, alpha, n1, n2, wo.z);
    r.reflectedShare = m.transmission * c.dielectric * F * masking +
                       (1 - m.transmission) * m.reflectivity * c.mirror * masking;
    if (refractDirection(direction, mw, n1, n2, r.refracted)) {
        double cosT = glm::dot(r.refracted, ns);
        if (cosT < 0)
            r.refractedShare = m.transmission * c.dielectric * (1 - F) *
                               (1 / (1 + lambda(wo.z, alpha) + lambda(cosT, alpha))) / g1;
    }
    // the flat triangle decides the sides (meshes)
    if (glm::dot(r.reflected, n) <= 0) r.reflectedShare = 0;
    if (glm::dot(r.refracted, n) >= 0) r.refractedShare = 0;
    return r;
}

double roughLobe(const ReferenceSettings& settings, const Material& m, double alpha,
                 double n1, double n2, const glm::dvec3& ns, const glm::dvec3& v,
                 const glm::dvec3& l) {
    double cosO = std::max(glm::dot(v, ns), 1e-6), cosI = glm::dot(l, ns);
    double g2 = 1 / (1 + lambda(cosO, alpha) + lambda(cosI, alpha));
    Compensation c = compensation(settings, m, alpha, n1, n2, cosO);
    if (cosI > 0) {  // reflection: F D G2 / (4 cos_o), the dielectric and the mirror
        glm::dvec3 h = glm::normalize(v + l);
        double F = referenceFresnel(settings.fresnelMode, m.f0, glm::dot(v, h), n1, n2);
        double d = ggx(glm::dot(h, ns), alpha);
        return (m.transmission * c.dielectric * F +
                (1 - m.transmission) * m.reflectivity * c.mirror) *
               d * g2 / (4 * cosO);
    }
    // transmission (Walter et al. 2007, eq. 21, times |cos_i|)
    glm::dvec3 h = -(n1 * v + n2 * l);
    if (glm::dot(h, h) == 0) return 0;
    h = glm::normalize(h);
    if (glm::dot(h, ns) < 0) h = -h;
    double om = glm::dot(v, h), im = glm::dot(l, h);
    if (om <= 0 || im >= 0) return 0;
    double F = referenceFresnel(settings.fresnelMode, m.f0, om, n1, n2);
    double denominator = n1 * om + n2 * im;
    return m.transmission * c.dielectric * (1 - F) * ggx(glm::dot(h, ns), alpha) * g2 *
           om * -im * n2 * n2 / (cosO * denominator * denominator);
}

}  // namespace rg::ref
