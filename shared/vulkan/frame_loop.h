// Frames in flight (thesis 2.1.2, chapter 02): the CPU records frame N+1
// while the GPU still renders frame N. Fences tell the CPU when a frame's
// resources are free again, semaphores order acquire -> render -> present on
// the GPU, an event lets the swapchain clear run while the render finishes,
// and pipeline barriers order the accesses to the render target.
#pragma once
#include "vulkan/context.h"
#include "vulkan/gpu_timer.h"
#include "vulkan/resources.h"
#include "vulkan/window.h"

#include <functional>
#include <memory>

namespace rg {

// Records the chapter's rendering into the target image (GENERAL layout).
using RecordFrame = std::function<void(VkCommandBuffer cmd, uint32_t frame)>;

class FrameLoop {
public:
    static constexpr uint32_t kFramesInFlight = 2;

    // window == nullptr: headless. renderStage: the stage that writes the
    // target (compute shader in chapters 01-02, ray tracing from 03 on).
    FrameLoop(const Gpu& gpu, Window* window, const Image& target,
              VkPipelineStageFlags renderStage, DeletionQueue& deletion);

    // Renders `frames` frames, or until the window closes when frames == 0.
    FrameTimes run(int frames, const RecordFrame& record);

    // Chapter 02's experiment: the blit waits for nothing (TOP_OF_PIPE, no
    // access) instead of the render's writes; synchronization validation
    // reports the read-after-write hazard (windowed runs only: headless
    // frames have no blit).
    bool omitRenderBarrier = false;

    // Interactive chapters (viewer.h) hook in here. overlay: records draws
    // over the presented image after the blit (it is in
    // COLOR_ATTACHMENT_OPTIMAL then). swapchainRecreated: runs after a
    // resize re-created the swapchain, with the device idle.
    std::function<void(VkCommandBuffer cmd, uint32_t imageIndex)> overlay;
    std::function<void()> swapchainRecreated;
    // The target's top left corner that the window shows (0x0: all of it):
    // the viewer traces a smaller image while a slow view moves.
    VkExtent2D shown{};

    // The target was re-created (a resize): moves it into GENERAL layout.
    void prepareTarget();
    // The frames measured so far in run().
    const FrameTimes& times() const { return times_; }

private:
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        // signalled when the GPU finished this frame
        VkFence inFlight = VK_NULL_HANDLE;
        VkSemaphore imageAvailable = VK_NULL_HANDLE;  // acquire -> render
        // render -> blit, with work in between
        VkEvent rendered = VK_NULL_HANDLE;
        bool timed = false;                           // its timestamps wait to be read
    };
    void recordPresentation(VkCommandBuffer cmd, Frame& frame, uint32_t imageIndex);
    void recreateSwapchain();
    void ensureRenderFinishedSemaphores();

    const Gpu& gpu_;
    Window* window_;
    const Image& target_;
    VkPipelineStageFlags renderStage_;
    DeletionQueue& deletion_;
    GpuTimer timer_;
    Frame frames_[kFramesInFlight];
    // One per swapchain image: render -> present. Shared with the deletion
    // queue, which destroys them after this object is gone.
    std::shared_ptr<std::vector<VkSemaphore>> renderFinished_ =
        std::make_shared<std::vector<VkSemaphore>>();
    VkFilter blitFilter_ = VK_FILTER_NEAREST;
    FrameTimes times_;
};

}  // namespace rg
