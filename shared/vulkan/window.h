// A GLFW window with a Vulkan surface and a swapchain that follows resizes.
// Presentation itself (acquire, blit, present) is in frame_loop.cpp.
#pragma once
#include "vulkan/context.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rg {

class Window {
public:
    // throws when no window can be opened
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    std::vector<const char*> instanceExtensions() const;
    VkSurfaceKHR createSurface(VkInstance instance, DeletionQueue& deletion);
    // (Re)creates the swapchain at the framebuffer's size. The first call
    // pushes its destruction onto `deletion` (before the device's).
    void createSwapchain(const Gpu& gpu, DeletionQueue& deletion);

    bool shouldClose() const { return glfwWindowShouldClose(window_); }
    // Processes events; while minimized (zero-sized framebuffer) it blocks
    // until the window is visible again or closed.
    void pollEvents();
    bool resized() const { return resized_; }
    void setTitle(const std::string& title) {
        glfwSetWindowTitle(window_, title.c_str());
    }
    const std::string& initialTitle() const { return title_; }
    // The keys pressed since the last call, oldest first, with the modifiers
    // held at the time (Ctrl+Q must not be read after Ctrl was let go).
    // Both kinds of event carry their place in one sequence (`order`): a
    // drag and the key after it can arrive in one poll, and must be taken
    // in that order.
    struct KeyPress {
        int key;   // GLFW_KEY_*
        int mods;  // GLFW_MOD_*
        uint64_t order;
    };
    std::vector<KeyPress> takeKeys() { return std::exchange(keys_, {}); }
    // Mouse button presses and releases since the last call, and the moves
    // while a button is held, oldest first, with the cursor's position then:
    // on a slow frame a whole click or drag can start and end in one poll.
    struct PointerEvent {
        enum Kind { Press, Release, Move } kind;
        int button;   // GLFW_MOUSE_BUTTON_* (Press, Release)
        double x, y;  // window coordinates
        uint64_t order;
    };
    std::vector<PointerEvent> takePointer() { return std::exchange(pointer_, {}); }
    // Scroll wheel steps since the last call (up: positive).
    double takeScroll() { return std::exchange(scroll_, 0.0); }
    GLFWwindow* handle() const { return window_; }

    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    std::vector<VkImage> images;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};

private:
    void destroySwapchain();
    GLFWwindow* window_ = nullptr;
    VkDevice device_ = VK_NULL_HANDLE;
    bool resized_ = false;
    std::vector<KeyPress> keys_;
    std::vector<PointerEvent> pointer_;
    double cursor_[2] = {0, 0};  // from the last motion event
    bool cursorKnown_ = false;
    int buttonsHeld_ = 0;  // moves are queued only while a button is down
    uint64_t events_ = 0;  // events so far: the next one's order
    double scroll_ = 0;
    std::string title_;
};

}  // namespace rg
