// The shaders' sampling code (shaders/common/sampling.glsl), compiled as C++:
// the Sobol sequence's stratification (every aligned block of 2^k points is a
// (0,k,2)-net: one point in each box of every 2^a x 2^(k-a) grid), which Owen
// scrambling must keep and per-pixel seeds must not break; the lobe mapping
// stays finite and inside its cone at the edges of [0,1)^2; and the same
// index always gives the same point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "glsl_as_cpp.h"

namespace {

// One point in each of the 2^k boxes of every 2^a x 2^(k-a) grid?
bool isNet(const std::vector<glm::vec2>& points, int k) {
    for (int a = 0; a <= k; ++a) {
        int nx = 1 << a, ny = 1 << (k - a);
        std::vector<int> count(size_t(nx) * ny, 0);
        for (const glm::vec2& p : points) {
            if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return false;
            int cx = std::min(nx - 1, int(p.x * nx)), cy = std::min(ny - 1, int(p.y * ny));
            if (++count[size_t(cy) * nx + cx] > 1) return false;
        }
    }
    return true;
}

std::vector<glm::vec2> block(std::uint32_t first, int k, std::uint32_t seed, bool scrambled) {
    std::vector<glm::vec2> points;
    for (std::uint32_t i = first; i < first + (1u << k); ++i) {
        if (scrambled) {
            points.push_back(shader::sobolPoint(i, seed));
        } else {  // the plain sequence
            points.push_back({shader::toUnit(glm::bitfieldReverse(i)), shader::toUnit(shader::sobolSecond(i))});
        }
    }
    return points;
}

TEST(Sobol, FirstPointsAreNets) {
    for (int k = 0; k <= 12; ++k) EXPECT_TRUE(isNet(block(0, k, 0, false), k)) << "2^" << k << " points";
}

TEST(Sobol, OwenScramblingKeepsEveryAlignedBlockANet) {
    // Progressive accumulation takes consecutive blocks: frame f of n = 2^k
    // samples is the block starting at f * n. Several pixels' seeds.
    for (std::uint32_t seed : {0u, 1u, 0x9E3779B9u, shader::pixelSeed({17u, 3u}, 0u), shader::pixelSeed({5u, 99u}, 7u)})
        for (int k : {0, 1, 2, 4, 6, 8, 10})
            for (std::uint32_t frame : {0u, 1u, 5u, 31u}) {
                std::uint32_t first = frame << k;
                EXPECT_TRUE(isNet(block(first, k, seed, true), k)) << "seed " << seed << ", 2^" << k << " from " << first;
            }
}

TEST(Sobol, ScramblingChangesThePointsPerPixel) {
    glm::vec2 a = shader::sobolPoint(5, shader::pixelSeed({0u, 0u}, 0u));
    glm::vec2 b = shader::sobolPoint(5, shader::pixelSeed({1u, 0u}, 0u));
    EXPECT_NE(a, b);
    // Point 0 of the plain sequence is (0, 0) for every pixel; scrambled, it is not.
    glm::vec2 plain(shader::toUnit(glm::bitfieldReverse(0u)), shader::toUnit(shader::sobolSecond(0u)));
    EXPECT_EQ(plain, glm::vec2(0.0f));
    EXPECT_NE(shader::sobolPoint(0, 12345u), glm::vec2(0.0f));
}

// Sequences of two seeds at the same index are two dimensions of one path
// (chapter 15: the facets of the first and the second bounce): together
// they must fill the 4D cube evenly. A chi-square test over 4 boxes per
// axis (their leading two bits); with unshuffled indices every
// coordinate's leading bit follows the index's lowest bit, and half the
// boxes stay empty.
TEST(Sobol, SequencesOfTwoSeedsAreIndependentDimensions) {
    const int n = 4096, cells = 4 * 4 * 4 * 4;
    for (auto [a, b] : {std::pair{1u, 2u}, std::pair{shader::pixelSeed({3u, 4u}, 0u), 77u},
                        std::pair{shader::pcgHash(5u), shader::pcgHash(6u)}}) {
        std::vector<int> count(cells, 0);
        for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
            glm::vec2 p = shader::sobolPoint(i, a), q = shader::sobolPoint(i, b);
            auto quarter = [](float u) { return std::min(3, int(u * 4)); };
            ++count[((quarter(p.x) * 4 + quarter(p.y)) * 4 + quarter(q.x)) * 4 + quarter(q.y)];
        }
        double expected = double(n) / cells, chi2 = 0;
        for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
        // 255 degrees of freedom: the 99.9th percentile is about 330
        EXPECT_LT(chi2, 330.0) << "seeds " << a << " and " << b;
    }
}

TEST(Sobol, SameIndexSamePoint) {
    for (std::uint32_t i : {0u, 1u, 1000u, 0xFFFFFFFFu})
        EXPECT_EQ(shader::samplePoint(PATTERN_SOBOL, i, 25, 77u), shader::samplePoint(PATTERN_SOBOL, i, 25, 77u));
}

// Chapter 04's antialiasing: after 2^k frames a pixel's jitter points are a
// net (one in each of 2^k equal boxes of the pixel, for every shape of box),
// in [0,1)^2; each pixel has its own points, and none of chapter 11's lobes
// (seeded by frame numbers) shares them.
TEST(PixelJitter, EveryPowerOfTwoOfFramesFillsThePixelEvenly) {
    for (glm::uvec2 pixel : {glm::uvec2(0, 0), glm::uvec2(1, 0), glm::uvec2(159, 89), glm::uvec2(1919, 1079)})
        for (int k = 0; k <= 10; ++k) {
            std::vector<glm::vec2> points;
            for (std::uint32_t i = 0; i < (1u << k); ++i) points.push_back(shader::pixelJitter(pixel, i));
            EXPECT_TRUE(isNet(points, k)) << pixel.x << "," << pixel.y << ": 2^" << k << " frames";
        }
    EXPECT_NE(shader::pixelJitter({3u, 4u}, 0u), shader::pixelJitter({4u, 3u}, 0u));
    for (std::uint32_t frame : {0u, 1u, 100u})
        EXPECT_NE(shader::pixelJitter({3u, 4u}, 0u), shader::sobolPoint(0u, shader::pixelSeed({3u, 4u}, frame)));
}

TEST(Lobe, FiniteAndInsideTheConeAtTheEdgesOfTheSquare) {
    const float almostOne = 1.0f - 1.0f / 16777216.0f;  // the largest value toUnit returns
    const std::vector<glm::vec3> axes = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0},
                                         glm::normalize(glm::vec3(1, 2, -3)), glm::normalize(glm::vec3(1e-7f, 0, -1))};
    for (const glm::vec3& r : axes)
        for (float roughness : {1e-6f, 0.1f, 0.5f, 1.0f})
            for (float u1 : {0.0f, 0.5f, almostOne})
                for (float u2 : {0.0f, 0.25f, almostOne}) {
                    glm::vec3 d = shader::lobeDirection(r, roughness, {u1, u2});
                    ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z))
                        << roughness << " " << u1 << " " << u2;
                    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
                    float cosMax = std::cos(roughness * 0.5f * shader::kPi);
                    EXPECT_GE(glm::dot(d, r), cosMax - 1e-5f);  // inside the cone
                }
}

}  // namespace
