// The SBT layout (shared/raytracing/sbt.h) with ordinary and unusual device
// properties: every region starts on shaderGroupBaseAlignment, every stride
// is a multiple of shaderGroupHandleAlignment and holds a handle, raygen's
// size equals its stride, and the regions do not overlap.
#include <gtest/gtest.h>

#include "raytracing/sbt.h"

namespace {

struct Props {
    uint32_t handleSize, handleAlignment, baseAlignment, maxStride;
};

class SbtLayoutTest : public ::testing::TestWithParam<Props> {};

TEST_P(SbtLayoutTest, RegionsAreAlignedAndDisjoint) {
    Props p = GetParam();
    for (uint32_t miss : {1u, 2u, 3u})
        for (uint32_t hit : {1u, 2u, 4u, 5u}) {
            rg::SbtLayout l = rg::computeSbtLayout(p.handleSize, p.handleAlignment, p.baseAlignment, p.maxStride,
                                                   miss, hit);
            for (const rg::SbtRegion* r : {&l.raygen, &l.miss, &l.hit}) {
                EXPECT_EQ(r->offset % p.baseAlignment, 0u);
                EXPECT_EQ(r->stride % p.handleAlignment, 0u);
                EXPECT_GE(r->stride, p.handleSize);
            }
            EXPECT_EQ(l.raygen.size, l.raygen.stride);
            EXPECT_LE(l.miss.stride, p.maxStride);
            EXPECT_LE(l.hit.stride, p.maxStride);
            EXPECT_GE(l.miss.size, miss * l.miss.stride);
            EXPECT_GE(l.hit.size, hit * l.hit.stride);
            EXPECT_GE(l.miss.offset, l.raygen.offset + l.raygen.size);
            EXPECT_GE(l.hit.offset, l.miss.offset + l.miss.size);
            EXPECT_EQ(l.totalSize, l.hit.offset + l.hit.size);
            // The last hit record ends inside the table.
            EXPECT_LE(l.hit.offset + (hit - 1) * l.hit.stride + p.handleSize, l.totalSize);
        }
}

INSTANTIATE_TEST_SUITE_P(Devices, SbtLayoutTest,
                         ::testing::Values(Props{32, 32, 64, 4096},     // NVIDIA
                                           Props{32, 16, 32, 16384},    // lavapipe
                                           Props{32, 32, 32, 4096},     // base == handle alignment
                                           Props{20, 8, 128, 4096},     // handle not a multiple of its alignment
                                           Props{48, 64, 256, 4096},    // alignment larger than the handle
                                           Props{8, 4, 4096, 65536}));  // huge base alignment

TEST(SbtLayout, NvidiaNumbersByHand) {
    rg::SbtLayout l = rg::computeSbtLayout(32, 32, 64, 4096, 2, 4);
    EXPECT_EQ(l.raygen.offset, 0u);
    EXPECT_EQ(l.raygen.size, 64u);
    EXPECT_EQ(l.miss.offset, 64u);
    EXPECT_EQ(l.miss.stride, 32u);
    EXPECT_EQ(l.miss.size, 64u);
    EXPECT_EQ(l.hit.offset, 128u);
    EXPECT_EQ(l.hit.size, 128u);
    EXPECT_EQ(l.totalSize, 256u);
}

TEST(SbtLayout, RejectsImpossibleProperties) {
    EXPECT_THROW(rg::computeSbtLayout(32, 24, 64, 4096, 1, 1), std::invalid_argument);  // not a power of two
    EXPECT_THROW(rg::computeSbtLayout(64, 32, 64, 32, 1, 1), std::invalid_argument);    // record > max stride
    EXPECT_THROW(rg::computeSbtLayout(0, 32, 64, 4096, 1, 1), std::invalid_argument);
}

}  // namespace
