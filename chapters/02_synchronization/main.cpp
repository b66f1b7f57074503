// Chapter 02 - Synchronization (thesis 2.1.2, figure 2.2).
// Chapter 01 waited for the GPU after every submission. Here the CPU records
// frame N+1 while the GPU renders frame N ("frames in flight"): fences,
// semaphores, an event and pipeline barriers keep them apart. That frame
// loop lives in shared/frame_loop.cpp, because every later chapter presents
// through it; this file sets it up and animates chapter 01's pattern.
#include "app.h"
#include "cli.h"
#include "frame_loop.h"
#include "host_device.h"
#include "output.h"
#include "resources.h"
#include "vk_check.h"

#include <cstdio>

namespace {

constexpr uint32_t kChecker = 32;

struct ComputePass {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

// Chapter 01's descriptors and compute pipeline, in one function.
ComputePass createPatternPass(const rg::Gpu& gpu, const rg::Image& target, rg::DeletionQueue& deletion) {
    ComputePass p;
    VkDescriptorSetLayoutBinding binding{
        .binding = PATTERN_BINDING_TARGET,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
        .descriptorCount = 1,
        .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
    };
    VkDescriptorSetLayoutCreateInfo setInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 1,
        .pBindings = &binding,
    };
    VK_CHECK(vkCreateDescriptorSetLayout(gpu.device, &setInfo, nullptr, &p.setLayout));
    VkDescriptorPoolSize size{.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .descriptorCount = 1};
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = 1,
        .pPoolSizes = &size,
    };
    VK_CHECK(vkCreateDescriptorPool(gpu.device, &poolInfo, nullptr, &p.pool));
    VkDescriptorSetAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = p.pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &p.setLayout,
    };
    VK_CHECK(vkAllocateDescriptorSets(gpu.device, &allocate, &p.set));
    VkDescriptorImageInfo image{.imageView = target.view, .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = p.set,
        .dstBinding = PATTERN_BINDING_TARGET,
        .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
        .pImageInfo = &image,
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);

    VkPushConstantRange push{.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .size = sizeof(rg::gpu::PatternPush)};
    VkPipelineLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &p.setLayout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    VK_CHECK(vkCreatePipelineLayout(gpu.device, &layoutInfo, nullptr, &p.layout));
    VkComputePipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = rg::loadShader(gpu, deletion, "02_synchronization/pattern.comp"),
            .pName = "main",
        },
        .layout = p.layout,
    };
    VK_CHECK(vkCreateComputePipelines(gpu.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline));
    VkDevice device = gpu.device;
    deletion.push([device, p] {
        vkDestroyPipeline(device, p.pipeline, nullptr);
        vkDestroyPipelineLayout(device, p.layout, nullptr);
        vkDestroyDescriptorPool(device, p.pool, nullptr);
        vkDestroyDescriptorSetLayout(device, p.setLayout, nullptr);
    });
    return p;
}

// [region record_frame]
// The animation time comes from the frame number, not the clock, so a run
// of N frames always ends on the same image (the test checks it).
void recordFrame(VkCommandBuffer cmd, uint32_t frame, const ComputePass& p, const rg::Image& target) {
    rg::gpu::PatternPush push{target.extent.width, target.extent.height, float(frame / PATTERN_FPS), kChecker};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
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
                     "Experiment (windowed): the blit no longer waits for the render; validation reports the hazard");
    };
    if (auto exit = rg::parseCommandLine(argc, argv, "02_synchronization",
                                         "RayGlass chapter 02: frames in flight, fences, semaphores, barriers",
                                         opts, extra))
        return *exit;
    return rg::runChapter(opts, [&] {
        rg::App app;
        rg::initApp(app, opts, "RayGlass 02: synchronization");
        rg::Image target = rg::createImage2D(app.gpu, app.deletion, opts.width, opts.height,
                                             VK_FORMAT_R32G32B32A32_SFLOAT,
                                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        ComputePass pass = createPatternPass(app.gpu, target, app.deletion);

        rg::FrameLoop loop(app.gpu, app.window.get(), target, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, app.deletion);
        loop.omitRenderBarrier = omitBarrier;
        rg::FrameTimes times = loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd, uint32_t frame) {
            recordFrame(cmd, frame, pass, target);
        });

        for (size_t i = 0; i < times.gpuMs.size() && i < times.cpuMs.size() && i < 5; ++i)
            std::printf("frame %zu: GPU %.3f ms, CPU %.3f ms\n", i, times.gpuMs[i], times.cpuMs[i]);
        std::printf("median over %zu frames: GPU %.3f ms, CPU %.3f ms\n", times.gpuMs.size(),
                    rg::median(times.gpuMs), rg::median(times.cpuMs));
        rg::FloatImage image = rg::readImage(app.gpu, target, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        rg::writePng(opts.output, image);
        nlohmann::json report = rg::makeReport(opts, app.gpu, times);
        report["frames_in_flight"] = rg::FrameLoop::kFramesInFlight;
        rg::writeReport(opts.report, report);
        std::printf("Wrote %s and %s\n", opts.output.c_str(), opts.report.c_str());
    });
}
