// The order objects go into a structure in (shared/raytracing/accel.cpp): median-split
// order is a permutation of the objects, and every split lavapipe's builder
// makes of the list at its middle index is a split in space.
#include <gtest/gtest.h>

#include "raytracing/accel.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

namespace {

rg::Scene randomSpheres(size_t n, unsigned seed) {
    rg::Scene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> where(-100.0, 100.0), radius(0.2, 0.5);
    for (size_t i = 0; i < n; ++i) {
        rg::Object o;
        o.radius = radius(rng);
        o.center = {where(rng), o.radius, where(rng)};  // on a floor: y is nearly flat
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

// Lavapipe's builder (lvp_build_internal_node): the node of list entries
// [first, last] has the children [first, (first + last) / 2] and the rest.
// Counts the nodes of three or more entries whose two children cannot be
// told apart by a plane across some axis (their centres overlap on all three).
size_t unseparatedNodes(const rg::Scene& s, const std::vector<uint32_t>& order, size_t first, size_t last) {
    if (last - first + 1 < 3) return 0;
    size_t split = (first + last) / 2;
    bool separated = false;
    for (int axis = 0; axis < 3; ++axis) {
        double leftMax = -1e300, rightMin = 1e300;
        for (size_t k = first; k <= split; ++k) leftMax = std::max(leftMax, s.objects[order[k]].center[axis]);
        for (size_t k = split + 1; k <= last; ++k) rightMin = std::min(rightMin, s.objects[order[k]].center[axis]);
        separated = separated || leftMax <= rightMin;
    }
    return !separated + unseparatedNodes(s, order, first, split) + unseparatedNodes(s, order, split + 1, last);
}

TEST(MedianSplitOrder, IsAPermutation) {
    rg::Scene s = randomSpheres(10000, 1);
    std::vector<uint32_t> order = rg::medianSplitOrder(s);
    ASSERT_EQ(order.size(), s.objects.size());
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(rg::fileOrder(s), sorted);
}

TEST(MedianSplitOrder, EveryMidpointSplitIsASplitInSpace) {
    for (size_t n : {3, 10, 1000, 1001, 4097}) {  // odd counts: the left half holds one more
        rg::Scene s = randomSpheres(n, unsigned(n));
        EXPECT_EQ(unseparatedNodes(s, rg::medianSplitOrder(s), 0, n - 1), 0u) << n << " spheres";
    }
    // The scene file's random order: almost every node spans the whole floor.
    rg::Scene s = randomSpheres(1000, 5);
    EXPECT_GT(unseparatedNodes(s, rg::fileOrder(s), 0, 999), 300u);
}

TEST(MedianSplitOrder, NeighboursInTheOrderAreCloseInSpace) {
    rg::Scene s = randomSpheres(10000, 2);
    double file = meanStep(s, rg::fileOrder(s)), median = meanStep(s, rg::medianSplitOrder(s));
    // Random order: about half the square's size (~104); median splits: about
    // the spacing of the points (~2), with rarer long jumps between cells.
    EXPECT_LT(median, 0.05 * file) << "file order " << file << ", median splits " << median;
}

TEST(MedianSplitOrder, ReordersOnlyTheObjectsGiven) {
    rg::Scene s = randomSpheres(50, 3);
    std::vector<uint32_t> some = {40, 7, 19, 3, 28};
    std::vector<uint32_t> order = rg::medianSplitOrder(s, some);
    std::sort(some.begin(), some.end());
    std::sort(order.begin(), order.end());
    EXPECT_EQ(order, some);
    EXPECT_TRUE(rg::medianSplitOrder(s, {}).empty());
}

TEST(MedianSplitOrder, OneObjectAndCoincidentCentres) {
    rg::Scene one = randomSpheres(1, 3);
    EXPECT_EQ(rg::medianSplitOrder(one), std::vector<uint32_t>{0});
    rg::Scene same = randomSpheres(5, 4);
    for (auto& o : same.objects) o.transform = same.objects[0].transform;  // ties: by index, the same everywhere
    EXPECT_EQ(rg::medianSplitOrder(same), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
}

}  // namespace
