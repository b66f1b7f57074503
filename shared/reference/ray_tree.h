// The rules the reference's ray tree follows at each hit (inside reference/
// only; media.cpp defines them, shading.cpp follows them), written again in
// double from the pages' rules, not from the GPU's shaders.
#pragma once
#include "host_device.h"
#include "reference/reference.h"

#include <glm/glm.hpp>

#include <cstddef>

namespace rg::ref {

constexpr size_t kMediaDepth = 4;  // as the GPU's MEDIA_DEPTH
constexpr double kMinNm = 380, kMaxNm = 780;
constexpr int kMaxPasses = 256;    // as the GPU's MAX_PASSES

// How light divides where a ray meets material m (chapters 08-11), and the
// indices on both sides; n faces the ray.
struct Split {
    double reflected = 0, refracted = 0, local = 1, n1 = 1, n2 = 1;
    // the highlight's share: the opaque part's and a dielectric's F
    double highlight = 1;
};

Split splitAt(const ReferenceSettings& settings, const Material& m, double n1, double n2,
              double cosI);
// Chapters 08-12: air outside every material.
Split splitAt(const ReferenceSettings& settings, const Material& m, bool entering,
              double cosI);

// Chapter 13: the medium at a place (-1: air), its index and its absorption.
int mediumOf(const Scene& scene, const MediumStack& media);
double mediumIor(const Scene& scene, int medium);
glm::dvec3 mediumAbsorption(const Scene& scene, int medium);

// Chapter 13: what a ray inside `media` meets where it enters or leaves
// `material`: the media on the two sides (-1: air) and the stack beyond.
// real = false where nothing changes there (no surface at all).
struct Crossing {
    int from = -1, to = -1;
    MediumStack beyond;
    bool real = true;
    bool dispersive = false;  // either side's index depends on the wavelength
};
Crossing crossingAt(const Scene& scene, const MediumStack& media, uint32_t material,
                    bool entering);

// Snell's law in vector form; false under total internal reflection.
bool refractDirection(const glm::dvec3& d, const glm::dvec3& n, double n1, double n2,
                      glm::dvec3& t);
glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& n);
// Chapter 12: with a mesh's two normals (geometric n, shading ns).
glm::dvec3 reflectSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns);
bool refractSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns,
                  double n1, double n2, glm::dvec3& t);
// Chapter 15 (microfacet.cpp): a rough surface's two branches about one
// visible normal, drawn with the GPU's sample point u of the branch.
struct RoughBranches {
    glm::dvec3 reflected{0}, refracted{0};
    double reflectedShare = 0, refractedShare = 0;
};
RoughBranches roughBranches(const ReferenceSettings& settings, const Material& m,
                            double alpha, double n1, double n2, const glm::dvec3& n,
                            const glm::dvec3& ns, const glm::dvec3& direction,
                            glm::dvec2 u);
// The microfacet lobe toward a light in direction l (BSDF times |cos|), v
// toward the viewer; l behind the surface: the transmission.
double roughLobe(const ReferenceSettings& settings, const Material& m, double alpha,
                 double n1, double n2, const glm::dvec3& ns, const glm::dvec3& v,
                 const glm::dvec3& l);
// Branch `path` at `depth`'s sample point in frame `accumulated` of the
// pixel's average (seed: the pixel's, ray_tree.glsl's branchSample).
glm::dvec2 branchSample(uint32_t seed, uint32_t accumulated, uint32_t depth,
                        uint32_t path);
// Past the depth limit (--roulette): the GPU's point for the branch's
// choice of child and its survival (ray_tree.glsl's roulette).
glm::dvec2 rouletteSample(uint32_t seed, uint32_t accumulated, uint32_t depth,
                          uint32_t path);
// the stream of the pixel's seed for its facets (FACET_STREAM)
constexpr uint32_t kFacetStream = 0xFACE75EDu;
inline uint32_t childPath(uint32_t path, uint32_t refracted) {
    return ((path << 1) | (refracted << BRANCH_PATH_SHIFT)) & BRANCH_PATH_MASK;
}

// The normals of a hit facing the ray.
void facingNormals(const ReferenceHit& hit, const glm::dvec3& direction, glm::dvec3& n,
                   glm::dvec3& ns);

}  // namespace rg::ref
