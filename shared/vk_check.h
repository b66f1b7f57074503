// VK_CHECK: every VkResult is checked, always (release builds too).
// A failure names the call, the VkResult and file:line, then throws
// rg::VulkanError so that main() can print one line and exit non-zero while
// the deletion queues still destroy what was created.
#pragma once
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace rg {

const char* vkResultName(VkResult result);

struct VulkanError : std::runtime_error {
    VkResult result;
    VulkanError(const std::string& what, VkResult r)
        : std::runtime_error(what), result(r) {}
};

[[noreturn]] void vkCheckFailed(const char* call, VkResult result, const char* file,
                                int line);

}  // namespace rg

#define VK_CHECK(call)                                                      \
    do {                                                                    \
        VkResult rg_result_ = (call);                                       \
        if (rg_result_ != VK_SUCCESS)                                       \
            ::rg::vkCheckFailed(#call, rg_result_, __FILE__, __LINE__);     \
    } while (0)
