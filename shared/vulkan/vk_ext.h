// The loader exports only core Vulkan; extension entry points (debug utils,
// acceleration structures, ray tracing pipelines) are fetched at run time.
// vk_ext.cpp defines them with their usual names, so chapters call
// vkCmdTraceRaysKHR(...) exactly as the specification writes it.
#pragma once
#include <vulkan/vulkan.h>

namespace rg {
void loadInstanceFunctions(VkInstance instance);
void loadDeviceFunctions(VkDevice device);
}  // namespace rg
