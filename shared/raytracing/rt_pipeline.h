// The ray tracing pipeline and its shader binding table (chapter 04).
#pragma once
#include "raytracing/sbt.h"
#include "vulkan/context.h"
#include "vulkan/resources.h"

#include <string>
#include <vector>

namespace rg {

// A hit group: closest-hit and intersection shaders (either may be empty;
// an intersection shader makes it a procedural group, for AABBs).
struct HitGroup {
    std::string closestHit;
    std::string intersection;
    std::string anyHit;  // chapter 12's alpha test (alpha.rahit)
};

// The hit groups of every ray tracing chapter from 05 on: quad, sphere and
// mesh for camera and bounce rays, then the same three for shadow rays.
std::vector<HitGroup> sceneHitGroups();

struct RtShaders {
    std::string raygen;
    // the ray generation shader's specialization constant 0 (chapter 10: its launch)
    uint32_t raygenConstant = 0;
    // Constant 1, kAverages (rt_bindings.glsl): 0 for a run that never
    // averages frames, whose shader then holds no jitter and no running mean.
    uint32_t raygenAverages = 1;
    // Constants 2 and 3, kCarefulSizes and kCarefulShininess
    // (rt_bindings.glsl), every stage: 0 for a scene that needs no care for
    // huge or tiny sizes, or for huge exponents (rt_scene.h's carefulNumerics).
    uint32_t carefulSizes = 1;
    uint32_t carefulShininess = 1;
    // Constant 4, kAlphaTest: 1 for a scene with an alpha-tested material
    // (rays without the opaque flag, so that alpha.rahit runs where marked).
    uint32_t alphaTest = 0;
    // Constant 5, kThinWalls: 1 for a scene with a thin-walled material.
    uint32_t thinWalls = 1;
    // Constant 6, kRayCones: 1 for a scene with a mip-mapped texture.
    uint32_t rayCones = 0;
    // Constant 7, kSunDiscs: 1 for a scene with a sun of some size (chapter 14).
    uint32_t sunDiscs = 0;
    // Constant 8, kMeshes: 1 for a scene with triangle meshes, whose hits
    // bring a shading normal of their own (chapter 12).
    uint32_t meshes = 1;
    std::vector<std::string> miss;
    std::vector<HitGroup> hitGroups;
    // where <path>.spv are: empty, bin/shaders (the build's); a reload's folder
    std::string spirvDir;
};

struct RtPipeline {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    Buffer sbt;
    SbtLayout sbtLayout;
    VkStridedDeviceAddressRegionKHR raygen{}, miss{}, hit{}, callable{};
    uint32_t maxRecursion = 1;
};

// maxRecursion: rays traced from raygen only need 1 (bounces loop in raygen).
RtPipeline createRtPipeline(const Gpu& gpu, DeletionQueue& deletion,
                            VkDescriptorSetLayout setLayout, uint32_t pushConstantBytes,
                            const RtShaders& shaders, uint32_t maxRecursion = 1);

// The stages that read the push constants (gpu::RtPush).
constexpr VkShaderStageFlags kRtPushStages =
    VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR |
    VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_INTERSECTION_BIT_KHR |
    VK_SHADER_STAGE_ANY_HIT_BIT_KHR;

// Binds the pipeline and its set, pushes constants, traces one ray
// generation invocation per pixel.
void recordTrace(VkCommandBuffer cmd, const RtPipeline& pipeline, VkDescriptorSet set,
                 const void* push, uint32_t pushBytes, uint32_t width, uint32_t height);

}  // namespace rg
