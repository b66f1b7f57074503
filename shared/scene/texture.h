// A mesh's texture (chapter 12): an image of 8-bit RGBA texels with its
// sampler's wrap modes and filters, and its mip levels, built once at load
// in linear light. The GPU samples these bytes (rt_textures.h, texture.glsl)
// and the reference decodes the same bytes (reference/textures.cpp).
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rg {

enum class TextureWrap { Repeat, Clamp, Mirror };
// glTF's minification filters (3.8.4.3; OpenGL's names): the filter within
// a level, and how levels are chosen: none (level 0 only), the nearest
// level, or a blend of the two nearest (trilinear).
enum class TextureMipmap { None, Nearest, Linear };

struct TextureLevel {
    uint32_t width = 0, height = 0;
    size_t offset = 0;  // its first byte in Texture::rgba
};

struct Texture {
    std::string name;  // for messages: "board.glb: image 0"
    uint32_t width = 0, height = 0;  // level 0's
    // Every level's texels, RGBA 8 bits a channel, row-major, top row first,
    // level 0 first: what the GPU samples, decoding sRGB itself where `srgb`.
    std::vector<uint8_t> rgba;
    std::vector<TextureLevel> levels;  // level 0, then each half as wide and high
    bool srgb = true;    // a colour, sRGB-encoded; false: data (metal-roughness, normals)
    bool opaque = true;  // every texel's alpha is 255
    TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
    bool nearest = false;     // magnification NEAREST: no bilinear filter
    bool minNearest = false;  // minification NEAREST within a level
    // glTF leaves an unset minification filter to the viewer: trilinear here
    TextureMipmap mipmap = TextureMipmap::Linear;
};

// 8-bit RGBA texels as a texture, its mip levels built: colours are
// sRGB-encoded, data (metal-roughness, normals) linear already (glTF 2.0,
// 3.9.2-3.9.3).
enum class TexelData { Colour, Linear };
Texture decodeTexture(const std::string& name, const unsigned char* rgba, int width,
                      int height, TexelData data = TexelData::Colour);

// Adds every mip level down to 1x1 (floor(log2(max side)) + 1 in all).
void buildMipLevels(Texture& texture);

// Texel (x, y) of a level as linear rgb and alpha, decoded in double.
glm::dvec4 texelValue(const Texture& texture, uint32_t level, uint32_t x, uint32_t y);

}  // namespace rg
