#include "scene/scene.h"

#include "core/files.h"
#include "core/progress.h"
#include "host_device.h"
#include "scene/mesh_objects.h"
#include "scene/scene_file.h"

#include <algorithm>
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

namespace {

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

}  // namespace

std::string describeObject(const Scene& scene, uint32_t index) {
    const Object& o = scene.objects[index];
    std::string entry = "objects[" + std::to_string(o.entry) + "]";
    if (o.part == 0) return entry;
    if (o.type == ShapeType::Mesh)
        return entry + " (" + scene.partNames[o.part - 1] + ")";
    return entry + " (sphere " + std::to_string(o.part - 1) + " of its data)";
}

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
    if (j.contains("ambient")) {
        s.ambient = r.vec3(j["ambient"], "ambient", 0, kHuge);
        s.ambientGiven = true;
    }

    if (j.contains("lights")) {
        if (!j["lights"].is_array()) r.fail("lights", "must be an array");
        for (size_t i = 0; i < j["lights"].size(); ++i) {
            const json& l = j["lights"][i];
            std::string key = "lights[" + std::to_string(i) + "]";
            PointLight light;
            if (l.contains("type") && r.string(l["type"], key + ".type") != "point") {
                // Chapter 14: a sun, far enough that its rays are parallel.
                if (r.string(l["type"], key + ".type") != "directional")
                    r.fail(key + ".type", "must be \"point\" or \"directional\"");
                r.onlyKeys(l, key,
                           {"type", "direction", "irradiance", "angular_radius_deg",
                            "comment"});
                light.kind = PointLight::Kind::Directional;
                if (!l.contains("direction")) r.fail(key + ".direction", "missing");
                glm::dvec3 d = r.vec3(l["direction"], key + ".direction");
                if (!(glm::length(d) > 0)) r.fail(key + ".direction", "must not be 0");
                light.direction = glm::normalize(d);
                if (!l.contains("irradiance")) r.fail(key + ".irradiance", "missing");
                light.irradiance = r.vec3(l["irradiance"], key + ".irradiance", 0, kHuge);
                // the real sun's is 0.27 degrees
                std::string disc = key + ".angular_radius_deg";
                if (l.contains("angular_radius_deg"))
                    light.angularRadius =
                        glm::radians(r.number(l["angular_radius_deg"], disc, 0, 10));
                s.lights.push_back(light);
                continue;
            }
            r.onlyKeys(l, key, {"type", "position", "intensity", "power", "comment"});
            if (!l.contains("position")) r.fail(key + ".position", "missing");
            light.position = r.vec3(l["position"], key + ".position");
            if (l.contains("intensity") && l.contains("power"))
                r.fail(key + ".power", "give power (watts, chapter 14) or intensity, "
                                       "not both");
            if (l.contains("intensity"))
                light.intensity = r.vec3(l["intensity"], key + ".intensity", 0, kHuge);
            if (l.contains("power")) {  // radiated evenly: power / 4 pi per steradian
                light.kind = PointLight::Kind::Point;
                light.intensity = r.vec3(l["power"], key + ".power", 0, kHuge) /
                                  (4.0 * 3.14159265358979323846);
            }
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
                    "priority", "dispersion", "thin"});
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
        if (m.contains("thin")) mat.thin = r.boolean(m["thin"], key + ".thin");
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
            meshFiles.place(r.string(o["file"], key + ".file"), key, uint32_t(i), place,
                            moving, material);
            continue;
        // the compact form for big scenes: one material, many spheres
        } else if (type == "spheres") {
            r.onlyKeys(o, key, {"type", "material", "data"});
            size_t first = s.objects.size();
            readSphereList(r, o, key, obj.material, s.objects);
            for (size_t k = first; k < s.objects.size(); ++k)
                s.objects[k].entry = uint32_t(i),
                s.objects[k].part = uint32_t(k - first + 1);
            continue;
        } else {
            r.fail(key + ".type",
                   "\"" + type + "\" is not a shape (sphere, quad, spheres or mesh)");
        }
        if (o.contains("transform"))
            obj.transform =
                readTransform(r, o["transform"], key + ".transform") * obj.transform;
        if (o.contains("moving")) obj.moving = r.boolean(o["moving"], key + ".moving");
        obj.entry = uint32_t(i);
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
            std::fprintf(stderr, "%s: %s coincides with %s; only the first is drawn\n",
                         path.c_str(), describeObject(s, byShape[k]).c_str(),
                         describeObject(s, byShape[first]).c_str());
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

}  // namespace rg
