// Chapter 14's photon map in double, for the reference: no random numbers.
// From each (light, glass or mirror) pair a stratified grid of photons over
// the cone (a point light) or the beam (a sun) that covers the object's
// bounding sphere, each weighted by the balance heuristic over the pairs of
// its light, as the GPU; but where the GPU's photon picks one branch by
// Russian roulette, this one follows every branch with its Fresnel share,
// and a dispersive surface splits it into 32 wavelengths. Photons are stored
// on diffuse surfaces after a mirror or glass (written from
// docs/14_caustics.md, not from photon_trace.glsl). Chapter 15: at a rough
// surface both branches leave about one facet drawn from the photon's key.
#pragma once
#include "reference/reference.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rg {

class ReferencePhotons {
public:
    ReferencePhotons(const ReferenceRenderer& renderer,
                     const ReferenceSettings& settings);
    // The irradiance the photons bring to p (normal n, facing the side they
    // must have come from) within a radius r: their power over pi r^2; the
    // mean of that over the frames' radii (settings.photonRadii), in one pass.
    glm::dvec3 irradiance(const glm::dvec3& p, const glm::dvec3& n) const;
    size_t size() const { return photons_.size(); }

private:
    // empty: one thread's part
    explicit ReferencePhotons(const ReferenceRenderer& renderer);
    struct Photon {
        glm::dvec3 position, normal, power;
    };
    void trace(const ReferenceSettings& settings, glm::dvec3 origin, glm::dvec3 direction,
               glm::dvec3 power, const MediumStack& media, bool specular, int bounces,
               int passes, uint32_t key);
    int64_t key(const glm::ivec3& cell) const;

    const ReferenceRenderer& renderer_;
    std::vector<Photon> photons_;
    double cell_ = 1;  // the grid's cell: the largest radius gathered
    // the radii, ascending, and for each the mean over it and the larger
    // ones of 1 / (pi r^2) / count: what a photon at distance d < r adds
    std::vector<double> radii_, weightFrom_;
    std::unordered_map<int64_t, std::vector<uint32_t>> grid_;
};

}  // namespace rg
