// Chapter 01 - Vulkan setup (thesis 2.1.1, figure 2.1).
// Creates, in order, every object of figure 2.1, runs one compute shader that
// writes a test pattern into a storage image, and shows it in a window or
// writes it to a PNG. Everything the CPU does here waits for the GPU
// (vkQueueWaitIdle, fences); chapter 02 removes those waits.
#include "app/app.h"
#include "app/report.h"
#include "core/cli.h"
#include "core/image.h"
#include "core/interrupt.h"
#include "host_device.h"
#include "vk_check.h"
#include "vulkan/context.h"
#include "vulkan/device_limits.h"
#include "vulkan/gpu_timer.h"
#include "vulkan/resources.h"
#include "vulkan/window.h"

#include <chrono>
#include <cstdio>

namespace {

constexpr uint32_t kChecker = 32;  // pixels per checker square

void printRayTracingProperties(const rg::PhysicalDeviceChoice& physical) {
    const auto& rt = physical.rayTracing;
    const auto& as = physical.accelerationStructure;
    std::printf("Ray tracing properties of %s:\n", physical.properties.deviceName);
    std::printf("  shaderGroupHandleSize        %u\n", rt.shaderGroupHandleSize);
    std::printf("  shaderGroupHandleAlignment   %u\n", rt.shaderGroupHandleAlignment);
    std::printf("  shaderGroupBaseAlignment     %u\n", rt.shaderGroupBaseAlignment);
    std::printf("  maxRayRecursionDepth         %u\n", rt.maxRayRecursionDepth);
    std::printf("  maxShaderGroupStride         %u\n", rt.maxShaderGroupStride);
    std::printf("  maxRayDispatchInvocations    %u\n", rt.maxRayDispatchInvocationCount);
    std::printf("  maxGeometryCount (per BLAS)  %llu\n",
                (unsigned long long)as.maxGeometryCount);
    std::printf("  maxInstanceCount (per TLAS)  %llu\n",
                (unsigned long long)as.maxInstanceCount);
    std::printf("  timestampPeriod              %.3f ns\n",
                physical.properties.limits.timestampPeriod);
}

// Descriptors (figure 2.1): the layout says "binding 0 is a storage image",
// the pool provides memory for sets, the set points binding 0 at our image.
struct Descriptors {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
};

Descriptors createDescriptors(const rg::Gpu& gpu, const rg::Image& target,
                              rg::DeletionQueue& deletion) {
    Descriptors d;
    VkDescriptorSetLayoutBinding binding{
        .binding = PATTERN_BINDING_TARGET,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
        .descriptorCount = 1,
        .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
    };
    VkDescriptorSetLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 1,
        .pBindings = &binding,
    };
    VK_CHECK(vkCreateDescriptorSetLayout(gpu.device, &layoutInfo, nullptr, &d.layout));
    VkDescriptorPoolSize size{.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                              .descriptorCount = 1};
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = 1,
        .pPoolSizes = &size,
    };
    VK_CHECK(vkCreateDescriptorPool(gpu.device, &poolInfo, nullptr, &d.pool));
    VkDevice device = gpu.device;
    deletion.push([device, d] {
        vkDestroyDescriptorPool(device, d.pool, nullptr);  // frees its sets too
        vkDestroyDescriptorSetLayout(device, d.layout, nullptr);
    });
    VkDescriptorSetAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = d.pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &d.layout,
    };
    VK_CHECK(vkAllocateDescriptorSets(gpu.device, &allocate, &d.set));
    VkDescriptorImageInfo image{.imageView = target.view,
                                .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = d.set,
        .dstBinding = PATTERN_BINDING_TARGET,
        .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
        .pImageInfo = &image,
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);
    return d;
}

// Pipeline (figure 2.1): a layout (one descriptor set, one push-constant
// range) plus the shader stage; a compute pipeline has no other state.
struct Pipeline {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

Pipeline createPatternPipeline(const rg::Gpu& gpu, VkDescriptorSetLayout setLayout,
                               rg::DeletionQueue& deletion) {
    Pipeline p;
    VkPushConstantRange push{.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
                             .size = sizeof(rg::gpu::PatternPush)};
    VkPipelineLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &setLayout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    VK_CHECK(vkCreatePipelineLayout(gpu.device, &layoutInfo, nullptr, &p.layout));
    VkComputePipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = rg::loadShader(gpu, deletion, "01_vulkan_setup/pattern.comp"),
            .pName = "main",
        },
        .layout = p.layout,
    };
    VK_CHECK(vkCreateComputePipelines(gpu.device, VK_NULL_HANDLE, 1, &info, nullptr,
                                      &p.pipeline));
    VkDevice device = gpu.device;
    deletion.push([device, p] {
        vkDestroyPipeline(device, p.pipeline, nullptr);
        vkDestroyPipelineLayout(device, p.layout, nullptr);
    });
    return p;
}

// [region record_dispatch]
void recordPattern(VkCommandBuffer cmd, const Pipeline& p, const Descriptors& d,
                   const rg::Image& target) {
    rg::gpu::PatternPush push{target.extent.width, target.extent.height, 0.0f, kChecker};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &d.set,
                            0, nullptr);
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                       &push);
    // round up
    uint32_t groupsX = (push.width + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE;
    uint32_t groupsY = (push.height + PATTERN_GROUP_SIZE - 1) / PATTERN_GROUP_SIZE;
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
}
// [end]

// Window: show the image until the window closes, one frame at a time and
// fully synchronous: acquire (wait on a fence), blit, present, wait idle.
void showInWindow(const rg::Gpu& gpu, rg::Window& window, const rg::Image& target,
                  rg::DeletionQueue& deletion, int frames) {
    window.createSwapchain(gpu, deletion);
    VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence acquired = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(gpu.device, &fenceInfo, nullptr, &acquired));
    VkDevice device = gpu.device;
    deletion.push([device, acquired] { vkDestroyFence(device, acquired, nullptr); });
    for (int frame = 0; (frames == 0 || frame < frames) && !window.shouldClose();
         ++frame) {
        window.pollEvents();
        uint32_t index = 0;
        VkResult result = vkAcquireNextImageKHR(gpu.device, window.swapchain, UINT64_MAX,
                                                VK_NULL_HANDLE, acquired, &index);
        if (result == VK_ERROR_OUT_OF_DATE_KHR) {
            window.createSwapchain(gpu, deletion);
            continue;
        }
        if (result != VK_SUBOPTIMAL_KHR) VK_CHECK(result);
        VK_CHECK(vkWaitForFences(gpu.device, 1, &acquired, VK_TRUE, UINT64_MAX));
        VK_CHECK(vkResetFences(gpu.device, 1, &acquired));
        VkImage swapImage = window.images[index];
        rg::submitOnce(gpu, [&](VkCommandBuffer cmd) {
            rg::imageBarrier(
                cmd, swapImage, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            rg::imageBarrier(cmd, target.handle, VK_IMAGE_LAYOUT_GENERAL,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_ACCESS_TRANSFER_READ_BIT);
            VkImageBlit blit{
                .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                .srcOffsets = {{0, 0, 0},
                               {int32_t(target.extent.width),
                                int32_t(target.extent.height), 1}},
                .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                .dstOffsets = {{0, 0, 0},
                               {int32_t(window.extent.width),
                                int32_t(window.extent.height), 1}},
            };
            vkCmdBlitImage(cmd, target.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                           VK_FILTER_NEAREST);
            rg::imageBarrier(cmd, target.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0);
            rg::imageBarrier(cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
        });  // waited on a fence: the blit is done, present needs no semaphore
        VkPresentInfoKHR present{
            .sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
            .swapchainCount = 1,
            .pSwapchains = &window.swapchain,
            .pImageIndices = &index,
        };
        result = vkQueuePresentKHR(gpu.queue, &present);
        if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR ||
            window.resized())
            window.createSwapchain(gpu, deletion);
        else
            VK_CHECK(result);
        // the simplest sync there is; chapter 02 does better
        VK_CHECK(vkQueueWaitIdle(gpu.queue));
    }
}

}  // namespace

int main(int argc, char** argv) {
    rg::Options opts;
    if (auto exit = rg::parseCommandLine(
            argc, argv, "01_vulkan_setup",
            "RayGlass chapter 01: the Vulkan objects, one compute shader", opts))
        return *exit;
    return rg::runChapter(opts, [&] {
        rg::App app;
        rg::DeletionQueue& deletion = app.deletion;
        rg::Gpu& gpu = app.gpu;

        // [region objects]
        // Instance: the application's connection to Vulkan (plus a window surface).
        std::vector<const char*> windowExtensions;
        if (!opts.headless) {
            app.window = std::make_unique<rg::Window>(opts.width, opts.height,
                                                      "RayGlass 01: Vulkan setup");
            windowExtensions = app.window->instanceExtensions();
        }
        gpu.instance =
            rg::createInstance(opts.chapter, opts.validation, windowExtensions, deletion);
        VkSurfaceKHR surface = app.window
                                   ? app.window->createSurface(gpu.instance, deletion)
                                   : VK_NULL_HANDLE;

        // Physical device: a GPU that can trace rays (and present, if windowed).
        gpu.physical = rg::pickPhysicalDevice(gpu.instance, surface, opts.device);
        printRayTracingProperties(gpu.physical);

        // Device and queue: our interface to that GPU.
        gpu.device = rg::createDevice(gpu.physical, surface != VK_NULL_HANDLE, deletion);
        vkGetDeviceQueue(gpu.device, gpu.physical.queueFamily, 0, &gpu.queue);

        // Command pool: command buffers are allocated from it.
        VkCommandPoolCreateInfo poolInfo{
            .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
            .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,  // short-lived buffers
            .queueFamilyIndex = gpu.physical.queueFamily,
        };
        VK_CHECK(vkCreateCommandPool(gpu.device, &poolInfo, nullptr, &gpu.commandPool));
        VkDevice device = gpu.device;
        VkCommandPool commandPool = gpu.commandPool;
        deletion.push([device, commandPool] {
            vkDeviceWaitIdle(device);
            vkDestroyCommandPool(device, commandPool, nullptr);
        });

        // The storage image the shader writes: linear RGBA, 32-bit float.
        // before any work
        rg::checkImageFits(gpu, opts.width, opts.height, {.rayTracing = false});
        rg::Image target = rg::createImage2D(
            gpu, deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        Descriptors descriptors = createDescriptors(gpu, target, deletion);
        Pipeline pipeline = createPatternPipeline(gpu, descriptors.layout, deletion);
        // [end]

        // Command buffer: record layout transition + dispatch, submit, wait.
        rg::GpuTimer timer(gpu, deletion, 1);
        rg::FrameTimes times;
        for (int frame = 0; frame < std::max(1, opts.framesToRun()); ++frame) {
            auto cpuStart = std::chrono::steady_clock::now();
            // [region submit]
            rg::submitOnce(gpu, [&](VkCommandBuffer cmd) {
                // A new image's layout is UNDEFINED; a storage image must be
                // GENERAL before the shader writes it. The barrier changes the
                // layout and orders the previous frame's copy before the writes.
                rg::imageBarrier(
                    cmd, target.handle, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
                timer.begin(cmd, 0);
                recordPattern(cmd, pipeline, descriptors, target);
                timer.end(cmd, 0);
            });  // records, submits, waits on a fence
            // [end]
            times.gpuMs.push_back(timer.readMs(0));
            times.cpuMs.push_back(std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - cpuStart)
                                      .count());
            // Ctrl-C: keep the frames done (shared/core/interrupt.h)
            if (rg::interrupted()) break;
        }
        std::printf("GPU time for the dispatch: %.3f ms (median of %zu)\n",
                    rg::median(times.gpuMs), times.gpuMs.size());

        rg::FloatImage image =
            rg::readImage(gpu, target, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        rg::writePng(opts.output, image);
        rg::writeReport(opts.report, rg::makeReport(opts, gpu, times));
        std::printf("Wrote %s and %s\n", opts.output.c_str(), opts.report.c_str());
        if (app.window) showInWindow(gpu, *app.window, target, deletion, opts.frames);
    });
}
