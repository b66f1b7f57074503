#include "scene.h"

#include "files.h"
#include "host_device.h"
#include "mesh_file.h"
#include "progress.h"
#include "resources.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>

namespace rg {

double largestStretch(const glm::dmat4& m) {
    return std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                     glm::length(glm::dvec3(m[2]))});
}

double smallestStretch(const glm::dmat4& m) {
    return std::min({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                     glm::length(glm::dvec3(m[2]))});
}

namespace {

using nlohmann::json;

// nlohmann's own DOM builder, plus a check that no object has a key twice.
// (Its parser callback could do this too, but makes a 1e6-object file take
// minutes instead of seconds.) Keys are kept per open object, in a list
// reused across objects; a list that grows long moves into a set.
// An array under the key "data" (a sphere list's numbers, a million spheres'
// four million) does not become a million JSON values: its numbers go into
// one block of doubles, stored in the tree as a binary value, which JSON
// text cannot otherwise produce. An element that is not a number is NaN
// there (JSON has no NaN), for readSphereList to name.
class StrictJson : public nlohmann::detail::json_sax_dom_parser<json> {
public:
    explicit StrictJson(json& j) : json_sax_dom_parser(j, false) {}
    std::string duplicate;  // the first key found twice
    size_t errorPosition = 0;  // a syntax error: the characters read up to it
    std::string errorReason;

    template <class Exception>
    bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
        errorPosition = position;
        // "[json.exception.parse_error.101] parse error at line 1, column 5: why"
        errorReason = e.what();
        size_t start = errorReason.find("] ");
        if (start != std::string::npos) errorReason.erase(0, start + 2);
        size_t colon = errorReason.find(": ");
        if (errorReason.rfind("parse error", 0) == 0 && colon != std::string::npos)
            errorReason.erase(0, colon + 2);
        return json_sax_dom_parser::parse_error(position, token, e);
    }

    bool start_object(std::size_t n) {
        // an element that is not a number
        if (capturing_) return inData(NAN), ++nested_, true;
        afterDataKey_ = false;
        if (++depth_ > levels_.size()) levels_.emplace_back();
        levels_[depth_ - 1].keys.clear();
        levels_[depth_ - 1].many.reset();
        return json_sax_dom_parser::start_object(n);
    }
    bool end_object() {
        if (capturing_) return --nested_, true;
        --depth_;
        return json_sax_dom_parser::end_object();
    }
    bool key(std::string& k) {
        if (capturing_) return true;
        Level& level = levels_[depth_ - 1];
        bool seen = level.many ? !level.many->insert(k).second
                               : std::find(level.keys.begin(), level.keys.end(), k) !=
                                     level.keys.end();
        if (!level.many) {
            level.keys.push_back(k);
            if (level.keys.size() > 32)
                level.many = std::make_unique<std::set<std::string>>(level.keys.begin(),
                                                                     level.keys.end());
        }
        if (seen && duplicate.empty()) duplicate = k;
        afterDataKey_ = k == "data";
        return json_sax_dom_parser::key(k);
    }
    bool start_array(std::size_t n) {
        if (capturing_) return inData(NAN), ++nested_, true;
        if (!std::exchange(afterDataKey_, false))
            return json_sax_dom_parser::start_array(n);
        capturing_ = true;
        bytes_.clear();
        return true;
    }
    bool end_array() {
        if (!capturing_) return json_sax_dom_parser::end_array();
        if (nested_ > 0) return --nested_, true;
        capturing_ = false;
        json::binary_t block(std::move(bytes_));  // moved into the tree, not copied
        bytes_ = {};
        return json_sax_dom_parser::binary(block);
    }
    bool number_integer(json::number_integer_t v) {
        return inData(double(v)) || json_sax_dom_parser::number_integer(v);
    }
    bool number_unsigned(json::number_unsigned_t v) {
        return inData(double(v)) || json_sax_dom_parser::number_unsigned(v);
    }
    bool number_float(double v, const std::string& text) {
        return inData(v) || json_sax_dom_parser::number_float(v, text);
    }
    bool string(std::string& v) { return inData(NAN) || json_sax_dom_parser::string(v); }
    bool boolean(bool v) { return inData(NAN) || json_sax_dom_parser::boolean(v); }
    bool null() { return inData(NAN) || json_sax_dom_parser::null(); }

private:
    // Inside a "data" array: records one element (what is inside a nested
    // container is not one) and returns true; elsewhere false.
    bool inData(double element) {
        afterDataKey_ = false;
        if (!capturing_) return false;
        if (nested_ == 0) {
            const auto* b = reinterpret_cast<const std::uint8_t*>(&element);
            bytes_.insert(bytes_.end(), b, b + sizeof element);
        }
        return true;
    }

    struct Level {
        std::vector<std::string> keys;
        std::unique_ptr<std::set<std::string>> many;
    };
    std::vector<Level> levels_;
    size_t depth_ = 0;
    bool afterDataKey_ = false, capturing_ = false;
    int nested_ = 0;  // containers open inside the captured array
    // the captured doubles, as the binary value holds them
    std::vector<std::uint8_t> bytes_;
};

// "line:column" (both from 1) of the character `position` counts up to.
std::string lineAndColumn(const std::string& text, size_t position) {
    size_t end = std::min(position > 0 ? position - 1 : 0, text.size());
    size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(end), '\n'));
    size_t lineStart = text.rfind('\n', end > 0 ? end - 1 : 0);
    size_t column =
        lineStart == std::string::npos || end == 0 ? end + 1 : end - lineStart;
    return std::to_string(line) + ":" + std::to_string(column);
}

// Reads one JSON value and names where it came from when it is wrong.
class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(file_ + ": " + key + ": " + what);
    }

    void onlyKeys(const json& j, const std::string& where,
                  const std::set<std::string>& allowed) const {
        if (!j.is_object()) fail(where, "must be an object");
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!allowed.count(it.key())) {
                std::string list;
                for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
                fail(where.empty() ? it.key() : where + "." + it.key(),
                     "unknown key (known: " + list + ")");
            }
    }

    double number(const json& j, const std::string& key, double lo, double hi) const {
        if (!j.is_number()) fail(key, "must be a number");
        double v = j.get<double>();
        if (!std::isfinite(v) || v < lo || v > hi)
            fail(key,
                 "value " + j.dump() + " is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
        return v;
    }

    glm::dvec3 vec3(const json& j, const std::string& key, double lo = -1e30,
                    double hi = 1e30) const {
        if (j.is_number()) {  // a single number means (v, v, v)
            double v = number(j, key, lo, hi);
            return {v, v, v};
        }
        if (!j.is_array() || j.size() != 3) fail(key, "must be an array of 3 numbers");
        return {number(j[0], key + "[0]", lo, hi), number(j[1], key + "[1]", lo, hi),
                number(j[2], key + "[2]", lo, hi)};
    }

    std::string string(const json& j, const std::string& key) const {
        if (!j.is_string()) fail(key, "must be a string");
        return j.get<std::string>();
    }

    bool boolean(const json& j, const std::string& key) const {
        if (!j.is_boolean()) fail(key, "must be true or false");
        return j.get<bool>();
    }

private:
    static std::string fmt(double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        return b;
    }
    std::string file_;
};

constexpr double kHuge = 1e30;

glm::dmat4 readTransform(const Reader& r, const json& j, const std::string& key) {
    r.onlyKeys(j, key, {"translate", "rotate_deg", "scale"});
    glm::dmat4 m(1.0);
    if (j.contains("translate"))
        m = glm::translate(m, r.vec3(j["translate"], key + ".translate"));
    // Euler angles about x, then y, then z (applied z last)
    if (j.contains("rotate_deg")) {
        glm::dvec3 a =
            glm::radians(r.vec3(j["rotate_deg"], key + ".rotate_deg", -3600, 3600));
        m = glm::rotate(m, a.z, {0, 0, 1});
        m = glm::rotate(m, a.y, {0, 1, 0});
        m = glm::rotate(m, a.x, {1, 0, 0});
    }
    if (j.contains("scale"))
        m = glm::scale(m, r.vec3(j["scale"], key + ".scale", 1e-12, kHuge));
    return m;
}

// [region eye_tmin]
// Rule 1 of docs/scene-format.md: camera rays ignore hits closer to the eye
// than this. It is 0 unless the eye lies on a surface within that
// surface's float rounding (an eye placed exactly on a sphere lands, once in
// float, a hair inside or outside it); then a reach a little beyond that
// rounding, so that the eye sees what a ray leaving the surface would. Each
// surface's rounding grows with its own size and distance, so the value
// depends on the surfaces at the eye alone, not on the rest of the scene.
double eyeTmin(const Scene& s) {
    // 8 units of float's relative rounding, 2^-24
    constexpr double kRounding = 8.0 / 16777216.0;
    constexpr double kReach = 1.0 / 16384.0;          // 2^-14 of the surface's size
    double tMin = 0;
    for (const Object& o : s.objects) {
        if (o.hidden) continue;
        const glm::dmat4& m = o.transform;
        double scale = largestStretch(m);
        double size = glm::length(glm::dvec3(m[3]) - s.camera.position) + scale;
        // the eye, in object space
        glm::dvec3 q = glm::dvec3(glm::inverse(m) * glm::dvec4(s.camera.position, 1.0));
        // in object units
        double rounding = kRounding * size / scale;
        bool onSurface =
            o.type == ShapeType::Sphere ? std::abs(glm::length(q) - 1.0) <= rounding
            : o.type == ShapeType::Quad
                ? std::abs(q.y) <= rounding && std::abs(q.x) <= 1 + rounding &&
                      std::abs(q.z) <= 1 + rounding
                // a mesh: an eye on one of its triangles is not looked for
                : false;
        if (onSurface) tMin = std::max(tMin, kReach * size);
    }
    return tMin;
}
// [end]

// The unit sphere scaled to `radius`, then moved to `center`.
glm::dmat4 sphereTransform(const glm::dvec3& center, double radius) {
    glm::dmat4 m(radius);
    m[3] = glm::dvec4(center, 1);
    return m;
}

// {"type": "spheres", "material": m, "data": [x, y, z, r, x, y, z, r, ...]}:
// a million spheres as one flat array of numbers (StrictJson's block) load
// three times as fast as a million JSON objects, in a third of the memory.
// The checks are those of single spheres; a key is built only to name an error.
void readSphereList(const Reader& r, const json& o, const std::string& key,
                    uint32_t material, std::vector<Object>& objects) {
    const json* data = o.contains("data") ? &o["data"] : nullptr;
    size_t count =
        data && data->is_binary() ? data->get_binary().size() / sizeof(double) : 0;
    if (count == 0 || count % 4 != 0)
        r.fail(key + ".data", "must be an array of x, y, z, radius: 4 numbers a sphere");
    // StrictJson's block of doubles
    const std::uint8_t* numbers = data->get_binary().data();
    auto value = [&](size_t k, double lo, double hi) {
        double d;
        std::memcpy(&d, numbers + k * sizeof(double), sizeof d);
        if (!(d >= lo && d <= hi)) {  // fails, naming the number
            std::string at = key + ".data[" + std::to_string(k) + "]";
            if (std::isnan(d)) r.fail(at, "must be a number");
            r.number(json(d), at, lo, hi);
        }
        return d;
    };
    for (size_t k = 0; k < count; k += 4) {
        Object& sphere =
            objects.emplace_back(Object{.type = ShapeType::Sphere, .material = material});
        sphere.center = {value(k, -1e30, 1e30), value(k + 1, -1e30, 1e30),
                         value(k + 2, -1e30, 1e30)};
        sphere.radius = value(k + 3, 1e-12, kHuge);
        sphere.transform = sphereTransform(sphere.center, sphere.radius);
    }
}

// A file a scene names: relative to the scene file first, then to
// bin/assets/; it must be a regular file.
std::string findInput(const Reader& r, const std::string& scenePath,
                      const std::filesystem::path& name, const std::string& key) {
    std::filesystem::path besideScene =
        std::filesystem::path(scenePath).parent_path() / name;
    std::filesystem::path inAssets = executableDir() / "assets" / name;
    std::error_code error;  // a loop of links: no exception, the check below names it
    std::string found;
    if (std::filesystem::symlink_status(besideScene, error).type() !=
        std::filesystem::file_type::not_found)
        found = besideScene.string();
    else if (std::filesystem::symlink_status(inAssets, error).type() !=
             std::filesystem::file_type::not_found)
        found = inAssets.string();
    else
        r.fail(key, "no such file: " + name.string());
    requireRegularFile(found, scenePath + ": " + key);
    return found;
}

// [region mesh_material]
// A glTF material in RayGlass's terms (docs/scene-format.md): the base
// colour is diffuse where the surface is neither metal nor glass; metal is
// an untinted mirror of that strength; the highlight narrows as the
// roughness falls (Blinn-Phong's exponent 2 / alpha^2 - 2 for GGX's alpha =
// roughness^2); f0 follows from the index, ((n - 1) / (n + 1))^2. A base
// colour texture multiplies ka and kd where a ray meets the mesh (its
// caller sets Material::texture).
Material materialFromFile(const FileMaterial& f) {
    Material m;  // named by the caller, after the file
    double dielectric = (1 - f.metallic) * (1 - f.transmission);
    m.kd = f.baseColor * dielectric;
    m.ka = m.kd;
    double alpha = std::max(f.roughness * f.roughness, 1e-3);
    m.shininess = std::min(1e6, std::max(1.0, 2 / (alpha * alpha) - 2));
    m.ks = glm::dvec3(0.04 * (1 - f.roughness));
    m.reflectivity = f.metallic * (1 - f.transmission);
    m.transmission = f.transmission;
    m.ior = f.ior;
    m.f0 = std::pow((f.ior - 1) / (f.ior + 1), 2);
    // rough reflection only for metal (ch 11)
    m.roughness = f.transmission > 0 ? 0.0 : f.roughness * f.metallic;
    // ch 13
    if (f.attenuationDistance > 0)
        m.absorption = absorptionOf(f.attenuationColor, f.attenuationDistance);
    m.dispersion = f.dispersion;  // ch 13
    return m;
}
// [end]

// Mesh objects (chapter 12): each file is read once, its meshes go into
// Scene::meshes once, and every placement adds one object per part.
class MeshFiles {
public:
    MeshFiles(const Reader& r, const std::string& scenePath, Scene& scene)
        : r_(r), path_(scenePath), scene_(scene) {}

    void place(const std::string& name, const std::string& key,
               const glm::dmat4& transform, bool moving,
               std::optional<uint32_t> material) {
        std::string file = findInput(r_, path_, name, key + ".file");
        auto it = loaded_.find(file);
        if (it == loaded_.end()) it = loaded_.emplace(file, load(file, key)).first;
        const Loaded& l = it->second;
        for (const MeshPart& part : l.parts) {
            if (!material && part.material < 0)
                r_.fail(key + ".material",
                        "missing: " + name + " names no material for its mesh");
            Object o{.type = ShapeType::Mesh,
                     .material = material ? *material : l.materials[part.material],
                     .moving = moving,
                     .transform = transform * part.transform,
                     .mesh = l.firstMesh + part.mesh};
            const Mesh& mesh = *scene_.meshes[o.mesh];
            bool open =
                scene_.materials[o.material].transmission > 0 && mesh.openEdges > 0;
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
    };
    Loaded load(const std::string& file, const std::string& key) {
        MeshFile mf;
        try {
            mf = loadMeshFile(file);
        } catch (const InputError& e) {
            throw InputError(path_ + ": " + key + ".file: " + e.what());
        }
        Loaded l{.firstMesh = uint32_t(scene_.meshes.size()), .parts = mf.parts};
        int firstTexture = int(scene_.textures.size());
        for (Texture& t : mf.textures)
            scene_.textures.push_back(std::make_shared<const Texture>(std::move(t)));
        for (const FileMaterial& f : mf.materials) {
            l.materials.push_back(uint32_t(scene_.materials.size()));
            scene_.materials.push_back(materialFromFile(f));
            scene_.materials.back().name =
                std::filesystem::path(file).filename().string() + ": " + f.name;
            if (f.baseColorTexture >= 0)
                scene_.materials.back().texture = firstTexture + f.baseColorTexture;
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
};

}  // namespace

std::string defaultScenePath(const std::string& name) {
    return (executableDir() / "assets" / "scenes" / (name + ".json")).string();
}

Scene loadScene(const std::string& path) {
    Reader r(path);
    // a FIFO would block the read, a device never end it
    requireRegularFile(path, "--scene");
    std::ifstream file(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(file)),
                     std::istreambuf_iterator<char>());
    if (!file && !file.eof()) throw InputError(path + ": cannot read the scene file");
    // JSON allows a key twice in one object and keeps the last; in a scene
    // file that is a mistake (two "radius" keys), so the parser refuses it.
    json j;
    StrictJson strict(j);
    try {
        json::sax_parse(text, &strict);
    } catch (const std::exception& e) {  // syntax errors are reported below
        throw InputError(path + ": cannot read the scene file (" + e.what() + ")");
    }
    if (strict.is_errored() || j.is_discarded())
        throw InputError(path + ":" + lineAndColumn(text, strict.errorPosition) +
                         ": not valid JSON: " + strict.errorReason);
    if (!strict.duplicate.empty())
        throw InputError(path + ": key \"" + strict.duplicate +
                         "\" appears twice in one object");
    r.onlyKeys(j, "",
               {"camera", "sky", "ambient", "lights", "materials", "objects", "scale",
                "comment"});

    Scene s;
    s.path = path;

    if (!j.contains("camera")) r.fail("camera", "missing");
    const json& c = j["camera"];
    r.onlyKeys(c, "camera", {"position", "look_at", "up", "fov_y_deg", "medium"});
    if (c.contains("position"))
        s.camera.position = r.vec3(c["position"], "camera.position");
    if (c.contains("look_at")) s.camera.lookAt = r.vec3(c["look_at"], "camera.look_at");
    if (c.contains("up")) s.camera.up = r.vec3(c["up"], "camera.up");
    if (c.contains("fov_y_deg"))
        s.camera.fovYDeg = r.number(c["fov_y_deg"], "camera.fov_y_deg", 1, 179);
    glm::dvec3 forward = s.camera.lookAt - s.camera.position;
    if (glm::length(forward) <= 0)
        r.fail("camera.look_at", "must differ from camera.position");
    if (glm::length(glm::cross(forward, s.camera.up)) <=
        1e-12 * glm::length(forward) * glm::length(s.camera.up))
        r.fail("camera.up", "must not be parallel to the viewing direction");

    if (j.contains("sky")) {
        const json& k = j["sky"];
        r.onlyKeys(k, "sky", {"image", "top", "horizon", "bottom"});
        if (k.contains("image")) {
            s.sky.image =
                findInput(r, path, r.string(k["image"], "sky.image"), "sky.image");
        }
        if (k.contains("top")) s.sky.top = r.vec3(k["top"], "sky.top", 0, kHuge);
        if (k.contains("horizon"))
            s.sky.horizon = r.vec3(k["horizon"], "sky.horizon", 0, kHuge);
        if (k.contains("bottom"))
            s.sky.bottom = r.vec3(k["bottom"], "sky.bottom", 0, kHuge);
    }
    if (j.contains("ambient")) s.ambient = r.vec3(j["ambient"], "ambient", 0, kHuge);

    if (j.contains("lights")) {
        if (!j["lights"].is_array()) r.fail("lights", "must be an array");
        for (size_t i = 0; i < j["lights"].size(); ++i) {
            const json& l = j["lights"][i];
            std::string key = "lights[" + std::to_string(i) + "]";
            r.onlyKeys(l, key, {"position", "intensity"});
            PointLight light;
            if (!l.contains("position")) r.fail(key + ".position", "missing");
            light.position = r.vec3(l["position"], key + ".position");
            if (l.contains("intensity"))
                light.intensity = r.vec3(l["intensity"], key + ".intensity", 0, kHuge);
            s.lights.push_back(light);
        }
    }

    // A scene whose meshes bring their own materials may leave them out.
    const json noMaterials = json::object();
    if (j.contains("materials") &&
        (!j["materials"].is_object() || j["materials"].empty()))
        r.fail("materials", "must be an object with at least one named material");
    const json& materials = j.contains("materials") ? j["materials"] : noMaterials;
    for (auto it = materials.begin(); it != materials.end(); ++it) {
        std::string key = "materials." + it.key();
        const json& m = it.value();
        r.onlyKeys(m, key,
                   {"ka", "kd", "ks", "shininess", "reflectivity", "transmission", "ior",
                    "f0", "roughness", "attenuation_color", "attenuation_distance",
                    "priority", "dispersion"});
        Material mat;
        mat.name = it.key();
        if (m.contains("ka")) mat.ka = r.vec3(m["ka"], key + ".ka", 0, 1);
        if (m.contains("kd")) mat.kd = r.vec3(m["kd"], key + ".kd", 0, 1);
        if (m.contains("ks")) mat.ks = r.vec3(m["ks"], key + ".ks", 0, 1);
        if (m.contains("shininess"))
            mat.shininess = r.number(m["shininess"], key + ".shininess", 0, 1e6);
        if (m.contains("reflectivity"))
            mat.reflectivity = r.number(m["reflectivity"], key + ".reflectivity", 0, 1);
        if (m.contains("transmission"))
            mat.transmission = r.number(m["transmission"], key + ".transmission", 0, 1);
        if (m.contains("ior")) mat.ior = r.number(m["ior"], key + ".ior", 1, 10);
        if (m.contains("f0")) mat.f0 = r.number(m["f0"], key + ".f0", 0, 1);
        if (m.contains("roughness"))
            mat.roughness = r.number(m["roughness"], key + ".roughness", 0, 1);
        // Chapter 13: the medium inside, as glTF's KHR_materials_volume gives it:
        // white light keeps attenuation_color after attenuation_distance.
        if (m.contains("attenuation_color") != m.contains("attenuation_distance"))
            r.fail(key + (m.contains("attenuation_color") ? ".attenuation_distance"
                                                          : ".attenuation_color"),
                   "missing (attenuation_color and attenuation_distance come together)");
        if (m.contains("attenuation_color")) {
            glm::dvec3 color =
                r.vec3(m["attenuation_color"], key + ".attenuation_color", 1e-6, 1);
            double distance = r.number(m["attenuation_distance"],
                                       key + ".attenuation_distance", 1e-12, kHuge);
            mat.absorption = absorptionOf(color, distance);
        }
        if (m.contains("priority")) {
            if (!m["priority"].is_number_integer())
                r.fail(key + ".priority", "must be a whole number");
            mat.priority = int(r.number(m["priority"], key + ".priority", 0, 255));
        }
        // Chapter 13: a glass by name, its index from Sellmeier's equation; or
        // glTF's KHR_materials_dispersion, 20 / Abbe number, about the ior.
        if (m.contains("dispersion") && m["dispersion"].is_string()) {
            static const std::map<std::string, Glass> glasses = {
                {"bk7", Glass::BK7},
                {"fused_silica", Glass::FusedSilica},
                {"water", Glass::Water},
                {"diamond", Glass::Diamond}};
            auto glass = glasses.find(m["dispersion"].get<std::string>());
            if (glass == glasses.end())
                r.fail(key + ".dispersion",
                       "no glass named \"" + m["dispersion"].get<std::string>() +
                           "\" (bk7, fused_silica, water, diamond, or 20 / Abbe number)");
            if (m.contains("ior"))
                r.fail(
                    key + ".ior",
                    "a named glass's dispersion sets the index; give one or the other");
            mat.glass = glass->second;
            mat.ior = glassIndex(mat.glass, 587.5618);  // the helium d line: n_d
        } else if (m.contains("dispersion")) {
            mat.dispersion = r.number(m["dispersion"], key + ".dispersion", 0, 20);
        }
        s.materials.push_back(mat);
    }
    MeshFiles meshFiles(r, path, s);
    auto materialIndex = [&](const json& v, const std::string& key) -> uint32_t {
        std::string name = r.string(v, key);
        for (size_t i = 0; i < s.materials.size(); ++i)
            if (s.materials[i].name == name) return uint32_t(i);
        r.fail(key, "no material named \"" + name + "\"");
    };
    // chapter 13: the eye under water, inside glass
    if (j["camera"].contains("medium")) {
        s.cameraMedium = int(materialIndex(j["camera"]["medium"], "camera.medium"));
        if (s.materials[s.cameraMedium].transmission <= 0)
            r.fail("camera.medium",
                   "must name a material that transmits (transmission > 0): an eye "
                   "cannot be inside an opaque one");
    }

    if (!j.contains("objects") || !j["objects"].is_array() || j["objects"].empty())
        r.fail("objects", "must be an array with at least one object");
    Progress progress(path, j["objects"].size());  // big scenes, on a terminal only
    // room for every object at once: a million are not copied as the list grows
    size_t count = 0;
    for (const json& o : j["objects"]) {
        const json* data = o.is_object() && o.contains("data") ? &o["data"] : nullptr;
        count += data && data->is_binary()
                     ? data->get_binary().size() / (4 * sizeof(double))
                     : 1;
    }
    s.objects.reserve(count);
    for (size_t i = 0; i < j["objects"].size(); ++i) {
        if (i % 4096 == 0) progress.update(i);
        const json& o = j["objects"][i];
        std::string key = "objects[" + std::to_string(i) + "]";
        if (!o.is_object() || !o.contains("type"))
            r.fail(key + ".type", "missing (sphere, quad, spheres or mesh)");
        std::string type = r.string(o["type"], key + ".type");
        Object obj;
        if (!o.contains("material") && type != "mesh")
            r.fail(key + ".material", "missing");
        if (type != "mesh")
            obj.material = materialIndex(o["material"], key + ".material");
        if (type == "sphere") {
            r.onlyKeys(o, key,
                       {"type", "material", "center", "radius", "transform", "moving"});
            obj.type = ShapeType::Sphere;
            if (o.contains("center")) obj.center = r.vec3(o["center"], key + ".center");
            if (!o.contains("radius")) r.fail(key + ".radius", "missing");
            obj.radius = r.number(o["radius"], key + ".radius", 1e-12, kHuge);
            obj.transform = sphereTransform(obj.center, obj.radius);
        } else if (type == "quad") {
            r.onlyKeys(o, key,
                       {"type", "material", "center", "u", "v", "transform", "moving"});
            obj.type = ShapeType::Quad;
            if (o.contains("center")) obj.center = r.vec3(o["center"], key + ".center");
            if (!o.contains("u") || !o.contains("v"))
                r.fail(key + ".u", "a quad needs half-edges u and v");
            obj.u = r.vec3(o["u"], key + ".u");
            obj.v = r.vec3(o["v"], key + ".v");
            glm::dvec3 n = glm::cross(obj.u, obj.v);  // the quad's front side faces u x v
            if (glm::length(n) <= 1e-12 * glm::length(obj.u) * glm::length(obj.v))
                r.fail(key + ".v", "u and v must not be parallel or zero");
            // Unit quad [-1,1] x {0} x [-1,1], front +y: local x -> u, y -> the
            // normal, z -> -v (a right-handed frame, so no mirroring).
            obj.transform =
                glm::dmat4(glm::dvec4(obj.u, 0), glm::dvec4(glm::normalize(n), 0),
                           glm::dvec4(-obj.v, 0), glm::dvec4(obj.center, 1));
        } else if (type == "mesh") {  // chapter 12: every part of the file, as objects
            r.onlyKeys(o, key, {"type", "material", "file", "transform", "moving"});
            if (!o.contains("file"))
                r.fail(key + ".file", "missing (a .gltf, .glb or .obj file)");
            glm::dmat4 place = o.contains("transform")
                                   ? readTransform(r, o["transform"], key + ".transform")
                                   : glm::dmat4(1.0);
            bool moving = o.contains("moving") && r.boolean(o["moving"], key + ".moving");
            std::optional<uint32_t> material;
            if (o.contains("material"))
                material = materialIndex(o["material"], key + ".material");
            meshFiles.place(r.string(o["file"], key + ".file"), key, place, moving,
                            material);
            continue;
        // the compact form for big scenes: one material, many spheres
        } else if (type == "spheres") {
            r.onlyKeys(o, key, {"type", "material", "data"});
            readSphereList(r, o, key, obj.material, s.objects);
            continue;
        } else {
            r.fail(key + ".type",
                   "\"" + type + "\" is not a shape (sphere, quad, spheres or mesh)");
        }
        if (o.contains("transform"))
            obj.transform =
                readTransform(r, o["transform"], key + ".transform") * obj.transform;
        if (o.contains("moving")) obj.moving = r.boolean(o["moving"], key + ".moving");
        s.objects.push_back(obj);
    }
    // [region coincident]
    // Two objects with the same shape and transform meet every ray at the
    // same distance; which one a GPU reports is up to its traversal order.
    // The rule: the first listed is drawn, later copies are hidden (the GPU
    // gives them instance mask 0, the reference skips them).
    // Shape, then the 16 numbers of the transform, compared in place (a
    // million objects are sorted by this), the translation first: it tells
    // almost any two objects apart at once, where the first column is the
    // radius that many spheres share.
    auto compare = [&](uint32_t a, uint32_t b) {
        const Object &oa = s.objects[a], &ob = s.objects[b];
        if (oa.type != ob.type) return oa.type < ob.type ? -1 : 1;
        // 0 for spheres and quads
        if (oa.mesh != ob.mesh) return oa.mesh < ob.mesh ? -1 : 1;
        const double *ta = &oa.transform[0][0], *tb = &ob.transform[0][0];
        for (int k = 0; k < 16; ++k) {
            int i = (k + 12) % 16;  // column 3 (the translation), then columns 0, 1, 2
            if (ta[i] != tb[i]) return ta[i] < tb[i] ? -1 : 1;
        }
        return 0;
    };
    std::vector<uint32_t> byShape(s.objects.size());
    for (uint32_t i = 0; i < byShape.size(); ++i) byShape[i] = i;
    std::sort(byShape.begin(), byShape.end(), [&](uint32_t a, uint32_t b) {
        int c = compare(a, b);
        return c != 0 ? c < 0 : a < b;  // equal shapes in file order: the first is kept
    });
    size_t copies = 0;
    for (size_t k = 1, first = 0; k < byShape.size(); ++k) {
        if (compare(byShape[k], byShape[first]) != 0) {
            first = k;  // a new shape: its first object (in file order) is kept
            continue;
        }
        s.objects[byShape[k]].hidden = true;
        if (++copies <= 3)
            std::fprintf(
                stderr,
                "%s: objects[%u] coincides with objects[%u]; only the first is drawn\n",
                path.c_str(), byShape[k], byShape[first]);
    }
    if (copies > 3)
        std::fprintf(stderr, "%s: %zu more objects coincide with earlier ones\n",
                     path.c_str(), copies - 3);
    // [end]
    // "scale" set the offsets of secondary rays until they came from each
    // hit's own error bound (chapter 06); older files still load, and it is
    // checked but changes nothing.
    if (j.contains("scale")) r.number(j["scale"], "scale", 1e-12, kHuge);
    s.eyeTmin = eyeTmin(s);
    return s;
}

void refuseUnstackableMedia(const Scene& scene) {
    for (size_t i = 255; i < scene.materials.size(); ++i)
        if (scene.materials[i].transmission > 0)
            throw InputError(scene.path + ": materials." + scene.materials[i].name +
                             ": a medium must be among the first 255 materials (chapter "
                             "13's stack keeps 8 bits an entry)");
}

void refuseMeshes(const Scene& scene) {
    for (const Object& o : scene.objects)
        if (o.type == ShapeType::Mesh)
            throw InputError(
                scene.path + ": " + scene.meshes[o.mesh]->name +
                ": triangle meshes come in chapter 12; run 12_triangle_meshes");
}

// [region camera_space]
Scene toCameraSpace(Scene s) {
    glm::dvec3 eye = s.camera.position;  // every subtraction below is in double
    for (Object& o : s.objects) {
        o.transform[3] -= glm::dvec4(eye, 0);
        o.center -= eye;
    }
    for (PointLight& l : s.lights) l.position -= eye;
    s.camera.lookAt -= eye;
    s.camera.position = glm::dvec3(0);
    s.origin -= eye;
    return s;
}
// [end]

nlohmann::json cameraToJson(const Camera& camera, const glm::dvec3& origin) {
    auto array = [](const glm::dvec3& v) {
        return nlohmann::json::array({v.x, v.y, v.z});
    };
    return {{"position", array(camera.position - origin)},
            {"look_at", array(camera.lookAt - origin)},
            {"up", array(camera.up)},
            {"fov_y_deg", camera.fovYDeg}};
}

glm::dvec3 absorptionOf(const glm::dvec3& color, double distance) {
    return -glm::log(color) / distance;  // exp(-sigma d) = color at d = distance
}

// [region sellmeier]
namespace {
double sellmeier(double nm, std::array<double, 8> c) {
    double l2 = nm * nm * 1e-6, n2 = 1;  // in square micrometres
    for (int i = 0; i < 4; ++i) n2 += c[i] * l2 / (l2 - c[4 + i]);
    return std::sqrt(n2);
}
}  // namespace

double glassIndex(Glass glass, double nm) {
    switch (glass) {
        case Glass::BK7: return sellmeier(nm, {SELLMEIER_BK7});
        case Glass::FusedSilica: return sellmeier(nm, {SELLMEIER_FUSED_SILICA});
        case Glass::Water: return sellmeier(nm, {SELLMEIER_WATER});
        case Glass::Diamond: return sellmeier(nm, {SELLMEIER_DIAMOND});
        case Glass::None: break;
    }
    return 1;
}

double indexAt(const Material& m, double nm) {
    if (m.glass != Glass::None) return glassIndex(m.glass, nm);
    if (m.dispersion <= 0) return m.ior;
    double abbe = 20 / m.dispersion;
    return std::max(m.ior + (m.ior - 1) / abbe * (523655 / (nm * nm) - 1.5168), 1.0);
}
// [end]

}  // namespace rg
