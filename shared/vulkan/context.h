// The Vulkan objects of thesis figure 2.1 that every chapter needs, in the
// order they are created: instance (with the validation layer's messenger),
// physical device choice, device and queue. Chapter 01 teaches them.
#pragma once
#include "vulkan/deletion_queue.h"

#include <vulkan/vulkan.h>

#include <atomic>
#include <string>
#include <vector>

namespace rg {

// Every message of the validation layer is printed and counted here.
std::atomic<uint32_t>& validationMessageCount();

VkInstance createInstance(const std::string& appName, bool validation,
                          const std::vector<const char*>& windowExtensions,
                          DeletionQueue& deletion);

struct PhysicalDeviceChoice {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    uint32_t index = 0;
    uint32_t queueFamily = 0;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceRayTracingPipelinePropertiesKHR rayTracing{};
    VkPhysicalDeviceAccelerationStructurePropertiesKHR accelerationStructure{};
    std::string driver;  // driver name and info, e.g. "llvmpipe / Mesa 25.0.7"
    // optional: a launch sized by the GPU (chapter 10's second launch)
    bool traceRaysIndirect = false;
    // optional: double in shaders (chapter 12's --triangles watertight)
    bool shaderFloat64 = false;
};

// The device extensions a ray tracing chapter needs.
std::vector<const char*> requiredDeviceExtensions(bool present);

// Lists every device with what it lacks; takes `requested` (>= 0) or else the
// best fit (discrete > integrated > virtual > CPU). Throws with the list of
// what is missing when none fits.
PhysicalDeviceChoice pickPhysicalDevice(VkInstance instance, VkSurfaceKHR surface,
                                        int requested);

struct Gpu {
    VkInstance instance = VK_NULL_HANDLE;
    PhysicalDeviceChoice physical;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE;  // for one-time submissions
};

// One queue that does graphics, compute and transfer (and presents, when a
// surface is given), with ray tracing and buffer device addresses enabled.
VkDevice createDevice(const PhysicalDeviceChoice& physical, bool present,
                      DeletionQueue& deletion);

}  // namespace rg
