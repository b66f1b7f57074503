// The one header that C++ and GLSL both include: descriptor bindings, push
// constants and the structs the GPU reads. Each struct follows std430 rules
// (vec4-aligned members first), and C++ static_asserts its size, so a field
// added on one side only fails the build instead of shifting every read.
#ifndef RG_HOST_DEVICE_H
#define RG_HOST_DEVICE_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace rg::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define RG_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T ": size differs from its GLSL layout")
#define RG_INLINE inline
#else
#define RG_SIZE(T, bytes)
#define RG_INLINE
#endif

// ---- Chapters 01-02: a compute shader writes a test pattern ----------------
#define PATTERN_BINDING_TARGET 0  // storage image, rgba32f, linear values
#define PATTERN_GROUP_SIZE 8      // 8x8 invocations per workgroup
#define PATTERN_SCROLL 240.0      // chapter 02: checker pixels scrolled per second
#define PATTERN_FPS 60.0          // chapter 02: animation time = frame / PATTERN_FPS

struct PatternPush {
    uint width;
    uint height;
    float time;     // seconds of animation time (chapter 02), 0 in chapter 01
    uint checker;   // checker square size in pixels
};
RG_SIZE(PatternPush, 16);

// ---- Chapter 03: a top view of the TLAS instances --------------------------
#define FOOTPRINT_BINDING_TARGET 0     // storage image
#define FOOTPRINT_BINDING_INSTANCES 1  // the VkAccelerationStructureInstanceKHR array the TLAS is built from

// VkAccelerationStructureInstanceKHR as GLSL sees it: a 3x4 row-major
// transform, then customIndex|mask, sbtOffset|flags, the BLAS address.
struct InstanceRecord {
    vec4 row0;
    vec4 row1;
    vec4 row2;
    uint customIndexAndMask;
    uint sbtOffsetAndFlags;
    uint blasAddressLow;
    uint blasAddressHigh;
};
RG_SIZE(InstanceRecord, 64);

struct FootprintPush {
    vec4 bounds;  // world x and z of the image's top-left corner, then the size covered
    uint width;
    uint height;
    uint instanceCount;
    uint pad;
};
RG_SIZE(FootprintPush, 32);

// Instance i's colour in the top view: 8 distinct colours.
RG_INLINE vec3 instanceColor(uint i) {
    uint k = i % 8u;
    return vec3(float(k & 1u), float((k >> 1u) & 1u), float((k >> 2u) & 1u)) * 0.6f + vec3(0.25f);
}

#ifdef __cplusplus
}  // namespace rg::gpu
#endif
#endif  // RG_HOST_DEVICE_H
