// Chapter 14's photon map (photon_map.h).
#include "photons/photon_map.h"

#include "app/app.h"
#include "core/files.h"
#include "raytracing/rt_scene.h"
#include "scene/scene.h"
#include "vulkan/descriptors.h"
#include "vulkan/device_limits.h"
#include "vk_check.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

namespace rg {

// [region emitters]
// Photons are aimed only where they can make a caustic (Jensen's projection
// map): at each glass and mirror, from each light, within the cone (a point
// light) or the beam (a sun) that covers the object's bounding sphere. Each
// (light, object) pair gets a share of the photons by the power it sends
// into that cone: the photon shader weighs every photon by how likely its
// direction was over all the pairs of its light, so overlapping cones
// count their light once.
struct BoundingBall {
    glm::dvec3 centre;
    double radius;
};

// A ball around an object, in world space.
static BoundingBall boundingBall(const Scene& scene, const Object& o) {
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
    std::vector<BoundingBall> targets, all;
    for (const Object& o : scene.objects) {
        if (o.hidden) continue;
        all.push_back(boundingBall(scene, o));
        const Material& m = scene.materials[o.material];
        if (m.transmission > 0 || m.reflectivity > 0) targets.push_back(all.back());
    }
    // Many small glasses (a field of spheres): one cone around them all.
    if (targets.size() > 64) {
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const BoundingBall& t : targets) {
            lo = glm::min(lo, t.centre - t.radius);
            hi = glm::max(hi, t.centre + t.radius);
        }
        targets = {{(lo + hi) * 0.5, glm::length(hi - lo) * 0.5}};
    }
    std::vector<gpu::PhotonEmitter> emitters;
    std::vector<double> power;
    for (uint32_t l = 0; l < scene.lights.size(); ++l) {
        const PointLight& light = scene.lights[l];
        for (const BoundingBall& t : targets) {
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
            for (const BoundingBall& o : all)
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

namespace {
// The grid's workgroups (recordPhotonMap's dispatches): one per
// GRID_GROUP_SIZE photons, or per prefix-sum block of GRID_SCAN_BLOCK buckets.
struct GridGroups {
    uint32_t photons, blocks;
};
GridGroups gridGroups(const PhotonMap& map) {
    return {(map.capacity + GRID_GROUP_SIZE - 1) / GRID_GROUP_SIZE,
            map.cellCount / GRID_SCAN_BLOCK};
}

// --photons against the device's limits, before any work: the photon
// launch (one ray a photon), the grid's dispatches and the photon buffers.
void checkPhotonsFit(const Gpu& gpu, const PhotonMap& map) {
    const VkPhysicalDeviceLimits& k = gpu.physical.properties.limits;
    uint64_t photons = map.capacity;
    GridGroups grid = gridGroups(map);
    uint32_t groups = std::max(grid.photons, grid.blocks);
    uint64_t widest =
        uint64_t(k.maxComputeWorkGroupCount[0]) * k.maxComputeWorkGroupSize[0];
    std::string storage;
    double bufferBytes = storageBufferLimit(gpu, &storage);
    std::string broken;
    uint64_t launch = gpu.physical.rayTracing.maxRayDispatchInvocationCount;
    if (photons > launch || photons > widest)
        broken = "the photon launch's width (maxRayDispatchInvocationCount, "
                 "maxComputeWorkGroupCount x maxComputeWorkGroupSize)";
    else if (groups > k.maxComputeWorkGroupCount[0])
        broken = "maxComputeWorkGroupCount (" +
                 std::to_string(k.maxComputeWorkGroupCount[0]) + " workgroups)";
    else if (double(photons) * sizeof(gpu::Photon) > bufferBytes)
        broken = storage + " (" + mebibytes(bufferBytes) + " in the photon buffer)";
    if (!broken.empty())
        throw InputError("--photons " + std::to_string(photons) +
                         " is too many for this device: " + broken);
}
}  // namespace

// [region photon_map]
// The photon map's buffers (photon_map.h's PhotonMap), its photon tracer
// and its grid's three compute shaders.
PhotonMap createPhotonMap(const FramePassContext& c, const PhotonSettings& settings,
                          const std::string& photonShader) {
    const Gpu& gpu = c.app.gpu;
    DeletionQueue& deletion = c.app.deletion;
    PhotonMap map;
    // A caustic photon lands on a diffuse surface at most once: room for all.
    map.capacity = uint32_t(settings.photons);
    // About two cells per photon, a power of two (the hash's last bits).
    map.cellCount = std::bit_ceil(std::max(2u * map.capacity, uint32_t(GRID_SCAN_BLOCK)));
    checkPhotonsFit(gpu, map);
    const VkBufferUsageFlags usage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
        VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    auto deviceBuffer = [&](VkDeviceSize bytes) {
        return createBuffer(gpu, deletion, bytes, usage,
                            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    };
    map.photons = deviceBuffer(VkDeviceSize(map.capacity) * sizeof(gpu::Photon));
    map.sorted = deviceBuffer(VkDeviceSize(map.capacity) * sizeof(gpu::Photon));
    // the buckets, then the prefix sum's blocks' totals
    VkDeviceSize buckets = map.cellCount + map.cellCount / GRID_SCAN_BLOCK;
    map.cells = deviceBuffer(buckets * sizeof(uint32_t));
    std::vector<gpu::PhotonEmitter> emitters = photonEmitters(c.scene);
    map.emitterCount = uint32_t(emitters.size());
    emitters.resize(std::max<size_t>(emitters.size(), 1));  // a buffer is never empty
    map.emitters = createDeviceBuffer(gpu, deletion, emitters.data(),
                                      emitters.size() * sizeof emitters[0], usage);
    // --gather-defer: room for one crowded cell's request per pixel (at
    // most 2^21, 96 MiB: lavapipe's storage buffers stop at 128 MiB); a
    // camera ray that finds no room gathers the cell itself.
    uint32_t pixels = c.rt.width * c.rt.height;
    map.deferCapacity = std::min(pixels, 1u << 21);
    map.requests = deviceBuffer(VkDeviceSize(map.deferCapacity) *
                                sizeof(gpu::GatherRequest));
    map.heads = deviceBuffer(VkDeviceSize(pixels) * sizeof(uint32_t));
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
                                .emitters = address(map.emitters),
                                .deferCapacity = map.deferCapacity,
                                .requests = address(map.requests),
                                .heads = address(map.heads)};
    map.header = createDeviceBuffer(gpu, deletion, &header, sizeof header, usage);

    // The photons' ray generation shader, with the camera rays' hit groups.
    RtShaders shaders = c.shaders;
    shaders.raygen = photonShader;
    map.tracer = createRtPipeline(gpu, deletion, c.rt.descriptors.layout,
                                  sizeof(gpu::RtPush), c.compile(shaders));
    // The grid: three compute shaders (count, prefix sum, scatter).
    map.gridLayout =
        createPipelineLayout(gpu, deletion, c.rt.descriptors.layout,
                             sizeof(gpu::GridPush), VK_SHADER_STAGE_COMPUTE_BIT);
    map.count = createComputePipeline(gpu, deletion, map.gridLayout,
                                      "14_caustics/grid_count.comp");
    map.scan = createComputePipeline(gpu, deletion, map.gridLayout,
                                     "14_caustics/grid_scan.comp");
    map.scanBlocks = createComputePipeline(gpu, deletion, map.gridLayout,
                                           "14_caustics/grid_scan_blocks.comp");
    map.scanAdd = createComputePipeline(gpu, deletion, map.gridLayout,
                                        "14_caustics/grid_scan_add.comp");
    map.scatter = createComputePipeline(gpu, deletion, map.gridLayout,
                                        "14_caustics/grid_scatter.comp");
    // --gather-defer's two (their push constants, DeferPush, are as long)
    map.deferred = createComputePipeline(gpu, deletion, map.gridLayout,
                                         "14_caustics/gather_deferred.comp");
    map.resolve = createComputePipeline(gpu, deletion, map.gridLayout,
                                        "14_caustics/gather_resolve.comp");
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

// The push constants' fields the camera rays read the map with.
void pointAtPhotonMap(gpu::RtPush& push, const PhotonMap& map, uint32_t photons,
                      float radius) {
    push.photonMap = {uint32_t(map.header.address), uint32_t(map.header.address >> 32)};
    push.photonRadius = radius;
    push.photonsEmitted = photons;
}

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

    pointAtPhotonMap(push, map, photons, radius);
    recordTrace(cmd, map.tracer, rt.descriptors.set, &push, sizeof push, photons, 1);
    memoryBarrier(cmd, rtStage, VK_ACCESS_SHADER_WRITE_BIT, compute, readWrite);

    gpu::GridPush grid{.photonMap = push.photonMap, .cellSize = 2 * radius};
    vkCmdPushConstants(cmd, map.gridLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof grid,
                       &grid);
    // workgroups: one per GRID_GROUP_SIZE photons, or per prefix-sum block
    GridGroups groups = gridGroups(map);
    const std::pair<VkPipeline, uint32_t> steps[] = {
        {map.count, groups.photons}, {map.scan, groups.blocks},       {map.scanBlocks, 1},
        {map.scanAdd, groups.blocks}, {map.scatter, groups.photons}};
    for (auto [stage, groups] : steps) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, stage);
        vkCmdDispatch(cmd, groups, 1, 1);
        memoryBarrier(cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute | rtStage,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
}
// [end]

// [region defer]
// --gather-defer (gather.glsl's gather_defer, a performance trick): the
// camera rays leave their crowded cells as requests, a list per pixel.
void recordDeferReset(VkCommandBuffer cmd, const PhotonMap& map) {
    constexpr VkPipelineStageFlags shaders =
        VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR |
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    constexpr VkAccessFlags readWrite =
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    // the last frame's camera rays and passes are done with the lists
    memoryBarrier(cmd, shaders, readWrite, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, map.header.handle, offsetof(gpu::PhotonMapHeader, deferred),
                    sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, map.heads.handle, 0, VK_WHOLE_SIZE, ~0u);  // no requests
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  shaders, readWrite);
}

// After the camera rays: 64 invocations gather each request, then each
// pixel adds its requests' light to the picture.
void recordDeferredGathers(VkCommandBuffer cmd, const PhotonMap& map, const RtScene& rt,
                           float radius, float resolveScale) {
    constexpr VkPipelineStageFlags rtStage = VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                                   compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    constexpr VkAccessFlags readWrite =
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    memoryBarrier(cmd, rtStage, readWrite, compute, readWrite);
    gpu::DeferPush push{.photonMap = {uint32_t(map.header.address),
                                      uint32_t(map.header.address >> 32)},
                        .radius = radius,
                        .resolveScale = resolveScale};
    vkCmdPushConstants(cmd, map.gridLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                       &push);
    // Workgroups loop over the requests, however many the frame left: a
    // few thousand fill any GPU (the GPU reads the count, the host never).
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map.deferred);
    vkCmdDispatch(cmd, std::min(map.deferCapacity, 4096u), 1, 1);
    memoryBarrier(cmd, compute, VK_ACCESS_SHADER_WRITE_BIT, compute,
                  VK_ACCESS_SHADER_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map.resolve);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map.gridLayout, 0, 1,
                            &rt.descriptors.set, 0, nullptr);
    vkCmdDispatch(cmd, (rt.width + 7) / 8, (rt.height + 7) / 8, 1);
    // The picture's next readers wait for the ray tracing stage (the frame
    // loop, the viewer, the PNG): chained to it, they wait for this too.
    memoryBarrier(cmd, compute, readWrite, rtStage, readWrite);
}
// [end]

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
// in the scene file's coordinates, for MeshLab or Blender, and the tests. A
// photon's power is a few microwatts, black as a colour, so each point also
// gets a colour: its power over the largest of any photon's channels.
void writePhotonsPly(const std::string& path, const std::vector<gpu::Photon>& photons,
                     const glm::dvec3& origin) {
    std::string tmp = path + ".part";  // a reader never sees half a file
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(path + ": cannot write the photons");
    std::fprintf(f,
                 "ply\nformat binary_little_endian 1.0\nelement vertex %zu\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "property float power_r\nproperty float power_g\n"
                 "property float power_b\n"
                 "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                 "end_header\n",
                 photons.size());
    float brightest = 0;
    for (const gpu::Photon& p : photons)
        brightest = std::max({brightest, p.power.r, p.power.g, p.power.b});
    auto shade = [&](float power) {  // black where no photon carries any power
        float share = brightest > 0.0f ? std::clamp(power / brightest, 0.0f, 1.0f) : 0.0f;
        return uint8_t(std::lround(255.0f * share));
    };
    for (const gpu::Photon& p : photons) {
        float v[6] = {float(p.position.x - origin.x),
                      float(p.position.y - origin.y),
                      float(p.position.z - origin.z),
                      p.power.r,
                      p.power.g,
                      p.power.b};
        uint8_t colour[3] = {shade(p.power.r), shade(p.power.g), shade(p.power.b)};
        std::fwrite(v, sizeof v, 1, f);
        std::fwrite(colour, sizeof colour, 1, f);
    }
    bool ok = std::fclose(f) == 0;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
        throw InputError(path + ": cannot write the photons");
}

}  // namespace rg
