#include "vulkan/frame_loop.h"

#include "core/interrupt.h"

#include "vk_check.h"

#include <algorithm>
#include <chrono>

namespace rg {

FrameLoop::FrameLoop(const Gpu& gpu, Window* window, const Image& target,
                     VkPipelineStageFlags renderStage, DeletionQueue& deletion)
    : gpu_(gpu),
      window_(window),
      target_(target),
      renderStage_(renderStage),
      deletion_(deletion),
      timer_(gpu, deletion, kFramesInFlight) {
    VkDevice device = gpu.device;
    VkCommandPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        // re-record each frame's buffer
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = gpu.physical.queueFamily,
    };
    VkCommandPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
    deletion.push([device, pool] { vkDestroyCommandPool(device, pool, nullptr); });

    // [region frame_sync_objects]
    for (Frame& f : frames_) {
        VkCommandBufferAllocateInfo allocate{
            .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
            .commandPool = pool,
            .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
            .commandBufferCount = 1,
        };
        VK_CHECK(vkAllocateCommandBuffers(device, &allocate, &f.cmd));
        // Created signalled: the first wait on a fresh frame returns at once.
        VkFenceCreateInfo fence{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO,
                                .flags = VK_FENCE_CREATE_SIGNALED_BIT};
        VK_CHECK(vkCreateFence(device, &fence, nullptr, &f.inFlight));
        VkSemaphoreCreateInfo semaphore{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VK_CHECK(vkCreateSemaphore(device, &semaphore, nullptr, &f.imageAvailable));
        VkEventCreateInfo event{.sType = VK_STRUCTURE_TYPE_EVENT_CREATE_INFO};
        VK_CHECK(vkCreateEvent(device, &event, nullptr, &f.rendered));
        deletion.push([device, f] {
            vkDestroyEvent(device, f.rendered, nullptr);
            vkDestroySemaphore(device, f.imageAvailable, nullptr);
            vkDestroyFence(device, f.inFlight, nullptr);
        });
    }
    // [end]
    deletion.push([device, semaphores = renderFinished_] {
        for (VkSemaphore s : *semaphores) vkDestroySemaphore(device, s, nullptr);
    });

    prepareTarget();
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(gpu.physical.handle, target.format, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT)
        blitFilter_ = VK_FILTER_LINEAR;
    if (window_) {
        window_->createSwapchain(gpu_, deletion_);
        ensureRenderFinishedSemaphores();
    }
}

void FrameLoop::prepareTarget() {
    // The target lives in GENERAL layout: shaders write it, blits and copies read it.
    submitOnce(gpu_, [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, target_.handle, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                     renderStage_, VK_ACCESS_SHADER_WRITE_BIT);
    });
}

void FrameLoop::ensureRenderFinishedSemaphores() {
    VkSemaphoreCreateInfo info{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    while (renderFinished_->size() < window_->images.size()) {
        VkSemaphore s = VK_NULL_HANDLE;
        VK_CHECK(vkCreateSemaphore(gpu_.device, &info, nullptr, &s));
        renderFinished_->push_back(s);
    }
}

void FrameLoop::recreateSwapchain() {
    window_->createSwapchain(gpu_, deletion_);
    ensureRenderFinishedSemaphores();
    if (swapchainRecreated) swapchainRecreated();
}

// [region frame_loop]
FrameTimes FrameLoop::run(int frames, const RecordFrame& record) {
    FrameTimes& times = times_;  // a member: the overlay shows it while frames run
    times = {};
    uint32_t frame = 0;
    while (frames == 0 || frame < uint32_t(frames)) {
        // Ctrl-C: the frames in flight finish below, then the run writes them
        if (interrupted()) break;
        auto cpuStart = std::chrono::steady_clock::now();
        if (window_) {
            window_->pollEvents();
            if (window_->shouldClose()) break;
        }
        uint32_t slot = frame % kFramesInFlight;
        Frame& f = frames_[slot];

        // 1. Fence (GPU -> CPU): wait until the GPU finished the frame that
        //    last used this slot, then its command buffer, semaphore and
        //    timestamps may be reused.
        VK_CHECK(vkWaitForFences(gpu_.device, 1, &f.inFlight, VK_TRUE, UINT64_MAX));
        if (f.timed) times.gpuMs.push_back(timer_.readMs(slot));
        f.timed = false;

        // 2. Acquire: the presentation engine signals f.imageAvailable when
        //    the image is really free; the CPU does not wait for it.
        uint32_t imageIndex = 0;
        if (window_) {
            VkResult acquired =
                vkAcquireNextImageKHR(gpu_.device, window_->swapchain, UINT64_MAX,
                                      f.imageAvailable, VK_NULL_HANDLE, &imageIndex);
            // resized: try again next iteration
            if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
                recreateSwapchain();
                continue;
            }
            if (acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);
        }
        // only once work will signal it
        VK_CHECK(vkResetFences(gpu_.device, 1, &f.inFlight));

        // 3. Record: barrier, the chapter's rendering (timed), presentation.
        VK_CHECK(vkResetCommandBuffer(f.cmd, 0));
        VkCommandBufferBeginInfo begin{
            .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
            .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
        };
        VK_CHECK(vkBeginCommandBuffer(f.cmd, &begin));
        // The previous frame wrote the target (and blitted from it): its
        // writes must land before this frame writes or reads it again.
        imageBarrier(
            f.cmd, target_.handle, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
            renderStage_ | VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            renderStage_, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        timer_.begin(f.cmd, slot);
        record(f.cmd, frame);
        timer_.end(f.cmd, slot);
        if (window_) recordPresentation(f.cmd, f, imageIndex);
        VK_CHECK(vkEndCommandBuffer(f.cmd));

        // 4. Submit: wait for the acquired image before the first transfer
        //    to it, signal renderFinished for present, and the fence for us.
        VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo submit{
            .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
            .waitSemaphoreCount = window_ ? 1u : 0u,
            .pWaitSemaphores = &f.imageAvailable,
            .pWaitDstStageMask = &waitStage,
            .commandBufferCount = 1,
            .pCommandBuffers = &f.cmd,
            .signalSemaphoreCount = window_ ? 1u : 0u,
            .pSignalSemaphores = window_ ? &(*renderFinished_)[imageIndex] : nullptr,
        };
        VK_CHECK(vkQueueSubmit(gpu_.queue, 1, &submit, f.inFlight));
        f.timed = true;

        // 5. Present once rendering finished (semaphore, GPU -> GPU).
        if (window_) {
            VkPresentInfoKHR present{
                .sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                .waitSemaphoreCount = 1,
                .pWaitSemaphores = &(*renderFinished_)[imageIndex],
                .swapchainCount = 1,
                .pSwapchains = &window_->swapchain,
                .pImageIndices = &imageIndex,
            };
            VkResult presented = vkQueuePresentKHR(gpu_.queue, &present);
            if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
                window_->resized())
                recreateSwapchain();
            else
                VK_CHECK(presented);
        }
        times.cpuMs.push_back(std::chrono::duration<double, std::milli>(
                                  std::chrono::steady_clock::now() - cpuStart)
                                  .count());
        ++frame;
    }
    VK_CHECK(vkDeviceWaitIdle(gpu_.device));
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {  // the last frames, oldest first
        Frame& f = frames_[(frame + i) % kFramesInFlight];
        if (f.timed) times.gpuMs.push_back(timer_.readMs((frame + i) % kFramesInFlight));
        f.timed = false;
    }
    return times;
}
// [end]

// [region present_blit]
void FrameLoop::recordPresentation(VkCommandBuffer cmd, Frame& f, uint32_t imageIndex) {
    VkImage swapImage = window_->images[imageIndex];
    // Event, set: the render is recorded; the clear below does not touch the
    // target, so it may run on the GPU while the render still finishes.
    if (!omitRenderBarrier) vkCmdSetEvent(cmd, f.rendered, renderStage_);

    imageBarrier(cmd, swapImage, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 // chained to the acquire semaphore's wait stage
                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    VkClearColorValue black{};
    VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1,
                         &whole);
    imageBarrier(cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 // clear ...
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 // ... before blit
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);

    // Event, wait: the blit reads the target only after the render wrote it.
    VkImageMemoryBarrier renderedToBlit{
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT,
        .oldLayout = VK_IMAGE_LAYOUT_GENERAL,
        .newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,  // the blit's preferred layout
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = target_.handle,
        .subresourceRange = whole,
    };
    if (omitRenderBarrier) {  // the bug chapter 02 shows: wait for nothing
        renderedToBlit.srcAccessMask = 0;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &renderedToBlit);
    } else {
        vkCmdWaitEvents(cmd,
                        1, &f.rendered,                  // the event set above
                        renderStage_,                    // stage given to vkCmdSetEvent
                        VK_PIPELINE_STAGE_TRANSFER_BIT,  // the blit waits
                        0, nullptr,                      // no global memory barriers
                        0, nullptr,                      // no buffer barriers
                        // the target's writes -> the blit's reads
                        1, &renderedToBlit);
        // ready for the next frame
        vkCmdResetEvent(cmd, f.rendered, VK_PIPELINE_STAGE_TRANSFER_BIT);
    }

    // Letterbox: keep the render's aspect ratio inside the window.
    VkExtent2D src = shown.width > 0 ? shown : target_.extent, dst = window_->extent;
    double scale =
        std::min(double(dst.width) / src.width, double(dst.height) / src.height);
    int32_t w = std::max(1, int32_t(src.width * scale)),
            h = std::max(1, int32_t(src.height * scale));
    int32_t x = (int32_t(dst.width) - w) / 2, y = (int32_t(dst.height) - h) / 2;
    VkImageBlit blit{
        .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .srcOffsets = {{0, 0, 0}, {int32_t(src.width), int32_t(src.height), 1}},
        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .dstOffsets = {{x, y, 0}, {x + w, y + h, 1}},
    };
    // Float -> *_SRGB: the blit converts, and the format encodes sRGB.
    vkCmdBlitImage(cmd, target_.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapImage,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, blitFilter_);
    // Back to GENERAL for the next frame's shaders (the next frame's first
    // barrier orders their writes after this blit's reads).
    imageBarrier(cmd, target_.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, renderStage_,
                 0);
    // drawn over the blitted image: the window's only pixels not ray traced
    if (overlay) {
        imageBarrier(
            cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
        overlay(cmd, imageIndex);
        imageBarrier(cmd, swapImage, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
        return;
    }
    imageBarrier(cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT,
                 // present waits on the semaphore
                 VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
}
// [end]

}  // namespace rg
