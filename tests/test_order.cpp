// The order objects become TLAS instances in (shared/accel.cpp): Morton order
// is a permutation of the objects, and objects next to each other in it are
// close in space, which is what a builder that splits the list at its
// middle (lavapipe's) needs for a good tree.
#include <gtest/gtest.h>

#include "accel.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

namespace {

rg::Scene randomSpheres(size_t n, unsigned seed) {
    rg::Scene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> where(-100.0, 100.0);
    for (size_t i = 0; i < n; ++i) {
        rg::Object o;
        o.center = {where(rng), 0.5, where(rng)};
        o.radius = 0.5;
        o.transform = glm::scale(glm::translate(glm::dmat4(1.0), o.center), glm::dvec3(o.radius));
        s.objects.push_back(o);
    }
    return s;
}

double meanStep(const rg::Scene& s, const std::vector<uint32_t>& order) {
    double sum = 0;
    for (size_t k = 1; k < order.size(); ++k) sum += glm::distance(s.objects[order[k - 1]].center, s.objects[order[k]].center);
    return sum / double(order.size() - 1);
}

TEST(MortonOrder, CodesInterleaveTheBits) {
    EXPECT_EQ(rg::mortonCode(1, 0, 0), 1u);
    EXPECT_EQ(rg::mortonCode(0, 1, 0), 2u);
    EXPECT_EQ(rg::mortonCode(0, 0, 1), 4u);
    EXPECT_EQ(rg::mortonCode(2, 0, 0), 8u);
    EXPECT_EQ(rg::mortonCode(1023, 1023, 1023), (1u << 30) - 1);
    EXPECT_EQ(rg::mortonCode(1024, 0, 0), 0u);  // only 10 bits per axis
}

TEST(MortonOrder, IsAPermutation) {
    rg::Scene s = randomSpheres(10000, 1);
    std::vector<uint32_t> order = rg::mortonOrder(s);
    ASSERT_EQ(order.size(), s.objects.size());
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
    EXPECT_EQ(rg::fileOrder(s), sorted);
}

TEST(MortonOrder, NeighboursInTheOrderAreCloseInSpace) {
    rg::Scene s = randomSpheres(10000, 2);
    double file = meanStep(s, rg::fileOrder(s)), morton = meanStep(s, rg::mortonOrder(s));
    // Random order: about half the square's size (~104); Morton: about the
    // spacing of the points (~2), with rare long jumps between cells.
    EXPECT_LT(morton, 0.05 * file) << "file order " << file << ", Morton " << morton;
}

TEST(MortonOrder, OneObjectAndCoincidentCentres) {
    rg::Scene one = randomSpheres(1, 3);
    EXPECT_EQ(rg::mortonOrder(one), std::vector<uint32_t>{0});
    rg::Scene same = randomSpheres(3, 4);
    for (auto& o : same.objects) o.transform = same.objects[0].transform;  // zero extent: no division by 0
    EXPECT_EQ(rg::mortonOrder(same), (std::vector<uint32_t>{0, 1, 2}));
}

}  // namespace
