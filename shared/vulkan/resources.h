// Buffers, images, one-time command submission and SPIR-V loading.
#pragma once
#include "core/image.h"
#include "vulkan/context.h"
#include "vulkan/deletion_queue.h"

#include <vulkan/vulkan.h>

#include <filesystem>
#include <functional>
#include <string>

namespace rg {

struct Buffer {
    VkBuffer handle = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    VkDeviceAddress address = 0;  // when created with SHADER_DEVICE_ADDRESS usage
    void* mapped = nullptr;       // when host visible
};

struct Image {
    VkImage handle = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};         // level 0's
    uint32_t levels = 1;         // mip levels (chapter 12's textures)
    VkDeviceSize bytes = 0;      // the device memory it takes
};

uint32_t findMemoryType(const Gpu& gpu, uint32_t typeBits,
                        VkMemoryPropertyFlags properties);

Buffer createBuffer(const Gpu& gpu, DeletionQueue& deletion, VkDeviceSize size,
                    VkBufferUsageFlags usage, VkMemoryPropertyFlags properties);
// Host-visible, coherent, persistently mapped.
Buffer createHostBuffer(const Gpu& gpu, DeletionQueue& deletion, VkDeviceSize size,
                        VkBufferUsageFlags usage);
// Device-local buffer filled through a staging buffer (waits for the copy).
Buffer createDeviceBuffer(const Gpu& gpu, DeletionQueue& deletion, const void* data,
                          VkDeviceSize size, VkBufferUsageFlags usage);

Image createImage2D(const Gpu& gpu, DeletionQueue& deletion, uint32_t width,
                    uint32_t height, VkFormat format, VkImageUsageFlags usage,
                    uint32_t levels = 1);

// Records with `record`, submits, and waits on a fence: the simplest GPU->CPU
// synchronization (thesis 2.1.2), right for set-up work, never per frame.
void submitOnce(const Gpu& gpu, const std::function<void(VkCommandBuffer)>& record);

// One image layout transition / memory dependency on a whole color image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags srcStage,
                  VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess);

// One global memory dependency: `srcAccess` writes in `srcStage` made
// visible to `dstAccess` in `dstStage` (buffers; images need imageBarrier).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage,
                   VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                   VkAccessFlags dstAccess);

// Loads bin/shaders/<relative>.spv (or <dir>/<relative>.spv) into a shader module.
VkShaderModule loadShader(const Gpu& gpu, DeletionQueue& deletion,
                          const std::string& relative, const std::string& dir = {});

// Copies an RGBA32F image in GENERAL layout to the host. Waits for the GPU.
FloatImage readImage(const Gpu& gpu, const Image& image, VkPipelineStageFlags lastWriter);

}  // namespace rg
