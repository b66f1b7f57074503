// Chapter 02 - Synchronization (thesis 2.1.2, figure 2.2).
// Chapter 01 waited for the GPU after every submission. Here the CPU records
// frame N+1 while the GPU renders frame N ("frames in flight"): fences,
// semaphores, an event and pipeline barriers keep them apart. That frame
// loop lives in shared/vulkan/frame_loop.cpp, because every later chapter presents
// through it; this file sets it up and animates chapter 01's pattern.
#include "app/app.h"
#include "app/report.h"
#include "core/cli.h"
#include "core/image.h"
#include "core/interrupt.h"
#include "host_device.h"
#include "vk_check.h"
#include "vulkan/descriptors.h"
#include "vulkan/device_limits.h"
#include "vulkan/frame_loop.h"
#include "vulkan/resources.h"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace {

constexpr uint32_t kChecker = 32;

struct ComputePass {
    rg::DescriptorSet descriptors;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

// Chapter 01's descriptors and compute pipeline, through the shared helpers
// (shared/vulkan/descriptors.cpp holds chapter 01's code for any number of bindings).
ComputePass createPatternPass(const rg::Gpu& gpu, const rg::Image& target,
                              rg::DeletionQueue& deletion) {
    ComputePass p;
    p.descriptors = rg::createDescriptorSet(
        gpu, deletion,
        {{PATTERN_BINDING_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
          VK_SHADER_STAGE_COMPUTE_BIT}});
    rg::writeStorageImage(gpu, p.descriptors.set, PATTERN_BINDING_TARGET, target.view);
    p.layout = rg::createPipelineLayout(gpu, deletion, p.descriptors.layout,
                                        sizeof(rg::gpu::PatternPush),
                                        VK_SHADER_STAGE_COMPUTE_BIT);
    p.pipeline = rg::createComputePipeline(gpu, deletion, p.layout,
                                           "02_synchronization/pattern.comp");
    return p;
}

// [region record_frame]
// The animation time comes from the frame number, not the clock, so a run
// of N frames always ends on the same image (the test checks it).
void recordFrame(VkCommandBuffer cmd, uint32_t frame, const ComputePass& p,
                 const rg::Image& target) {
    rg::gpu::PatternPush push{target.extent.width, target.extent.height,
                              float(frame / PATTERN_FPS), kChecker};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1,
                            &p.descriptors.set, 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                       &push);
    vkCmdDispatch(cmd, (push.width + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE,
                  (push.height + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE, 1);
}
// [end]

}  // namespace

int main(int argc, char** argv) {
    rg::Options opts;
    bool omitBarrier = false;
    auto extra = [&](CLI::App& app, rg::Options&) {
        app.add_flag("--omit-barrier", omitBarrier,
                     "Experiment (windowed): the blit no longer waits for the render; "
                     "validation reports the hazard");
    };
    if (auto exit = rg::parseCommandLine(
            argc, argv, "02_synchronization",
            "RayGlass chapter 02: frames in flight, fences, semaphores, barriers", opts,
            extra))
        return *exit;
    // headless frames have no blit: the experiment would show nothing
    if (omitBarrier && opts.headless) {
        std::fprintf(stderr,
                     "02_synchronization: --omit-barrier needs a window; without a "
                     "display run it as "
                     "xvfb-run -a build/bin/02_synchronization --validation "
                     "--omit-barrier --frames 3\n");
        return 2;
    }
    return rg::runChapter(opts, [&] {
        rg::App app;
        rg::initApp(app, opts, "RayGlass 02: synchronization");
        // before any work
        rg::checkImageFits(app.gpu, opts.width, opts.height, {.rayTracing = false});
        rg::Image target = rg::createImage2D(
            app.gpu, app.deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        ComputePass pass = createPatternPass(app.gpu, target, app.deletion);

        rg::FrameLoop loop(app.gpu, app.window.get(), target,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, app.deletion);
        loop.omitRenderBarrier = omitBarrier;
        rg::FrameTimes times =
            loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd, uint32_t frame) {
                recordFrame(cmd, frame, pass, target);
            });

        for (size_t i = 0; i < times.gpuMs.size() && i < times.cpuMs.size() && i < 5; ++i)
            std::printf("frame %zu: GPU %.3f ms, CPU %.3f ms\n", i, times.gpuMs[i],
                        times.cpuMs[i]);
        std::printf("median over %zu frames: GPU %.3f ms, CPU %.3f ms\n",
                    times.gpuMs.size(), rg::median(times.gpuMs), rg::median(times.cpuMs));
        // Ctrl-C before the first frame: nothing to write
        if (rg::interrupted() && times.gpuMs.empty()) return;
        rg::FloatImage image =
            rg::readImage(app.gpu, target, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        rg::writePng(opts.output, image);
        nlohmann::json report = rg::makeReport(opts, app.gpu, times);
        report["frames_in_flight"] = rg::FrameLoop::kFramesInFlight;
        rg::writeReport(opts.report, report);
        std::printf("Wrote %s and %s\n", opts.output.c_str(), opts.report.c_str());
    });
}
