// The order in which structures are built (chapter 03): lavapipe's builder
// keeps the order it is given, so median splits in space, made here, give it
// a good tree; the file's own order shows what a bad one costs.
#include "raytracing/accel.h"

#include <algorithm>
#include <cmath>

namespace rg {

// [region median_split]
struct Centred {
    glm::dvec3 centre;  // of the object's box (or the triangle's centroid)
    uint32_t object;
};

// Orders [first, last) so that lavapipe's split of it at the middle index is
// a split in space, then each half the same way: the tree it builds is the
// tree of median splits.
static void splitAtMedian(Centred* first, Centred* last) {
    size_t n = size_t(last - first);
    if (n <= 2) return;  // one node with two leaves: nothing to choose
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (Centred* c = first; c != last; ++c)
        lo = glm::min(lo, c->centre), hi = glm::max(hi, c->centre);
    glm::dvec3 extent = hi - lo;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
               : extent.y >= extent.z                       ? 1
                                                            : 2;
    Centred* middle = first + (n + 1) / 2;  // lavapipe's left half holds ceil(n / 2)
    std::nth_element(first, middle, last, [axis](const Centred& a, const Centred& b) {
        double ca = a.centre[axis], cb = b.centre[axis];
        // ties by index: the same order on every machine
        return ca != cb ? ca < cb : a.object < b.object;
    });
    splitAtMedian(first, middle);
    splitAtMedian(middle, last);
}

std::vector<uint32_t> medianSplitOrder(const Scene& scene,
                                       std::vector<uint32_t> objects) {
    // the centres beside the indices: a million objects' splits stay in cache
    std::vector<Centred> list;
    list.reserve(objects.size());
    for (uint32_t i : objects)
        list.push_back({glm::dvec3(scene.objects[i].transform[3]), i});
    splitAtMedian(list.data(), list.data() + list.size());
    for (size_t k = 0; k < list.size(); ++k) objects[k] = list[k].object;
    return objects;
}
// [end]

// Chapter 12: the same for a mesh's triangles, by their centroids.
void medianSplitTriangles(Mesh& mesh) {
    std::vector<Centred> list(mesh.indices.size() / 3);
    for (uint32_t t = 0; t < list.size(); ++t) {
        glm::dvec3 sum(0);
        for (int c = 0; c < 3; ++c)
            sum += glm::dvec3(mesh.vertices[mesh.indices[3 * t + c]]);
        list[t] = {sum / 3.0, t};
    }
    splitAtMedian(list.data(), list.data() + list.size());
    std::vector<uint32_t> indices(mesh.indices.size());
    for (size_t k = 0; k < list.size(); ++k)
        for (int c = 0; c < 3; ++c)
            indices[3 * k + c] = mesh.indices[3 * list[k].object + c];
    mesh.indices = std::move(indices);
}

std::vector<uint32_t> fileOrder(const Scene& scene) {
    std::vector<uint32_t> order(scene.objects.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    return order;
}

}  // namespace rg
