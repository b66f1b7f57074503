// Chapter 12's meshes as BLASes: their triangles, or (--triangles
// watertight) one box per triangle, in which shaders/common/triangle.rint
// tests the triangle.
#include "raytracing/accel.h"

#include <algorithm>
#include <cmath>

namespace rg {

// [region mesh_blas]
MeshBlas buildMeshBlas(const Gpu& gpu, DeletionQueue& deletion, const Mesh& mesh,
                       BlasStats& stats, TriangleTest test) {
    // Read by the build (BUILD_INPUT) and by the closest-hit shader through
    // its device address: one buffer serves both.
    const VkBufferUsageFlags usage =
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    MeshBlas m{.triangles = uint32_t(mesh.indices.size() / 3)};
    m.vertices = createDeviceBuffer(gpu, deletion, mesh.vertices.data(),
                                    mesh.vertices.size() * sizeof(glm::vec3), usage);
    m.indices = createDeviceBuffer(gpu, deletion, mesh.indices.data(),
                                   mesh.indices.size() * sizeof(uint32_t), usage);
    if (!mesh.normals.empty())
        m.normals = createDeviceBuffer(gpu, deletion, mesh.normals.data(),
                                       mesh.normals.size() * sizeof(glm::vec3), usage);
    if (!mesh.texcoords.empty())
        m.texcoords =
            createDeviceBuffer(gpu, deletion, mesh.texcoords.data(),
                               mesh.texcoords.size() * sizeof(glm::vec2), usage);
    // Opaque, as every geometry here: the closest triangle is the hit (an
    // alpha-tested instance alone turns that off: makeInstances).
    // maxVertex: the highest index a triangle may use.
    if (test == TriangleTest::Builtin) {
        stats.geometry = "triangles";
        m.blas = buildCompactedBlas(
            gpu, deletion,
            triangleGeometry(m.vertices, uint32_t(mesh.vertices.size() - 1), m.indices),
            m.triangles, stats);
        return m;
    }
    // --triangles watertight: boxes, needed only while the BLAS builds
    DeletionQueue inputs;
    std::vector<VkAabbPositionsKHR> boxes = triangleBoxes(mesh);
    Buffer boxBuffer = createDeviceBuffer(
        gpu, inputs, boxes.data(), boxes.size() * sizeof(VkAabbPositionsKHR),
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
            VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
    stats.geometry = "triangle boxes";
    m.blas =
        buildCompactedBlas(gpu, deletion, aabbGeometry(boxBuffer), m.triangles, stats);
    return m;
}
// [end]

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
