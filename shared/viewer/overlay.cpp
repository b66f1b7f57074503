#include "viewer/overlay.h"

#include "core/display.h"
#include "vk_check.h"
#include "vulkan/resources.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <stdexcept>

namespace rg {

namespace {
// The one place where Dear ImGui's versions differ for RayGlass: how the
// Vulkan backend takes the render pass and uploads its font texture.
// Debian 12 has 1.86, Debian 13 (and Ubuntu 24.04) 1.90.1: both tested.
// 1.90.3 to 1.91 take the render pass in the init info: written from their
// header, not run here. 1.92 manages textures itself: not supported yet.
void initVulkanBackend(const Gpu& gpu, ImGui_ImplVulkan_InitInfo& info,
                       VkRenderPass renderPass) {
#if IMGUI_VERSION_NUM >= 19200
#error "Dear ImGui 1.92 or newer: RayGlass's overlay supports 1.86 to 1.91"
#elif IMGUI_VERSION_NUM >= 19030
    info.RenderPass = renderPass;
    bool ok = ImGui_ImplVulkan_Init(&info);
#else
    bool ok = ImGui_ImplVulkan_Init(&info, renderPass);
#endif
    if (!ok) throw std::runtime_error("ImGui: Vulkan backend failed");
#if IMGUI_VERSION_NUM >= 19000
    (void)gpu;  // 1.90 records and waits for the upload on info.Queue itself
    if (!ImGui_ImplVulkan_CreateFontsTexture())
        throw std::runtime_error("ImGui: font upload failed");
#else
    submitOnce(gpu,
               [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
#endif
}
}  // namespace

Overlay::Overlay(const Gpu& gpu, Window& window) : gpu_(gpu), window_(window) {
    // The font texture's one descriptor (the 1.86 backend allocates one set).
    VkDescriptorPoolSize size{.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                              .descriptorCount = 4};
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT,
        .maxSets = 4,
        .poolSizeCount = 1,
        .pPoolSizes = &size,
    };
    VK_CHECK(vkCreateDescriptorPool(gpu.device, &poolInfo, nullptr, &pool_));

    // Draws over what the blit left: load, not clear; the frame loop moves the
    // image into and out of COLOR_ATTACHMENT_OPTIMAL around this pass.
    VkAttachmentDescription color{
        .format = window.format,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
    };
    VkAttachmentReference reference{.attachment = 0,
                                    .layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{
        .pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
        .colorAttachmentCount = 1,
        .pColorAttachments = &reference,
    };
    VkRenderPassCreateInfo passInfo{
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
        .attachmentCount = 1,
        .pAttachments = &color,
        .subpassCount = 1,
        .pSubpasses = &subpass,
    };
    VK_CHECK(vkCreateRenderPass(gpu.device, &passInfo, nullptr, &renderPass_));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini in the reader's working directory
    ImGui::StyleColorsDark();
    // The swapchain is *_SRGB: it encodes what is written. ImGui's colours are
    // sRGB already, so decode them once here or the overlay looks washed out.
    for (ImVec4& c : ImGui::GetStyle().Colors)
        c = ImVec4(float(srgbToLinear(c.x)), float(srgbToLinear(c.y)),
                   float(srgbToLinear(c.z)), c.w);
    if (!ImGui_ImplGlfw_InitForVulkan(window.handle(), true))
        throw std::runtime_error("ImGui: GLFW backend failed");

    uint32_t images = uint32_t(window.images.size());
    // fields set by name: their order differs between versions
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = gpu.instance;
    info.PhysicalDevice = gpu.physical.handle;
    info.Device = gpu.device;
    info.QueueFamily = gpu.physical.queueFamily;
    info.Queue = gpu.queue;
    info.DescriptorPool = pool_;
    info.MinImageCount = 2;
    // vertex buffers it cycles: at least the frames in flight
    info.ImageCount = images < 2 ? 2 : images;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = [](VkResult r) { VK_CHECK(r); };
    initVulkanBackend(gpu, info, renderPass_);
    swapchainRecreated();
}

Overlay::~Overlay() {
    vkDeviceWaitIdle(gpu_.device);
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    destroyFramebuffers();
    vkDestroyRenderPass(gpu_.device, renderPass_, nullptr);
    vkDestroyDescriptorPool(gpu_.device, pool_, nullptr);
}

void Overlay::destroyFramebuffers() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(gpu_.device, f, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(gpu_.device, v, nullptr);
    framebuffers_.clear();
    views_.clear();
}

void Overlay::swapchainRecreated() {
    destroyFramebuffers();  // the swapchain's re-creation waited for the device
    for (VkImage image : window_.images) {
        VkImageViewCreateInfo viewInfo{
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = image,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = window_.format,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
        VkImageView view = VK_NULL_HANDLE;
        VK_CHECK(vkCreateImageView(gpu_.device, &viewInfo, nullptr, &view));
        views_.push_back(view);
        VkFramebufferCreateInfo framebufferInfo{
            .sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
            .renderPass = renderPass_,
            .attachmentCount = 1,
            .pAttachments = &view,
            .width = window_.extent.width,
            .height = window_.extent.height,
            .layers = 1,
        };
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VK_CHECK(
            vkCreateFramebuffer(gpu_.device, &framebufferInfo, nullptr, &framebuffer));
        framebuffers_.push_back(framebuffer);
    }
    ImGui_ImplVulkan_SetMinImageCount(2);
}

void Overlay::beginFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    begun_ = true;
}

void Overlay::record(VkCommandBuffer cmd, uint32_t imageIndex) {
    if (!begun_) beginFrame();  // nothing was built this frame: draw an empty one
    ImGui::Render();
    begun_ = false;
    VkRenderPassBeginInfo begin{
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
        .renderPass = renderPass_,
        .framebuffer = framebuffers_[imageIndex],
        .renderArea = {{0, 0}, window_.extent},
    };
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

bool Overlay::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace rg
