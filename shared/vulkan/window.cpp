#include "vulkan/window.h"

#include "vk_check.h"

#include <X11/Xlib.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <stdexcept>

namespace rg {

namespace {
// Xlib's default answer to a lost display connection (the X server went
// away) is exit(), which runs destructors while the GPU may still use the
// window's objects. Say so in one line and end the process at once: the
// system frees everything, no half-destroyed Vulkan state is left to report.
int onDisplayLost(Display*) {
    std::fprintf(
        stderr,
        "%s: error: the display connection was lost (the X server went away); quitting\n",
        program_invocation_short_name);
    std::fflush(stderr);
    _exit(1);
}
}  // namespace

Window::Window(int width, int height, const std::string& title) : title_(title) {
    if (!glfwInit())
        throw std::runtime_error(
            "GLFW cannot open a window here (no display?); use --headless");
    XSetIOErrorHandler(onDisplayLost);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("GLFW could not create a window; use --headless");
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) {
        static_cast<Window*>(glfwGetWindowUserPointer(w))->resized_ = true;
    });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
        Window* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        if (action == GLFW_PRESS) self->keys_.push_back({key, mods, self->events_++});
    });
    // Where the pointer was when a button went down: the last motion event
    // before it. glfwGetCursorPos asks the X server for the pointer now,
    // which after a slow frame (a second on lavapipe) is where a drag went.
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
        Window* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        self->cursor_[0] = x, self->cursor_[1] = y, self->cursorKnown_ = true;
        if (self->buttonsHeld_ > 0)
            self->pointer_.push_back({PointerEvent::Move, -1, x, y, self->events_++});
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
        Window* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        double x = self->cursor_[0], y = self->cursor_[1];
        if (!self->cursorKnown_) glfwGetCursorPos(w, &x, &y);  // no motion yet
        bool press = action == GLFW_PRESS;
        self->buttonsHeld_ = std::max(0, self->buttonsHeld_ + (press ? 1 : -1));
        self->pointer_.push_back(
            {press ? PointerEvent::Press : PointerEvent::Release, button, x, y,
             self->events_++});
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double y) {
        static_cast<Window*>(glfwGetWindowUserPointer(w))->scroll_ += y;
    });
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<const char*> Window::instanceExtensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw std::runtime_error("GLFW found no Vulkan surface support");
    return {names, names + count};
}

VkSurfaceKHR Window::createSurface(VkInstance instance, DeletionQueue& deletion) {
    VK_CHECK(glfwCreateWindowSurface(instance, window_, nullptr, &surface));
    VkSurfaceKHR s = surface;
    deletion.push([instance, s] { vkDestroySurfaceKHR(instance, s, nullptr); });
    return surface;
}

void Window::pollEvents() {
    glfwPollEvents();
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    while ((w == 0 || h == 0) && !glfwWindowShouldClose(window_)) {  // minimized
        glfwWaitEvents();
        glfwGetFramebufferSize(window_, &w, &h);
    }
}

void Window::createSwapchain(const Gpu& gpu, DeletionQueue& deletion) {
    bool first = device_ == VK_NULL_HANDLE;
    device_ = gpu.device;
    VK_CHECK(vkDeviceWaitIdle(gpu.device));  // the old images may still be in use

    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(
        vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu.physical.handle, surface, &caps));
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw std::runtime_error(
            "the surface's images cannot be blit targets (TRANSFER_DST)");
    // (COLOR_ATTACHMENT, the overlay's usage, every surface supports.)
    uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu.physical.handle, surface, &count,
                                                  nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu.physical.handle, surface, &count,
                                                  formats.data()));
    // An *_SRGB format applies the display transform (display.h) in hardware.
    VkSurfaceFormatKHR chosen = formats[0];
    for (const auto& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB ||
             f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            chosen = f;

    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    extent = caps.currentExtent.width != UINT32_MAX
                 ? caps.currentExtent
                 : VkExtent2D{std::clamp(uint32_t(w), caps.minImageExtent.width,
                                         caps.maxImageExtent.width),
                              std::clamp(uint32_t(h), caps.minImageExtent.height,
                                         caps.maxImageExtent.height)};
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainKHR old = swapchain;
    VkSwapchainCreateInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
        .surface = surface,
        .minImageCount = imageCount,
        .imageFormat = chosen.format,
        .imageColorSpace = chosen.colorSpace,
        .imageExtent = extent,
        .imageArrayLayers = 1,
        // Filled by a blit; the overlay (overlay.h) then draws on it.
        .imageUsage =
            VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
        .presentMode = VK_PRESENT_MODE_FIFO_KHR,  // always available; waits for vblank
        .clipped = VK_TRUE,
        .oldSwapchain = old,
    };
    VK_CHECK(vkCreateSwapchainKHR(gpu.device, &info, nullptr, &swapchain));
    if (old) vkDestroySwapchainKHR(gpu.device, old, nullptr);
    format = chosen.format;
    VK_CHECK(vkGetSwapchainImagesKHR(gpu.device, swapchain, &count, nullptr));
    images.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(gpu.device, swapchain, &count, images.data()));
    resized_ = false;
    if (first) deletion.push([this] { destroySwapchain(); });
}

void Window::destroySwapchain() {
    if (swapchain) vkDestroySwapchainKHR(device_, swapchain, nullptr);
    swapchain = VK_NULL_HANDLE;
}

}  // namespace rg
