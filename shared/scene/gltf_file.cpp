// glTF 2.0 files (chapter 12), .gltf and .glb, through tinygltf: every
// range checked, materials in the metal-roughness model, textures decoded.
#include "scene/mesh_file.h"
#include "scene/mesh_readers.h"

#include "core/display.h"
#include "core/files.h"

#include <stb_image.h>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <tuple>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace rg {

namespace {

// ---- glTF ----------------------------------------------------------------

// The elements of an accessor as floats (3 or 2 a vertex) or indices, with
// every range checked against its buffer: a file could point anywhere.
struct AccessorReader {
    const tinygltf::Model& model;
    const std::string& path;

    const unsigned char* bytes(int index, int type, size_t componentSize, size_t& count,
                               size_t& stride, const std::string& what) const {
        if (index < 0 || size_t(index) >= model.accessors.size())
            refuseFile(path,
                       what + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = model.accessors[index];
        if (a.sparse.isSparse) refuseFile(path, what + ": sparse accessors are not read");
        if (a.type != type)
            refuseFile(path, what + ": accessor " + std::to_string(index) +
                                 " has the wrong element type");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
            refuseFile(path, what + ": accessor " + std::to_string(index) +
                                 " has no buffer view");
        const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            refuseFile(path, what + ": buffer view " + std::to_string(a.bufferView) +
                                 " has no buffer");
        const tinygltf::Buffer& buffer = model.buffers[view.buffer];
        int components = tinygltf::GetNumComponentsInType(a.type);
        size_t element = componentSize * size_t(components);
        count = a.count;
        stride = view.byteStride ? view.byteStride : element;
        size_t need = count == 0 ? 0 : a.byteOffset + (count - 1) * stride + element;
        if (view.byteOffset > buffer.data.size() ||
            view.byteLength > buffer.data.size() - view.byteOffset ||
            need > view.byteLength)
            refuseFile(path, what + ": accessor " + std::to_string(index) +
                                 " reaches past the end of its buffer");
        return buffer.data.data() + view.byteOffset + a.byteOffset;
    }

    std::vector<glm::vec3> vec3s(int index, const std::string& what) const {
        if (index >= 0 && size_t(index) < model.accessors.size() &&
            model.accessors[index].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            refuseFile(
                path,
                what + ": only float components are read (no KHR_mesh_quantization)");
        size_t count, stride;
        const unsigned char* p = bytes(index, TINYGLTF_TYPE_VEC3, 4, count, stride, what);
        std::vector<glm::vec3> out(count);
        for (size_t i = 0; i < count; ++i)
            std::memcpy(&out[i], p + i * stride, sizeof(glm::vec3));
        return out;
    }

    // TEXCOORD_n: floats, or unsigned bytes or shorts normalized to [0, 1]
    // (glTF 3.7.2.1).
    std::vector<glm::vec2> vec2s(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= model.accessors.size())
            refuseFile(path,
                       what + ": accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& a = model.accessors[index];
        int type = a.componentType;
        size_t size = type == TINYGLTF_COMPONENT_TYPE_FLOAT            ? 4
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                                                                       : 0;
        if (size == 0 || (size < 4 && !a.normalized))
            refuseFile(path,
                       what +
                           ": texture coordinates must be floats or normalized unsigned "
                           "bytes or shorts");
        size_t count, stride;
        const unsigned char* p =
            bytes(index, TINYGLTF_TYPE_VEC2, size, count, stride, what);
        std::vector<glm::vec2> out(count);
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < 2; ++c) {
                const unsigned char* e = p + i * stride + c * size;
                if (size == 4) std::memcpy(&out[i][c], e, 4);
                else if (size == 2)
                    out[i][c] = float(uint32_t(e[0]) | uint32_t(e[1]) << 8) / 65535.0f;
                else out[i][c] = float(e[0]) / 255.0f;
            }
        return out;
    }

    std::vector<uint32_t> indices(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= model.accessors.size())
            refuseFile(path,
                       what + ": accessor " + std::to_string(index) + " does not exist");
        int type = model.accessors[index].componentType;
        size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                       : 0;
        if (size == 0)
            refuseFile(path, what + ": indices must be unsigned bytes, shorts or ints");
        size_t count, stride;
        const unsigned char* p =
            bytes(index, TINYGLTF_TYPE_SCALAR, size, count, stride, what);
        std::vector<uint32_t> out(count);
        for (size_t i = 0; i < count; ++i) {
            uint32_t v = 0;
            // little-endian, as glTF's buffers are
            std::memcpy(&v, p + i * stride, size);
            out[i] = v;
        }
        return out;
    }
};

double extensionNumber(const tinygltf::ExtensionMap& extensions, const std::string& name,
                       const std::string& key, double fallback) {
    auto it = extensions.find(name);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key))
        return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// A node's transform: its matrix, or translation * rotation * scale.
glm::dmat4 nodeTransform(const tinygltf::Node& node) {
    // column-major, as glm
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
        m[3] =
            glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1);
    if (node.rotation.size() == 4)  // x, y, z, w
        m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0],
                                       node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3)
        m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

// tinygltf hands over each image's bytes (from a buffer view, a data URI or
// a file beside the .gltf); stb_image decodes them, as it does the sky.
// Its message begins with kImageError, so that loadGltf can tell it from
// tinygltf's own. A KTX image (KHR_texture_basisu) is left undecoded and
// listed in `ktx` (a std::set<int>): refused only if a material uses it, as
// a file may give a PNG beside it for readers without KTX.
const char kImageError[] = "image ";
bool decodeGltfImage(tinygltf::Image* image, const int index, std::string* error,
                     std::string*, int, int, const unsigned char* bytes, int size,
                     void* ktx) {
    const unsigned char magic[] = {0xAB, 'K', 'T', 'X', ' '};
    if (size >= 5 && std::memcmp(bytes, magic, sizeof magic) == 0) {
        static_cast<std::set<int>*>(ktx)->insert(index);
        return true;
    }
    std::string why = decodeImage(bytes, size, image->width, image->height, image->image);
    if (!why.empty()) {
        if (error) *error = kImageError + std::to_string(index) + ": " + why;
        return false;
    }
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    return true;
}

// A sampler's wrap mode (glTF 3.9.4's GL enums).
TextureWrap wrapOf(int mode) {
    return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? TextureWrap::Clamp
           : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::Mirror
                                                           : TextureWrap::Repeat;
}

// A URI as glTF writes it (RFC 3986): %20 is a space.
std::string decodeUri(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uri[i + 1]) &&
            std::isxdigit(uri[i + 2])) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// The files a .gltf names beside itself (its buffers' .bin, its images),
// each checked before tinygltf reads it, so that a missing one is named as
// missing. A file tinygltf cannot parse is left to tinygltf's own message.
void requireNamedFiles(const std::string& path) {
    nlohmann::json j;
    try {
        std::ifstream in(path);
        j = nlohmann::json::parse(in);
    } catch (const std::exception&) {
        return;
    }
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const char* kind : {"buffers", "images"}) {
        if (!j.contains(kind) || !j[kind].is_array()) continue;
        for (size_t i = 0; i < j[kind].size(); ++i) {
            const nlohmann::json& item = j[kind][i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string())
                continue;
            std::string uri = item["uri"];
            if (uri.rfind("data:", 0) == 0) continue;
            std::string what = std::string(kind == std::string("buffers") ? "buffer "
                                                                          : "image ") +
                               std::to_string(i) + ": " + uri;
            std::error_code ec;
            if (!std::filesystem::is_regular_file(dir / decodeUri(uri), ec))
                refuseFile(path, what + ": not found (looked beside the file)");
        }
    }
}

}  // namespace

MeshFile loadGltf(const std::string& path, bool binary) {
    if (!binary) requireNamedFiles(path);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::set<int> ktxImages;
    loader.SetImageLoader(decodeGltfImage, &ktxImages);
    std::string error, warning;
    bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                     : loader.LoadASCIIFromFile(&model, &error, &warning, path);
    if (!ok) {
        std::replace(error.begin(), error.end(), '\n', ' ');
        while (!error.empty() && error.back() == ' ') error.pop_back();
        // an image that would not decode: its own message, not "not a glTF file"
        if (error.rfind(kImageError, 0) == 0) refuseFile(path, error);
        refuseFile(path, "not a glTF file tinygltf reads (" +
                             (error.empty() ? std::string("no reason given") : error) +
                             ")");
    }
    MeshFile file;
    // [region gltf_texture]
    // A glTF texture is an image and a sampler; each one a material uses
    // becomes one decoded Texture, however many materials share it (a colour
    // decoded from sRGB, or data: metal-roughness, normals).
    std::map<std::pair<int, TexelData>, int> textureOf;
    auto decodedTexture = [&](int index, const std::string& material, const char* role,
                              TexelData data) -> int {
        // `material`: "material leaf", or "material 3" for an unnamed one
        if (index < 0) return -1;
        auto [it, added] =
            textureOf.try_emplace({index, data}, int(file.textures.size()));
        if (!added) return it->second;
        std::string what = material + ": " + role + " texture " + std::to_string(index);
        if (size_t(index) >= model.textures.size())
            refuseFile(path, what + " does not exist");
        const tinygltf::Texture& texture = model.textures[index];
        const char* noKtx =
            "a KTX image, which RayGlass does not read (PNG and JPEG only)";
        if (texture.source < 0 && texture.extensions.count("KHR_texture_basisu"))
            refuseFile(path, what + " has only " + noKtx);
        if (texture.source < 0 || size_t(texture.source) >= model.images.size())
            refuseFile(path, what + " has no image");
        if (ktxImages.count(texture.source))
            refuseFile(path, what + ": image " + std::to_string(texture.source) + " is " +
                                 noKtx);
        const tinygltf::Image& image = model.images[texture.source];
        if (image.image.size() != size_t(image.width) * image.height * 4)
            refuseFile(path, what + ": its image was not decoded");
        Texture t = decodeTexture(path + ": image " + std::to_string(texture.source),
                                  image.image.data(), image.width, image.height, data);
        if (texture.sampler >= 0 && size_t(texture.sampler) < model.samplers.size()) {
            const tinygltf::Sampler& sampler = model.samplers[texture.sampler];
            t.wrapU = wrapOf(sampler.wrapS);
            t.wrapV = wrapOf(sampler.wrapT);
            t.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            // minFilter (3.8.4.3): within a level, and between levels; unset: trilinear
            switch (sampler.minFilter) {
            case TINYGLTF_TEXTURE_FILTER_NEAREST:
                t.minNearest = true, t.mipmap = TextureMipmap::None;
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR: t.mipmap = TextureMipmap::None; break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
                t.minNearest = true, t.mipmap = TextureMipmap::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
                t.mipmap = TextureMipmap::Nearest;
                break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
                t.minNearest = true;
                break;
            default: break;  // LINEAR_MIPMAP_LINEAR, or unset
            }
        }
        file.textures.push_back(std::move(t));
        return it->second;
    };
    // [end]
    std::vector<int> texcoordSet;  // per material: the TEXCOORD_n its textures read
    for (const tinygltf::Material& m : model.materials) {
        const auto& pbr = m.pbrMetallicRoughness;
        FileMaterial f{.name = m.name.empty()
                                   ? "material " + std::to_string(file.materials.size())
                                   : m.name};
        if (pbr.baseColorFactor.size() >= 3)
            f.baseColor = {pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                           pbr.baseColorFactor[2]};
        if (pbr.baseColorFactor.size() == 4)
            f.alpha = std::clamp(pbr.baseColorFactor[3], 0.0, 1.0);
        using Alpha = FileMaterial::AlphaMode;
        f.alphaMode = m.alphaMode == "MASK"    ? Alpha::Mask
                      : m.alphaMode == "BLEND" ? Alpha::Blend
                                               : Alpha::Opaque;
        f.alphaCutoff = m.alphaCutoff;
        if (!(f.alphaCutoff >= 0))
            refuseFile(path, "material " + f.name + ": alphaCutoff is not >= 0");
        f.metallic = std::clamp(pbr.metallicFactor, 0.0, 1.0);
        f.roughness = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
        f.transmission =
            std::clamp(extensionNumber(m.extensions, "KHR_materials_transmission",
                                       "transmissionFactor", 0.0),
                       0.0, 1.0);
        f.ior = std::clamp(extensionNumber(m.extensions, "KHR_materials_ior", "ior", 1.5),
                           1.0, 10.0);
        // an unnamed one is already "material N"
        std::string label = m.name.empty() ? f.name : "material " + f.name;
        f.baseColorTexture = decodedTexture(pbr.baseColorTexture.index, label,
                                            "base colour", TexelData::Colour);
        f.metallicRoughnessTexture =
            decodedTexture(pbr.metallicRoughnessTexture.index, label, "metal-roughness",
                           TexelData::Linear);
        f.normalTexture =
            decodedTexture(m.normalTexture.index, label, "normal", TexelData::Linear);
        f.normalScale = m.normalTexture.scale;
        if (!std::isfinite(f.normalScale))
            refuseFile(path, label + ": the normal texture's scale is not finite");
        // one set of texture coordinates per material (every texture's texCoord)
        std::set<int> sets;
        if (f.baseColorTexture >= 0) sets.insert(pbr.baseColorTexture.texCoord);
        if (f.metallicRoughnessTexture >= 0)
            sets.insert(pbr.metallicRoughnessTexture.texCoord);
        if (f.normalTexture >= 0) sets.insert(m.normalTexture.texCoord);
        if (sets.size() > 1)
            refuseFile(path, label + ": its textures name different TEXCOORD sets "
                                     "(RayGlass reads one per material)");
        texcoordSet.push_back(sets.empty() ? 0 : *sets.begin());
        // KHR_materials_volume: a thicknessFactor above 0 makes a transmissive
        // material a volume (its value is for rasterizers: a ray tracer meets
        // the real thickness); without one it is thin-walled. The volume's
        // absorption is chapter 13's.
        f.thickness = extensionNumber(m.extensions, "KHR_materials_volume",
                                      "thicknessFactor", 0.0);
        if (!(f.thickness >= 0 && std::isfinite(f.thickness)))
            refuseFile(path, "material " + f.name + ": thicknessFactor is not >= 0");
        f.attenuationDistance = extensionNumber(m.extensions, "KHR_materials_volume",
                                                "attenuationDistance", 0.0);
        if (!(f.attenuationDistance > 0 && std::isfinite(f.attenuationDistance)))
            f.attenuationDistance = 0;
        auto volume = m.extensions.find("KHR_materials_volume");
        if (f.attenuationDistance > 0 && volume->second.Has("attenuationColor")) {
            const tinygltf::Value& c = volume->second.Get("attenuationColor");
            if (!c.IsArray() || c.ArrayLen() != 3)
                refuseFile(path,
                           "material " + f.name + ": attenuationColor is not 3 numbers");
            for (int k = 0; k < 3; ++k)
                f.attenuationColor[k] = std::clamp(
                    c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : 1.0, 1e-6, 1.0);
        }
        f.dispersion =
            extensionNumber(m.extensions, "KHR_materials_dispersion", "dispersion", 0.0);
        if (!(f.dispersion >= 0 && f.dispersion <= 20))
            refuseFile(path, "material " + f.name + ": dispersion is not in [0, 20]");
        file.materials.push_back(f);
    }
    AccessorReader read{model, path};
    // One checked mesh per primitive, made on first use; every placement shares it.
    std::map<std::pair<int, int>, int> meshOf;
    auto primitiveMesh = [&](int meshIndex, int p) -> int {
        auto [it, added] = meshOf.try_emplace({meshIndex, p}, -1);
        if (!added) return it->second;
        const tinygltf::Primitive& primitive = model.meshes[meshIndex].primitives[p];
        std::string what =
            "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
            ++file.skippedPrimitives;  // points, lines, strips and fans: not read
            return -1;
        }
        auto position = primitive.attributes.find("POSITION");
        if (position == primitive.attributes.end())
            refuseFile(path, what + ": no POSITION attribute");
        Mesh mesh{.name = path + ": " + what};
        mesh.vertices = read.vec3s(position->second, what + " POSITION");
        auto normal = primitive.attributes.find("NORMAL");
        if (normal != primitive.attributes.end())
            mesh.normals = read.vec3s(normal->second, what + " NORMAL");
        // The texture coordinates the material's textures name (TEXCOORD_0 by default).
        int material = primitive.material, set = 0;
        if (material >= 0 && size_t(material) < texcoordSet.size())
            set = texcoordSet[material];
        auto texcoord = primitive.attributes.find("TEXCOORD_" + std::to_string(set));
        if (texcoord != primitive.attributes.end()) {
            mesh.texcoords =
                read.vec2s(texcoord->second, what + " TEXCOORD_" + std::to_string(set));
            if (mesh.texcoords.size() != mesh.vertices.size())
                refuseFile(path, what + ": TEXCOORD_" + std::to_string(set) +
                                     " and POSITION differ in count");
        }
        if (primitive.indices >= 0) {
            mesh.indices = read.indices(primitive.indices, what + " indices");
        } else {  // not indexed: every three vertices a triangle
            mesh.indices.resize(mesh.vertices.size());
            for (uint32_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = i;
        }
        // floats near 0: a mesh far from the file's origin keeps its shape
        recentre(mesh);
        checkMesh(mesh);
        file.meshes.push_back(std::move(mesh));
        return it->second = int(file.meshes.size() - 1);
    };
    // The default scene's nodes (or every root node), down the hierarchy.
    std::vector<int> roots;
    if (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size())
        roots = model.scenes[model.defaultScene].nodes;
    else if (!model.scenes.empty()) roots = model.scenes[0].nodes;
    size_t visited = 0;
    std::function<void(int, const glm::dmat4&, int)> visit =
        [&](int n, const glm::dmat4& parent, int depth) {
            if (n < 0 || size_t(n) >= model.nodes.size())
                refuseFile(path, "node " + std::to_string(n) + " does not exist");
            if (depth > 64 || ++visited > 10000000)
                refuseFile(path, "the node hierarchy is deeper than 64 or has a cycle");
            const tinygltf::Node& node = model.nodes[n];
            glm::dmat4 transform = parent * nodeTransform(node);
            if (node.mesh >= 0) {
                if (size_t(node.mesh) >= model.meshes.size())
                    refuseFile(path, "node " + std::to_string(n) + ": mesh " +
                                         std::to_string(node.mesh) + " does not exist");
                for (size_t p = 0; p < model.meshes[node.mesh].primitives.size(); ++p) {
                    int mesh = primitiveMesh(node.mesh, int(p));
                    if (mesh < 0) continue;
                    int material = model.meshes[node.mesh].primitives[p].material;
                    if (material >= int(file.materials.size()))
                        refuseFile(path, "node " + std::to_string(n) + ": material " +
                                             std::to_string(material) +
                                             " does not exist");
                    // the mesh was recentred: its part puts it back
                    glm::dmat4 origin =
                        glm::translate(glm::dmat4(1.0), file.meshes[mesh].origin);
                    std::string nodeName =
                        "node " + std::to_string(n) +
                        (node.name.empty() ? "" : " \"" + node.name + "\"");
                    file.parts.push_back({.mesh = uint32_t(mesh),
                                          .material = material,
                                          .transform = transform * origin,
                                          .name = nodeName + ", primitive " +
                                                  std::to_string(p)});
                }
            }
            for (int child : node.children) visit(child, transform, depth + 1);
        };
    for (int n : roots) visit(n, glm::dmat4(1.0), 0);
    for (const MeshPart& part : file.parts)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(part.transform[c][r]))
                    refuseFile(path, "a node's transform is not finite");
    if (file.parts.empty())
        refuseFile(path,
                   "no triangles placed (an empty mesh, or a scene without mesh nodes)");
    return file;
}

}  // namespace rg
