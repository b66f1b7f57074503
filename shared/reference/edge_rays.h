// Rays aimed exactly at the edges and vertices of a closed mesh: chapter
// 12's measure of leaks, for the CPU reference's triangle test and the
// GPU's (tools/leak_probe.cpp). Geometry only: what the first hit must be
// follows from the mesh, not from either test.
#pragma once
#include "scene/mesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rg {

struct EdgeRay {
    glm::dvec3 origin, direction;  // direction: unit length
    // true: from outside, in front of every face that meets at the target,
    // so the first hit is a front face; false: from the centre of the
    // mesh's box, so in a star-shaped mesh the first hit is a back face
    bool outside = true;
};

// `count` rays, alternately from outside and from inside; every fourth of
// each kind aims at a vertex, the others at a random point of an edge.
// Deterministic for a seed. The mesh must be closed and, for the rays from
// inside, star-shaped about its box's centre (spheres, lenses, boxes).
std::vector<EdgeRay> edgeRays(const Mesh& mesh, size_t count, uint64_t seed);

}  // namespace rg
