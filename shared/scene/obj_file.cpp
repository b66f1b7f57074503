// Wavefront OBJ files (chapter 12), through tinyobjloader: one mesh per
// material the faces use.
#include "scene/mesh_file.h"
#include "scene/mesh_readers.h"

#include "core/files.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <glm/gtc/matrix_transform.hpp>

namespace rg {

// ---- OBJ -----------------------------------------------------------------

namespace {
// tinyobjloader reads "nan", "inf" or a word as 0 and goes on: a corner
// silently at the origin. So every number of a v, vn or vt line is read
// here first, and anything but a finite number refuses the file, naming
// the line (as glTF's numbers are refused, mesh.cpp).
void refuseNonFiniteNumbers(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        size_t at = line.find_first_not_of(" \t");
        if (at == std::string::npos || line[at] != 'v') continue;  // fast: f, #, ...
        size_t keyEnd = line.find_first_of(" \t", at);
        std::string keyword = line.substr(at, keyEnd - at);
        if (keyword != "v" && keyword != "vn" && keyword != "vt") continue;
        size_t comment = line.find('#');
        for (at = keyEnd; at < comment;) {
            at = line.find_first_not_of(" \t", at);
            if (at >= comment) break;
            size_t wordEnd = std::min(line.find_first_of(" \t", at), comment);
            std::string word = line.substr(at, wordEnd - at);
            char* end = nullptr;
            double value = std::strtod(word.c_str(), &end);
            if (*end != '\0' || !std::isfinite(value))
                refuseFile(
                    path,
                    "line " + std::to_string(number) + ": " + line + ": " + word +
                        (*end != '\0' ? " is not a number" : " is not a finite number"));
            at = wordEnd;
        }
    }
}
}  // namespace

// One mesh per material the faces use; vertices that share position,
// normal and texture coordinate indices are one vertex.
MeshFile loadObj(const std::string& path) {
    refuseNonFiniteNumbers(path);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = std::filesystem::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string why = reader.Error();
        why.erase(std::remove(why.begin(), why.end(), '\n'), why.end());
        refuseFile(path, "not an OBJ file tinyobjloader reads (" +
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
                refuseFile(path, "material " + m.name + ": map_Kd " + image + ": " + why);
            Texture t = decodeTexture(image, rgba.data(), w, h);
            if (m.diffuse_texopt.clamp) t.wrapU = t.wrapV = TextureWrap::Clamp;
            f.baseColorTexture = int(file.textures.size());
            file.textures.push_back(std::move(t));
        }
        file.materials.push_back(f);
    }
    // The file's numbers are read in double (tinyobjloader_double) and taken
    // relative to the centre of their box before they become floats: a mesh
    // written around (1e6, 0, 0) keeps its shape (Mesh::origin).
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
        glm::dvec3 v(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
        lo = glm::min(lo, v), hi = glm::max(hi, v);
    }
    glm::dvec3 centre = lo.x <= hi.x ? (lo + hi) / 2.0 : glm::dvec3(0);
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
                file.parts.push_back(
                    {.mesh = it->second,
                     .material = material,
                     .name = material >= 0
                                 ? "faces of material " + file.materials[material].name
                                 : "faces without a material"});
                vertexOf.emplace_back();
            }
            Mesh& mesh = file.meshes[it->second];
            if (corners != 3)
                refuseFile(path, "face " + std::to_string(f) + " of \"" + shape.name +
                                     "\" is not a triangle");
            for (size_t k = 0; k < 3; ++k) {
                tinyobj::index_t index = shape.mesh.indices[offset + k];
                if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertexCount)
                    refuseFile(path, "face " + std::to_string(f) + " uses vertex " +
                                         std::to_string(index.vertex_index + 1) +
                                         ", but there are " +
                                         std::to_string(vertexCount) + " vertices");
                int normal = index.normal_index;
                if (normal >= 0 && size_t(normal) >= normalCount)
                    refuseFile(path, "face " + std::to_string(f) + " uses normal " +
                                         std::to_string(normal + 1) + ", but there are " +
                                         std::to_string(normalCount) + " normals");
                int texcoord = index.texcoord_index;
                if (texcoord >= 0 && size_t(texcoord) >= texcoordCount)
                    refuseFile(path,
                               "face " + std::to_string(f) + " uses texture coordinate " +
                                   std::to_string(texcoord + 1) + ", but there are " +
                                   std::to_string(texcoordCount));
                auto [v, isNew] = vertexOf[it->second].try_emplace(
                    {index.vertex_index, normal, texcoord},
                    uint32_t(mesh.vertices.size()));
                if (isNew) {
                    const tinyobj::real_t* p =
                        &attrib.vertices[3 * size_t(index.vertex_index)];
                    mesh.vertices.push_back(glm::dvec3(p[0], p[1], p[2]) - centre);
                    if (normal >= 0) {
                        const tinyobj::real_t* n = &attrib.normals[3 * size_t(normal)];
                        mesh.normals.push_back(glm::dvec3(n[0], n[1], n[2]));
                    }
                    if (texcoord >= 0) {  // OBJ's v points up the image, glTF's down
                        const tinyobj::real_t* uv =
                            &attrib.texcoords[2 * size_t(texcoord)];
                        mesh.texcoords.push_back(glm::dvec2(uv[0], 1.0 - uv[1]));
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
        mesh.origin = centre;
        recentre(mesh);  // each mesh on its own box
        checkMesh(mesh);
    }
    for (MeshPart& part : file.parts)
        part.transform = glm::translate(glm::dmat4(1.0), file.meshes[part.mesh].origin);
    if (file.meshes.empty()) refuseFile(path, "no faces: an empty mesh");
    return file;
}

}  // namespace rg
