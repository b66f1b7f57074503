// Mesh files (chapter 12): glTF 2.0 (.gltf, .glb) through tinygltf and
// Wavefront OBJ (.obj, with its .mtl) through tinyobjloader, both Debian's.
// A file becomes checked meshes (mesh.h), the materials it names, and parts:
// one placed mesh each (a glTF node's mesh primitive, an OBJ's faces of one
// material). The scene format (mesh_objects.h) maps the materials onto RayGlass's.
#pragma once
#include "scene/mesh.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rg {

// A material as a glTF file describes it (an OBJ's .mtl is translated to
// the same terms): metallic-roughness with its base colour texture, plus
// KHR_materials_transmission and KHR_materials_ior.
struct FileMaterial {
    std::string name;
    glm::dvec3 baseColor{1.0};  // linear
    double metallic = 1, roughness = 1;  // glTF's defaults
    double transmission = 0;    // KHR_materials_transmission
    double ior = 1.5;           // KHR_materials_ior
    // KHR_materials_volume (chapter 13): the colour white light
    glm::dvec3 attenuationColor{1.0};
    // keeps after this distance in the scene's units; 0: no absorption
    double attenuationDistance = 0;
    // KHR_materials_volume's thicknessFactor: > 0, the mesh bounds a volume
    // of glass; 0 (the default), a transmissive surface is thin-walled
    double thickness = 0;
    // KHR_materials_dispersion (chapter 13): 20 / Abbe number, 0: none
    double dispersion = 0;
    // index into MeshFile::textures (times baseColor), -1: none
    int baseColorTexture = -1;
    // index into MeshFile::textures: roughness in G, metalness in B (times
    // the factors), linear; -1: none
    int metallicRoughnessTexture = -1;
    // index into MeshFile::textures: tangent-space normals, linear; -1: none
    int normalTexture = -1;
    double normalScale = 1;  // normalTexture's scale: of the normal's x and y
    // glTF's alpha (3.9.2 and 3.9.4): baseColorFactor's fourth number times
    // the texture's alpha; alphaMode OPAQUE ignores it, MASK keeps a hit
    // only where it is at least alphaCutoff, BLEND (read here as MASK at
    // 0.5: chapter 12's page says why)
    double alpha = 1;
    enum class AlphaMode { Opaque, Mask, Blend } alphaMode = AlphaMode::Opaque;
    double alphaCutoff = 0.5;
};

struct MeshPart {
    uint32_t mesh = 0;        // index into MeshFile::meshes
    // index into MeshFile::materials (-1 while a reader has found none: loadMeshFile
    // gives such a part the format's default material)
    int material = -1;
    glm::dmat4 transform{1};  // the file's own placement (glTF node hierarchy)
    // for messages: "node 3 \"Leaves\", primitive 0" (glTF), "faces of material
    // glass" (OBJ)
    std::string name;
};

struct MeshFile {
    // each checked (checkMesh); one per glTF primitive, however often placed
    std::vector<Mesh> meshes;
    // the file's own, then (if a part names none) the format's default
    std::vector<FileMaterial> materials;
    // parts that name no material and take the default (materials.back())
    size_t defaultMaterialParts = 0;
    std::vector<Texture> textures;  // the textures the materials use, decoded
    std::vector<MeshPart> parts;
    size_t skippedPrimitives = 0;  // points and lines: not surfaces
};

// Throws InputError "<path>: <why>" for a file that is missing, not one of
// the formats, malformed (accessors outside their buffers, sparse or
// quantized positions), naming an image stb_image cannot decode, or holding
// a mesh checkMesh refuses.
MeshFile loadMeshFile(const std::string& path);

// The material of a part that names none (MeshFile::defaultMaterialParts).
// glTF defines one (glTF 2.0, 3.7.2.1: "If material is undefined, then a
// default material MUST be used"): base colour 1, metallic 1, roughness 1,
// a rough white metal. OBJ defines none; Blender's default stands in: a
// diffuse grey of 0.8, not metal.
FileMaterial gltfDefaultMaterial();
FileMaterial objDefaultMaterial();

}  // namespace rg
