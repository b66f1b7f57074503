#include "vk_check.h"

#include <cstring>

namespace rg {

const char* vkResultName(VkResult result) {
    switch (result) {
#define RG_CASE(x) case x: return #x;
        RG_CASE(VK_SUCCESS) RG_CASE(VK_NOT_READY) RG_CASE(VK_TIMEOUT)
        RG_CASE(VK_EVENT_SET) RG_CASE(VK_EVENT_RESET) RG_CASE(VK_INCOMPLETE)
        RG_CASE(VK_ERROR_OUT_OF_HOST_MEMORY) RG_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        RG_CASE(VK_ERROR_INITIALIZATION_FAILED)
        RG_CASE(VK_ERROR_DEVICE_LOST) RG_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        RG_CASE(VK_ERROR_LAYER_NOT_PRESENT) RG_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        RG_CASE(VK_ERROR_FEATURE_NOT_PRESENT) RG_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        RG_CASE(VK_ERROR_TOO_MANY_OBJECTS) RG_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        RG_CASE(VK_ERROR_FRAGMENTED_POOL) RG_CASE(VK_ERROR_UNKNOWN)
        RG_CASE(VK_ERROR_OUT_OF_POOL_MEMORY) RG_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        RG_CASE(VK_ERROR_FRAGMENTATION) RG_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        RG_CASE(VK_ERROR_SURFACE_LOST_KHR) RG_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        RG_CASE(VK_SUBOPTIMAL_KHR) RG_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        RG_CASE(VK_ERROR_VALIDATION_FAILED_EXT) RG_CASE(VK_THREAD_IDLE_KHR)
        RG_CASE(VK_THREAD_DONE_KHR) RG_CASE(VK_OPERATION_DEFERRED_KHR)
        RG_CASE(VK_OPERATION_NOT_DEFERRED_KHR) RG_CASE(VK_PIPELINE_COMPILE_REQUIRED)
#undef RG_CASE
        default: return "VK_RESULT_UNKNOWN";
    }
}

void vkCheckFailed(const char* call, VkResult result, const char* file, int line) {
    const char* base = std::strrchr(file, '/');
    std::string what = std::string(call) + " returned " + vkResultName(result) + " at " +
                       (base ? base + 1 : file) + ":" + std::to_string(line);
    // Out of memory is no bug: say what to try (what was made is freed as
    // the error unwinds through the deletion queues).
    bool gpuMemory = result == VK_ERROR_OUT_OF_DEVICE_MEMORY;
    if (gpuMemory || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        what = std::string(gpuMemory ? "out of GPU memory" : "out of host memory") +
               " (" + what + "); try a smaller --width and --height or a smaller scene";
    throw VulkanError(what, result);
}

}  // namespace rg
