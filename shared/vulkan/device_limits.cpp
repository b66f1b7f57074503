#include "vulkan/device_limits.h"

#include "core/files.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rg {

namespace {
struct DeviceLimits {
    VkPhysicalDeviceLimits core;
    VkDeviceSize maxAllocation = 0;    // one vkAllocateMemory
    VkDeviceSize deviceLocalHeap = 0;  // the largest DEVICE_LOCAL heap
};

DeviceLimits readLimits(const Gpu& gpu) {
    VkPhysicalDeviceVulkan11Properties v11{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &v11};
    vkGetPhysicalDeviceProperties2(gpu.physical.handle, &properties);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(gpu.physical.handle, &memory);
    DeviceLimits l{.core = properties.properties.limits,
                   .maxAllocation = v11.maxMemoryAllocationSize};
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            l.deviceLocalHeap = std::max(l.deviceLocalHeap, memory.memoryHeaps[i].size);
    return l;
}

}  // namespace

std::string mebibytes(double b) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", b / (1024.0 * 1024.0));
    return text;
}

namespace {
// The first limit that w x h breaks, or "".
std::string brokenLimit(const DeviceLimits& l, const Gpu& gpu, double w, double h,
                        const PixelCosts& c) {
    const VkPhysicalDeviceLimits& k = l.core;
    if (w > k.maxImageDimension2D || h > k.maxImageDimension2D)
        return "maxImageDimension2D (" + std::to_string(k.maxImageDimension2D) +
               " pixels a side)";
    if (c.rayTracing) {
        if (w * h > gpu.physical.rayTracing.maxRayDispatchInvocationCount)
            return "maxRayDispatchInvocationCount (" +
                   std::to_string(gpu.physical.rayTracing.maxRayDispatchInvocationCount) +
                   " rays a launch)";
        if (w > double(k.maxComputeWorkGroupCount[0]) * k.maxComputeWorkGroupSize[0] ||
            h > double(k.maxComputeWorkGroupCount[1]) * k.maxComputeWorkGroupSize[1])
            return "maxComputeWorkGroupCount x maxComputeWorkGroupSize (a launch's width "
                   "and height)";
    } else if (std::ceil(w / c.groupSize) > k.maxComputeWorkGroupCount[0] ||
               std::ceil(h / c.groupSize) > k.maxComputeWorkGroupCount[1]) {
        return "maxComputeWorkGroupCount (" +
               std::to_string(k.maxComputeWorkGroupCount[0]) + " x " +
               std::to_string(k.maxComputeWorkGroupCount[1]) + " workgroups)";
    }
    double pixels = w * h;
    if (c.storageBytesPerPixel * pixels > k.maxStorageBufferRange)
        return "maxStorageBufferRange (" + mebibytes(k.maxStorageBufferRange) +
               " in one per-pixel buffer)";
    // The image (and the buffer it is read back through), or a larger buffer.
    if (std::max(16.0, c.addressedBytesPerPixel) * pixels > l.maxAllocation)
        return "maxMemoryAllocationSize (" + mebibytes(double(l.maxAllocation)) +
               " in one allocation)";
    double device = (16 + c.storageBytesPerPixel + c.addressedBytesPerPixel) * pixels;
    // room for the rest
    if (l.deviceLocalHeap > 0 && device > 0.75 * double(l.deviceLocalHeap))
        return "the device memory (" + mebibytes(double(l.deviceLocalHeap)) +
               ", of which a run may take 3/4)";
    return "";
}
}  // namespace

void checkImageFits(const Gpu& gpu, uint32_t width, uint32_t height,
                    const PixelCosts& costs) {
    DeviceLimits limits = readLimits(gpu);
    std::string broken = brokenLimit(limits, gpu, width, height, costs);
    if (broken.empty()) return;
    // The largest size of the same shape that fits: every limit grows with
    // the scale, so bisect it.
    double lo = 0, hi = 1;
    for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        bool fits = brokenLimit(limits, gpu, std::floor(width * mid),
                                std::floor(height * mid), costs)
                        .empty();
        (fits ? lo : hi) = mid;
    }
    uint32_t w = std::max(1u, uint32_t(std::floor(width * lo))),
             h = std::max(1u, uint32_t(std::floor(height * lo)));
    throw InputError(std::to_string(width) + "x" + std::to_string(height) +
                     " is too large for this device: " + broken +
                     "; the largest size of this shape that fits is --width " +
                     std::to_string(w) + " --height " + std::to_string(h));
}

double storageBufferLimit(const Gpu& gpu, std::string* name) {
    DeviceLimits limits = readLimits(gpu);
    bool range = limits.core.maxStorageBufferRange <= limits.maxAllocation;
    if (name) *name = range ? "maxStorageBufferRange" : "maxMemoryAllocationSize";
    return range ? double(limits.core.maxStorageBufferRange)
                 : double(limits.maxAllocation);
}

}  // namespace rg
