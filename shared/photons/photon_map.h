// Chapter 14's photon map (page 14 teaches it): the settings of the photon
// pass, the photons' emitters (a projection map over the glasses and
// mirrors), the map's buffers and pipelines, one frame's map recorded
// (trace, then a hash grid by three compute shaders), the shrinking radius,
// and the last frame's photons read back. photon_pass.h hooks it into a
// chapter's frames.
#pragma once
#include "chapter/rt_chapter.h"
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "vulkan/resources.h"

#include <string>
#include <vector>

namespace rg {

struct PhotonSettings {
    // off: glass casts chapter 13's black shadow; transmit: shadow rays pass
    // glass unbent (transmit.glsl), what real-time engines do
    enum { kOff, kPhotons, kTransmit };
    int caustics = kPhotons;
    int photons = 100000;     // traced from the lights each frame
    float radius = 0;  // the first frame's gathering radius; 0: from the glasses' size
    // Knaus and Zwicker's alpha: each frame the radius^2 shrinks by
    // (i + alpha) / (i + 1); 1 keeps it fixed (biased, never converges)
    float alpha = 2.0f / 3.0f;
    std::string ply;       // --photons-ply: the last frame's photons, written here
    // --reference-photons: the CPU reference's photons from each light and
    // glass, a stratified grid this many a side
    int referenceGrid = 1000;
    // --photon-seed: another set of photons (independent runs, for studies)
    int seed = 0;
    // --gather-cap: photons read of one cell at most (0: all; the
    // performance page measures it)
    int gatherCap = 0;
    // --gather-defer: a cell with more photons than this is gathered by a
    // compute pass after the camera rays (0: every cell in place)
    int gatherDefer = 64;
    float lastRadius = 0;  // the last frame's radius (the report)
    bool kept = false;     // the last frame reused the map before it (the overlay)
};

std::vector<gpu::PhotonEmitter> photonEmitters(const Scene& scene);

// The photon map's buffers: each frame's photons in the order they were
// stored, the same sorted by grid cell, the grid's cells, the emitters, and
// a header that holds their device addresses (PhotonMapHeader).
struct PhotonMap {
    Buffer header, photons, sorted, cells, emitters;
    Buffer requests, heads;  // --gather-defer's requests, each pixel's last one
    uint32_t capacity = 0, cellCount = 0, emitterCount = 0, deferCapacity = 0;
    RtPipeline tracer;  // the photons' ray generation shader with the scene's hit groups
    uint32_t traced = 0;  // maps traced in this run (the report)
    float radius = 0;     // the radius of the map traced last (0: none yet)
    VkPipelineLayout gridLayout = VK_NULL_HANDLE;
    // count, prefix sum (three steps), scatter
    VkPipeline count = VK_NULL_HANDLE, scan = VK_NULL_HANDLE, scanBlocks = VK_NULL_HANDLE,
               scanAdd = VK_NULL_HANDLE, scatter = VK_NULL_HANDLE;
    // --gather-defer: the crowded cells' gathers, then each pixel's sum
    VkPipeline deferred = VK_NULL_HANDLE, resolve = VK_NULL_HANDLE;
};
// `photonShader`: the photons' ray generation shader ("14_caustics/photon.rgen").
PhotonMap createPhotonMap(const FramePassContext& c, const PhotonSettings& settings,
                          const std::string& photonShader);
float frameRadius(const PhotonSettings& s, uint32_t accumulated);
void pointAtPhotonMap(gpu::RtPush& push, const PhotonMap& map, uint32_t photons,
                      float radius);
void recordPhotonMap(VkCommandBuffer cmd, const PhotonMap& map, const RtScene& rt,
                     gpu::RtPush& push, uint32_t photons, float radius);
// --gather-defer: before the camera rays, no requests yet; after them, the
// requests gathered and their light added to the picture (`resolveScale`:
// the exposure over the frames averaged, as the camera rays write it).
void recordDeferReset(VkCommandBuffer cmd, const PhotonMap& map);
void recordDeferredGathers(VkCommandBuffer cmd, const PhotonMap& map, const RtScene& rt,
                           float radius, float resolveScale);

// The last frame's photon map's counts, and with `withPhotons` its stored
// photons too (--photons-ply), copied to the host (waits for the GPU).
struct LastPhotons {
    gpu::PhotonMapHeader header{};  // its counts
    std::vector<gpu::Photon> stored;
};
LastPhotons readPhotons(const Gpu& gpu, DeletionQueue& deletion, const PhotonMap& map,
                        bool withPhotons);
void writePhotonsPly(const std::string& path, const std::vector<gpu::Photon>& photons,
                     const glm::dvec3& origin);

}  // namespace rg
