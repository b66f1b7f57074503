// Scenes are data (chapter 03): a JSON file with the camera, the sky, the
// lights, the materials and the objects. docs/scene-format.md documents every
// key. Everything is double precision here; the GPU gets floats from it and
// the CPU reference renderer uses it as it is.
#pragma once
#include "scene/mesh.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace rg {

struct Camera {
    glm::dvec3 position{0, 1, 5};
    glm::dvec3 lookAt{0, 1, 0};
    glm::dvec3 up{0, 1, 0};
    double fovYDeg = 45.0;  // vertical field of view
};

struct Sky {
    std::string image;  // equirectangular image, sRGB (empty: the gradient below)
    // linear
    glm::dvec3 top{0.25, 0.45, 0.85}, horizon{0.8, 0.85, 0.9}, bottom{0.2, 0.18, 0.15};
};

// A light: the thesis's point light (chapters 06-13), or chapter 14's
// lights in physical units (docs/14_caustics.md, "Radiometry").
struct PointLight {
    enum class Kind {
        Thesis,      // intensity: the thesis's radiance scale I_i, no falloff
        Point,       // "power" in watts: intensity = power / 4 pi W/sr, E falls as 1/r^2
        Directional  // a sun: irradiance on a surface facing it, from `direction`
    };
    Kind kind = Kind::Thesis;
    glm::dvec3 position{0, 5, 0};
    glm::dvec3 intensity{1, 1, 1};  // Thesis: I_i; Point: radiant intensity, W/sr
    glm::dvec3 direction{0, -1, 0};  // Directional: where its light travels (unit)
    glm::dvec3 irradiance{0};        // Directional: W/m^2 on a surface facing it
    // Directional: the sun's disc, its angular radius (radians; 0: a point)
    double angularRadius = 0;
};

// Chapter 13: the glasses with a measured dispersion (host_device.h's GLASS_*).
enum class Glass { None, BK7, FusedSilica, Water, Diamond };

// Every parameter of chapters 05-11; each chapter reads what it needs.
struct Material {
    std::string name;
    // ambient coefficient (ch 05), times the scene's ambient light
    glm::dvec3 ka{1, 1, 1};
    // diffuse (ch 06); chapter 04 shows it as the flat colour
    glm::dvec3 kd{0.7, 0.7, 0.7};
    glm::dvec3 ks{0, 0, 0};        // specular (ch 07)
    double shininess = 32;         // Blinn-Phong exponent (ch 07)
    double reflectivity = 0;       // mirror fraction (ch 08)
    double transmission = 0;       // 1: a dielectric that refracts (ch 10)
    double ior = 1.517;            // index of refraction (ch 09-10)
    double f0 = 0.08;              // Schlick's reflectance at normal incidence (ch 09)
    double roughness = 0;          // lobe width for rough reflection (ch 11)
    // A transmissive surface with no volume behind it (glTF's thin-walled
    // default, KHR_materials_volume): light crosses it unbent, keeping the
    // Fresnel share 1 - F, and no medium begins or ends there (ch 10 on).
    bool thin = false;
    // ch 12: a mesh file's base colour texture (Scene::textures), times ka and kd
    int texture = -1;
    // ch 12, glTF's alphaMode MASK: a hit whose alpha (`alpha` times the
    // texture's) is below alphaCutoff does not count; 0: every hit counts
    double alphaCutoff = 0;
    double alpha = 1;
    // ch 12, glTF's metal-roughness texture: metalness and roughness vary
    // per hit, so the glTF mapping (applyMetalRoughness) is redone at each
    // hit from these factors, each times the texture's value there
    struct MetalRoughness {
        int texture = -1;  // Scene::textures: roughness in G, metalness in B; -1: none
        glm::dvec3 baseColor{1};
        double metallic = 1, roughness = 1;
    } metalRough;
    // ch 12: glTF's normal texture (tangent space; Scene::textures, -1: none)
    int normalTexture = -1;
    double normalScale = 1;  // its x and y are scaled by this
    // Chapter 13, for a material that transmits: the medium inside it.
    // Beer-Lambert coefficient per unit length: light falls by exp(-absorption d)
    glm::dvec3 absorption{0};
    // where media overlap, the one of highest priority fills the space
    int priority = 0;
    // Its dispersion: a named glass (Sellmeier), else glTF's 20 / Abbe number (0: none).
    Glass glass = Glass::None;
    double dispersion = 0;
};

enum class ShapeType { Sphere, Quad, Mesh };

// Every object becomes one instance of a unit shape (a sphere of radius 1 at
// the origin, or the quad [-1,1] x {0} x [-1,1]) or of a mesh (chapter 12)
// with a world transform.
struct Object {
    ShapeType type = ShapeType::Sphere;
    uint32_t material = 0;
    // chapter 03 moves it every frame by its TLAS transform alone
    bool moving = false;
    glm::dmat4 transform{1.0};  // object -> world
    // the same shape and transform as an earlier object: that one is drawn
    bool hidden = false;
    // As written in the file (the reference renderer intersects these directly):
    glm::dvec3 center{0};
    double radius = 1;       // spheres
    glm::dvec3 u{1, 0, 0}, v{0, 0, 1};  // quads: half-edges, the quad is center +- u +- v
    uint32_t mesh = 0;       // meshes: index into Scene::meshes
    // Where it came from, for messages: the scene file's objects[entry], and
    // which part of that entry (0: the entry itself; k: a spheres list's k-th
    // sphere, or a mesh file's part Scene::partNames[k - 1]).
    uint32_t entry = 0, part = 0;
};

struct Scene {
    std::string path;
    Camera camera;
    Sky sky;
    glm::dvec3 ambient{0.1, 0.1, 0.1};  // I_a (ch 05)
    bool ambientGiven = false;          // the file names it (chapter 14: else 0)
    std::vector<PointLight> lights;
    std::vector<Material> materials;
    std::vector<Object> objects;
    // Chapter 12: each mesh once, however many objects place it (one BLAS each).
    std::vector<std::shared_ptr<const Mesh>> meshes;
    // the meshes' base colour textures
    std::vector<std::shared_ptr<const Texture>> textures;
    // what each placed mesh part is in its file, for messages (Object::part):
    // "tree.gltf: node 3 \"Leaves\", primitive 0"
    std::vector<std::string> partNames;
    // Camera rays ignore hits closer to the eye than this: 0 unless the eye
    // lies on a surface (eyeTmin in rules.cpp; docs/scene-format.md's rule 1).
    double eyeTmin = 0;
    // chapter 13: the material whose medium the eye is in (camera.medium), -1: air
    int cameraMedium = -1;
    // where the file's origin lies in this scene's space (toCameraSpace): file = p -
    // origin
    glm::dvec3 origin{0};
};

// The longest column of a transform's 3x3 part: the largest stretch it
// applies (the format's transforms are rotations times scales, whose columns
// are orthogonal), an ellipsoid's longest semi-axis.
double largestStretch(const glm::dmat4& transform);
// The shortest such column: an ellipsoid's shortest semi-axis.
double smallestStretch(const glm::dmat4& transform);

// Chapter 13: the Beer-Lambert coefficient of a medium in which white light
// keeps `color` after `distance` (glTF's KHR_materials_volume): -ln(color) / distance.
glm::dvec3 absorptionOf(const glm::dvec3& color, double distance);

// Chapter 12: glTF's metal-roughness model in RayGlass's terms (its ka, kd,
// ks, shininess, reflectivity and rough lobe), as mesh_objects.h's
// materialFromFile describes; raygen_common.glsl's hitMaterial repeats it
// per hit where a metal-roughness texture varies it.
void applyMetalRoughness(Material& m, const glm::dvec3& baseColor, double metallic,
                         double roughness, double transmission);

// Chapter 13: a material's index of refraction at a wavelength (nm): a
// named glass's Sellmeier equation, or glTF's KHR_materials_dispersion line
// n = max(n_d + (n_d - 1) / V (523655 / L^2 - 1.5168), 1) through its ior
// at 587.6 nm; the ior itself without dispersion.
double indexAt(const Material& m, double nm);
double glassIndex(Glass glass, double nm);

// Rule 1 of docs/scene-format.md: how far from the eye camera rays start
// (Scene::eyeTmin; 0 unless the eye lies on a surface). loadScene sets it.
double eyeTmin(const Scene& scene);

// The sky as linear RGBA floats (an image file decoded from sRGB, or none).
struct SkyTexels {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};
SkyTexels loadSky(const Scene& scene);

// Reads and checks a scene file. Throws rg::InputError (exit code 2) naming
// the file and the key for a missing file, bad JSON, an unknown key, a
// missing value or one out of range.
Scene loadScene(const std::string& path);

// Chapters before 12 draw spheres and quads only: throws InputError naming
// the first mesh object and chapter 12.
void refuseMeshes(const Scene& scene);

// Chapters before 14 light the thesis's way: throws InputError naming the
// first light in physical units ("power", a directional light) and chapter 14.
void refusePhysicalLights(const Scene& scene);
// Chapter 14 lights in physical units only: throws InputError naming the
// first light given the thesis's way ("intensity" without units).
void requirePhysicalLights(const Scene& scene);
// Chapter 14's --reference: a sun with a disc (angular_radius_deg) is refused.
void refuseSunDiscInReference(const Scene& scene);

// Chapter 13's medium stack holds material indices in 8 bits (media.glsl):
// throws InputError naming the first transmitting material past index 254.
void refuseUnstackableMedia(const Scene& scene);

// The rendering space of the ray tracing chapters (04 on), as PBRT-v4 does:
// the whole scene translated, in double precision, so that the camera sits
// at the origin. Floats are densest near 0, so what the camera sees close up
// keeps the precision it would have at the world's origin, wherever the
// scene is (a float's spacing is 0.008 at 1e5). Returns the moved scene;
// `origin` says where it was.
Scene toCameraSpace(Scene scene);

// A camera as a scene file's "camera" object, in the file's coordinates
// (`origin`: Scene::origin of the space the camera is in).
nlohmann::json cameraToJson(const Camera& camera, const glm::dvec3& origin);

// The chapter's default scene: bin/assets/scenes/<name>.json.
std::string defaultScenePath(const std::string& name);
// An object as the scene file names it, for messages: "objects[3]", or for
// a part of an entry "objects[3] (tree.gltf: node 5, primitive 0)" or
// "objects[0] (sphere 12 of its data)".
std::string describeObject(const Scene& scene, uint32_t index);

}  // namespace rg
