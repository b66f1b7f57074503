// Chapter 14's photon pass (photon_pass.h).
#include "photons/photon_pass.h"

#include "app/app.h"
#include "core/params.h"
#include "photons/photon_map.h"
#include "raytracing/rt_scene.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace rg {

namespace {

// [region options]
// The photon pass's parameters: command-line options and overlay controls.
void declarePhotonOptions(Params& params, PhotonSettings& photons) {
    params
        .choice("--caustics", photons.caustics,
                "Light through glass: none (black shadows, as chapter 13), photons, or "
                "shadow rays that pass glass unbent (transmit)",
                {"off", "photons", "transmit"})
        .live = false;  // transmit's shaders are chosen when the pipeline is made
    params
        .integer("--photons", photons.photons,
                 "Photons traced from the lights each frame", 1000, 4000000)
        .live = false;  // the map's buffers are sized for them
    params.number("--radius", photons.radius,
                  "First frame's gathering radius (0: the largest glass's bounding "
                  "radius / 20 at 100,000 photons, smaller as the square root of more)",
                  0, 1e6);
    params.number("--alpha", photons.alpha,
                  "How slowly the radius shrinks (Knaus-Zwicker; 1: fixed)", 0.05, 1);
    params
        .integer("--reference-photons", photons.referenceGrid,
                 "The CPU reference's photons from each light and glass: a grid this "
                 "many a side, each split at every surface",
                 16, 4000)
        .live = false;
    params
        .integer("--photon-seed", photons.seed,
                 "Draw another set of photons (an independent estimate)", 0, 1000000)
        .live = false;
    params.integer("--gather-cap", photons.gatherCap,
                   "Photons a gather reads of one cell at most, a random run of them "
                   "weighted up (0: all; a performance trick, see the performance page)",
                   0, 1 << 30);
    params.integer("--gather-defer", photons.gatherDefer,
                   "A cell with more photons than this is gathered after the camera rays "
                   "by 64 invocations at once (0: in place; a performance trick, see the "
                   "performance page)",
                   0, 1 << 30);
    params
        .text("--photons-ply", photons.ply,
              "Write the last frame's photons to this PLY point cloud (power in "
              "watts, and as a colour)")
        .live = false;
}
// [end]

// [region transmit_shaders]
// --caustics transmit: the shadow hit groups get any-hit shaders that pass
// glass (transmit.glsl), and the shadow rays their own miss shader.
void adaptShaders(const PhotonSettings& photons, RtShaders& shaders) {
    if (photons.caustics != PhotonSettings::kTransmit) return;
    shaders.miss.emplace_back("14_caustics/transmit.rmiss");  // MISS_TRANSMIT
    shaders.hitGroups.at(RAY_TYPE_SHADOW + HIT_GROUP_QUAD).anyHit =
        "14_caustics/transmit_triangle.rahit";
    shaders.hitGroups.at(RAY_TYPE_SHADOW + HIT_GROUP_MESH).anyHit =
        "14_caustics/transmit_triangle.rahit";
    shaders.hitGroups.at(RAY_TYPE_SHADOW + HIT_GROUP_SPHERE).anyHit =
        "14_caustics/transmit_sphere.rahit";
}
// [end]

// [region pass]
// The photon pass, made once the scene is on the GPU: each frame records
// the photon map before the camera rays (rt_chapter.cpp).
FramePass photonPass(const FramePassContext& c, PhotonSettings& photons,
                     const std::string& photonShader) {
    if (photons.radius <= 0) {  // a twentieth of the largest glass
        float largest = 0;
        for (const gpu::PhotonEmitter& e : photonEmitters(c.scene))
            largest = std::max(largest, e.target.w);
        // More photons, a smaller disc: a disc of the caustic holds about as
        // many photons at any count, so the gather costs about the same
        // (the performance page: 10^6 photons at the radius of 10^5 read ten
        // times as many each).
        float fewer = std::sqrt(std::min(1.0f, 100000.0f / float(photons.photons)));
        photons.radius = (largest > 0 ? largest / 20 : 0.05f) * fewer;
    }
    FramePass pass;
    if (photons.caustics != PhotonSettings::kPhotons) {  // no photon map
        pass.record = [&photons](VkCommandBuffer, gpu::RtPush& push, FrameChange) {
            push.caustics = photons.caustics == PhotonSettings::kTransmit
                                ? CAUSTICS_TRANSMIT
                                : CAUSTICS_OFF;
        };
        pass.reference = [&photons](ReferenceSettings& r) {
            r.transmitShadows = photons.caustics == PhotonSettings::kTransmit;
        };
        return pass;
    }
    auto map = std::make_shared<PhotonMap>(createPhotonMap(c, photons, photonShader));
    const RtScene& rt = c.rt;
    App& app = c.app;
    const Scene& scene = c.scene;
    pass.record = [map, &rt, &photons](VkCommandBuffer cmd, gpu::RtPush& push,
                             FrameChange change) {
        push.caustics = CAUSTICS_PHOTONS;
        push.photonSeed = uint32_t(photons.seed);
        push.gatherCap = uint32_t(photons.gatherCap);
        push.gatherDefer = uint32_t(photons.gatherDefer);
        recordDeferReset(cmd, *map);
        photons.lastRadius = frameRadius(photons, change.accumulated);
        // The map does not depend on the camera: while only the view moves
        // (every such frame starts a new average, at the first radius), the
        // map of the first radius is kept, and a light, material or
        // parameter changed traces it again.
        photons.kept = change.viewOnly && map->radius == photons.lastRadius;
        if (photons.kept) {
            pointAtPhotonMap(push, *map, uint32_t(photons.photons), map->radius);
            return;
        }
        recordPhotonMap(cmd, *map, rt, push, uint32_t(photons.photons),
                        photons.lastRadius);
        map->radius = photons.lastRadius;
        ++map->traced;
    };
    // after the camera rays: the crowded cells they left (--gather-defer)
    pass.after = [map, &rt, &photons](VkCommandBuffer cmd, const gpu::RtPush& push,
                                      bool averages) {
        if (push.gatherDefer == 0 || push.gatherCap != 0) return;
        float frames = averages ? float(push.accumulated + 1) : 1.0f;
        recordDeferredGathers(cmd, *map, rt, push.photonRadius, push.exposure / frames);
    };
    pass.finish = [map, &app, &scene, &photons] {
        LastPhotons last = readPhotons(app.gpu, app.deletion, *map, !photons.ply.empty());
        if (!photons.ply.empty()) writePhotonsPly(photons.ply, last.stored, scene.origin);
        // the last frame's photons: stored (a caustic), escaped, stopped by a limit
        return nlohmann::json{{"photons",
                               {{"emitted_per_frame", photons.photons},
                                {"stored_last_frame", last.header.stored},
                                {"escaped_last_frame", last.header.escaped},
                                {"lost_last_frame", last.header.lost},
                                {"gathers_deferred_last_frame",
                                 std::min(last.header.deferred, map->deferCapacity)},
                                {"gathers_deferred_wanted_last_frame",
                                 last.header.deferred},
                                {"maps_traced", map->traced},
                                {"emitters", map->emitterCount},
                                {"grid_cells", map->cellCount},
                                {"first_radius", photons.radius},
                                {"last_radius", photons.lastRadius},
                                {"alpha", photons.alpha},
                                {"gather_cap", photons.gatherCap},
                                {"gather_defer", photons.gatherDefer}}}};
    };
    // the window's overlay: how fast photons go, and the radius now
    pass.overlay = [&photons](double gpuMs) {
        char line[96];
        if (photons.kept) return std::string("photon map kept while the view moves");
        std::snprintf(line, sizeof line, "%.2f M photons/s, radius %.4g",
                      gpuMs > 0 ? photons.photons / (gpuMs * 1e3) : 0.0,
                      double(photons.lastRadius));
        return std::string(line);
    };
    // the reference averages its estimates over the same frames' radii
    pass.reference = [&photons](ReferenceSettings& r) {
        r.photonGrid = photons.referenceGrid;
        for (uint32_t i = 0; i < r.frames; ++i)
            r.photonRadii.push_back(frameRadius(photons, i));
    };
    return pass;
}
// [end]

}  // namespace

PhotonChapter photonChapter(const std::string& photonShader) {
    // one set of settings for the run, which the options fill and the pass reads
    auto photons = std::make_shared<PhotonSettings>();
    return {
        .options = [photons](Params& params, RtChapterSettings&) {
            declarePhotonOptions(params, *photons);
        },
        .adaptShaders = [photons](RtShaders& shaders, const Scene&) {
            adaptShaders(*photons, shaders);
        },
        .framePass =
            [photons, photonShader](const FramePassContext& c) {
                return photonPass(c, *photons, photonShader);
            },
    };
}

}  // namespace rg
