#include "reference/photons.h"

#include "reference/ray_tree.h"
#include "reference/sampling.h"
#include "core/workers.h"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace rg {

using namespace ref;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr int kPhotonBounces = 16;  // as the GPU's PHOTON_BOUNCES
constexpr int kWavelengths = 32;    // a dispersive surface splits a photon into these

struct Sphere {
    glm::dvec3 centre;
    double radius = 0;
};

// A sphere around an object in world space.
Sphere bounds(const Scene& scene, const Object& o) {
    glm::dvec3 c(o.transform[3]);
    double r = 0;
    if (o.type == ShapeType::Sphere) {
        r = largestStretch(o.transform);
    } else if (o.type == ShapeType::Quad) {
        r = glm::length(glm::dvec3(o.transform[0]) + glm::dvec3(o.transform[2]));
    } else {
        for (const glm::vec3& v : scene.meshes[o.mesh]->vertices)
            r = std::max(r, glm::length(glm::dvec3(o.transform * glm::dvec4(v, 1)) - c));
    }
    return {c, r * (1 + 1e-6)};
}

// Two unit vectors perpendicular to w and to each other.
void basis(const glm::dvec3& w, glm::dvec3& t, glm::dvec3& b) {
    glm::dvec3 helper = std::abs(w.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(glm::cross(helper, w));
    b = glm::cross(w, t);
}
}  // namespace

ReferencePhotons::ReferencePhotons(const ReferenceRenderer& renderer,
                                   const ReferenceSettings& settings)
    : renderer_(renderer) {
    const Scene& scene = renderer.scene();
    std::vector<Sphere> targets, all;
    for (const Object& o : scene.objects) {
        if (o.hidden) continue;
        all.push_back(bounds(scene, o));
        const Material& m = scene.materials[o.material];
        if (m.transmission > 0 || m.reflectivity > 0) targets.push_back(all.back());
    }
    if (targets.size() > 64) {  // many small glasses: one sphere around them
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const Sphere& t : targets)
            lo = glm::min(lo, t.centre - t.radius),
            hi = glm::max(hi, t.centre + t.radius);
        targets = {{(lo + hi) * 0.5, glm::length(hi - lo) * 0.5}};
    }
    const int side = std::max(1, settings.photonGrid);
    const double perTarget = double(side) * side;
    std::mutex lock;
    for (const PointLight& light : scene.lights) {
        bool sun = light.kind == PointLight::Kind::Directional;
        // Each target gets side^2 photons; a photon's weight is the light over
        // the sum of every target's density at what was drawn (balance heuristic).
        auto cosMaxOf = [&](const Sphere& t) {
            double d = glm::length(t.centre - light.position);
            return d > t.radius ? std::sqrt(1 - (t.radius / d) * (t.radius / d)) : -1.0;
        };
        auto density = [&](const glm::dvec3& x, const glm::dvec3& d) {
            double sum = 0;
            for (const Sphere& t : targets) {
                if (sun) {
                    glm::dvec3 off = x - t.centre;
                    off -= light.direction * glm::dot(off, light.direction);
                    if (glm::dot(off, off) < t.radius * t.radius)
                        sum += perTarget / (kPi * t.radius * t.radius);
                } else {
                    double cosMax = cosMaxOf(t);
                    if (glm::dot(d, glm::normalize(t.centre - light.position)) >= cosMax)
                        sum += perTarget / (2 * kPi * (1 - cosMax));
                }
            }
            return sum;
        };
        for (const Sphere& t : targets) {
            double backoff = t.radius;  // a sun's photons start beyond everything
            for (const Sphere& o : all)
                backoff = std::max(
                    backoff, glm::dot(o.centre - t.centre, -light.direction) + o.radius);
            backoff = std::min(backoff, 1000 * t.radius);
            unsigned threads = workerCount();
            runWorkers(threads, size_t(8) << 20, [&](unsigned w) {  // short paths
                ReferencePhotons part(renderer_);
                for (int j = int(w); j < side; j += int(threads))
                    for (int i = 0; i < side; ++i) {
                        double u = (i + 0.5) / side, v = (j + 0.5) / side;
                        glm::dvec3 origin, direction, tangent, bitangent, power;
                        if (sun) {
                            direction = light.direction;
                            basis(direction, tangent, bitangent);
                            double r = t.radius * std::sqrt(u), phi = 2 * kPi * v;
                            glm::dvec3 x = t.centre + r * (std::cos(phi) * tangent +
                                                           std::sin(phi) * bitangent);
                            power = light.irradiance / density(x, direction);
                            origin = x - direction * backoff;
                        } else {
                            glm::dvec3 axis =
                                glm::normalize(t.centre - light.position);
                            double cosine = 1 - u * (1 - cosMaxOf(t));
                            double sine =
                                std::sqrt(std::max(0.0, 1 - cosine * cosine));
                            basis(axis, tangent, bitangent);
                            direction = glm::normalize(
                                cosine * axis +
                                sine * (std::cos(2 * kPi * v) * tangent +
                                        std::sin(2 * kPi * v) * bitangent));
                            power =
                                light.intensity / density(light.position, direction);
                            origin = light.position;
                        }
                        // its own facets at rough hits (chapter 15)
                        uint32_t key = shader::pcgHash(uint32_t(j * side + i) ^
                                                       shader::pcgHash(uint32_t(
                                                           &t - targets.data())));
                        part.trace(settings, origin, direction, power, MediumStack{},
                                   false, 0, 0, key);
                    }
                std::lock_guard<std::mutex> guard(lock);
                photons_.insert(photons_.end(), part.photons_.begin(),
                                part.photons_.end());
            });
        }
    }
    // Photons on a grid of cells as wide as the largest radius: a gather
    // reads the 27 cells around its point.
    radii_ = settings.photonRadii;
    std::sort(radii_.begin(), radii_.end());
    weightFrom_.assign(radii_.size() + 1, 0.0);
    for (size_t i = radii_.size(); i-- > 0;)
        weightFrom_[i] = weightFrom_[i + 1] +
                         1 / (kPi * radii_[i] * radii_[i]) / double(radii_.size());
    cell_ = radii_.empty() ? 1.0 : radii_.back();
    for (uint32_t i = 0; i < photons_.size(); ++i)
        grid_[key(glm::ivec3(glm::floor(photons_[i].position / cell_)))].push_back(i);
}

ReferencePhotons::ReferencePhotons(const ReferenceRenderer& renderer)
    : renderer_(renderer) {}

int64_t ReferencePhotons::key(const glm::ivec3& c) const {
    return (int64_t(c.x) & 0x1FFFFF) | ((int64_t(c.y) & 0x1FFFFF) << 21) |
           ((int64_t(c.z) & 0x1FFFFF) << 42);
}

// [region reference_photon]
// One photon, following every branch: its power times each share.
void ReferencePhotons::trace(const ReferenceSettings& settings, glm::dvec3 origin,
                             glm::dvec3 direction, glm::dvec3 power,
                             const MediumStack& media, bool specular, int bounces,
                             int passes, uint32_t key) {
    if (std::max({std::abs(power.r), std::abs(power.g), std::abs(power.b)}) < 1e-14)
        return;
    const Scene& scene = renderer_.scene();
    ReferenceHit hit = renderer_.trace(origin, direction, 0, 1e300);
    if (hit.t < 0) return;  // escaped
    renderer_.textureAt(hit, direction, RayCone{});
    const glm::dvec3 sent = power;  // before this segment's absorption
    glm::dvec3 sigma = mediumAbsorption(scene, mediumOf(scene, media));
    for (int c = 0; c < 3; ++c) power[c] *= std::exp(-sigma[c] * hit.t);  // Beer-Lambert
    const Material m = renderer_.hitMaterial(hit);
    glm::dvec3 n, ns;
    facingNormals(hit, direction, n, ns);
    glm::dvec3 p = origin + hit.t * direction;
    bool entering = hit.frontFace, thin = m.thin;
    double n1 = entering ? 1.0 : m.ior, n2 = entering ? m.ior : 1.0;
    if (thin) n1 = mediumIor(scene, mediumOf(scene, media)), n2 = m.ior;
    MediumStack beyond = media;
    if (m.transmission > 0 && !thin) {
        Crossing c =
            crossingAt(scene, media, scene.objects[hit.object].material, entering);
        if (!c.real) {  // no surface: on into the new media
            // still glass to the shadow rays: what passes is the photons' light
            if (passes < kMaxPasses)
                trace(settings, renderer_.secondaryOrigin(p, hit.error, -n), direction,
                      power, c.beyond, true, bounces, passes + 1, key);
            return;
        }
        n1 = mediumIor(scene, c.from), n2 = mediumIor(scene, c.to), beyond = c.beyond;
        if (c.dispersive) {
            if (media.wavelength == 0) {  // from here on one wavelength each
                MediumStack at = media;
                if (settings.wavelength >= kMinNm) {
                    at.wavelength = settings.wavelength;
                    trace(settings, origin, direction, sent, at, specular, bounces,
                          passes, key);
                    return;
                }
                for (int k = 0; k < kWavelengths; ++k) {
                    at.wavelength = kMinNm + (k + 0.5) * (kMaxNm - kMinNm) / kWavelengths;
                    trace(settings, origin, direction,
                          sent * referenceSpectralWeight(at.wavelength) /
                              double(kWavelengths),
                          at, specular, bounces, passes,
                          shader::pcgHash(key + uint32_t(k)));
                }
                return;
            }
            auto index = [&](int k) {
                return k < 0 ? 1.0 : indexAt(scene.materials[k], media.wavelength);
            };
            n1 = index(c.from), n2 = index(c.to);
        }
    }
    Split split = splitAt(settings, m, n1, n2, glm::dot(ns, -direction));
    // a diffuse surface after a mirror or glass: stored whole
    if (specular && split.local > 0 && std::max({m.kd.r, m.kd.g, m.kd.b}) > 0)
        photons_.push_back({p, n, power});
    if (bounces >= kPhotonBounces) return;
    double reflected = split.reflected, refracted = split.refracted;
    // Chapter 15: at a rough surface both branches leave about one facet,
    // drawn from the photon's own hash (the grid's many photons average
    // the facets; the GPU's photons draw theirs by chance).
    double alpha = settings.stage >= ReferenceStage::Frosted && !thin
                       ? m.roughness * m.roughness
                       : 0.0;
    RoughBranches rough;
    if (alpha > 0) {
        uint32_t a = shader::pcgHash(key), b = shader::pcgHash(a);
        rough = roughBranches(settings, m, alpha, split.n1, split.n2, n, ns, direction,
                              glm::dvec2(shader::toUnit(a), shader::toUnit(b)));
        reflected = rough.reflectedShare, refracted = rough.refractedShare;
    }
    if (refracted > 0) {
        glm::dvec3 t = direction;  // a thin wall's: unbent
        bool crosses = true;
        if (alpha > 0) t = rough.refracted;
        else crosses = thin || refractSides(direction, n, ns, split.n1, split.n2, t);
        if (crosses)
            trace(settings, renderer_.secondaryOrigin(p, hit.error, -n), t,
                  power * refracted, beyond, true, bounces + 1, passes,
                  shader::pcgHash(key ^ 0x5bd1e995u));
        else
            reflected += refracted;
    }
    if (reflected > 0)
        trace(settings, renderer_.secondaryOrigin(p, hit.error, n),
              alpha > 0 ? rough.reflected : reflectSides(direction, n, ns),
              power * reflected, media, true, bounces + 1, passes,
              shader::pcgHash(key ^ 0x27d4eb2fu));
}
// [end]

glm::dvec3 ReferencePhotons::irradiance(const glm::dvec3& p, const glm::dvec3& n) const {
    if (radii_.empty()) return glm::dvec3(0);
    glm::ivec3 centre(glm::floor(p / cell_));
    const double largest = radii_.back();
    glm::dvec3 sum(0);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                auto it = grid_.find(key(centre + glm::ivec3(dx, dy, dz)));
                if (it == grid_.end()) continue;
                for (uint32_t i : it->second) {
                    const Photon& photon = photons_[i];
                    glm::dvec3 d = photon.position - p;
                    double d2 = glm::dot(d, d);
                    if (d2 >= largest * largest || glm::dot(photon.normal, n) <= 0)
                        continue;
                    // the radii this photon lies within: the first above d, and on
                    size_t first =
                        std::upper_bound(radii_.begin(), radii_.end(), std::sqrt(d2)) -
                        radii_.begin();
                    sum += photon.power * weightFrom_[first];
                }
            }
    return sum;
}

}  // namespace rg
