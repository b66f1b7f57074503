// Dear ImGui (Debian's libimgui-dev 1.86) over the presented image. Its GLFW
// backend reads the mouse and the keyboard; its Vulkan backend draws in a
// render pass of its own on the swapchain image, after the ray traced image
// was blitted there (FrameLoop::overlay). So the overlay is only ever in the
// window: the target image, the PNGs and the reports never contain it.
#pragma once
#include "vulkan/context.h"
#include "vulkan/window.h"

#include <vector>

namespace rg {

class Overlay {
public:
    // Window's own callbacks must already be installed: ImGui chains to them.
    Overlay(const Gpu& gpu, Window& window);
    ~Overlay();  // before the device: the viewer owning it dies first
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    // Framebuffers for the window's current swapchain images.
    void swapchainRecreated();
    // Starts an ImGui frame: ImGui:: calls after it build the overlay.
    void beginFrame();
    // Records the frame's ImGui draws; the image is in COLOR_ATTACHMENT_OPTIMAL.
    void record(VkCommandBuffer cmd, uint32_t imageIndex);
    // ImGui uses the mouse or keyboard now (the camera must not react).
    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    void destroyFramebuffers();
    const Gpu& gpu_;
    Window& window_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    bool begun_ = false;  // beginFrame ran since the last record
};

}  // namespace rg
