// The one display transform (thesis chapters shade in linear radiance):
// clamp to [0, 1], then the sRGB transfer function. The GPU's window path
// gets the same function from its *_SRGB swapchain format; the PNG writer
// and every error metric use this code. Header-only, used by the CPU
// reference too.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rg {

inline double linearToSrgb(double linear) {
    double c = std::clamp(linear, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

inline double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92
                              : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// NaN is shown as 0 (black) here; the reports count NaN/Inf separately.
inline uint8_t toDisplay8(double linear) {
    if (std::isnan(linear)) return 0;
    return static_cast<uint8_t>(std::lround(linearToSrgb(linear) * 255.0));
}

}  // namespace rg
