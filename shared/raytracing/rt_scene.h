// A scene on the GPU for ray tracing (chapter 04): the acceleration
// structures of chapter 03 plus the buffers the shaders read, bound in one
// descriptor set (bindings in host_device.h).
#pragma once
#include "core/cli.h"
#include "host_device.h"
#include "raytracing/accel.h"
#include "raytracing/rt_pipeline.h"
#include "raytracing/rt_textures.h"
#include "scene/scene.h"
#include "vulkan/descriptors.h"
#include "vulkan/resources.h"

#include <vector>

namespace rg {

// Camera matrices as the thesis's ray generation shader uses them (2.2.2):
// view inverse, and the projection's inverse for Vulkan's y-down clip space.
void cameraMatrices(const Camera& camera, double aspect, glm::mat4& viewInverse,
                    glm::mat4& projInverse);

struct RtScene {
    UnitShapes shapes;
    // --layout grouped: the static spheres' one BLAS (empty otherwise)
    SphereGroup group;
    std::vector<VkAccelerationStructureInstanceKHR> instances;
    Tlas tlas;
    Buffer camera, objects, materials, lights, sky, rayCount;
    Buffer meshes;          // gpu::GpuMesh per mesh (chapter 12)
    RtTextures textures;    // the meshes' textures, one image each (chapter 12)
    DescriptorSet descriptors;
    uint32_t width = 0, height = 0;
};

// A material as the shaders read it (host_device.h).
gpu::GpuMaterial toGpuMaterial(const Material& m, const Scene& scene);
// The scene's point lights as the shaders read them (the viewer uploads them again when
// one moves).
std::vector<gpu::GpuLight> toGpuLights(const Scene& scene);

// How the scene goes into acceleration structures (chapter 03; the command
// line's --layout, --file-order and --sphere-mesh).
struct SceneLayout {
    // static spheres as boxes of one BLAS; else one instance per object
    bool groupSpheres = true;
    bool fileOrder = false;    // build in the scene file's order, not medianSplitOrder
    // > 0: icospheres of that level, one instance each (never grouped)
    int sphereMeshLevel = 0;
    // chapter 12's --triangles: the driver's triangle test or the watertight one
    TriangleTest triangles = TriangleTest::Builtin;
};

// --triangles watertight: the mesh hit groups (primary and shadow rays) get
// the intersection shader that finds the triangle in each box (triangle.rint).
// Throws InputError where the device cannot run it (no double in shaders).
void useTriangleTest(const Gpu& gpu, RtShaders& shaders, TriangleTest test);

// Chapter 12's alpha test: for a scene with an alpha-tested material (glTF's
// alphaMode MASK) the mesh hit groups get the any-hit shader (alpha.rahit)
// and constant 4 turns the rays' opaque flag off; makeInstances marks only
// those instances not opaque. Returns whether it did.
bool useAlphaTest(RtShaders& shaders, const Scene& scene);
// Constant 5 (kThinWalls): the ray tree's thin-wall branches only for a
// scene with a thin-walled material. Returns whether it has one.
bool useThinWalls(RtShaders& shaders, const Scene& scene);
// Chapter 12's mip levels: --mips off keeps level 0 alone of every texture
// (before the upload and the reference); constant 6 (kRayCones) makes rays
// carry their cones where a texture has more than one level. Returns whether.
void keepLevelZero(Scene& scene);
bool useRayCones(RtShaders& shaders, const Scene& scene);
// Constant 7 (kSunDiscs): a sun's disc is drawn from only in a scene with a
// sun of some size (chapter 14's angular_radius_deg): the code alone cost
// chapter 15 10 % of a frame on an H100. Returns whether.
bool useSunDiscs(RtShaders& shaders, const Scene& scene);
// Constant 8 (kMeshes): hits write and ray generation shaders read a
// shading normal only in a scene with meshes (or spheres drawn as one,
// --sphere-mesh). Returns whether.
bool useMeshes(RtShaders& shaders, const RtScene& rt);

// [region needs_careful]
// Which of the shaders' branches for extreme numbers (rt_bindings.glsl)
// this scene needs, in the camera space of toCameraSpace:
// - sizes: a sphere seen from closer than 1/1024 of its radius (a floor
//   sphere), or a length outside 1e-8..1e8 (a sky dome of radius 1e20);
// - shininess: an exponent of 1e4 or more (a smooth glTF glass).
struct CarefulNumerics {
    bool sizes = true;
    bool shininess = true;
};
CarefulNumerics needsCarefulNumerics(const Scene& scene);
// [end]
// For a run: --numerics careful or fast, else (auto) the rule above.
CarefulNumerics carefulNumerics(const Options& opts, const Scene& scene);
// Sets RtShaders's constants 2 and 3, and says which for the report.
void specialize(RtShaders& shaders, const CarefulNumerics& careful);
nlohmann::json toJson(const CarefulNumerics& careful);

// Uploads everything and writes the descriptor set for `target`.
RtScene uploadScene(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene,
                    const Image& target, const SceneLayout& layout);

// A resized window (viewer.h): re-creates `target` and the per-pixel ray
// counts at the new size and rebinds both. The device must be idle; the old
// ones stay with whichever queue destroys them.
void resizeTarget(const Gpu& gpu, DeletionQueue& deletion, RtScene& rt, Image& target,
                  VkExtent2D size);

// Sum of the per-pixel ray counts of the last frame (host readback).
uint64_t countRays(const Gpu& gpu, const RtScene& scene);

}  // namespace rg
