// Mesh objects in a scene file (chapter 12), inside scene/ only: a glTF or
// OBJ file's materials in RayGlass's terms, and each file read once however
// often the scene places it.
#pragma once
#include "scene/mesh_file.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

namespace rg {

// [region mesh_material]
// A glTF material in RayGlass's terms (docs/scene-format.md): the metal-
// roughness factors by applyMetalRoughness (rules.cpp), which they are kept
// for, should a texture vary them per hit; f0 follows from the index,
// ((n - 1) / (n + 1))^2. Its caller sets the textures: a base colour texture
// multiplies ka and kd where a ray meets the mesh.
inline Material materialFromFile(const FileMaterial& f) {
    Material m;  // named by the caller, after the file
    applyMetalRoughness(m, f.baseColor, f.metallic, f.roughness, f.transmission);
    m.metalRough = {.baseColor = f.baseColor,
                    .metallic = f.metallic,
                    .roughness = f.roughness};  // the caller sets its texture
    m.normalScale = f.normalScale;
    m.transmission = f.transmission;
    m.thin = f.transmission > 0 && !(f.thickness > 0);  // KHR_materials_volume
    m.ior = f.ior;
    m.f0 = std::pow((f.ior - 1) / (f.ior + 1), 2);
    // ch 13
    if (f.attenuationDistance > 0 && !m.thin)  // a thin wall holds no medium
        m.absorption = absorptionOf(f.attenuationColor, f.attenuationDistance);
    m.dispersion = f.dispersion;  // ch 13
    // ch 12: alpha-tested cut-outs (BLEND as MASK at its default cutoff)
    if (f.alphaMode != FileMaterial::AlphaMode::Opaque) {
        bool mask = f.alphaMode == FileMaterial::AlphaMode::Mask;
        m.alphaCutoff = mask ? f.alphaCutoff : 0.5;
        m.alpha = f.alpha;
    }
    return m;
}
// [end]

// Mesh objects (chapter 12): each file is read once, its meshes go into
// Scene::meshes once, and every placement adds one object per part.
class MeshFiles {
public:
    MeshFiles(const Reader& r, const std::string& scenePath, Scene& scene)
        : r_(r), path_(scenePath), scene_(scene) {}

    // `entry`: the scene file's objects[entry], which `key` names
    void place(const std::string& name, const std::string& key, uint32_t entry,
               const glm::dmat4& transform, bool moving,
               std::optional<uint32_t> material) {
        std::string file = findInput(r_, path_, name, key + ".file");
        auto it = loaded_.find(file);
        if (it == loaded_.end()) it = loaded_.emplace(file, load(file, key)).first;
        const Loaded& l = it->second;
        // once per file, and only where the scene gives no material instead
        if (!material && l.defaultMaterialParts > 0 && noted_.insert(file).second)
            std::fprintf(stderr,
                         "%s: %s: note: %zu of %s's meshes name no material: they take "
                         "%s\n",
                         path_.c_str(), key.c_str(), l.defaultMaterialParts,
                         name.c_str(), l.defaultMaterial.c_str());
        for (const MeshPart& part : l.parts) {
            Object o{.type = ShapeType::Mesh,
                     .material = material ? *material : l.materials[part.material],
                     .moving = moving,
                     .transform = transform * part.transform,
                     .mesh = l.firstMesh + part.mesh,
                     .entry = entry};
            scene_.partNames.push_back(
                std::filesystem::path(file).filename().string() + ": " + part.name);
            o.part = uint32_t(scene_.partNames.size());
            const Mesh& mesh = *scene_.meshes[o.mesh];
            // glass needs a closed surface; a thin wall (Material::thin) does not
            const Material& glass = scene_.materials[o.material];
            bool open = glass.transmission > 0 && !glass.thin && mesh.openEdges > 0;
            // once per mesh, however often it is placed
            if (open && warnedOpen_.insert(o.mesh).second)
                std::fprintf(
                    stderr,
                    "%s: %s: warning: %s is transmissive but not closed: %zu open edges "
                    "(glass needs a closed surface)\n",
                    path_.c_str(), key.c_str(), mesh.name.c_str(), mesh.openEdges);
            scene_.objects.push_back(o);
        }
    }

private:
    struct Loaded {
        uint32_t firstMesh = 0;
        std::vector<uint32_t> materials;  // the file's materials in the scene's list
        std::vector<MeshPart> parts;
        size_t defaultMaterialParts = 0;  // parts that name none (mesh_file.h)
        std::string defaultMaterial;      // what they take, for the note
    };
    Loaded load(const std::string& file, const std::string& key) {
        MeshFile mf;
        try {
            mf = loadMeshFile(file);
        } catch (const InputError& e) {
            throw InputError(path_ + ": " + key + ".file: " + e.what());
        }
        Loaded l{.firstMesh = uint32_t(scene_.meshes.size()),
                 .parts = mf.parts,
                 .defaultMaterialParts = mf.defaultMaterialParts};
        if (mf.defaultMaterialParts > 0) {
            const FileMaterial& d = mf.materials.back();
            char values[96];
            std::snprintf(values, sizeof values,
                          " (base colour %g, metallic %g, roughness %g)", d.baseColor.x,
                          d.metallic, d.roughness);
            l.defaultMaterial = d.name + values;
        }
        int firstTexture = int(scene_.textures.size());
        for (Texture& t : mf.textures)
            scene_.textures.push_back(std::make_shared<const Texture>(std::move(t)));
        for (const FileMaterial& f : mf.materials) {
            l.materials.push_back(uint32_t(scene_.materials.size()));
            scene_.materials.push_back(materialFromFile(f));
            scene_.materials.back().name =
                std::filesystem::path(file).filename().string() + ": " + f.name;
            Material& m = scene_.materials.back();
            if (f.baseColorTexture >= 0) m.texture = firstTexture + f.baseColorTexture;
            if (f.metallicRoughnessTexture >= 0)
                m.metalRough.texture = firstTexture + f.metallicRoughnessTexture;
            if (f.normalTexture >= 0) m.normalTexture = firstTexture + f.normalTexture;
        }
        for (Mesh& m : mf.meshes) {
            if (m.degenerate > 0)
                std::fprintf(stderr, "%s: %s: dropped %zu degenerate triangles\n",
                             path_.c_str(), m.name.c_str(), m.degenerate);
            scene_.meshes.push_back(std::make_shared<const Mesh>(std::move(m)));
        }
        if (mf.skippedPrimitives > 0)
            std::fprintf(stderr,
                         "%s: %s: skipped %zu primitives that are points or lines\n",
                         path_.c_str(), file.c_str(), mf.skippedPrimitives);
        return l;
    }
    const Reader& r_;
    const std::string& path_;
    Scene& scene_;
    std::map<std::string, Loaded> loaded_;
    std::set<uint32_t> warnedOpen_;
    std::set<std::string> noted_;  // files whose default material was named
};

}  // namespace rg
