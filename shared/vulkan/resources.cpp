#include "vulkan/resources.h"

#include "core/files.h"
#include "vk_check.h"

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace rg {

uint32_t findMemoryType(const Gpu& gpu, uint32_t typeBits,
                        VkMemoryPropertyFlags properties) {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(gpu.physical.handle, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) &&
            (memory.memoryTypes[i].propertyFlags & properties) == properties)
            return i;
    throw std::runtime_error("no memory type with the requested properties");
}

Buffer createBuffer(const Gpu& gpu, DeletionQueue& deletion, VkDeviceSize size,
                    VkBufferUsageFlags usage, VkMemoryPropertyFlags properties) {
    Buffer buffer{.size = size};
    VkBufferCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VK_CHECK(vkCreateBuffer(gpu.device, &info, nullptr, &buffer.handle));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(gpu.device, buffer.handle, &requirements);
    // [region device_address]
    // A buffer that the GPU reads by address (build inputs, acceleration
    // structures, the SBT) needs the usage bit and memory allocated with
    // DEVICE_ADDRESS; vkGetBufferDeviceAddress then gives a 64-bit pointer.
    bool addressable = usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateFlagsInfo flags{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT,
    };
    VkMemoryAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = addressable ? &flags : nullptr,
        .allocationSize = requirements.size,
        .memoryTypeIndex = findMemoryType(gpu, requirements.memoryTypeBits, properties),
    };
    VK_CHECK(vkAllocateMemory(gpu.device, &allocate, nullptr, &buffer.memory));
    VK_CHECK(vkBindBufferMemory(gpu.device, buffer.handle, buffer.memory, 0));
    if (properties & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
        VK_CHECK(
            vkMapMemory(gpu.device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
    if (addressable) {
        VkBufferDeviceAddressInfo address{
            .sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO,
            .buffer = buffer.handle};
        buffer.address = vkGetBufferDeviceAddress(gpu.device, &address);
    }
    // [end]
    VkDevice device = gpu.device;
    deletion.push([device, buffer] {
        vkDestroyBuffer(device, buffer.handle, nullptr);
        vkFreeMemory(device, buffer.memory, nullptr);  // unmaps implicitly
    });
    return buffer;
}

Buffer createHostBuffer(const Gpu& gpu, DeletionQueue& deletion, VkDeviceSize size,
                        VkBufferUsageFlags usage) {
    return createBuffer(
        gpu, deletion, size, usage,
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
}

Buffer createDeviceBuffer(const Gpu& gpu, DeletionQueue& deletion, const void* data,
                          VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer buffer =
        createBuffer(gpu, deletion, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    DeletionQueue staging;  // freed when this function returns, after the copy finished
    Buffer upload =
        createHostBuffer(gpu, staging, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::memcpy(upload.mapped, data, size);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        VkBufferCopy region{.size = size};
        vkCmdCopyBuffer(cmd, upload.handle, buffer.handle, 1, &region);
    });
    return buffer;
}

Image createImage2D(const Gpu& gpu, DeletionQueue& deletion, uint32_t width,
                    uint32_t height, VkFormat format, VkImageUsageFlags usage,
                    uint32_t levels) {
    Image image{.format = format, .extent = {width, height}, .levels = levels};
    VkImageCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = format,
        .extent = {width, height, 1},
        .mipLevels = levels,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    VK_CHECK(vkCreateImage(gpu.device, &info, nullptr, &image.handle));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(gpu.device, image.handle, &requirements);
    image.bytes = requirements.size;
    VkMemoryAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = requirements.size,
        .memoryTypeIndex = findMemoryType(gpu, requirements.memoryTypeBits,
                                          VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
    };
    VK_CHECK(vkAllocateMemory(gpu.device, &allocate, nullptr, &image.memory));
    VK_CHECK(vkBindImageMemory(gpu.device, image.handle, image.memory, 0));
    VkImageViewCreateInfo view{
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = image.handle,
        .viewType = VK_IMAGE_VIEW_TYPE_2D,
        .format = format,
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1},
    };
    VK_CHECK(vkCreateImageView(gpu.device, &view, nullptr, &image.view));
    VkDevice device = gpu.device;
    deletion.push([device, image] {
        vkDestroyImageView(device, image.view, nullptr);
        vkDestroyImage(device, image.handle, nullptr);
        vkFreeMemory(device, image.memory, nullptr);
    });
    return image;
}

void submitOnce(const Gpu& gpu, const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = gpu.commandPool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(gpu.device, &allocate, &cmd));
    DeletionQueue local;
    local.push([&] { vkFreeCommandBuffers(gpu.device, gpu.commandPool, 1, &cmd); });
    VkCommandBufferBeginInfo begin{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(gpu.device, &fenceInfo, nullptr, &fence));
    local.push([&] { vkDestroyFence(gpu.device, fence, nullptr); });
    VkSubmitInfo submit{
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &cmd,
    };
    VK_CHECK(vkQueueSubmit(gpu.queue, 1, &submit, fence));
    VK_CHECK(vkWaitForFences(gpu.device, 1, &fence, VK_TRUE, UINT64_MAX));
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags srcStage,
                  VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess) {
    VkImageMemoryBarrier barrier{
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
        .srcAccessMask = srcAccess,  // writes to make available
        .dstAccessMask = dstAccess,  // accesses that must see them
        .oldLayout = oldLayout,
        .newLayout = newLayout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        // every mip level (chapter 12's textures have several)
        .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1},
    };
    vkCmdPipelineBarrier(cmd,
                         srcStage,        // stages that must finish first
                         dstStage,        // stages that wait
                         0,               // no dependency flags
                         0, nullptr,      // no global memory barriers
                         0, nullptr,      // no buffer barriers
                         1, &barrier);    // this image
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage,
                   VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                   VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                            .srcAccessMask = srcAccess,
                            .dstAccessMask = dstAccess};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

VkShaderModule loadShader(const Gpu& gpu, DeletionQueue& deletion,
                          const std::string& relative, const std::string& dir) {
    std::filesystem::path path =
        (dir.empty() ? executableDir() / "shaders" : std::filesystem::path(dir)) /
        (relative + ".spv");
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file)
        throw std::runtime_error("cannot open shader " + path.string() +
                                 " (was it built?)");
    std::vector<uint32_t> code(static_cast<size_t>(file.tellg()) / 4);
    file.seekg(0);
    file.read(reinterpret_cast<char*>(code.data()),
              static_cast<std::streamsize>(code.size() * 4));
    VkShaderModuleCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = code.size() * 4,
        .pCode = code.data(),
    };
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(gpu.device, &info, nullptr, &module));
    VkDevice device = gpu.device;
    deletion.push([device, module] { vkDestroyShaderModule(device, module, nullptr); });
    return module;
}

FloatImage readImage(const Gpu& gpu, const Image& image,
                     VkPipelineStageFlags lastWriter) {
    FloatImage out{image.extent.width, image.extent.height, {}};
    VkDeviceSize size = VkDeviceSize(out.width) * out.height * 4 * sizeof(float);
    DeletionQueue local;
    Buffer staging = createHostBuffer(gpu, local, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        // GENERAL -> TRANSFER_SRC for the copy, and back: shaders keep writing GENERAL.
        imageBarrier(cmd, image.handle, VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, lastWriter,
                     VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy region{
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .imageExtent = {out.width, out.height, 1},
        };
        vkCmdCopyImageToBuffer(cmd, image.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.handle, 1, &region);
        imageBarrier(cmd, image.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                     lastWriter, VK_ACCESS_SHADER_WRITE_BIT);
        VkBufferMemoryBarrier toHost{
            .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .buffer = staging.handle,
            .size = VK_WHOLE_SIZE,
        };
        vkCmdPipelineBarrier(cmd,
                             VK_PIPELINE_STAGE_TRANSFER_BIT,  // after the copy
                             VK_PIPELINE_STAGE_HOST_BIT,      // before the CPU reads
                             0, 0, nullptr, 1, &toHost, 0, nullptr);
    });
    out.rgba.resize(size / sizeof(float));
    std::memcpy(out.rgba.data(), staging.mapped, size);
    return out;
}

}  // namespace rg
