#include "reference/edge_rays.h"

#include <algorithm>
#include <map>
#include <random>
#include <tuple>

namespace rg {

// [region edge_rays]
std::vector<EdgeRay> edgeRays(const Mesh& mesh, size_t count, uint64_t seed) {
    size_t triangles = mesh.indices.size() / 3;
    auto vertex = [&](size_t t, int k) {
        return glm::dvec3(mesh.vertices[mesh.indices[3 * t + k]]);
    };
    // The faces at each position (a file repeats a vertex where normals split).
    std::map<std::tuple<double, double, double>, std::vector<uint32_t>> facesAt;
    auto key = [](const glm::dvec3& v) { return std::make_tuple(v.x, v.y, v.z); };
    std::vector<glm::dvec3> faceNormal(triangles);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (uint32_t t = 0; t < triangles; ++t) {
        faceNormal[t] = glm::normalize(
            glm::cross(vertex(t, 1) - vertex(t, 0), vertex(t, 2) - vertex(t, 0)));
        for (int k = 0; k < 3; ++k) {
            facesAt[key(vertex(t, k))].push_back(t);
            lo = glm::min(lo, vertex(t, k));
            hi = glm::max(hi, vertex(t, k));
        }
    }
    glm::dvec3 centre = (lo + hi) / 2.0;
    double reach = 2 * glm::length(hi - lo);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::normal_distribution<double> gauss;
    std::vector<EdgeRay> rays;
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        size_t t = std::min(size_t(uniform(rng) * triangles), triangles - 1);
        int k = std::min(int(uniform(rng) * 3), 2);
        glm::dvec3 a = vertex(t, k), b = vertex(t, (k + 1) % 3);
        bool atVertex = (i / 2) % 4 == 0;
        glm::dvec3 target = atVertex ? a : a + uniform(rng) * (b - a);
        if (i % 2 == 1) {  // from inside
            rays.push_back({centre, glm::normalize(target - centre), false});
            continue;
        }
        // From outside: the faces that meet at the target, and a random
        // direction in front of all of them (else the ray may graze a
        // silhouette and miss by rights).
        std::vector<uint32_t> faces;
        const std::vector<uint32_t>& atB = facesAt[key(b)];
        for (uint32_t f : facesAt[key(a)])
            if (atVertex || std::count(atB.begin(), atB.end(), f)) faces.push_back(f);
        glm::dvec3 base(0);
        for (uint32_t f : faces) base += faceNormal[f];
        glm::dvec3 w = glm::normalize(base);
        for (int tries = 0; tries < 20; ++tries) {
            glm::dvec3 jitter(gauss(rng), gauss(rng), gauss(rng));
            glm::dvec3 c = glm::normalize(base + 0.5 * jitter);
            auto inFront = [&](uint32_t f) { return glm::dot(c, faceNormal[f]) > 0.02; };
            if (std::all_of(faces.begin(), faces.end(), inFront)) {
                w = c;
                break;
            }
        }
        rays.push_back({target + reach * w, -w, true});
    }
    return rays;
}
// [end]

}  // namespace rg
