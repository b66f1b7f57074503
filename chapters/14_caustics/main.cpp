// Chapter 14 - Light through glass (past the thesis, toward its task:
// "compare with similar objects in the real world"). Until now a shadow ray
// that meets glass says "dark": every glass casts a black shadow, where a
// real one focuses sunlight into a caustic. Eye rays cannot find that light:
// the path sun -> glass -> floor -> eye reaches the floor from the one
// direction the glass bends the sun into, which no ray from a diffuse point
// picks out. So light is traced from the lights instead (photon mapping,
// Jensen 1996): each frame a launch sends photons at the glasses and
// mirrors, follows them through reflection and refraction, and stores where
// they land on diffuse surfaces; compute shaders sort them into a hash
// grid; and the camera rays' diffuse hits add the photons' power within a
// radius that shrinks frame by frame (Knaus and Zwicker 2011), so the
// average converges to the right light. Lights are now in watts.
#include "app/app.h"
#include "chapter/rt_options.h"
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "raytracing/rt_scene.h"
#include "scene/scene.h"
#include "vulkan/descriptors.h"
#include "vk_check.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {
using namespace rg;

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
    float lastRadius = 0;  // the last frame's radius (the report)
    bool kept = false;     // the last frame reused the map before it (the overlay)
};

// [region emitters]
// Photons are aimed only where they can make a caustic (Jensen's projection
// map): at each glass and mirror, from each light, within the cone (a point
// light) or the beam (a sun) that covers the object's bounding sphere. Each
// (light, object) pair gets a share of the photons by the power it sends
// into that cone: the photon shader weighs every photon by how likely its
// direction was over all the pairs of its light, so overlapping cones
// count their light once.
struct Sphere {
    glm::dvec3 centre;
    double radius;
};

// A sphere around an object, in world space.
Sphere boundingSphere(const Scene& scene, const Object& o) {
    glm::dvec3 c(o.transform[3]);
    double r = 0;
    if (o.type == ShapeType::Sphere) {
        r = largestStretch(o.transform);
    } else if (o.type == ShapeType::Quad) {  // corners at +-u +-v
        r = glm::length(glm::dvec3(o.transform[0]) + glm::dvec3(o.transform[2]));
    } else {
        for (const glm::vec3& v : scene.meshes[o.mesh]->vertices)
            r = std::max(r, glm::length(glm::dvec3(o.transform * glm::dvec4(v, 1)) - c));
    }
    return {c, r * (1 + 1e-6)};
}

std::vector<gpu::PhotonEmitter> photonEmitters(const Scene& scene) {
    std::vector<Sphere> targets, all;
    for (const Object& o : scene.objects) {
        if (o.hidden) continue;
        all.push_back(boundingSphere(scene, o));
        const Material& m = scene.materials[o.material];
        if (m.transmission > 0 || m.reflectivity > 0) targets.push_back(all.back());
    }
    // Many small glasses (a field of spheres): one cone around them all.
    if (targets.size() > 64) {
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const Sphere& t : targets) {
            lo = glm::min(lo, t.centre - t.radius);
            hi = glm::max(hi, t.centre + t.radius);
        }
        targets = {{(lo + hi) * 0.5, glm::length(hi - lo) * 0.5}};
    }
    std::vector<gpu::PhotonEmitter> emitters;
    std::vector<double> power;
    for (uint32_t l = 0; l < scene.lights.size(); ++l) {
        const PointLight& light = scene.lights[l];
        for (const Sphere& t : targets) {
            double watts;  // the light's power into the cone or beam (all colours)
            if (light.kind == PointLight::Kind::Directional) {
                watts = (light.irradiance.r + light.irradiance.g + light.irradiance.b) *
                        M_PI * t.radius * t.radius;
            } else {
                double d = glm::length(t.centre - light.position);
                double cosMax =
                    d > t.radius ? std::sqrt(1 - (t.radius / d) * (t.radius / d)) : -1.0;
                watts = (light.intensity.r + light.intensity.g + light.intensity.b) * 2 *
                        M_PI * (1 - cosMax);
            }
            if (!(watts > 0)) continue;
            double backoff = t.radius;  // how far toward the sun things reach
            for (const Sphere& o : all)
                backoff = std::max(
                    backoff, glm::dot(o.centre - t.centre, -light.direction) + o.radius);
            emitters.push_back({.target = glm::vec4(glm::vec3(t.centre), float(t.radius)),
                                .light = l,
                                .backoff = float(std::min(backoff, 1000 * t.radius))});
            power.push_back(watts);
        }
    }
    double total = 0, running = 0;
    for (double w : power) total += w;
    for (size_t i = 0; i < emitters.size(); ++i) {
        running += power[i];
        emitters[i].probability = float(power[i] / total);
        emitters[i].cumulative = i + 1 == emitters.size() ? 1.0f : float(running / total);
    }
    return emitters;
}
// [end]

// [region photon_map]
// The photon map's buffers: each frame's photons in the order they were
// stored, the same sorted by grid cell, the grid's cells, the emitters, and
// a header that holds their device addresses (PhotonMapHeader).
struct PhotonMap {
    Buffer header, photons, sorted, cells, emitters;
    uint32_t capacity = 0, cellCount = 0, emitterCount = 0;
    RtPipeline tracer;  // photon.rgen with the scene's hit groups
    uint32_t traced = 0;  // maps traced in this run (the report)
    float radius = 0;     // the radius of the map traced last (0: none yet)
    VkPipelineLayout gridLayout = VK_NULL_HANDLE;
    VkPipeline count = VK_NULL_HANDLE, scan = VK_NULL_HANDLE, scatter = VK_NULL_HANDLE;
};

PhotonMap createPhotonMap(const FramePassContext& c, const PhotonSettings& settings) {
    const Gpu& gpu = c.app.gpu;
    DeletionQueue& deletion = c.app.deletion;
    PhotonMap map;
    // A caustic photon lands on a diffuse surface at most once: room for all.
    map.capacity = uint32_t(settings.photons);
    // About two cells per photon, a power of two (the hash's last bits).
    map.cellCount = std::bit_ceil(std::max(2u * map.capacity, 1024u));
    const VkBufferUsageFlags usage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
        VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    auto deviceBuffer = [&](VkDeviceSize bytes) {
        return createBuffer(gpu, deletion, bytes, usage,
                            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    };
    map.photons = deviceBuffer(VkDeviceSize(map.capacity) * sizeof(gpu::Photon));
    map.sorted = deviceBuffer(VkDeviceSize(map.capacity) * sizeof(gpu::Photon));
    map.cells = deviceBuffer(VkDeviceSize(map.cellCount) * sizeof(uint32_t));
    std::vector<gpu::PhotonEmitter> emitters = photonEmitters(c.scene);
    map.emitterCount = uint32_t(emitters.size());
    emitters.resize(std::max<size_t>(emitters.size(), 1));  // a buffer is never empty
    map.emitters = createDeviceBuffer(gpu, deletion, emitters.data(),
                                      emitters.size() * sizeof emitters[0], usage);
    auto address = [](const Buffer& b) {
        return gpu::uvec2(uint32_t(b.address), uint32_t(b.address >> 32));
    };
    gpu::PhotonMapHeader header{.stored = 0,
                                .capacity = map.capacity,
                                .cellCount = map.cellCount,
                                .emitterCount = map.emitterCount,
                                .photons = address(map.photons),
                                .sorted = address(map.sorted),
                                .cells = address(map.cells),
                                .emitters = address(map.emitters)};
    map.header = createDeviceBuffer(gpu, deletion, &header, sizeof header, usage);

    // The photons' ray generation shader, with the camera rays' hit groups.
    RtShaders shaders = c.shaders;
    shaders.raygen = "14_caustics/photon.rgen";
    shaders.spirvDir.clear();  // the build's, also under --shader-source
    map.tracer = createRtPipeline(gpu, deletion, c.rt.descriptors.layout,
                                  sizeof(gpu::RtPush), shaders);
    // The grid: three compute shaders (count, prefix sum, scatter).
    map.gridLayout =
        createPipelineLayout(gpu, deletion, c.rt.descriptors.layout,
                             sizeof(gpu::GridPush), VK_SHADER_STAGE_COMPUTE_BIT);
    map.count = createComputePipeline(gpu, deletion, map.gridLayout,
                                      "14_caustics/grid_count.comp");
    map.scan = createComputePipeline(gpu, deletion, map.gridLayout,
                                     "14_caustics/grid_scan.comp");
    map.scatter = createComputePipeline(gpu, deletion, map.gridLayout,
                                        "14_caustics/grid_scatter.comp");
    return map;
}
// [end]

// [region radius]
// Progressive photon mapping's radius (Knaus and Zwicker 2011): frame i
// gathers within r_i, r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1). The mean of
// the frames' estimates then converges: the radius shrinks slowly enough
// that each frame still finds more photons than the last in total.
float frameRadius(const PhotonSettings& s, uint32_t accumulated) {
    double r2 = double(s.radius) * s.radius;
    for (uint32_t i = 1; i <= accumulated; ++i) r2 *= (i + s.alpha) / (i + 1.0);
    return float(std::sqrt(r2));
}
// [end]

// [region record]
// One frame's photon map: clear, trace, count per cell, prefix sum, scatter.
void recordPhotonMap(VkCommandBuffer cmd, const PhotonMap& map, const RtScene& rt,
                     gpu::RtPush& push, uint32_t photons, float radius) {
    constexpr VkPipelineStageFlags rtStage = VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                                   compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                   transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
    constexpr VkAccessFlags readWrite =
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    // The last frame's camera rays and grid are done with the map.
    memoryBarrier(cmd, rtStage | compute, readWrite, transfer,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    // stored = 0, and the fates' counts
    vkCmdFillBuffer(cmd, map.header.handle, 0, sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, map.header.handle, offsetof(gpu::PhotonMapHeader, escaped),
                    2 * sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, map.cells.handle, 0, VK_WHOLE_SIZE, 0);
    memoryBarrier(cmd, transfer, VK_ACCESS_TRANSFER_WRITE_BIT, rtStage | compute,
                  readWrite);

    push.photonMap = {uint32_t(map.header.address), uint32_t(map.header.address >> 32)};
    push.photonRadius = radius;
    push.photonsEmitted = photons;
    recordTrace(cmd, map.tracer, rt.descriptors.set, &push, sizeof push, photons, 1);
    memoryBarrier(cmd, rtStage, VK_ACCESS_SHADER_WRITE_BIT, compute, readWrite);

    gpu::GridPush grid{.photonMap = push.photonMap, .cellSize = 2 * radius};
    vkCmdPushConstants(cmd, map.gridLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof grid,
                       &grid);
    uint32_t groups = (map.capacity + GRID_GROUP_SIZE - 1) / GRID_GROUP_SIZE;
    for (VkPipeline stage : {map.count, map.scan, map.scatter}) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, stage);
        vkCmdDispatch(cmd, stage == map.scan ? 1 : groups, 1, 1);
        memoryBarrier(cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute | rtStage,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
}
// [end]

// The last frame's photon map's counts, and with `withPhotons` its stored
// photons too (--photons-ply), copied to the host (waits for the GPU).
struct LastPhotons {
    gpu::PhotonMapHeader header{};  // its counts
    std::vector<gpu::Photon> stored;
};
LastPhotons readPhotons(const Gpu& gpu, DeletionQueue& deletion, const PhotonMap& map,
                        bool withPhotons) {
    constexpr VkDeviceSize headerBytes = sizeof(gpu::PhotonMapHeader);
    VkDeviceSize bytes =
        headerBytes +
        (withPhotons ? VkDeviceSize(map.capacity) * sizeof(gpu::Photon) : 0);
    Buffer host =
        createHostBuffer(gpu, deletion, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        memoryBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy header{.size = headerBytes};
        vkCmdCopyBuffer(cmd, map.header.handle, host.handle, 1, &header);
        VkBufferCopy photons{.dstOffset = headerBytes, .size = bytes - headerBytes};
        if (withPhotons)
            vkCmdCopyBuffer(cmd, map.photons.handle, host.handle, 1, &photons);
    });
    LastPhotons last;
    const auto* data = static_cast<const char*>(host.mapped);
    std::memcpy(&last.header, data, headerBytes);
    const auto* first = reinterpret_cast<const gpu::Photon*>(data + headerBytes);
    if (withPhotons)
        last.stored.assign(first, first + std::min(last.header.stored, map.capacity));
    return last;
}

// --photons-ply: the photons as a point cloud (position, power in watts),
// in the scene file's coordinates, for MeshLab or Blender, and the tests.
void writePhotonsPly(const std::string& path, const std::vector<gpu::Photon>& photons,
                     const glm::dvec3& origin) {
    std::string tmp = path + ".part";  // a reader never sees half a file
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(path + ": cannot write the photons");
    std::fprintf(f,
                 "ply\nformat binary_little_endian 1.0\nelement vertex %zu\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "property float red\nproperty float green\nproperty float blue\n"
                 "end_header\n",
                 photons.size());
    for (const gpu::Photon& p : photons) {
        float v[6] = {float(p.position.x - origin.x),
                      float(p.position.y - origin.y),
                      float(p.position.z - origin.z),
                      p.power.r,
                      p.power.g,
                      p.power.b};
        std::fwrite(v, sizeof v, 1, f);
    }
    bool ok = std::fclose(f) == 0;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
        throw InputError(path + ": cannot write the photons");
}

// [region options]
// The chapter's parameters: command-line options and overlay controls.
PhotonSettings photons;

void declareOptions(Params& params, RtChapterSettings& s) {
    addDepthOption(params, s, 8);
    s.fresnelMode = 2;  // exact, as chapter 13
    addSpectralOptions(params, s);
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
                  "radius / 20)",
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
    params
        .text("--photons-ply", photons.ply,
              "Write the last frame's photons to this PLY point cloud")
        .live = false;
}
// [end]

// [region transmit_shaders]
// --caustics transmit: the shadow hit groups get any-hit shaders that pass
// glass (transmit.glsl), and the shadow rays their own miss shader.
void adaptShaders(RtShaders& shaders, const Scene&) {
    if (photons.caustics != PhotonSettings::kTransmit) return;
    shaders.miss.push_back("14_caustics/transmit.rmiss");  // MISS_TRANSMIT
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
FramePass photonPass(const FramePassContext& c) {
    if (photons.radius <= 0) {  // a twentieth of the largest glass
        float largest = 0;
        for (const gpu::PhotonEmitter& e : photonEmitters(c.scene))
            largest = std::max(largest, e.target.w);
        photons.radius = largest > 0 ? largest / 20 : 0.05f;
    }
    FramePass pass;
    if (photons.caustics != PhotonSettings::kPhotons) {  // no photon map
        pass.record = [](VkCommandBuffer, gpu::RtPush& push, FrameChange) {
            push.caustics = photons.caustics == PhotonSettings::kTransmit
                                ? CAUSTICS_TRANSMIT
                                : CAUSTICS_OFF;
        };
        pass.reference = [](ReferenceSettings& r) {
            r.transmitShadows = photons.caustics == PhotonSettings::kTransmit;
        };
        return pass;
    }
    auto map = std::make_shared<PhotonMap>(createPhotonMap(c, photons));
    const RtScene& rt = c.rt;
    App& app = c.app;
    const Scene& scene = c.scene;
    pass.record = [map, &rt](VkCommandBuffer cmd, gpu::RtPush& push,
                             FrameChange change) {
        push.caustics = CAUSTICS_PHOTONS;
        push.photonSeed = uint32_t(photons.seed);
        photons.lastRadius = frameRadius(photons, change.accumulated);
        // The map does not depend on the camera: while only the view moves
        // (every such frame starts a new average, at the first radius), the
        // map of the first radius is kept, and a light, material or
        // parameter changed traces it again.
        photons.kept = change.viewOnly && map->radius == photons.lastRadius;
        if (photons.kept) {
            push.photonMap = {uint32_t(map->header.address),
                              uint32_t(map->header.address >> 32)};
            push.photonRadius = map->radius;
            push.photonsEmitted = uint32_t(photons.photons);
            return;
        }
        recordPhotonMap(cmd, *map, rt, push, uint32_t(photons.photons),
                        photons.lastRadius);
        map->radius = photons.lastRadius;
        ++map->traced;
    };
    pass.finish = [map, &app, &scene] {
        LastPhotons last = readPhotons(app.gpu, app.deletion, *map, !photons.ply.empty());
        if (!photons.ply.empty()) writePhotonsPly(photons.ply, last.stored, scene.origin);
        // the last frame's photons: stored (a caustic), escaped, stopped by a limit
        return nlohmann::json{{"photons",
                               {{"emitted_per_frame", photons.photons},
                                {"stored_last_frame", last.header.stored},
                                {"escaped_last_frame", last.header.escaped},
                                {"lost_last_frame", last.header.lost},
                                {"maps_traced", map->traced},
                                {"emitters", map->emitterCount},
                                {"grid_cells", map->cellCount},
                                {"first_radius", photons.radius},
                                {"last_radius", photons.lastRadius},
                                {"alpha", photons.alpha}}}};
    };
    // the window's overlay: how fast photons go, and the radius now
    pass.overlay = [](double gpuMs) {
        char line[96];
        if (photons.kept) return std::string("photon map kept while the view moves");
        std::snprintf(line, sizeof line, "%.2f M photons/s, radius %.4g",
                      gpuMs > 0 ? photons.photons / (gpuMs * 1e3) : 0.0,
                      double(photons.lastRadius));
        return std::string(line);
    };
    // the reference averages its estimates over the same frames' radii
    pass.reference = [](ReferenceSettings& r) {
        r.photonGrid = photons.referenceGrid;
        for (uint32_t i = 0; i < r.frames; ++i)
            r.photonRadii.push_back(frameRadius(photons, i));
    };
    return pass;
}
// [end]

}  // namespace

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "14_caustics",
        .description = "RayGlass chapter 14: light through glass, caustics and coloured "
                       "shadows by photon mapping",
        .title = "RayGlass 14: caustics",
        .stage = rg::ReferenceStage::Caustics,
        .meshes = true,
        // A clear and an amber glass ball on a floor in low sunlight.
        .scene = "caustics",
        .options = declareOptions,
        .physicalLights = true,  // watts, and no ambient light unless the scene gives it
        .adaptShaders = adaptShaders,  // --caustics transmit's any-hit shaders
        .framePass = photonPass,  // photons traced and sorted before each frame
    });
}
