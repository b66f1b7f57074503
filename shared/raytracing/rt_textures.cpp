#include "raytracing/rt_textures.h"

#include "core/files.h"
#include "vk_check.h"
#include "vulkan/device_limits.h"

#include <algorithm>
#include <cstring>

namespace rg {

void checkTexturesFit(const Gpu& gpu, const Scene& scene) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(gpu.physical.handle, &p);
    uint32_t side = p.limits.maxImageDimension2D;
    for (const auto& t : scene.textures)
        if (t->width > side || t->height > side)
            throw InputError(scene.path + ": " + t->name + ": " +
                             std::to_string(t->width) + "x" + std::to_string(t->height) +
                             " texels, larger than this device's images may be "
                             "(maxImageDimension2D " + std::to_string(side) + ")");
    uint32_t count = std::min(p.limits.maxPerStageDescriptorSampledImages,
                              p.limits.maxDescriptorSetSampledImages);
    if (scene.textures.size() > count)
        throw InputError(scene.path + ": the meshes use " +
                         std::to_string(scene.textures.size()) +
                         " textures, more than a shader may bind on this device (" +
                         std::to_string(count) + ")");
}

// [region texture_image]
// An image of one texture and its mip levels: 8 bits a channel as the file
// has them, 4 bytes a texel. UNORM for colours too: VK_FORMAT_R8G8B8A8_SRGB
// would decode sRGB in the read, but only within a tolerance (with it,
// chapter 12's picture on lavapipe moved by up to 7.9e-4), so the shader
// decodes with the exact curve (texture.glsl), as the reference does.
static Image textureImage(const Gpu& gpu, DeletionQueue& deletion, const Texture& t) {
    return createImage2D(gpu, deletion, t.width, t.height, VK_FORMAT_R8G8B8A8_UNORM,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                         uint32_t(t.levels.size()));
}
// [end]

RtTextures uploadTextures(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene) {
    RtTextures out;
    std::vector<const Texture*> textures;
    for (const auto& t : scene.textures) textures.push_back(t.get());
    // no textures: a 1x1 stand-in, so that the array still has an element
    Texture standIn{.name = "none", .width = 1, .height = 1};
    standIn.rgba = {255, 255, 255, 255};
    standIn.levels = {{1, 1, 0}};
    if (textures.empty()) textures.push_back(&standIn);
    VkDeviceSize staged = 0;
    for (const Texture* t : textures) {
        out.images.push_back(textureImage(gpu, deletion, *t));
        staged += t->rgba.size();
        if (t == &standIn) continue;
        out.bytes += out.images.back().bytes;
        out.texels += uint64_t(t->width) * t->height;
        out.levels = std::max(out.levels, uint32_t(t->levels.size()));
    }
    DeletionQueue local;  // the staging buffer lives until the copies are done
    Buffer staging =
        createHostBuffer(gpu, local, staged, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        VkDeviceSize offset = 0;
        for (size_t i = 0; i < textures.size(); ++i) {
            const Texture& t = *textures[i];
            std::memcpy(static_cast<char*>(staging.mapped) + offset, t.rgba.data(),
                        t.rgba.size());
            VkImage image = out.images[i].handle;
            imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            std::vector<VkBufferImageCopy> copies;  // one per mip level
            for (uint32_t level = 0; level < t.levels.size(); ++level)
                copies.push_back({
                    .bufferOffset = offset + t.levels[level].offset,
                    .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1},
                    .imageExtent = {t.levels[level].width, t.levels[level].height, 1},
                });
            vkCmdCopyBufferToImage(cmd, staging.handle, image,
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                   uint32_t(copies.size()), copies.data());
            // the copy's writes, visible to the ray tracing shaders' reads
            imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                         VK_ACCESS_SHADER_READ_BIT);
            offset += t.rgba.size();
        }
    });
    local.flush();
    return out;
}

void writeTextures(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                   const RtTextures& textures) {
    std::vector<VkDescriptorImageInfo> infos;
    for (const Image& image : textures.images)
        infos.push_back({.imageView = image.view,
                         .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = uint32_t(infos.size()),
        .descriptorType = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
        .pImageInfo = infos.data(),
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);
}

}  // namespace rg
