#include "vulkan/gpu_timer.h"

#include "vk_check.h"

#include <algorithm>

namespace rg {

GpuTimer::GpuTimer(const Gpu& gpu, DeletionQueue& deletion, uint32_t slots)
    : device_(gpu.device), periodNs_(gpu.physical.properties.limits.timestampPeriod) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical.handle, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical.handle, &count,
                                             families.data());
    uint32_t bits = families[gpu.physical.queueFamily].timestampValidBits;
    mask_ = bits >= 64 ? ~0ull : (1ull << bits) - 1;
    VkQueryPoolCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_TIMESTAMP,
        .queryCount = 2 * slots,
    };
    VK_CHECK(vkCreateQueryPool(device_, &info, nullptr, &pool_));
    // hostQueryReset: queries start reset
    vkResetQueryPool(device_, pool_, 0, 2 * slots);
    VkDevice device = device_;
    VkQueryPool pool = pool_;
    deletion.push([device, pool] { vkDestroyQueryPool(device, pool, nullptr); });
}

void GpuTimer::begin(VkCommandBuffer cmd, uint32_t slot) {
    vkCmdResetQueryPool(cmd, pool_, 2 * slot, 2);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_, 2 * slot);
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t slot) {
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * slot + 1);
}

double GpuTimer::readMs(uint32_t slot) const {
    uint64_t stamps[2] = {0, 0};
    VK_CHECK(vkGetQueryPoolResults(device_, pool_, 2 * slot, 2, sizeof(stamps), stamps,
                                   sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    uint64_t ticks = (stamps[1] - stamps[0]) & mask_;
    return static_cast<double>(ticks) * periodNs_ * 1e-6;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace rg
