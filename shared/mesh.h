// A triangle mesh of the unit sphere, for comparing the analytic sphere
// (chapter 04) with tessellated ones (docs/performance.md).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rg {

struct Mesh {
    std::vector<glm::vec3> vertices;
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
};

// An icosahedron subdivided `level` times, vertices on the unit sphere:
// 20 * 4^level triangles.
Mesh icosphere(int level);

}  // namespace rg
