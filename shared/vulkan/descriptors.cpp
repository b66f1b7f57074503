#include "vulkan/descriptors.h"

#include "vk_check.h"

namespace rg {

DescriptorSet createDescriptorSet(const Gpu& gpu, DeletionQueue& deletion,
                                  const std::vector<DescriptorBinding>& bindings) {
    DescriptorSet d;
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& b : bindings) {
        layoutBindings.push_back({.binding = b.binding,
                                  .descriptorType = b.type,
                                  .descriptorCount = b.count,
                                  .stageFlags = b.stages});
        sizes.push_back({.type = b.type, .descriptorCount = b.count});
    }
    VkDescriptorSetLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = uint32_t(layoutBindings.size()),
        .pBindings = layoutBindings.data(),
    };
    VK_CHECK(vkCreateDescriptorSetLayout(gpu.device, &layoutInfo, nullptr, &d.layout));
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = uint32_t(sizes.size()),
        .pPoolSizes = sizes.data(),
    };
    VK_CHECK(vkCreateDescriptorPool(gpu.device, &poolInfo, nullptr, &d.pool));
    VkDevice device = gpu.device;
    deletion.push([device, d] {
        vkDestroyDescriptorPool(device, d.pool, nullptr);
        vkDestroyDescriptorSetLayout(device, d.layout, nullptr);
    });
    VkDescriptorSetAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = d.pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &d.layout,
    };
    VK_CHECK(vkAllocateDescriptorSets(gpu.device, &allocate, &d.set));
    return d;
}

void writeStorageImage(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                       VkImageView view) {
    VkDescriptorImageInfo image{.imageView = view,
                                .imageLayout = VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
        .pImageInfo = &image,
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);
}

void writeBuffer(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                 VkDescriptorType type, const Buffer& buffer) {
    VkDescriptorBufferInfo info{
        .buffer = buffer.handle, .offset = 0, .range = VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = type,
        .pBufferInfo = &info,
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);
}

void writeAccelerationStructure(const Gpu& gpu, VkDescriptorSet set, uint32_t binding,
                                VkAccelerationStructureKHR as) {
    VkWriteDescriptorSetAccelerationStructureKHR info{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
        .accelerationStructureCount = 1,
        .pAccelerationStructures = &as,
    };
    VkWriteDescriptorSet write{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
        .pNext = &info,  // acceleration structures are written through the chained struct
        .dstSet = set,
        .dstBinding = binding,
        .descriptorCount = 1,
        .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR,
    };
    vkUpdateDescriptorSets(gpu.device, 1, &write, 0, nullptr);
}

VkPipelineLayout createPipelineLayout(const Gpu& gpu, DeletionQueue& deletion,
                                      VkDescriptorSetLayout setLayout,
                                      uint32_t pushConstantBytes,
                                      VkShaderStageFlags pushStages) {
    VkPushConstantRange push{.stageFlags = pushStages, .size = pushConstantBytes};
    VkPipelineLayoutCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &setLayout,
        .pushConstantRangeCount = pushConstantBytes ? 1u : 0u,
        .pPushConstantRanges = &push,
    };
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(gpu.device, &info, nullptr, &layout));
    VkDevice device = gpu.device;
    deletion.push([device, layout] { vkDestroyPipelineLayout(device, layout, nullptr); });
    return layout;
}

VkPipeline createComputePipeline(const Gpu& gpu, DeletionQueue& deletion,
                                 VkPipelineLayout layout, const std::string& shader) {
    VkComputePipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = loadShader(gpu, deletion, shader),
            .pName = "main",
        },
        .layout = layout,
    };
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateComputePipelines(gpu.device, VK_NULL_HANDLE, 1, &info, nullptr,
                                      &pipeline));
    VkDevice device = gpu.device;
    deletion.push([device, pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });
    return pipeline;
}

}  // namespace rg
