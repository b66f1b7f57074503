// Images on the host: linear RGBA floats, written as a PNG through the one
// display transform (display.h) or as a lossless PFM (chapter 01 on).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rg {

// Linear RGBA float pixels, top row first.
struct FloatImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};

void writePng(const std::string& path, const FloatImage& image);
void writePfm(const std::string& path, const FloatImage& image);  // lossless, linear
FloatImage readPfm(const std::string& path);

}  // namespace rg
