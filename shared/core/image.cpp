#include "core/image.h"

#include "core/display.h"
#include "core/files.h"

#include <stb_image_write.h>

#include <fstream>
#include <stdexcept>

namespace rg {

void writePng(const std::string& path, const FloatImage& image) {
    std::vector<uint8_t> rgb(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = toDisplay8(image.rgba[4 * i + c]);
    std::string png;  // encoded in memory: stb's own file writer ignores write errors
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, int(image.width), int(image.height), 3,
                                rgb.data(), int(image.width) * 3))
        throw std::runtime_error("cannot encode " + path);
    writeFileAtomically(path, png.data(), png.size());
}

void writePfm(const std::string& path, const FloatImage& image) {
    std::string pfm = "PF\n" + std::to_string(image.width) + " " +
                      std::to_string(image.height) +
                      "\n-1.0\n";  // negative: little endian
    for (uint32_t y = image.height; y-- > 0;)  // PFM stores the bottom row first
        for (uint32_t x = 0; x < image.width; ++x)
            pfm.append(reinterpret_cast<const char*>(
                           &image.rgba[4 * (size_t(y) * image.width + x)]),
                       12);
    writeFileAtomically(path, pfm.data(), pfm.size());
}

FloatImage readPfm(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::string magic;
    FloatImage image;
    double scale = 0;
    if (!(file >> magic >> image.width >> image.height >> scale) || magic != "PF" ||
        scale >= 0)
        throw std::runtime_error(path + ": not a little-endian RGB PFM file");
    file.get();
    image.rgba.assign(size_t(image.width) * image.height * 4, 1.0f);
    for (uint32_t y = image.height; y-- > 0;)
        for (uint32_t x = 0; x < image.width; ++x)
            if (!file.read(reinterpret_cast<char*>(
                               &image.rgba[4 * (size_t(y) * image.width + x)]),
                           12))
                throw std::runtime_error(path + ": truncated PFM file");
    return image;
}

}  // namespace rg
