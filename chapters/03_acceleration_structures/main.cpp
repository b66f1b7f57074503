// Chapter 03 - Acceleration structures (thesis 2.2.1).
// Loads a scene file, builds a BLAS of triangles (the unit quad) and a BLAS
// of one AABB (the box around the analytic unit sphere), compacts both, and
// builds a TLAS with one instance per scene object. Every frame, the objects
// marked "moving" get a new transform and the TLAS is refitted in place: a
// moving object needs nothing else. The image is the TLAS's view from above:
// each instance's box, drawn from the buffer the TLAS is built from.
// Chapter 04 traces rays through these structures.
#include "app/app.h"
#include "app/report.h"
#include "core/image.h"
#include "core/interrupt.h"
#include "host_device.h"
#include "raytracing/accel.h"
#include "scene/scene.h"
#include "vk_check.h"
#include "vulkan/descriptors.h"
#include "vulkan/device_limits.h"
#include "vulkan/frame_loop.h"
#include "vulkan/gpu_timer.h"

#include <CLI/CLI.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

// [region motion]
// Where a moving object is at `frame`: up to 0.5 units along x, one cycle
// per 240 frames, so that the default 60 frames end near its farthest.
glm::dmat4 movedTransform(const rg::Object& o, uint32_t frame) {
    double offset = 0.5 * std::sin(2.0 * 3.14159265358979323846 * frame / 240.0);
    return glm::translate(glm::dmat4(1.0), glm::dvec3(offset, 0, 0)) * o.transform;
}
// [end]

// The world box of an instance's unit shape ([-1,1]^3 through its transform),
// as x/z extents: what the top view draws.
struct TopBox { double minX, minZ, maxX, maxZ; };
TopBox topBox(const glm::dmat4& m) {
    glm::dvec3 half(std::abs(m[0][0]) + std::abs(m[1][0]) + std::abs(m[2][0]), 0,
                    std::abs(m[0][2]) + std::abs(m[1][2]) + std::abs(m[2][2]));
    return {m[3][0] - half.x, m[3][2] - half.z, m[3][0] + half.x, m[3][2] + half.z};
}

void printStatistics(const rg::UnitShapes& shapes, const rg::Tlas& tlas) {
    std::printf("%-12s %-10s %12s %14s %10s %12s\n", "structure", "geometry",
                "built bytes", "compacted", "build ms", "compact ms");
    for (const auto& s : shapes.stats)
        std::printf("%-12s %-10s %12llu %14llu %10.3f %12.3f\n", s.name.c_str(),
                    s.geometry.c_str(), (unsigned long long)s.buildBytes,
                    (unsigned long long)s.compactBytes, s.buildMs, s.compactMs);
    std::printf(
        "%-12s %-10s %12llu %14s %10.3f   (%u instances, update scratch %llu bytes)\n",
        "tlas", "instances", (unsigned long long)tlas.buildBytes, "-", tlas.buildMs,
        tlas.count, (unsigned long long)tlas.updateScratchBytes);
}

}  // namespace

int main(int argc, char** argv) {
    rg::Options opts;
    auto extra = [](CLI::App& app, rg::Options& o) {
        rg::addSceneOptions(app, o, false);
    };
    if (auto exit = rg::parseCommandLine(
            argc, argv, "03_acceleration_structures",
            "RayGlass chapter 03: BLAS, TLAS, compaction, refit", opts, extra))
        return *exit;
    return rg::runChapter(opts, [&] {
        rg::Scene scene = rg::loadScene(
            opts.scene.empty() ? rg::defaultScenePath("default") : opts.scene);
        rg::refuseMeshes(scene);  // spheres and quads only, until chapter 12
        rg::App app;
        rg::initApp(app, opts, "RayGlass 03: acceleration structures");
        rg::Gpu& gpu = app.gpu;

        // [region build]
        // two BLASes
        rg::UnitShapes shapes = rg::buildUnitShapes(gpu, app.deletion);
        // Instance k is object order[k]: the list's halves are halves in space.
        std::vector<uint32_t> order =
            opts.fileOrder ? rg::fileOrder(scene) : rg::medianSplitOrder(scene);
        std::vector<VkAccelerationStructureInstanceKHR> instances =
            rg::makeInstances(scene, shapes, order);
        // one TLAS
        rg::Tlas tlas = rg::buildTlas(gpu, app.deletion, instances);
        // [end]
        printStatistics(shapes, tlas);

        // The top view: a compute shader reads the TLAS's instance buffer.
        // before any work
        rg::checkImageFits(gpu, opts.width, opts.height, {.rayTracing = false});
        rg::Image target = rg::createImage2D(
            gpu, app.deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        rg::DescriptorSet set = rg::createDescriptorSet(
            gpu, app.deletion,
            {
                {FOOTPRINT_BINDING_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                 VK_SHADER_STAGE_COMPUTE_BIT},
                {FOOTPRINT_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                 VK_SHADER_STAGE_COMPUTE_BIT},
            });
        rg::writeStorageImage(gpu, set.set, FOOTPRINT_BINDING_TARGET, target.view);
        rg::writeBuffer(gpu, set.set, FOOTPRINT_BINDING_INSTANCES,
                        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, tlas.instances);
        VkPipelineLayout layout = rg::createPipelineLayout(gpu, app.deletion, set.layout,
                                                           sizeof(rg::gpu::FootprintPush),
                                                           VK_SHADER_STAGE_COMPUTE_BIT);
        VkPipeline pipeline = rg::createComputePipeline(
            gpu, app.deletion, layout, "03_acceleration_structures/footprint.comp");

        // The view covers every object's box (at any motion) with a margin, at the
        // image's aspect.
        double minX = 1e300, minZ = 1e300, maxX = -1e300, maxZ = -1e300;
        for (const auto& o : scene.objects) {
            TopBox b = topBox(o.transform);
            double slack = o.moving ? 0.5 : 0.0;
            minX = std::min(minX, b.minX - slack), maxX = std::max(maxX, b.maxX + slack);
            minZ = std::min(minZ, b.minZ), maxZ = std::max(maxZ, b.maxZ);
        }
        double spanX = (maxX - minX) * 1.1, spanZ = (maxZ - minZ) * 1.1;
        double aspect = double(opts.width) / opts.height;
        if (spanX / spanZ < aspect) spanX = spanZ * aspect;
        else spanZ = spanX / aspect;
        glm::vec4 bounds(float(0.5 * (minX + maxX) - 0.5 * spanX),
                         float(0.5 * (minZ + maxZ) - 0.5 * spanZ), float(spanX),
                         float(spanZ));

        // [region per_frame]
        uint32_t lastFrame = 0;
        const uint32_t slots = rg::FrameLoop::kFramesInFlight;
        // the refit alone: what moving costs
        rg::GpuTimer refitTimer(gpu, app.deletion, slots);
        std::vector<double> refitMs;
        std::vector<uint32_t> moving;  // the instances that move
        for (uint32_t k = 0; k < order.size(); ++k)
            if (scene.objects[order[k]].moving) moving.push_back(k);
        rg::FrameLoop loop(gpu, app.window.get(), target,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, app.deletion);
        rg::FrameTimes times = loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd,
                                                                uint32_t frame) {
            // The loop waited for the frame that last used this slot: its time is ready.
            if (frame >= slots) refitMs.push_back(refitTimer.readMs(frame % slots));
            for (uint32_t k : moving)  // new transforms for moving objects only
                instances[k].transform =
                    rg::toVkTransform(movedTransform(scene.objects[order[k]], frame));
            refitTimer.begin(cmd, frame % slots);
            // refit
            rg::recordTlasUpdate(cmd, tlas, instances, moving,
                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
            refitTimer.end(cmd, frame % slots);

            rg::gpu::FootprintPush push{bounds, uint32_t(opts.width),
                                        uint32_t(opts.height), tlas.count, 0};
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1,
                                    &set.set, 0, nullptr);
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                               &push);
            vkCmdDispatch(cmd, (push.width + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE,
                          (push.height + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE, 1);
            lastFrame = frame;
        });
        // [end]
        uint32_t recorded = uint32_t(times.gpuMs.size());  // frames recorded, each timed
        // the last frames' (the device is idle)
        for (uint32_t i = std::min(recorded, slots); i > 0; --i)
            refitMs.push_back(refitTimer.readMs((recorded - i) % slots));
        std::printf(
            "median frame (refit + top view): GPU %.3f ms over %zu frames; the refit "
            "alone %.3f ms\n",
            rg::median(times.gpuMs), times.gpuMs.size(), rg::median(refitMs));

        // Ctrl-C before the first frame: nothing to write
        if (rg::interrupted() && times.gpuMs.empty()) return;
        rg::FloatImage image =
            rg::readImage(gpu, target, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        rg::writePng(opts.output, image);
        nlohmann::json report = rg::makeReport(opts, gpu, times);
        report["scene"] = scene.path;
        for (const auto& s : shapes.stats)
            report["blas"].push_back({{"name", s.name},
                                      {"geometry", s.geometry},
                                      {"size_bytes", s.buildBytes},
                                      {"compacted_bytes", s.compactBytes},
                                      {"build_ms", s.buildMs},
                                      {"compact_ms", s.compactMs}});
        report["tlas"] = {{"instances", tlas.count},
                          {"size_bytes", tlas.buildBytes},
                          {"update_scratch_bytes", tlas.updateScratchBytes},
                          {"build_ms", tlas.buildMs},
                          {"update_ms", rg::median(refitMs)},
                          {"update", "refit in place every frame (mode UPDATE)"}};
        report["top_view"] = {{"x0", bounds.x},
                              {"z0", bounds.y},
                              {"width", bounds.z},
                              {"depth", bounds.w},
                              {"last_frame", lastFrame}};
        for (uint32_t i : order) {  // in TLAS order, as the top view reads them
            const rg::Object& o = scene.objects[i];
            TopBox b = topBox(o.moving ? movedTransform(o, lastFrame) : o.transform);
            report["instances"].push_back(
                {{"object", i},
                 {"shape", o.type == rg::ShapeType::Sphere ? "sphere" : "quad"},
                 {"moving", o.moving},
                 {"box_min_xz", {b.minX, b.minZ}},
                 {"box_max_xz", {b.maxX, b.maxZ}}});
        }
        rg::writeReport(opts.report, report);
        std::printf("Wrote %s and %s\n", opts.output.c_str(), opts.report.c_str());
    });
}
