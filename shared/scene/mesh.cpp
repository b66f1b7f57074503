#include "scene/mesh.h"

#include "core/files.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

namespace rg {

Mesh icosphere(int level) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    Mesh m;
    for (glm::vec3 v : {glm::vec3(-1, t, 0), glm::vec3(1, t, 0), glm::vec3(-1, -t, 0),
                        glm::vec3(1, -t, 0), glm::vec3(0, -1, t), glm::vec3(0, 1, t),
                        glm::vec3(0, -1, -t), glm::vec3(0, 1, -t), glm::vec3(t, 0, -1),
                        glm::vec3(t, 0, 1), glm::vec3(-t, 0, -1), glm::vec3(-t, 0, 1)})
        m.vertices.push_back(glm::normalize(v));
    m.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            m.vertices.push_back(glm::normalize(m.vertices[a] + m.vertices[b]));
            return midpoints[key] = uint32_t(m.vertices.size() - 1);
        };
        std::vector<uint32_t> next;
        for (size_t i = 0; i < m.indices.size(); i += 3) {
            uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m.indices = std::move(next);
    }
    m.name = "icosphere_" + std::to_string(level);
    m.normals = m.vertices;  // on the unit sphere the normal is the position
    m.lo = glm::vec3(-1);
    m.hi = glm::vec3(1);
    return m;
}

// [region check_mesh]
void checkMesh(Mesh& mesh) {
    auto fail = [&](const std::string& what) {
        throw InputError(mesh.name + ": " + what);
    };
    const size_t n = mesh.vertices.size();
    if (mesh.indices.size() % 3 != 0) fail("the index count is not a multiple of 3");
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        fail("the normals do not match the vertices one to one");
    if (!mesh.texcoords.empty() && mesh.texcoords.size() != n)
        fail("the texture coordinates do not match the vertices one to one");
    auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    for (size_t i = 0; i < n; ++i) {
        if (!finite(mesh.vertices[i]))
            fail("vertex " + std::to_string(i) + " is not a finite number");
        if (!mesh.normals.empty() && !finite(mesh.normals[i]))
            fail("the normal of vertex " + std::to_string(i) + " is not a finite number");
        if (!mesh.texcoords.empty() &&
            !(std::isfinite(mesh.texcoords[i].x) && std::isfinite(mesh.texcoords[i].y)))
            fail("the texture coordinate of vertex " + std::to_string(i) +
                 " is not a finite number");
    }
    // Degenerate triangles have no inside and no normal: dropped.
    std::vector<uint32_t> kept;
    kept.reserve(mesh.indices.size());
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        for (uint32_t i : {a, b, c})
            if (i >= n)
                fail("triangle " + std::to_string(t / 3) + " uses vertex " +
                     std::to_string(i) + ", but there are " + std::to_string(n) +
                     " vertices");
        glm::dvec3 pa(mesh.vertices[a]), pb(mesh.vertices[b]), pc(mesh.vertices[c]);
        if (pa == pb || pb == pc || pc == pa ||
            glm::dot(glm::cross(pb - pa, pc - pa), glm::cross(pb - pa, pc - pa)) == 0) {
            ++mesh.degenerate;
            continue;
        }
        kept.insert(kept.end(), {a, b, c});
    }
    mesh.indices = std::move(kept);
    if (mesh.indices.empty())
        fail("no triangles (an empty mesh, or only degenerate ones)");

    // Vertices that share a position are one vertex for the edge count:
    // sorted by position, each takes the first index of its run.
    std::vector<uint32_t> byPosition(n), canonical(n);
    for (uint32_t i = 0; i < n; ++i) byPosition[i] = i;
    auto key = [&](uint32_t i) {
        const glm::vec3& v = mesh.vertices[i];
        // + 0: -0 and +0 are one position
        return std::make_tuple(v.x + 0.0f, v.y + 0.0f, v.z + 0.0f);
    };
    std::sort(byPosition.begin(), byPosition.end(), [&](uint32_t a, uint32_t b) {
        auto ka = key(a), kb = key(b);
        return ka != kb ? ka < kb : a < b;
    });
    for (size_t k = 0; k < n; ++k)
        canonical[byPosition[k]] = k > 0 && key(byPosition[k]) == key(byPosition[k - 1])
                                       ? canonical[byPosition[k - 1]]
                                       : byPosition[k];
    // A closed, consistently wound surface uses every edge a -> b exactly
    // once and b -> a exactly once (two triangles of opposite orientation).
    // Sorted, equal directed edges are neighbours and a reverse is found by
    // binary search: no hash table for a million triangles.
    std::vector<uint64_t> edges;
    edges.reserve(mesh.indices.size());
    for (size_t t = 0; t < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            edges.push_back(uint64_t(canonical[mesh.indices[t + k]]) << 32 |
                            canonical[mesh.indices[t + (k + 1) % 3]]);
    std::sort(edges.begin(), edges.end());
    auto uses = [&](uint64_t edge) {
        auto range = std::equal_range(edges.begin(), edges.end(), edge);
        return size_t(range.second - range.first);
    };
    mesh.openEdges = 0;
    for (size_t k = 0; k < edges.size();) {
        size_t run = 1;
        while (k + run < edges.size() && edges[k + run] == edges[k]) ++run;
        uint64_t edge = edges[k], reverse = edge << 32 | edge >> 32;
        size_t back = uses(reverse);
        // Each undirected edge once: from its lower direction, or from the
        // only one it is used in.
        if ((edge >> 32) < (edge & 0xFFFFFFFFu) || back == 0)
            mesh.openEdges += run != 1 || back != 1;
        k += run;
    }
    mesh.lo = glm::vec3(INFINITY);
    mesh.hi = glm::vec3(-INFINITY);
    for (uint32_t i : mesh.indices)
        mesh.lo = glm::min(mesh.lo, mesh.vertices[i]),
        mesh.hi = glm::max(mesh.hi, mesh.vertices[i]);
}
// [end]

// [region recentre]
void recentre(Mesh& mesh) {
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& v : mesh.vertices)
        if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z))
            lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    if (!(lo.x <= hi.x)) return;  // no finite vertex: checkMesh names the first
    glm::dvec3 centre = (lo + hi) / 2.0;
    for (glm::vec3& v : mesh.vertices) v = glm::vec3(glm::dvec3(v) - centre);
    mesh.origin += centre;
}
// [end]

}  // namespace rg
