// GPU time from timestamp queries: two timestamps per slot, written by the
// GPU around the work; the difference times timestampPeriod is nanoseconds.
#pragma once
#include "context.h"

#include <optional>

namespace rg {

class GpuTimer {
public:
    GpuTimer(const Gpu& gpu, DeletionQueue& deletion, uint32_t slots);
    // resets the slot, then writes the first timestamp
    void begin(VkCommandBuffer cmd, uint32_t slot);
    void end(VkCommandBuffer cmd, uint32_t slot);
    // Milliseconds between begin and end; waits until the GPU has written them.
    double readMs(uint32_t slot) const;

private:
    VkDevice device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    double periodNs_;
    uint64_t mask_;
};

}  // namespace rg
