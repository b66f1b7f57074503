#include "raytracing/rt_pipeline.h"

#include "vk_check.h"
#include "vulkan/descriptors.h"

#include <cstring>
#include <iterator>

namespace rg {

// [region create_pipeline]
RtPipeline createRtPipeline(const Gpu& gpu, DeletionQueue& deletion,
                            VkDescriptorSetLayout setLayout, uint32_t pushConstantBytes,
                            const RtShaders& shaders, uint32_t maxRecursion) {
    RtPipeline p;
    p.maxRecursion = maxRecursion;
    p.layout =
        createPipelineLayout(gpu, deletion, setLayout, pushConstantBytes, kRtPushStages);

    // Specialization: the driver compiles each stage with constants 0-8
    // fixed, so branches on them cost nothing (and no registers). One list
    // for every stage: an entry a shader does not declare is ignored.
    uint32_t constants[] = {shaders.raygenConstant, shaders.raygenAverages,
                            shaders.carefulSizes,   shaders.carefulShininess,
                            shaders.alphaTest,      shaders.thinWalls,
                            shaders.rayCones,       shaders.sunDiscs,
                            shaders.meshes};
    constexpr uint32_t kConstants = std::size(constants);
    VkSpecializationMapEntry entries[kConstants];
    for (uint32_t id = 0; id < kConstants; ++id)
        entries[id] = {.constantID = id,
                       .offset = id * uint32_t(sizeof(uint32_t)),
                       .size = sizeof(uint32_t)};
    VkSpecializationInfo specialization{.mapEntryCount = kConstants,
                                        .pMapEntries = entries,
                                        .dataSize = sizeof constants,
                                        .pData = constants};
    // Every stage of the pipeline, and the groups that point into that list:
    // group 0 raygen, then the miss groups, then the hit groups (the SBT's order).
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups;
    auto addStage = [&](VkShaderStageFlagBits stage, const std::string& path) {
        stages.push_back({.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                          .stage = stage,
                          .module = loadShader(gpu, deletion, path, shaders.spirvDir),
                          .pName = "main",
                          .pSpecializationInfo = &specialization});
        return uint32_t(stages.size() - 1);
    };
    auto general = [&](uint32_t stage) {
        groups.push_back(
            {.sType = VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR,
             .type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR,
             .generalShader = stage,
             .closestHitShader = VK_SHADER_UNUSED_KHR,
             .anyHitShader = VK_SHADER_UNUSED_KHR,
             .intersectionShader = VK_SHADER_UNUSED_KHR});
    };
    general(addStage(VK_SHADER_STAGE_RAYGEN_BIT_KHR, shaders.raygen));
    for (const auto& miss : shaders.miss)
        general(addStage(VK_SHADER_STAGE_MISS_BIT_KHR, miss));
    for (const auto& hit : shaders.hitGroups) {
        uint32_t chit =
            hit.closestHit.empty()
                ? VK_SHADER_UNUSED_KHR
                : addStage(VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, hit.closestHit);
        uint32_t rint =
            hit.intersection.empty()
                ? VK_SHADER_UNUSED_KHR
                : addStage(VK_SHADER_STAGE_INTERSECTION_BIT_KHR, hit.intersection);
        uint32_t rahit = hit.anyHit.empty()
                             ? VK_SHADER_UNUSED_KHR
                             : addStage(VK_SHADER_STAGE_ANY_HIT_BIT_KHR, hit.anyHit);
        groups.push_back(
            {.sType = VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR,
             .type = hit.intersection.empty()
                         ? VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR
                         : VK_RAY_TRACING_SHADER_GROUP_TYPE_PROCEDURAL_HIT_GROUP_KHR,
             .generalShader = VK_SHADER_UNUSED_KHR,
             .closestHitShader = chit,
             .anyHitShader = rahit,
             .intersectionShader = rint});
    }
    VkRayTracingPipelineCreateInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR,
        .stageCount = uint32_t(stages.size()),
        .pStages = stages.data(),
        .groupCount = uint32_t(groups.size()),
        .pGroups = groups.data(),
        .maxPipelineRayRecursionDepth = maxRecursion,  // 1: only raygen traces
        .layout = p.layout,
    };
    VK_CHECK(vkCreateRayTracingPipelinesKHR(gpu.device, VK_NULL_HANDLE, VK_NULL_HANDLE, 1,
                                            &info, nullptr, &p.pipeline));
    VkDevice device = gpu.device;
    VkPipeline pipeline = p.pipeline;
    deletion.push([device, pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });
    // [end]

    // [region build_sbt]
    // The SBT: the driver's opaque handle for each group, copied into a
    // buffer in the layout of shared/raytracing/sbt.h.
    const auto& props = gpu.physical.rayTracing;
    uint32_t missCount = uint32_t(shaders.miss.size()),
             hitCount = uint32_t(shaders.hitGroups.size());
    p.sbtLayout = computeSbtLayout(
        props.shaderGroupHandleSize, props.shaderGroupHandleAlignment,
        props.shaderGroupBaseAlignment, props.maxShaderGroupStride, missCount, hitCount);
    std::vector<uint8_t> handles(size_t(groups.size()) * props.shaderGroupHandleSize);
    VK_CHECK(vkGetRayTracingShaderGroupHandlesKHR(gpu.device, p.pipeline, 0,
                                                  uint32_t(groups.size()), handles.size(),
                                                  handles.data()));
    std::vector<uint8_t> table(p.sbtLayout.totalSize, 0);
    auto put = [&](uint32_t group, uint64_t offset) {
        std::memcpy(&table[offset], &handles[size_t(group) * props.shaderGroupHandleSize],
                    props.shaderGroupHandleSize);
    };
    put(0, p.sbtLayout.raygen.offset);
    for (uint32_t i = 0; i < missCount; ++i)
        put(1 + i, p.sbtLayout.miss.offset + i * p.sbtLayout.miss.stride);
    for (uint32_t i = 0; i < hitCount; ++i)
        put(1 + missCount + i, p.sbtLayout.hit.offset + i * p.sbtLayout.hit.stride);

    // Over-allocate by one base alignment and start the table at an aligned address.
    p.sbt = createHostBuffer(gpu, deletion,
                             p.sbtLayout.totalSize + props.shaderGroupBaseAlignment,
                             VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR |
                                 VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
    VkDeviceAddress base = alignUp(p.sbt.address, props.shaderGroupBaseAlignment);
    std::memcpy(static_cast<uint8_t*>(p.sbt.mapped) + (base - p.sbt.address),
                table.data(), table.size());
    auto region = [&](const SbtRegion& r) {
        return VkStridedDeviceAddressRegionKHR{
            .deviceAddress = base + r.offset, .stride = r.stride, .size = r.size};
    };
    p.raygen = region(p.sbtLayout.raygen);
    p.miss = region(p.sbtLayout.miss);
    p.hit = region(p.sbtLayout.hit);
    // [end]
    return p;
}

// [region trace_rays]
void recordTrace(VkCommandBuffer cmd, const RtPipeline& p, VkDescriptorSet set,
                 const void* push, uint32_t pushBytes, uint32_t width, uint32_t height) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, p.layout, 0, 1,
                            &set, 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, kRtPushStages, 0, pushBytes, push);
    vkCmdTraceRaysKHR(cmd,
                      &p.raygen,    // one record: the ray generation shader
                      &p.miss,      // missIndex in traceRayEXT selects the record
                      &p.hit,       // instance offset + ray type offset select the record
                      &p.callable,  // no callable shaders
                      width, height, 1);  // one invocation per pixel
}
// [end]

// [region hit_groups]
// SBT hit records: quad, sphere, mesh (camera and bounce rays), then the
// same three for shadow rays (RAY_TYPE_SHADOW = 3): no closest hit there,
// "a hit is a hit"; the sphere still needs its intersection shader to be
// found at all.
std::vector<HitGroup> sceneHitGroups() {
    return {{.closestHit = "common/quad.rchit"},
            {.closestHit = "common/sphere.rchit", .intersection = "common/sphere.rint"},
            {.closestHit = "common/mesh.rchit"},
            {},
            {.intersection = "common/sphere.rint"},
            {}};
}
// [end]

}  // namespace rg
