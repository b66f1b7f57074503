// The reference's optics and media (chapters 08-13): Fresnel, how light
// divides at a surface, reflected and refracted directions, the medium
// stack's rules, and the wavelengths of chapter 13's paths.
#include "reference/ray_tree.h"

#include <algorithm>
#include <cmath>

namespace rg {

double referenceFresnel(int mode, double f0, double cosI, double n1, double n2) {
    double sin2T = (n1 / n2) * (n1 / n2) * std::max(0.0, 1 - cosI * cosI);  // Snell
    // total internal reflection
    if (sin2T >= 1) return 1;
    double cosT = std::sqrt(1 - sin2T);
    if (mode == 2) {  // unpolarized: the mean of the s and p reflectances
        double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
        double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
        return (rs * rs + rp * rp) / 2;
    }
    if (mode == 1) f0 = std::pow((n1 - n2) / (n1 + n2), 2);
    // Schlick leaving a denser medium uses the transmitted angle
    double c = n1 > n2 ? cosT : cosI;
    return f0 + (1 - f0) * std::pow(1 - c, 5);
}

namespace ref {

Split splitAt(const ReferenceSettings& settings, const Material& m, double n1, double n2,
              double cosI) {
    Split s;
    s.n1 = n1;
    s.n2 = n2;
    s.reflected = m.reflectivity;
    if (settings.stage >= ReferenceStage::Fresnel) {
        double F = referenceFresnel(settings.fresnelMode, m.f0, cosI, s.n1, s.n2);
        s.reflected = m.transmission * F + (1 - m.transmission) * m.reflectivity;
        if (settings.stage >= ReferenceStage::Refraction)
            s.refracted = m.transmission * (1 - F);
        s.highlight = (1 - m.transmission) * (1 - m.reflectivity) + m.transmission * F;
    }
    s.local = 1 - s.reflected - s.refracted;
    // chapter 08: the thesis's mix
    if (settings.stage < ReferenceStage::Fresnel) s.highlight = s.local;
    return s;
}

// Chapters 08-12: air outside every material.
Split splitAt(const ReferenceSettings& settings, const Material& m, bool entering,
              double cosI) {
    // a thin wall (chapter 10 on) has air on both sides: air into glass
    bool thin = m.thin && settings.stage >= ReferenceStage::Refraction;
    return entering || thin ? splitAt(settings, m, 1.0, m.ior, cosI)
                            : splitAt(settings, m, m.ior, 1.0, cosI);
}

// Chapter 13's media (written again from the rule on docs/13_real_glass.md,
// not from media.glsl): the medium at a place is the stack's entry of
// highest priority, of equal ones the last entered; -1 is air.
Crossing crossingAt(const Scene& scene, const MediumStack& media, uint32_t material,
                    bool entering) {
    Crossing c;
    c.from = mediumOf(scene, media);
    c.beyond = media;
    if (entering) {
        c.beyond.materials.push_back(material);
        if (c.beyond.materials.size() > kMediaDepth)
            c.beyond.materials.erase(c.beyond.materials.begin());
    } else {
        auto it = std::find(c.beyond.materials.rbegin(), c.beyond.materials.rend(),
                            material);
        if (it != c.beyond.materials.rend())
            c.beyond.materials.erase(std::next(it).base());
        // leaving what it never entered: chapter 10's view
        else c.from = int(material);
    }
    c.to = mediumOf(scene, c.beyond);
    auto dispersionOf = [&](int k) {
        return k < 0 ? std::pair(Glass::None, 0.0)
                     : std::pair(scene.materials[k].glass, scene.materials[k].dispersion);
    };
    c.real = mediumIor(scene, c.from) != mediumIor(scene, c.to) ||
             mediumAbsorption(scene, c.from) != mediumAbsorption(scene, c.to) ||
             dispersionOf(c.from) != dispersionOf(c.to);
    const auto none = std::pair(Glass::None, 0.0);
    c.dispersive = dispersionOf(c.from) != none || dispersionOf(c.to) != none;
    return c;
}

int mediumOf(const Scene& scene, const MediumStack& media) {
    int best = -1, bestPriority = -1;
    for (size_t k = media.materials.size(); k-- > 0;) {
        int priority = scene.materials[media.materials[k]].priority;
        if (priority > bestPriority)
            best = int(media.materials[k]), bestPriority = priority;
    }
    return best;
}
double mediumIor(const Scene& scene, int medium) {
    return medium < 0 ? 1.0 : scene.materials[medium].ior;
}
glm::dvec3 mediumAbsorption(const Scene& scene, int medium) {
    return medium < 0 ? glm::dvec3(0) : scene.materials[medium].absorption;
}

// Snell's law in vector form: t = eta d + (eta cos_i - cos_t) n, n facing
// the ray; false under total internal reflection.
bool refractDirection(const glm::dvec3& d, const glm::dvec3& n, double n1, double n2,
                      glm::dvec3& t) {
    double eta = n1 / n2, cosI = -glm::dot(n, d);
    double k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0) return false;
    t = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& n) {
    return d - 2 * glm::dot(d, n) * n;
}

// Chapter 12's rules for a mesh's two normals (shaders/common/ray_tree.glsl):
// a direction found with the shading normal ns that lands on the wrong
// side of the flat triangle (normal n, facing the ray) is found with n.
glm::dvec3 reflectSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns) {
    glm::dvec3 r = reflectDirection(d, ns);
    return glm::dot(r, n) > 0 ? r : reflectDirection(d, n);
}
bool refractSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns,
                  double n1, double n2, glm::dvec3& t) {
    if (refractDirection(d, ns, n1, n2, t) && glm::dot(t, n) < 0) return true;
    return refractDirection(d, n, n1, n2, t);
}

// The normals of a hit facing the ray: geometric n, and the shading normal
// turned with it, or n where it faces away (raygen_common.glsl's facingShading).
void facingNormals(const ReferenceHit& hit, const glm::dvec3& direction, glm::dvec3& n,
                   glm::dvec3& ns) {
    bool front = glm::dot(hit.normal, direction) < 0;
    n = front ? hit.normal : -hit.normal;
    ns = front ? hit.shading : -hit.shading;
    if (glm::dot(ns, direction) >= 0) ns = n;
}
}  // namespace ref

using ref::kMaxNm, ref::kMinNm;  // the visible range: 380-780 nm

// [region path_wavelength]
double referencePathWavelength(uint32_t x, uint32_t y, uint32_t first, uint32_t k) {
    // PCG (Jarzynski and Olano 2020), as sampling.glsl's pcgHash
    auto hash = [](uint32_t v) {
        uint32_t state = v * 747796405u + 2891336453u;
        uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
        return (word >> 22u) ^ word;
    };
    uint32_t reversed = 0;  // k's bits mirrored: the radical inverse
    for (int b = 0; b < 32; ++b) reversed |= ((k >> b) & 1u) << (31 - b);
    uint32_t seed = hash(x + hash(y + hash(first)));
    double u = double(reversed >> 8) / 16777216.0 + double(seed >> 8) / 16777216.0;
    return kMinNm + (kMaxNm - kMinNm) * (u - std::floor(u));
}
// [end]

// [region spectral_weight]
glm::dvec3 referenceSpectralWeight(double nm) {
    auto lobe = [](double x, double peak, double below, double above) {
        double t = (x - peak) / (x < peak ? below : above);
        return std::exp(-0.5 * t * t);
    };
    // CIE XYZ (Wyman, Sloan and Shirley 2013), then XYZ to linear sRGB
    auto srgb = [&](double x) {
        glm::dvec3 xyz(
            1.056 * lobe(x, 599.8, 37.9, 31.0) + 0.362 * lobe(x, 442.0, 16.0, 26.7) -
                0.065 * lobe(x, 501.1, 20.4, 26.2),
            0.821 * lobe(x, 568.8, 46.9, 40.5) + 0.286 * lobe(x, 530.9, 16.3, 31.1),
            1.217 * lobe(x, 437.0, 11.8, 36.0) + 0.681 * lobe(x, 459.0, 26.0, 13.8));
        return glm::dvec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                          -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                          0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
    };
    static const glm::dvec3 mean = [&] {  // over the range, by a fine midpoint rule
        glm::dvec3 sum(0);
        const int steps = 40000;
        for (int k = 0; k < steps; ++k)
            sum += srgb(kMinNm + (kMaxNm - kMinNm) * (k + 0.5) / steps);
        return sum / double(steps);
    }();
    return srgb(nm) / mean;
}
// [end]

}  // namespace rg
