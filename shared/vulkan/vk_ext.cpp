#include "vulkan/vk_ext.h"

#include <stdexcept>
#include <string>

#define RG_INSTANCE_FUNCTIONS(X)         \
    X(vkCreateDebugUtilsMessengerEXT)    \
    X(vkDestroyDebugUtilsMessengerEXT)

#define RG_DEVICE_FUNCTIONS(X)                          \
    X(vkCreateAccelerationStructureKHR)                 \
    X(vkDestroyAccelerationStructureKHR)                \
    X(vkGetAccelerationStructureBuildSizesKHR)          \
    X(vkGetAccelerationStructureDeviceAddressKHR)       \
    X(vkCmdBuildAccelerationStructuresKHR)              \
    X(vkCmdCopyAccelerationStructureKHR)                \
    X(vkCmdWriteAccelerationStructuresPropertiesKHR)    \
    X(vkCreateRayTracingPipelinesKHR)                   \
    X(vkGetRayTracingShaderGroupHandlesKHR)             \
    X(vkCmdTraceRaysKHR)                                \
    X(vkCmdTraceRaysIndirectKHR)

namespace {
#define RG_DECLARE(name) PFN_##name pfn_##name = nullptr;
RG_INSTANCE_FUNCTIONS(RG_DECLARE)
RG_DEVICE_FUNCTIONS(RG_DECLARE)
#undef RG_DECLARE

template <typename T>
T required(T fn, const char* name) {
    if (!fn) throw std::runtime_error(std::string("the driver does not provide ") + name);
    return fn;
}
}  // namespace

namespace rg {
void loadInstanceFunctions(VkInstance instance) {
#define RG_LOAD(name) \
    pfn_##name = reinterpret_cast<PFN_##name>(vkGetInstanceProcAddr(instance, #name));
    RG_INSTANCE_FUNCTIONS(RG_LOAD)
#undef RG_LOAD
}
void loadDeviceFunctions(VkDevice device) {
#define RG_LOAD(name) \
    pfn_##name = reinterpret_cast<PFN_##name>(vkGetDeviceProcAddr(device, #name));
    RG_DEVICE_FUNCTIONS(RG_LOAD)
#undef RG_LOAD
}
}  // namespace rg

// Trampolines with the prototypes of vulkan_core.h.
extern "C" {
VKAPI_ATTR VkResult VKAPI_CALL vkCreateDebugUtilsMessengerEXT(
    VkInstance i, const VkDebugUtilsMessengerCreateInfoEXT* c,
    const VkAllocationCallbacks* a, VkDebugUtilsMessengerEXT* m) {
    return required(pfn_vkCreateDebugUtilsMessengerEXT, "vkCreateDebugUtilsMessengerEXT")(
        i, c, a, m);
}
VKAPI_ATTR void VKAPI_CALL vkDestroyDebugUtilsMessengerEXT(
    VkInstance i, VkDebugUtilsMessengerEXT m, const VkAllocationCallbacks* a) {
    required(pfn_vkDestroyDebugUtilsMessengerEXT, "vkDestroyDebugUtilsMessengerEXT")(i, m,
                                                                                     a);
}
VKAPI_ATTR VkResult VKAPI_CALL vkCreateAccelerationStructureKHR(
    VkDevice d, const VkAccelerationStructureCreateInfoKHR* c,
    const VkAllocationCallbacks* a, VkAccelerationStructureKHR* s) {
    return required(pfn_vkCreateAccelerationStructureKHR,
                    "vkCreateAccelerationStructureKHR")(d, c, a, s);
}
VKAPI_ATTR void VKAPI_CALL vkDestroyAccelerationStructureKHR(
    VkDevice d, VkAccelerationStructureKHR s, const VkAllocationCallbacks* a) {
    required(pfn_vkDestroyAccelerationStructureKHR, "vkDestroyAccelerationStructureKHR")(
        d, s, a);
}
VKAPI_ATTR void VKAPI_CALL vkGetAccelerationStructureBuildSizesKHR(
    VkDevice d, VkAccelerationStructureBuildTypeKHR t,
    const VkAccelerationStructureBuildGeometryInfoKHR* b, const uint32_t* m,
    VkAccelerationStructureBuildSizesInfoKHR* s) {
    required(pfn_vkGetAccelerationStructureBuildSizesKHR,
             "vkGetAccelerationStructureBuildSizesKHR")(d, t, b, m, s);
}
VKAPI_ATTR VkDeviceAddress VKAPI_CALL vkGetAccelerationStructureDeviceAddressKHR(
    VkDevice d, const VkAccelerationStructureDeviceAddressInfoKHR* i) {
    return required(pfn_vkGetAccelerationStructureDeviceAddressKHR,
                    "vkGetAccelerationStructureDeviceAddressKHR")(d, i);
}
VKAPI_ATTR void VKAPI_CALL vkCmdBuildAccelerationStructuresKHR(
    VkCommandBuffer c, uint32_t n, const VkAccelerationStructureBuildGeometryInfoKHR* i,
    const VkAccelerationStructureBuildRangeInfoKHR* const* r) {
    required(pfn_vkCmdBuildAccelerationStructuresKHR,
             "vkCmdBuildAccelerationStructuresKHR")(c, n, i, r);
}
VKAPI_ATTR void VKAPI_CALL vkCmdCopyAccelerationStructureKHR(
    VkCommandBuffer c, const VkCopyAccelerationStructureInfoKHR* i) {
    required(pfn_vkCmdCopyAccelerationStructureKHR, "vkCmdCopyAccelerationStructureKHR")(
        c, i);
}
VKAPI_ATTR void VKAPI_CALL vkCmdWriteAccelerationStructuresPropertiesKHR(
    VkCommandBuffer c, uint32_t n, const VkAccelerationStructureKHR* s, VkQueryType t,
    VkQueryPool p, uint32_t f) {
    required(pfn_vkCmdWriteAccelerationStructuresPropertiesKHR,
             "vkCmdWriteAccelerationStructuresPropertiesKHR")(c, n, s, t, p, f);
}
VKAPI_ATTR VkResult VKAPI_CALL
vkCreateRayTracingPipelinesKHR(VkDevice d, VkDeferredOperationKHR o, VkPipelineCache pc,
                               uint32_t n, const VkRayTracingPipelineCreateInfoKHR* c,
                               const VkAllocationCallbacks* a, VkPipeline* p) {
    return required(pfn_vkCreateRayTracingPipelinesKHR, "vkCreateRayTracingPipelinesKHR")(
        d, o, pc, n, c, a, p);
}
VKAPI_ATTR VkResult VKAPI_CALL vkGetRayTracingShaderGroupHandlesKHR(
    VkDevice d, VkPipeline p, uint32_t f, uint32_t n, size_t s, void* data) {
    return required(pfn_vkGetRayTracingShaderGroupHandlesKHR,
                    "vkGetRayTracingShaderGroupHandlesKHR")(d, p, f, n, s, data);
}
VKAPI_ATTR void VKAPI_CALL vkCmdTraceRaysKHR(VkCommandBuffer c,
                                             const VkStridedDeviceAddressRegionKHR* rg,
                                             const VkStridedDeviceAddressRegionKHR* ms,
                                             const VkStridedDeviceAddressRegionKHR* ht,
                                             const VkStridedDeviceAddressRegionKHR* cl,
                                             uint32_t w, uint32_t h, uint32_t d) {
    required(pfn_vkCmdTraceRaysKHR, "vkCmdTraceRaysKHR")(c, rg, ms, ht, cl, w, h, d);
}
VKAPI_ATTR void VKAPI_CALL vkCmdTraceRaysIndirectKHR(
    VkCommandBuffer c, const VkStridedDeviceAddressRegionKHR* rg,
    const VkStridedDeviceAddressRegionKHR* ms, const VkStridedDeviceAddressRegionKHR* ht,
    const VkStridedDeviceAddressRegionKHR* cl, VkDeviceAddress a) {
    required(pfn_vkCmdTraceRaysIndirectKHR, "vkCmdTraceRaysIndirectKHR")(c, rg, ms, ht,
                                                                         cl, a);
}
}
