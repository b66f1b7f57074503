// Triangle meshes (chapter 12): what a mesh file holds once loaded, and the
// checks every mesh gets before it goes to the GPU. Also the tessellated
// unit sphere that compares the analytic sphere with triangles
// (docs/performance.md).
#pragma once
#include "scene/texture.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rg {

struct Mesh {
    // for messages: "lens.obj" or "glass.gltf: mesh 0 primitive 1"
    std::string name;
    std::vector<glm::vec3> vertices;  // object space
    // one per vertex (smooth shading), or empty: the faces' own
    std::vector<glm::vec3> normals;
    // one per vertex, glTF's convention ((0, 0): the image's top-left), or empty
    std::vector<glm::vec2> texcoords;
    // three per triangle, counter-clockwise seen from outside
    std::vector<uint32_t> indices;
    // Set by checkMesh:
    // edges not shared by exactly two triangles of opposite orientation
    size_t openEdges = 0;
    size_t degenerate = 0;   // triangles dropped: zero area, or a repeated vertex
    glm::vec3 lo{0}, hi{0};  // bounding box of the vertices the triangles use
    // Where the vertices' (0, 0, 0) lies in the file's own frame: file =
    // vertex + origin. Loaders recentre each mesh on its box, in double, so a
    // mesh written far from its file's origin keeps float's precision (a
    // float's spacing is 0.06 at 1e6); its parts' transforms add `origin` back.
    glm::dvec3 origin{0};
};

// An icosahedron subdivided `level` times, vertices on the unit sphere (each
// vertex's normal is its position): 20 * 4^level triangles.
Mesh icosphere(int level);

// Moves the vertices so that the centre of their box (of the finite ones)
// is 0, in double, and adds that centre to `origin` (meshes written far
// from their file's origin).
void recentre(Mesh& mesh);

// What every loaded mesh goes through (chapter 12). Throws InputError naming
// `mesh.name` for an index out of range, a NaN or infinite vertex or
// normal or texture coordinate, or no triangle left; drops degenerate triangles (counted
// in `degenerate`); counts open edges. Edges are matched by vertex position, not index: a
// file may repeat a vertex where its normals differ.
void checkMesh(Mesh& mesh);

}  // namespace rg
