// The reference's shading (chapters 05-13): Blinn-Phong, the ray tree of
// reflection and refraction through media (the rules in ray_tree.h), and the
// render over all cores.
#include "reference/reference.h"
#include "reference/ray_tree.h"
#include "reference/photons.h"

#include "core/interrupt.h"

#include "core/display.h"
#include "core/progress.h"
#include "core/workers.h"
#include "reference/sampling.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cmath>
#include <random>

namespace rg {

namespace {
// 64 MiB: a bounce's frame of radiance() is about 1.3 KiB at -O3 and
// several times that in the sanitizer's build
constexpr size_t kStackBytes = size_t(64) << 20;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

using namespace ref;  // the ray tree's rules (ray_tree.h)

glm::dvec3 ReferenceRenderer::localShading(const ReferenceSettings& settings,
                                           const Material& m, const glm::dvec3& p,
                                           double error, const glm::dvec3& n,
                                           const glm::dvec3& ns, const glm::dvec3& v,
                                           double local, double highlight) const {
    glm::dvec3 color = local * m.ka * scene_.ambient;  // 3.1
    if (settings.stage == ReferenceStage::Ambient) return color;
    glm::dvec3 from = secondaryOrigin(p, error, n);
    for (const PointLight& light : scene_.lights) {  // 3.2 and 3.3
        glm::dvec3 l = glm::normalize(light.position - p);
        double ndotl = glm::dot(ns, l);
        if (ndotl <= 0) continue;
        glm::dvec3 added = local * light.intensity * m.kd * ndotl;
        if (settings.stage != ReferenceStage::Diffuse) {
            glm::dvec3 h = glm::normalize(l + v);
            added += highlight * light.intensity * m.ks *
                     std::pow(std::max(0.0, glm::dot(ns, h)), m.shininess);
            // As the GPU (shading.glsl's MIN_LIGHT): a light adding less than
            // 1e-4 is left out, as a branch carrying less is not traced.
            if (std::max({added.r, added.g, added.b}) < 1e-4) continue;
        }
        if (lightVisible(from, light.position)) color += added;
    }
    return color;
}

// [region reference_direct]
// Chapter 14: what the page's radiometry says, in double.
glm::dvec3 ReferenceRenderer::directLight(const ReferenceSettings& settings,
                                          const Material& m, const glm::dvec3& p,
                                          double error, const glm::dvec3& n,
                                          const glm::dvec3& ns, const glm::dvec3& v,
                                          double local, double highlight) const {
    glm::dvec3 color = local * m.ka * scene_.ambient;
    glm::dvec3 from = secondaryOrigin(p, error, n);
    for (const PointLight& light : scene_.lights) {
        bool sun = light.kind == PointLight::Kind::Directional;
        glm::dvec3 toLight = light.position - p;
        glm::dvec3 l = sun ? -light.direction : glm::normalize(toLight);
        double cosine = glm::dot(ns, l);
        if (cosine <= 0) continue;
        glm::dvec3 E =
            sun ? light.irradiance : light.intensity / glm::dot(toLight, toLight);
        glm::dvec3 h = glm::normalize(l + v);
        glm::dvec3 brdf = local * m.kd / kPi +
                          highlight * m.ks * (m.shininess + 8) / (8 * kPi) *
                              std::pow(std::max(0.0, glm::dot(ns, h)), m.shininess);
        glm::dvec3 added = brdf * E * cosine;
        if (std::max({added.r, added.g, added.b}) < 1e-4) continue;  // as MIN_LIGHT
        color += added * lightArriving(settings, light, from, l);
    }
    return color;
}
// [end]

// What of the light reaches `from` from direction l: 1 or 0 by a shadow
// ray, or with transmitted shadows what the glass on the way lets through.
glm::dvec3 ReferenceRenderer::lightArriving(const ReferenceSettings& settings,
                                            const PointLight& light,
                                            const glm::dvec3& from,
                                            const glm::dvec3& l) const {
    bool sun = light.kind == PointLight::Kind::Directional;
    if (settings.transmitShadows) {
        glm::dvec3 toLight = light.position - from;
        double d = glm::length(toLight);
        return sun ? transmittedLight(settings, from, l, 1e300)
                   : transmittedLight(settings, from, toLight / d, d * (1 - 1e-5));
    }
    bool visible = sun ? sunVisible(from, l) : lightVisible(from, light.position);
    return glm::dvec3(visible ? 1.0 : 0.0);
}

// Chapter 15: the lights' glints on a rough surface, the microfacet lobe
// toward each (reflection on the viewer's side, transmission behind, its
// shadow ray from the far side). The GPU traces one shadow ray per light
// for the glint and the local part together (rough_surface.glsl's
// roughLight); both rays would start at the same point, so the sum is
// the same.
glm::dvec3 ReferenceRenderer::roughGlints(const ReferenceSettings& settings,
                                          const Material& m, double alpha, double n1,
                                          double n2, const glm::dvec3& p, double error,
                                          const glm::dvec3& n, const glm::dvec3& ns,
                                          const glm::dvec3& v,
                                          const glm::dvec3& throughput) const {
    glm::dvec3 color(0);
    for (const PointLight& light : scene_.lights) {
        bool sun = light.kind == PointLight::Kind::Directional;
        glm::dvec3 toLight = light.position - p;
        glm::dvec3 l = sun ? -light.direction : glm::normalize(toLight);
        bool behind = glm::dot(l, n) < 0;
        if (behind != (glm::dot(l, ns) < 0)) continue;  // between the two normals
        glm::dvec3 E =
            sun ? light.irradiance : light.intensity / glm::dot(toLight, toLight);
        glm::dvec3 added = roughLobe(settings, m, alpha, n1, n2, ns, v, l) * E;
        glm::dvec3 seen = added * throughput;  // what it adds to the pixel
        if (std::max({seen.r, seen.g, seen.b}) < 1e-4) continue;  // as MIN_LIGHT
        glm::dvec3 from = secondaryOrigin(p, error, behind ? -n : n);
        color += added * lightArriving(settings, light, from, l);
    }
    return color;
}

glm::dvec3 ReferenceRenderer::transmittedLight(const ReferenceSettings& settings,
                                               glm::dvec3 from, const glm::dvec3& l,
                                               double tMax) const {
    glm::dvec3 kept(1);
    bool absorbed = false;  // the glass the ray is in has been accounted for
    for (int surfaces = 0; surfaces < kMaxPasses; ++surfaces) {
        ReferenceHit hit = trace(from, l, 0, tMax);
        if (hit.t < 0) return kept;
        const Material m = hitMaterial(hit);
        if (m.transmission <= 0) return glm::dvec3(0);
        // leaving glass the ray started in (a highlight's shadow ray from
        // inside a ball): absorbed from its start
        if (!hit.frontFace && !absorbed)
            for (int c = 0; c < 3; ++c) kept[c] *= std::exp(-m.absorption[c] * hit.t);
        absorbed = false;
        double cosine = std::abs(glm::dot(hit.normal, l));
        kept *= m.transmission * (1 - referenceFresnel(settings.fresnelMode, m.f0, cosine,
                                                       1.0, m.ior));
        // inside from here to the next surface: absorbed on the way there
        glm::dvec3 p = from + hit.t * l;
        from = secondaryOrigin(p, hit.error, glm::dot(hit.normal, l) < 0 ? -hit.normal
                                                                       : hit.normal);
        if (tMax < 1e300) tMax -= glm::length(from - (p - hit.t * l));
        if (hit.frontFace) {  // entering: Beer-Lambert to where it leaves
            ReferenceHit out = trace(from, l, 0, tMax);
            double inside = out.t < 0 ? tMax : out.t;
            for (int c = 0; c < 3; ++c) kept[c] *= std::exp(-m.absorption[c] * inside);
            absorbed = true;
        }
    }
    return kept;
}

bool ReferenceRenderer::sunVisible(const glm::dvec3& from, const glm::dvec3& l) const {
    return trace(from, l, 0, 1e300).t < 0;
}

glm::dvec3 ReferenceRenderer::radiance(const ReferenceSettings& settings,
                                       const glm::dvec3& origin,
                                       const glm::dvec3& direction, int depth,
                                       const glm::dvec3& throughput,
                                       const RayCone& cone) const {
    int passes = 0;
    return radiance(settings, origin, direction, depth, throughput, MediumStack{},
                    passes, cone);
}

glm::dvec3 ReferenceRenderer::radiance(const ReferenceSettings& settings,
                                       const glm::dvec3& origin,
                                       const glm::dvec3& direction, int depth,
                                       const glm::dvec3& throughput,
                                       const MediumStack& media, int& passes,
                                       const RayCone& cone,
                                       const BranchId& branch) const {
    // depth 0: a camera ray
    ReferenceHit hit = trace(origin, direction, depth == 0 ? eyeTmin() : 0.0, 1e300);
    textureAt(hit, direction, cone);
    // the deeper rays' cones start at the camera ray's hit (ray_tree.glsl)
    const RayCone deeper = depth == 0 ? RayCone{cone.spread, hit.t} : cone;
    bool nested = settings.stage >= ReferenceStage::Media;
    // Chapter 13: Beer-Lambert along the way, in the medium the ray is in.
    int here = nested ? mediumOf(scene_, media) : -1;  // -1: air
    glm::dvec3 kept(1), sigma = mediumAbsorption(scene_, here);
    for (int c = 0; c < 3; ++c)
        if (sigma[c] > 0) kept[c] = hit.t < 0 ? 0.0 : std::exp(-sigma[c] * hit.t);
    if (hit.t < 0) return kept * sky(direction);
    glm::dvec3 n, ns;  // toward the ray's origin: geometric, shading
    facingNormals(hit, direction, n, ns);
    if (settings.stage == ReferenceStage::Normals) return 0.5 * n + 0.5;
    const Material m = hitMaterial(hit);  // a mesh's texture tints it (chapter 12)
    glm::dvec3 p = origin + hit.t * direction;
    glm::dvec3 v = -direction;
    if (settings.stage <= ReferenceStage::Specular)
        return localShading(settings, m, p, hit.error, n, n, v);

    // How the light divides at this surface (chapters 08-10).
    bool entering = hit.frontFace;
    // air outside (chapter 10)
    double n1 = entering ? 1.0 : m.ior, n2 = entering ? m.ior : 1.0;
    // A thin wall (Material::thin): the same medium on both sides; Fresnel
    // from it into the material from either side, the light crossing unbent.
    bool thin = m.thin && settings.stage >= ReferenceStage::Refraction;
    if (thin) n1 = nested ? mediumIor(scene_, here) : 1.0, n2 = m.ior;
    const glm::dvec3 arriving = throughput * kept;
    MediumStack beyond = media;  // chapter 13: the media of a ray that crosses here
    if (nested && m.transmission > 0 && !thin) {
        Crossing crossing =
            crossingAt(scene_, media, scene_.objects[hit.object].material, entering);
        int from = crossing.from, to = crossing.to;
        beyond = crossing.beyond;
        n1 = mediumIor(scene_, from), n2 = mediumIor(scene_, to);
        if (!crossing.real) {  // no surface here
            if (passes++ >= kMaxPasses) return glm::dvec3(0);
            return kept * radiance(settings, secondaryOrigin(p, hit.error, -n), direction,
                                   depth, arriving, beyond, passes, cone, branch);
        }
        if (crossing.dispersive) {
            if (media.wavelength == 0) {
                // The first dispersive surface of this path: from here on its light
                // depends on the wavelength. The same ray again at each wavelength.
                MediumStack at = media;
                if (settings.wavelength >= kMinNm || !media.wavelengths) {
                    at.wavelength =
                        settings.wavelength >= kMinNm ? settings.wavelength : 587.5618;
                    return radiance(settings, origin, direction, depth, throughput, at,
                                    passes, cone, branch);
                }
                glm::dvec3 sum(0);
                for (double nm : *media.wavelengths) {
                    at.wavelength = nm;
                    glm::dvec3 w = referenceSpectralWeight(nm);
                    int passesAt = passes;
                    sum += w * radiance(settings, origin, direction, depth,
                                        throughput * w, at, passesAt, cone, branch);
                }
                return sum / double(media.wavelengths->size());
            }
            auto indexOf = [&](int k) {
                return k < 0 ? 1.0 : indexAt(scene_.materials[k], media.wavelength);
            };
            n1 = indexOf(from), n2 = indexOf(to);
        }
    }
    Split split = splitAt(settings, m, n1, n2, glm::dot(ns, v));
    double reflected = split.reflected, refracted = split.refracted;
    glm::dvec3 color(0);
    // Chapter 15: a rough surface's branches leave about one visible normal,
    // drawn at the GPU's sample point of this branch; its glints are the lobe's.
    double alpha = settings.stage >= ReferenceStage::Frosted && !thin
                       ? m.roughness * m.roughness
                       : 0.0;
    RoughBranches rough;
    if (alpha > 0) {
        rough = roughBranches(
            settings, m, alpha, split.n1, split.n2, n, ns, direction,
            branchSample(branch.seed, branch.accumulated, uint32_t(depth), branch.path));
        reflected = rough.reflectedShare, refracted = rough.refractedShare;
        color +=
            roughGlints(settings, m, alpha, split.n1, split.n2, p, hit.error, n, ns, v,
                        arriving);
        split.highlight = split.local;
    }
    if (settings.stage >= ReferenceStage::Caustics) {
        // chapter 14: direct light in watts, and the photons' caustic light
        if (split.highlight > 0)
            color += directLight(settings, m, p, hit.error, n, ns, v, split.local,
                                 split.highlight);
        if (split.local > 0 && photons_ && !settings.photonRadii.empty()) {
            // the mean of the frames' estimates
            color += split.local * m.kd / kPi * photons_->irradiance(p, n);
        }
    } else if (split.highlight > 0) {
        color += localShading(settings, m, p, hit.error, n, ns, v, split.local,
                              split.highlight);
    }
    // chapter 15: one child instead of two, u in [0,1): the refracted with
    // probability T / (R + T), carrying R + T (ray_tree.glsl's keepOneChild)
    auto keepOneChild = [&](double u) {
        bool refract = u * (reflected + refracted) < refracted;
        double share = reflected + refracted;
        refracted = refract ? share : 0.0;
        reflected = refract ? 0.0 : share;
    };
    if (settings.oneRoughBranch && alpha > 0 && depth > 0 && reflected > 0 &&
        refracted > 0) {
        // chapter 15's --rough-branches one, with roulette's point (the GPU's
        // oneBranch)
        keepOneChild(rouletteSample(branch.seed, branch.accumulated, uint32_t(depth),
                                    branch.path)
                         .x);
    }
    if (depth >= settings.maxDepth) {
        // chapter 15's --roulette: one child goes on, chosen by the shares
        // and kept by Russian roulette with the GPU's points
        if (depth >= settings.maxPathDepth || reflected + refracted <= 0)
            return kept * color;
        glm::dvec2 u = rouletteSample(branch.seed, branch.accumulated, uint32_t(depth),
                                      branch.path);
        glm::dvec3 carried = arriving * (reflected + refracted);
        double q = std::min(1.0, std::max({carried.r, carried.g, carried.b}));
        if (u.y >= q) return kept * color;
        keepOneChild(u.x);
        refracted /= q, reflected /= q;
    }
    constexpr double kMinThroughput = 1e-4;  // as the GPU's ray tree (chapter 10)
    auto strongEnough = [&](double w) {
        glm::dvec3 t = arriving * w;
        return settings.stage < ReferenceStage::Refraction ||
               std::max({t.r, t.g, t.b}) >= kMinThroughput;
    };
    glm::dvec3 t = direction;  // a thin wall's: unbent
    BranchId through = branch, back = branch;  // the children (chapter 15)
    through.path = childPath(branch.path, 1), back.path = childPath(branch.path, 0);
    if (refracted > 0 && strongEnough(refracted)) {
        bool crosses = true;
        if (alpha > 0) t = rough.refracted;
        else crosses = thin || refractSides(direction, n, ns, split.n1, split.n2, t);
        if (crosses)
            color +=
                refracted * radiance(settings, secondaryOrigin(p, hit.error, -n), t,
                                     depth + 1, arriving * refracted, beyond, passes,
                                     deeper, through);
        else
            reflected += refracted;  // a mesh's flat triangle reflects it all
    }
    if (reflected > 0 && strongEnough(reflected)) {
        glm::dvec3 r = alpha > 0 ? rough.reflected : reflectSides(direction, n, ns);
        color += reflected * radiance(settings, secondaryOrigin(p, hit.error, n), r,
                                      depth + 1, arriving * reflected, media, passes,
                                      deeper, back);
    }
    return kept * color;
}

// [region reference_footprint]
glm::dvec3 ReferenceRenderer::shade(const ReferenceSettings& settings, uint32_t x,
                                    uint32_t y, uint32_t width, uint32_t height,
                                    double* stdError) const {
    if (!settings.antialias)
        return shadeRay(settings, x, y, width, height, glm::dvec2(0.5), -1, stdError);
    // --antialias: the mean over the points of the pixel the GPU's frames
    // sampled (sampling.glsl's, compiled as C++), one camera ray each.
    uint32_t frames = std::max(1u, settings.frames);
    glm::dvec3 sum(0);
    double errorSq = 0;
    for (uint32_t k = 0; k < frames; ++k) {
        glm::dvec2 offset(shader::pixelJitter(shader::uvec2(x, y), k));
        double e = 0;
        sum += shadeRay(settings, x, y, width, height, offset, int(k), &e);
        errorSq += e * e;
    }
    // of a mean of independent estimates
    if (stdError) *stdError = std::sqrt(errorSq) / frames;
    return sum / double(frames);
}
// [end]

glm::dvec3 ReferenceRenderer::shadeRay(const ReferenceSettings& settings, uint32_t x,
                                       uint32_t y, uint32_t width, uint32_t height,
                                       glm::dvec2 offset, int frame,
                                       double* stdError) const {
    glm::dvec3 origin, direction;
    cameraRay(x, y, width, height, origin, direction, offset);
    if (stdError) *stdError = 0;
    const RayCone camera{pixelSpread(height), 0};  // chapter 12's ray cones
    // chapter 13: the eye may be inside a medium
    if (settings.stage >= ReferenceStage::Media) {
        MediumStack eye;
        if (scene_.cameraMedium >= 0)
            eye.materials.push_back(uint32_t(scene_.cameraMedium));
        // the GPU's, frame after frame (one frame's: that frame's)
        std::vector<uint32_t> frames;
        std::vector<double> wavelengths;
        for (uint32_t k = 0; k < std::max(1u, settings.frames); ++k)
            if (frame < 0 || int(k) == frame) {
                frames.push_back(k);
                wavelengths.push_back(
                    referencePathWavelength(x, y, settings.firstFrame, k));
            }
        int passes = 0;
        if (settings.stage < ReferenceStage::Frosted) {
            eye.wavelengths = &wavelengths;
            return radiance(settings, origin, direction, 0, glm::dvec3(1.0), eye, passes,
                            camera);
        }
        // Chapter 15: every frame's tree has its own rough branches: the mean
        // of the frames' trees, each with its frame's wavelength.
        glm::dvec3 sum(0);
        for (size_t i = 0; i < frames.size(); ++i) {
            std::vector<double> one{wavelengths[i]};
            eye.wavelengths = &one;
            BranchId branch{
                .seed = shader::pixelSeed(shader::uvec2(x, y), kFacetStream),
                .accumulated = frames[i]};
            passes = 0;
            sum += radiance(settings, origin, direction, 0, glm::dvec3(1.0), eye, passes,
                            camera, branch);
        }
        return sum / double(frames.size());
    }
    if (settings.stage != ReferenceStage::Rough)
        return radiance(settings, origin, direction, 0, glm::dvec3(1.0), camera);

    // Chapter 11: the first surface's mirror branch becomes the mean over a
    // cone of directions. Same split and cone as the GPU; the integral is
    // estimated with many stratified samples from this code's own generator.
    ReferenceHit hit = trace(origin, direction, eyeTmin(), 1e300);
    if (hit.t < 0) return sky(direction);
    textureAt(hit, direction, camera);
    const RayCone deeper{camera.spread, hit.t};
    const Material m = hitMaterial(hit);  // a mesh's texture tints it (chapter 12)
    glm::dvec3 n, ns;
    facingNormals(hit, direction, n, ns);
    if (m.roughness <= 0 || settings.maxDepth == 0)
        return radiance(settings, origin, direction, 0, glm::dvec3(1.0), camera);
    glm::dvec3 p = origin + hit.t * direction, v = -direction;
    bool entering = hit.frontFace;
    Split split = splitAt(settings, m, entering, glm::dot(ns, v));
    double reflected = split.reflected, refracted = split.refracted;
    glm::dvec3 color(0);
    if (split.highlight > 0)
        color += localShading(settings, m, p, hit.error, n, ns, v, split.local,
                              split.highlight);
    if (refracted >= 1e-4) {
        glm::dvec3 t = direction;  // a thin wall's: unbent
        if (m.thin || refractSides(direction, n, ns, split.n1, split.n2, t))
            color += refracted * radiance(settings, secondaryOrigin(p, hit.error, -n), t,
                                          1, glm::dvec3(refracted), deeper);
        else
            reflected += refracted;
    }
    if (reflected < 1e-4) return color;
    glm::dvec3 mirror = reflectSides(direction, n, ns);
    // A basis around the mirror direction, and the cone of half-angle roughness * pi/2.
    glm::dvec3 helper =
        std::abs(mirror.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 t1 = glm::normalize(glm::cross(helper, mirror)),
               t2 = glm::cross(mirror, t1);
    double cosMax = std::cos(m.roughness * kPi / 2);
    int side = std::max(1, int(std::lround(std::sqrt(double(settings.samples)))));
    std::mt19937_64 rng(0x9E3779B97F4A7C15ull ^ (uint64_t(y) << 32 | x) ^
                        (settings.seed * 0xD1B54A32D192ED03ull) ^
                        // each antialiased ray its own
                        (uint64_t(frame + 1) * 0x8CB92BA72F3D8DD7ull));
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    glm::dvec3 from = secondaryOrigin(p, hit.error, n), sum(0), sumSq(0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            double u1 = (i + uniform(rng)) / side, u2 = (j + uniform(rng)) / side;
            double cosTheta = 1 - u1 * (1 - cosMax),
                   sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
            glm::dvec3 d = glm::normalize(sinTheta * std::cos(2 * kPi * u2) * t1 +
                                          sinTheta * std::sin(2 * kPi * u2) * t2 +
                                          cosTheta * mirror);
            glm::dvec3 value(0);  // below the surface: absorbed
            if (glm::dot(d, n) > 0)
                value = radiance(settings, from, d, 1, glm::dvec3(reflected), deeper);
            sum += value;
            sumSq += value * value;
        }
    double count = double(side) * side;
    glm::dvec3 mean = sum / count,
               variance = (sumSq / count - mean * mean) * (count / (count - 1));
    if (stdError)  // of independent samples: stratification makes the true error smaller
        *stdError =
            reflected *
            std::sqrt(std::max(0.0, (variance.r + variance.g + variance.b) / 3) / count);
    return color + reflected * mean;
}

FloatImage ReferenceRenderer::render(const ReferenceSettings& settings, uint32_t width,
                                     uint32_t height) const {
    FloatImage image{width, height, std::vector<float>(size_t(width) * height * 4, 1.0f)};
    // chapter 14: the photons first, once
    if (settings.stage >= ReferenceStage::Caustics && !settings.photonRadii.empty() &&
        !photons_)
        photons_ = std::make_shared<ReferencePhotons>(*this, settings);
    unsigned threads = workerCount();
    std::atomic<uint32_t> rowsDone{0};
    Progress progress("CPU reference", height);  // on a terminal only
    // a path recurses once a bounce, up to ROULETTE_MAX_DEPTH (chapter 15)
    runWorkers(threads, kStackBytes, [&](unsigned t) {
        for (uint32_t y = t; y < height; y += threads, ++rowsDone)
            // Ctrl-C: the rest stays unset
            for (uint32_t x = 0; x < width && !interrupted(); ++x) {
                double stdError = 0;
                glm::dvec3 c = shade(settings, x, y, width, height, &stdError) *
                               settings.exposure;
                float* p = &image.rgba[4 * (size_t(y) * width + x)];
                p[0] = float(c.r), p[1] = float(c.g), p[2] = float(c.b);
                if (settings.stage == ReferenceStage::Rough)
                    p[3] = float(stdError * settings.exposure);
            }
    }, [&] { progress.update(rowsDone.load()); });
    return image;
}

}  // namespace rg
