// A run's sizes against the device's limits, checked before anything is
// built (every chapter): too large gets one line that names the limit and
// the largest size that fits (exit code 2), not a validation error or an
// out-of-memory failure after minutes of work.
#pragma once
#include "vulkan/context.h"

#include <string>

namespace rg {

// What grows with the image, besides the RGBA32F target (16 bytes a pixel,
// and as much again to read it back).
struct PixelCosts {
    // vkCmdTraceRaysKHR's limits, else a compute dispatch's
    bool rayTracing = true;
    uint32_t groupSize = 16;          // compute: the workgroup's width and height
    // the largest storage buffer bound by pixel (ray counts: 4)
    double storageBytesPerPixel = 0;
    // a buffer read by address, no range limit (chapter 10's queue)
    double addressedBytesPerPixel = 0;
};

// Throws InputError when `width` x `height` does not fit.
void checkImageFits(const Gpu& gpu, uint32_t width, uint32_t height,
                    const PixelCosts& costs);

// The most bytes one storage buffer may hold here (maxStorageBufferRange,
// or one allocation's maximum if smaller), and its name for a message.
double storageBufferLimit(const Gpu& gpu, std::string* name = nullptr);
std::string mebibytes(double bytes);

}  // namespace rg
