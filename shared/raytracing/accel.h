// Acceleration structures (thesis 2.2.1, chapter 03). Two levels: bottom
// level (BLAS) holds geometry in its own coordinates, top level (TLAS) holds
// instances of BLASes, each with a world transform.
#pragma once
#include "scene/mesh.h"
#include "scene/scene.h"
#include "vulkan/context.h"
#include "vulkan/resources.h"

#include <string>
#include <vector>

namespace rg {

struct AccelerationStructure {
    VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
    Buffer buffer;                 // the memory it lives in
    VkDeviceAddress address = 0;   // what a TLAS instance or a shader refers to
};

struct BlasStats {
    std::string name;
    std::string geometry;          // "triangles", "aabbs" or "triangle boxes"
    VkDeviceSize buildBytes = 0;   // size when built
    VkDeviceSize compactBytes = 0; // size after compaction
    double buildMs = 0, compactMs = 0;
};

// One BLAS of `geometry` (`primitiveCount` triangles or boxes), built and
// compacted (chapter 03).
AccelerationStructure buildCompactedBlas(
    const Gpu& gpu, DeletionQueue& deletion,
    const VkAccelerationStructureGeometryKHR& geometry, uint32_t primitiveCount,
    BlasStats& stats);
// What it is built from: boxes (VkAabbPositionsKHR one after another), or
// indexed triangles (float x, y, z vertices, uint32 indices). Opaque.
VkAccelerationStructureGeometryKHR aabbGeometry(const Buffer& boxes);
VkAccelerationStructureGeometryKHR triangleGeometry(const Buffer& vertices,
                                                    uint32_t maxVertex,
                                                    const Buffer& indices);

// Chapter 12: a triangle mesh on the GPU. The BLAS is built from the
// vertex and index buffers, which stay: the closest-hit shader reads them
// by their device addresses (barycentrics, smooth normals, texture coordinates).
struct MeshBlas {
    AccelerationStructure blas;
    // normals: empty when the mesh has none (flat faces)
    Buffer vertices, normals, indices;
    Buffer texcoords;                   // empty when the mesh has none (untextured)
    uint32_t triangles = 0;
};
// How rays meet a mesh's triangles (chapter 12's --triangles): the driver's
// own test (Builtin), which the Vulkan specification does not require to be
// watertight, or one box per triangle in the BLAS and Woop, Benthin and
// Wald's test in an intersection shader (Watertight: shaders/common/triangle.rint).
enum class TriangleTest { Builtin, Watertight };
// Builds `mesh` as given: its triangles in the order they come (chapter 03:
// on lavapipe that order is the tree; medianSplitTriangles first).
MeshBlas buildMeshBlas(const Gpu& gpu, DeletionQueue& deletion, const Mesh& mesh,
                       BlasStats& stats, TriangleTest test = TriangleTest::Builtin);
// --triangles watertight: box k holds triangle k, a little larger than the
// triangle, so that the traversal's own box test (in float, in ways the
// specification leaves open) cannot drop a ray that grazes an edge.
std::vector<VkAabbPositionsKHR> triangleBoxes(const Mesh& mesh);

// The two unit shapes every scene object instances (scene.h): the quad
// [-1,1] x {0} x [-1,1] as two triangles, and the box [-1,1]^3 that holds the
// analytic unit sphere (an intersection shader finds the sphere inside it).
// Chapter 12 adds the scene's meshes, each once.
struct UnitShapes {
    AccelerationStructure quad, sphere;
    // Scene::meshes in order, then the icosphere of sphereMeshLevel > 0
    std::vector<MeshBlas> meshes;
    // which of `meshes` replaces the analytic sphere (-1: none)
    int sphereMesh = -1;
    std::vector<BlasStats> stats;
};
// sphereMeshLevel > 0 also builds an icosphere of that subdivision level,
// which makeInstances then uses for every sphere instead of the analytic one.
// `scene` (chapter 12): its meshes too, in median-split order unless
// `fileOrder`, tested as `test` says (the icosphere too).
UnitShapes buildUnitShapes(const Gpu& gpu, DeletionQueue& deletion,
                           int sphereMeshLevel = 0, const Scene* scene = nullptr,
                           bool fileOrder = false,
                           TriangleTest test = TriangleTest::Builtin);

// The order in which objects go into a structure (thesis 2.2.1). A builder
// may take the order it is given as the tree: lavapipe's splits the list at
// its middle index, recursively, without sorting, so objects far apart in the
// list must be far apart in space. medianSplitOrder makes every one of those
// halves a half in space: it splits the objects' box centres at the median of
// their longest axis, as many to the left as lavapipe puts there, and
// recurses into each half. `objects` are indices into scene.objects.
std::vector<uint32_t> medianSplitOrder(const Scene& scene, std::vector<uint32_t> objects);
std::vector<uint32_t> fileOrder(const Scene& scene);  // every object: 0, 1, 2, ...
inline std::vector<uint32_t> medianSplitOrder(const Scene& scene) {
    return medianSplitOrder(scene, fileOrder(scene));
}
// Chapter 12: a mesh's triangles in the same order, by their centroids.
void medianSplitTriangles(Mesh& mesh);

// TLAS instances: instance k is object objects[k] (its custom index is the
// object's index, which the shaders use), pointing at the quad or sphere
// BLAS with the object's transform. Hit group offset: 0 for quads, 1 for
// spheres, 2 for meshes and the sphere mesh (chapter 04's SBT).
// The thesis's other layout (2.2.1: spatially close geometry belongs in one
// BLAS): static, visible spheres become boxes of a single BLAS of AABBs, in
// the order given, placed by one instance with the identity transform.
// Box k's sphere is GPU object firstObject + k (gl_PrimitiveID = k).
struct SphereGroup {
    AccelerationStructure blas;
    std::vector<uint32_t> objects;  // box k holds scene object objects[k]
    // its custom index: where its entries start in the GPU's object array
    uint32_t firstObject = 0;
    BlasStats stats;
};
// A sphere the group can hold: static, visible, and round: its transform
// scales evenly (and may rotate, which a sphere does not show). An ellipsoid
// (uneven scale) stays an instance. Its sphere is groupSphere(o).
bool inSphereGroup(const Object& o);
glm::dvec4 groupSphere(const Object& o);  // world centre, radius
// Every one of `objects` must be inSphereGroup.
SphereGroup buildSphereGroup(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene,
                             const std::vector<uint32_t>& objects, uint32_t firstObject);

// Chapter 12: whether `o`'s hits go through the any-hit shader's alpha test
// (its material is alpha-tested: glTF's alphaMode MASK).
inline bool alphaTested(const Scene& scene, const Object& o) {
    return scene.materials[o.material].alphaCutoff > 0;
}
// The group's one instance (if it has spheres) first, then one per object.
std::vector<VkAccelerationStructureInstanceKHR> makeInstances(
    const Scene& scene, const UnitShapes& shapes, const std::vector<uint32_t>& objects,
    const SphereGroup* group = nullptr);
VkTransformMatrixKHR toVkTransform(const glm::dmat4& m);

struct Tlas {
    AccelerationStructure as;
    Buffer instances;   // device-local VkAccelerationStructureInstanceKHR array
    Buffer scratch;     // kept for updates
    VkDeviceAddress scratchAddress = 0;  // aligned start inside `scratch`
    uint32_t count = 0;
    VkDeviceSize buildBytes = 0, updateScratchBytes = 0;
    double buildMs = 0;  // GPU time of the first build
};
// Builds with ALLOW_UPDATE so that moving objects can be refitted in place.
Tlas buildTlas(const Gpu& gpu, DeletionQueue& deletion,
               const std::vector<VkAccelerationStructureInstanceKHR>& instances);
// Records the new data of the instances listed in `changed` (same
// instances, only their transforms changed) and an in-place update (refit)
// of the TLAS, ordered after the rays of earlier frames and before
// `consumerStage` of this one.
void recordTlasUpdate(VkCommandBuffer cmd, const Tlas& tlas,
                      const std::vector<VkAccelerationStructureInstanceKHR>& instances,
                      const std::vector<uint32_t>& changed,
                      VkPipelineStageFlags consumerStage);

}  // namespace rg
