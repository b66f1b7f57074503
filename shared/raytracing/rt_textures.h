// Chapter 12's textures on the GPU: each one a sampled image of 8 bits a
// channel with its mip levels, all of them one array of
// descriptors that the shaders index by the material's texture record.
#pragma once
#include "scene/scene.h"
#include "vulkan/resources.h"

#include <cstdint>
#include <vector>

namespace rg {

struct RtTextures {
    // Scene::textures' order; one 1x1 stand-in when the scene has none (the
    // descriptor array is never empty)
    std::vector<Image> images;
    uint64_t texels = 0;      // of the scene's textures, level 0
    VkDeviceSize bytes = 0;   // the device memory their images take, every level
    uint32_t levels = 0;      // the most mip levels of any (1: --mips off)
};

// Throws InputError naming the scene when a texture is larger than the
// device's images may be, or there are more than a shader may bind.
void checkTexturesFit(const Gpu& gpu, const Scene& scene);

// Uploads every texture (waits for the copies) into an image the ray
// tracing shaders read.
RtTextures uploadTextures(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene);

// Binds them as the array `binding` (its descriptor count: images.size()).
void writeTextures(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                   const RtTextures& textures);

}  // namespace rg
