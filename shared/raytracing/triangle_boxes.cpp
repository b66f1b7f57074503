// Chapter 12's --triangles watertight: a mesh's BLAS holds one box per
// triangle, and shaders/common/triangle.rint tests the triangle inside.
#include "raytracing/accel.h"

#include <algorithm>
#include <cmath>

namespace rg {

// [region triangle_boxes]
std::vector<VkAabbPositionsKHR> triangleBoxes(const Mesh& mesh) {
    std::vector<VkAabbPositionsKHR> boxes;
    boxes.reserve(mesh.indices.size() / 3);
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        glm::vec3 a = mesh.vertices[mesh.indices[i]];
        glm::vec3 b = mesh.vertices[mesh.indices[i + 1]];
        glm::vec3 c = mesh.vertices[mesh.indices[i + 2]];
        glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
        // A ray along an edge runs on the faces of both triangles' boxes,
        // where the traversal's box test (float, its rounding the driver's
        // own) may go either way: 2^-20 of the box's largest coordinate
        // (about 8 float steps) larger on every side, it goes in.
        float largest =
            std::max(glm::length(glm::max(glm::abs(lo), glm::abs(hi))), 1e-30f);
        glm::vec3 pad(std::ldexp(largest, -20));
        lo -= pad;
        hi += pad;
        boxes.push_back({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z});
    }
    return boxes;
}
// [end]

}  // namespace rg
