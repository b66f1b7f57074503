// Descriptor sets and pipeline layouts as chapter 01 builds them, for any
// number of bindings: one layout, a pool sized for it, one set.
#pragma once
#include "vulkan/context.h"
#include "vulkan/resources.h"

#include <string>
#include <vector>

namespace rg {

struct DescriptorBinding {
    uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
    uint32_t count = 1;  // an array of this many (chapter 12's textures)
};

struct DescriptorSet {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
};

DescriptorSet createDescriptorSet(const Gpu& gpu, DeletionQueue& deletion,
                                  const std::vector<DescriptorBinding>& bindings);
void writeStorageImage(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                       VkImageView view);
void writeBuffer(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                 VkDescriptorType type, const Buffer& buffer);
void writeAccelerationStructure(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                                VkAccelerationStructureKHR as);

VkPipelineLayout createPipelineLayout(const Gpu& gpu, DeletionQueue& deletion,
                                      VkDescriptorSetLayout setLayout,
                                      uint32_t pushConstantBytes,
                                      VkShaderStageFlags pushStages);
VkPipeline createComputePipeline(const Gpu& gpu, DeletionQueue& deletion,
                                 VkPipelineLayout layout, const std::string& shader);

}  // namespace rg
