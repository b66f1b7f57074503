// Wavefront OBJ files (chapter 12), through tinyobjloader: one mesh per
// material the faces use.
#include "scene/mesh_file.h"
#include "scene/mesh_readers.h"

#include "core/display.h"
#include "core/files.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <tuple>
#include <glm/gtc/type_ptr.hpp>

namespace rg {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what);
}
}  // namespace

// ---- OBJ -----------------------------------------------------------------

// One mesh per material the faces use; vertices that share position,
// normal and texture coordinate indices are one vertex.
MeshFile loadObj(const std::string& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = std::filesystem::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string why = reader.Error();
        why.erase(std::remove(why.begin(), why.end(), '\n'), why.end());
        fail(path, "not an OBJ file tinyobjloader reads (" +
                       (why.empty() ? std::string("no reason given") : why) + ")");
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    MeshFile file;
    for (const tinyobj::material_t& m : reader.GetMaterials()) {
        FileMaterial f{.name = m.name,
                       .baseColor = {m.diffuse[0], m.diffuse[1], m.diffuse[2]},
                       .metallic = 0};
        // Blinn-Phong exponent -> roughness
        f.roughness = std::clamp(std::sqrt(2.0 / (m.shininess + 2.0)), 0.0, 1.0);
        f.transmission = std::clamp(1.0 - m.dissolve, 0.0, 1.0);
        f.ior = m.ior >= 1 ? m.ior : 1.5;
        if (m.illum == 3 || m.illum == 5)
            f.metallic = 1, f.baseColor = {m.specular[0], m.specular[1], m.specular[2]};
        if (!m.diffuse_texname.empty()) {  // map_Kd: an image file beside the .mtl
            std::string image =
                (std::filesystem::path(config.mtl_search_path) / m.diffuse_texname)
                    .string();
            std::vector<unsigned char> bytes = readImageFile(path, image), rgba;
            int w = 0, h = 0;
            std::string why = decodeImage(bytes.data(), int(bytes.size()), w, h, rgba);
            if (!why.empty())
                fail(path, "material " + m.name + ": map_Kd " + image + ": " + why);
            Texture t = decodeTexture(image, rgba.data(), w, h);
            if (m.diffuse_texopt.clamp) t.wrapU = t.wrapV = TextureWrap::Clamp;
            f.baseColorTexture = int(file.textures.size());
            file.textures.push_back(std::move(t));
        }
        file.materials.push_back(f);
    }
    std::map<int, uint32_t> meshOfMaterial;
    std::vector<std::map<std::tuple<int, int, int>, uint32_t>> vertexOf;
    auto vertexCount = attrib.vertices.size() / 3,
         normalCount = attrib.normals.size() / 3;
    auto texcoordCount = attrib.texcoords.size() / 2;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        size_t offset = 0;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            size_t corners = shape.mesh.num_face_vertices[f];
            int material =
                f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (material >= int(file.materials.size())) material = -1;
            auto [it, added] =
                meshOfMaterial.try_emplace(material, uint32_t(file.meshes.size()));
            if (added) {
                file.meshes.push_back(
                    {.name = path + (material >= 0
                                         ? ": material " + file.materials[material].name
                                         : "")});
                file.parts.push_back({.mesh = it->second, .material = material});
                vertexOf.emplace_back();
            }
            Mesh& mesh = file.meshes[it->second];
            if (corners != 3)
                fail(path, "face " + std::to_string(f) + " of \"" + shape.name +
                               "\" is not a triangle");
            for (size_t k = 0; k < 3; ++k) {
                tinyobj::index_t index = shape.mesh.indices[offset + k];
                if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertexCount)
                    fail(path, "face " + std::to_string(f) + " uses vertex " +
                                   std::to_string(index.vertex_index + 1) +
                                   ", but there are " + std::to_string(vertexCount) +
                                   " vertices");
                int normal = index.normal_index;
                if (normal >= 0 && size_t(normal) >= normalCount)
                    fail(path, "face " + std::to_string(f) + " uses normal " +
                                   std::to_string(normal + 1) + ", but there are " +
                                   std::to_string(normalCount) + " normals");
                int texcoord = index.texcoord_index;
                if (texcoord >= 0 && size_t(texcoord) >= texcoordCount)
                    fail(path, "face " + std::to_string(f) + " uses texture coordinate " +
                                   std::to_string(texcoord + 1) + ", but there are " +
                                   std::to_string(texcoordCount));
                auto [v, isNew] = vertexOf[it->second].try_emplace(
                    {index.vertex_index, normal, texcoord},
                    uint32_t(mesh.vertices.size()));
                if (isNew) {
                    const float* p = &attrib.vertices[3 * size_t(index.vertex_index)];
                    mesh.vertices.push_back({p[0], p[1], p[2]});
                    if (normal >= 0) {
                        const float* n = &attrib.normals[3 * size_t(normal)];
                        mesh.normals.push_back({n[0], n[1], n[2]});
                    }
                    if (texcoord >= 0) {  // OBJ's v points up the image, glTF's down
                        const float* uv = &attrib.texcoords[2 * size_t(texcoord)];
                        mesh.texcoords.push_back({uv[0], 1.0f - uv[1]});
                    }
                }
                mesh.indices.push_back(v->second);
            }
            offset += corners;
        }
    }
    for (Mesh& mesh : file.meshes) {
        // some faces without: flat
        if (mesh.normals.size() != mesh.vertices.size()) mesh.normals.clear();
        // some without: untextured
        if (mesh.texcoords.size() != mesh.vertices.size()) mesh.texcoords.clear();
        checkMesh(mesh);
    }
    if (file.meshes.empty()) fail(path, "no faces: an empty mesh");
    return file;
}

}  // namespace rg
