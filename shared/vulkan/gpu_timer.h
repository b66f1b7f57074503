// GPU time from timestamp queries: two timestamps per slot, written by the
// GPU around the work; the difference times timestampPeriod is nanoseconds.
#pragma once
#include "vulkan/context.h"

#include <optional>
#include <vector>

namespace rg {

// Per-frame measurements of a run.
struct FrameTimes {
    std::vector<double> gpuMs;  // timestamp queries around the chapter's work
    std::vector<double> cpuMs;  // wall clock of each frame on the host
};

double median(std::vector<double> values);

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
