// Textures (chapter 12): decoding a file's texels, and the mip levels.
#include "scene/texture.h"

#include "core/display.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rg {

// [region decode_texture]
// The file's bytes are kept as they are, 4 a texel: base colour textures
// sRGB-encoded (glTF 2.0, 3.9.2), decoded to linear light where they are
// read (texture.glsl, and texelValue below for the reference), so that
// filtering and shading work in linear light.
Texture decodeTexture(const std::string& name, const unsigned char* rgba, int width,
                      int height, TexelData data) {
    Texture t{.name = name, .width = uint32_t(width), .height = uint32_t(height)};
    t.rgba.assign(rgba, rgba + size_t(width) * height * 4);
    t.levels = {{t.width, t.height, 0}};
    t.srgb = data == TexelData::Colour;
    // a data texture's alpha is no coverage: ignored
    for (size_t i = 3; i < t.rgba.size() && t.srgb && t.opaque; i += 4)
        t.opaque = t.rgba[i] == 255;
    buildMipLevels(t);
    return t;
}
// [end]

glm::dvec4 texelValue(const Texture& t, uint32_t level, uint32_t x, uint32_t y) {
    static const std::array<double, 256> kDecoded = [] {
        std::array<double, 256> table;
        for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(i / 255.0);
        return table;
    }();
    const TextureLevel& l = t.levels[level];
    const uint8_t* p = &t.rgba[l.offset + 4 * (size_t(y) * l.width + x)];
    auto channel = [&](int c) { return t.srgb ? kDecoded[p[c]] : p[c] / 255.0; };
    return {channel(0), channel(1), channel(2), t.opaque ? 1.0 : p[3] / 255.0};
}

// [region mip_levels]
// Each level halves the one above (rounding down, at least 1 texel): a
// texel is the mean of the 2x2 texels it covers, taken in linear light (an
// sRGB colour decoded, averaged, encoded again: averaging the encoded bytes
// would darken every edge), then stored in 8 bits like level 0. An odd
// side's last row or column is left out of the next level.
void buildMipLevels(Texture& t) {
    t.levels.resize(1);
    while (t.levels.back().width > 1 || t.levels.back().height > 1) {
        uint32_t from = uint32_t(t.levels.size() - 1);
        TextureLevel above = t.levels.back();
        TextureLevel level{std::max(1u, above.width / 2), std::max(1u, above.height / 2),
                           t.rgba.size()};
        t.rgba.resize(level.offset + 4 * size_t(level.width) * level.height);
        t.levels.push_back(level);
        for (uint32_t y = 0; y < level.height; ++y)
            for (uint32_t x = 0; x < level.width; ++x) {
                glm::dvec4 sum(0);
                for (uint32_t dy = 0; dy < 2; ++dy)
                    for (uint32_t dx = 0; dx < 2; ++dx)
                        sum += texelValue(t, from, std::min(2 * x + dx, above.width - 1),
                                          std::min(2 * y + dy, above.height - 1));
                glm::dvec4 mean = sum / 4.0;
                uint8_t* p = &t.rgba[level.offset + 4 * (size_t(y) * level.width + x)];
                for (int c = 0; c < 3; ++c)
                    p[c] = uint8_t(std::lround(
                        (t.srgb ? linearToSrgb(mean[c]) : std::clamp(mean[c], 0.0, 1.0)) *
                        255.0));
                p[3] = uint8_t(std::lround(mean.a * 255.0));
            }
    }
}
// [end]

}  // namespace rg
