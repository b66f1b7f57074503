// The shader binding table's layout (chapter 04), as pure arithmetic so it
// can be unit-tested with unusual device properties.
//
//  SBT buffer (start aligned to shaderGroupBaseAlignment)
//  +--------------------+ 0
//  | raygen handle      |  raygen region: size == stride (the spec demands it)
//  +--------------------+ missOffset   (multiple of shaderGroupBaseAlignment)
//  | miss 0 | miss 1 .. |  stride = handle size rounded up to shaderGroupHandleAlignment
//  +--------------------+ hitOffset    (multiple of shaderGroupBaseAlignment)
//  | hit 0 | hit 1 | .. |  same stride; hit group index = instance offset + ray type
//  offset
//  +--------------------+ totalSize
#pragma once
#include <cstdint>
#include <stdexcept>

namespace rg {

struct SbtRegion {
    uint64_t offset = 0, stride = 0, size = 0;
};

struct SbtLayout {
    uint64_t handleStride = 0;  // one record: a handle, aligned
    SbtRegion raygen, miss, hit;
    uint64_t totalSize = 0;
};

inline uint64_t alignUp(uint64_t value, uint64_t alignment) {
    return (value + alignment - 1) / alignment * alignment;
}

inline SbtLayout computeSbtLayout(uint32_t handleSize, uint32_t handleAlignment,
                                  uint32_t baseAlignment, uint32_t maxStride,
                                  uint32_t missCount, uint32_t hitCount) {
    if (handleSize == 0 || handleAlignment == 0 || baseAlignment == 0)
        throw std::invalid_argument("SBT: zero handle size or alignment");
    if ((handleAlignment & (handleAlignment - 1)) ||
        (baseAlignment & (baseAlignment - 1)))
        throw std::invalid_argument("SBT: alignments must be powers of two");
    SbtLayout l;
    l.handleStride = alignUp(handleSize, handleAlignment);
    if (l.handleStride > maxStride)
        throw std::invalid_argument("SBT: record larger than maxShaderGroupStride");
    // Raygen: one record whose stride equals its size; padded to the base
    // alignment so the next region starts aligned.
    l.raygen = {0, alignUp(l.handleStride, baseAlignment),
                alignUp(l.handleStride, baseAlignment)};
    l.miss = {l.raygen.offset + l.raygen.size, l.handleStride,
              alignUp(missCount * l.handleStride, baseAlignment)};
    l.hit = {l.miss.offset + l.miss.size, l.handleStride,
             alignUp(hitCount * l.handleStride, baseAlignment)};
    l.totalSize = l.hit.offset + l.hit.size;
    return l;
}

}  // namespace rg
