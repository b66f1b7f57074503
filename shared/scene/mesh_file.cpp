// Mesh files (chapter 12): the reader each file's extension picks, and the
// images their materials name (scene/texture.h decodes them).
#include "scene/mesh_file.h"

#include "core/display.h"
#include "core/files.h"
#include "scene/mesh_readers.h"

#include <stb_image.h>

#include <algorithm>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>

namespace rg {

[[noreturn]] void refuseFile(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what);
}

namespace {
std::string lowerExtension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

}  // namespace

std::string decodeImage(const unsigned char* bytes, int size, int& width, int& height,
                        std::vector<unsigned char>& rgba) {
    int channels = 0;
    // KTX (KHR_texture_basisu's compressed textures) starts with its own
    // identifier: say what it is rather than that it is no image
    const unsigned char ktx[] = {0xAB, 'K', 'T', 'X', ' '};
    if (size >= 5 && std::memcmp(bytes, ktx, sizeof ktx) == 0)
        return "a KTX image, which RayGlass does not read (PNG and JPEG only: export "
               "the textures as PNG or JPEG)";
    if (!stbi_info_from_memory(bytes, size, &width, &height, &channels))
        return stbi_failure_reason() ? stbi_failure_reason()
                                     : "not an image stb_image reads";
    if (width > kMaxTextureSide || height > kMaxTextureSide)
        return std::to_string(width) + "x" + std::to_string(height) +
               " texels, more than " + std::to_string(kMaxTextureSide) + " a side";
    unsigned char* data =
        stbi_load_from_memory(bytes, size, &width, &height, &channels, 4);
    if (!data) return stbi_failure_reason() ? stbi_failure_reason() : "a truncated image";
    rgba.assign(data, data + size_t(width) * height * 4);
    stbi_image_free(data);
    return "";
}

std::vector<unsigned char> readImageFile(const std::string& meshPath,
                                         const std::string& image) {
    // missing, a folder, a FIFO: each its own reason
    requireRegularFile(image, meshPath + ": map_Kd");
    std::ifstream in(image, std::ios::binary);
    if (!in) refuseFile(meshPath, "cannot read the image " + image);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

FileMaterial gltfDefaultMaterial() {
    return {.name = "glTF's default material", .baseColor = glm::dvec3(1.0),
            .metallic = 1, .roughness = 1};
}

FileMaterial objDefaultMaterial() {
    return {.name = "RayGlass's default for OBJ",
            .baseColor = glm::dvec3(0.8),
            .metallic = 0,
            .roughness = 1};
}

// [region load_mesh_file]
MeshFile loadMeshFile(const std::string& path) {
    requireRegularFile(path, "mesh file");
    std::string extension = lowerExtension(path);
    bool gltf = extension == ".gltf" || extension == ".glb";
    if (extension != ".obj" && !gltf)
        refuseFile(path, "not a mesh file RayGlass reads (.gltf, .glb or .obj)");
    MeshFile file = gltf ? loadGltf(path, extension == ".glb") : loadObj(path);
    // A part that names no material takes the format's default, once per file.
    for (MeshPart& part : file.parts) {
        if (part.material >= 0) continue;
        if (file.defaultMaterialParts++ == 0)
            file.materials.push_back(gltf ? gltfDefaultMaterial() : objDefaultMaterial());
        part.material = int(file.materials.size() - 1);
    }
    return file;
}
// [end]

}  // namespace rg
