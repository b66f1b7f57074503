// Chapter 12: meshes from files, checked as they load, watertight where it
// matters, and right by optics. The CPU tests use the loader and the
// reference's ray-triangle test directly; the GPU tests run the chapter as
// a user would (lavapipe in CI, validation on).
#include "gltf_square.h"
#include "harness.h"
#include "optics_image.h"

#include "core/display.h"
#include "core/files.h"
#include "core/image.h"
#include "reference/edge_rays.h"
#include "reference/reference.h"
#include "scene/mesh.h"
#include "scene/mesh_file.h"
#include "scene/scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <random>

namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

std::string meshDir() { return (fs::path(RG_EXE_12).parent_path() / "assets" / "meshes").string(); }

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// The message of the InputError that `f` throws ("" if none).
template <typename F>
std::string inputError(F f) {
    try {
        f();
    } catch (const rg::InputError& e) {
        return e.what();
    }
    return "";
}

double signedVolume(const rg::Mesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        v += glm::dot(glm::dvec3(m.vertices[m.indices[t]]),
                      glm::cross(glm::dvec3(m.vertices[m.indices[t + 1]]), glm::dvec3(m.vertices[m.indices[t + 2]])));
    return v / 6;
}

// ---- Loading and checking -------------------------------------------------

TEST(Meshes, GeneratedObjectsAreClosedAndWoundOutward) {
    for (const char* name : {"lens.obj", "prism.obj", "slab.obj", "wine_glass.gltf", "icosphere_1.obj",
                             "icosphere_3.obj", "icosphere_5.obj"}) {
        rg::MeshFile file = rg::loadMeshFile(meshDir() + "/" + name);
        ASSERT_FALSE(file.meshes.empty()) << name;
        for (const rg::Mesh& m : file.meshes) {
            EXPECT_EQ(m.openEdges, 0u) << name;
            EXPECT_EQ(m.degenerate, 0u) << name;
            EXPECT_GT(signedVolume(m), 0) << name << ": counter-clockwise seen from outside";
        }
    }
    // The lens's volume, from its two spherical caps and the rim's cylinder (mm^3).
    rg::Mesh lens = rg::loadMeshFile(meshDir() + "/lens.obj").meshes[0];
    double R = 50, a = 15, sag = R - std::sqrt(R * R - a * a), rim = 5 - 2 * sag;
    double exact = 2 * kPi * sag * sag * (3 * R - sag) / 3 + kPi * a * a * rim;
    EXPECT_NEAR(signedVolume(lens), exact, 0.002 * exact);
}

TEST(Meshes, OpenAndMisorientedEdgesAreCounted) {
    rg::Mesh closed = rg::icosphere(2);
    rg::checkMesh(closed);
    EXPECT_EQ(closed.openEdges, 0u);
    rg::Mesh hole = rg::icosphere(2);
    hole.indices.resize(hole.indices.size() - 3);  // one triangle less: its 3 edges are used once
    rg::checkMesh(hole);
    EXPECT_EQ(hole.openEdges, 3u);
    rg::Mesh flipped = rg::icosphere(2);
    std::swap(flipped.indices[1], flipped.indices[2]);  // one triangle wound the other way
    rg::checkMesh(flipped);
    EXPECT_EQ(flipped.openEdges, 3u);
    rg::Mesh doubled = rg::icosphere(1);
    doubled.indices.insert(doubled.indices.end(), doubled.indices.begin(), doubled.indices.begin() + 3);
    rg::checkMesh(doubled);
    EXPECT_EQ(doubled.openEdges, 3u);  // three edges now shared by three triangles
    // Seams: the same positions under other indices (a file's split normals) still close.
    rg::Mesh seams = rg::icosphere(1);
    uint32_t copy = uint32_t(seams.vertices.size());
    seams.vertices.push_back(seams.vertices[seams.indices[0]]);
    seams.normals.push_back(seams.normals[seams.indices[0]]);
    seams.indices[0] = copy;
    rg::checkMesh(seams);
    EXPECT_EQ(seams.openEdges, 0u);
}

TEST(Meshes, DegenerateTrianglesAreDroppedAndCounted) {
    rg::Mesh m = rg::icosphere(1);
    size_t triangles = m.indices.size() / 3;
    m.indices.insert(m.indices.end(), {0, 0, 1, 2, 5, 2});  // a repeated vertex, twice
    m.vertices.push_back(m.vertices[0] * 0.5f);
    m.vertices.push_back(m.vertices[0] * 0.25f);
    uint32_t a = uint32_t(m.vertices.size() - 2), b = a + 1;
    m.normals.push_back(m.normals[0]), m.normals.push_back(m.normals[0]);
    m.indices.insert(m.indices.end(), {0, a, b});  // three points on one line: no area
    rg::checkMesh(m);
    EXPECT_EQ(m.degenerate, 3u);
    EXPECT_EQ(m.indices.size() / 3, triangles);
}

TEST(Meshes, BrokenMeshesAreRefusedWithOneLine) {
    auto refused = [](rg::Mesh m) { return inputError([&] { rg::checkMesh(m); }); };
    rg::Mesh outOfRange = rg::icosphere(0);
    outOfRange.name = "m";
    outOfRange.indices[4] = 12;
    EXPECT_EQ(refused(outOfRange), "m: triangle 1 uses vertex 12, but there are 12 vertices");
    rg::Mesh nan = rg::icosphere(0);
    nan.name = "m";
    nan.vertices[3].y = NAN;
    EXPECT_EQ(refused(nan), "m: vertex 3 is not a finite number");
    rg::Mesh infinite = rg::icosphere(0);
    infinite.name = "m";
    infinite.normals[5].x = INFINITY;
    EXPECT_EQ(refused(infinite), "m: the normal of vertex 5 is not a finite number");
    rg::Mesh empty;
    empty.name = "m";
    EXPECT_EQ(refused(empty), "m: no triangles (an empty mesh, or only degenerate ones)");
}

// A scene with one mesh object naming `file` (written beside it).
std::string meshScene(const std::string& dir, const std::string& file, const std::string& material = "\"glass\"") {
    std::string path = dir + "/scene.json";
    writeText(path, R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"glass": {"transmission": 1, "ior": 1.5}},
        "objects": [{"type": "mesh", "file": ")" + file + R"(", "material": )" + material + "}]}");
    return path;
}

// A glTF file of one triangle list, its floats in a base64 data URI, the
// accessor claiming `count` vertices.
std::string triangleGltf(const std::vector<float>& xyz, size_t count) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string bytes(reinterpret_cast<const char*>(xyz.data()), xyz.size() * sizeof(float)), text;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
        for (size_t k = 0; k < 4; ++k) text += i + k <= bytes.size() + (k == 0) ? digits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": )" + std::to_string(bytes.size()) +
           R"(, "uri": "data:application/octet-stream;base64,)" + text + R"("}],
        "bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(bytes.size()) + R"(}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(count) +
           R"(, "type": "VEC3"}]})";
}

TEST(Meshes, BadFilesAreRefusedByTheSceneWithOneLine) {
    std::string dir = rgtest::outputDir("12_bad_files");
    struct Case {
        std::string name, text, expected;  // expected: a part of the message
    };
    std::vector<Case> cases = {
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "uses vertex 9, but there are 3 vertices"},
        // tinyobjloader reads these as 0: refused, naming the line and the value
        {"nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n", "nan.obj: line 2: v nan 1 0: nan is not a finite number"},
        {"inf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 -inf 0  # a comment\r\nf 1 2 3\r\n",
         "inf.obj: line 3: v 0 -inf 0  # a comment: -inf is not a finite number"},
        {"huge.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", "line 2: v 1e999 0 0: 1e999 is not a finite number"},
        {"normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 NaN\nf 1//1 2//1 3//1\n", "line 4: vn 0 0 NaN: NaN is not a finite number"},
        {"word.obj", "v 0 0 0\nv 1 0 0\nvt 0 one\nf 1 2 3\n", "line 3: vt 0 one: one is not a number"},
        {"nan.gltf", triangleGltf({0, 0, 0, 1, NAN, 0, 0, 1, 0}, 3), "vertex 1 is not a finite number"},
        {"empty.obj", "# nothing\n", "empty"},
        {"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "no triangles"},
        {"bad.gltf", "{ not json", "not a glTF file tinygltf reads"},
        {"past.gltf", triangleGltf({0, 0, 0, 1, 0, 0, 0, 1, 0}, 30), ""},  // tinygltf or the loader: one line either way
        {"model.stl", "solid x\n", "not a mesh file RayGlass reads (.gltf, .glb or .obj)"},
    };
    for (const Case& c : cases) {
        writeText(dir + "/" + c.name, c.text);
        std::string message = inputError([&] { rg::loadScene(meshScene(dir, c.name)); });
        EXPECT_NE(message.find("scene.json: objects[0].file: "), std::string::npos) << c.name << ": " << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    }
    EXPECT_NE(inputError([&] { rg::loadScene(meshScene(dir, "missing.obj")); }).find("no such file: missing.obj"),
              std::string::npos);
}

// glTF files as people send them, with a part missing: each refusal names
// the file and the cause in one line (exit 2).
TEST(Meshes, MissingAndUnreadablePartsOfAGltfAreNamed) {
    std::string dir = rgtest::outputDir("12_gltf_parts");
    std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::string data = triangleGltf(xyz, 3);
    // the same triangle with its buffer in a .bin that is not there
    std::string lostBin = data;
    size_t uri = lostBin.find("data:application");
    lostBin.replace(uri, lostBin.find('"', uri) - uri, "gone%20away.bin");
    // with a base colour texture whose image is missing, or is a KTX file
    auto textured = [&](const std::string& image, const std::string& texture) {
        std::string g = data;
        g.insert(g.rfind('}'), R"(, "materials": [{"name": "leaf", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
            "textures": [)" + texture + R"(], "images": [{"uri": ")" + image + R"("}])");
        size_t at = g.find(R"({"attributes": {"POSITION": 0}})");
        g.replace(at, 31, R"({"attributes": {"POSITION": 0}, "material": 0})");
        return g;
    };
    writeText(dir + "/leaf.ktx2", std::string("\xABKTX 20\xBB\r\n\x1A\n") + std::string(64, '\0'));
    struct Case {
        std::string name, text, expected;
    };
    std::vector<Case> cases = {
        {"lost_bin.gltf", lostBin, "lost_bin.gltf: buffer 0: gone%20away.bin: not found (looked beside the file)"},
        {"lost_image.gltf", textured("leaf.png", R"({"source": 0})"),
         "lost_image.gltf: image 0: leaf.png: not found (looked beside the file)"},
        {"ktx.gltf", textured("leaf.ktx2", R"({"source": 0})"),
         "ktx.gltf: material leaf: base colour texture 0: image 0 is a KTX image, which RayGlass does not read "
         "(PNG and JPEG only)"},
        {"basisu.gltf", textured("leaf.ktx2", R"({"extensions": {"KHR_texture_basisu": {"source": 0}}})"),
         "basisu.gltf: material leaf: base colour texture 0 has only a KTX image, which RayGlass does not read"},
    };
    for (const Case& c : cases) {
        writeText(dir + "/" + c.name, c.text);
        std::string message = inputError([&] { rg::loadScene(meshScene(dir, c.name)); });
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
        EXPECT_EQ(message.find("not a glTF file"), std::string::npos) << c.name << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    }
}

// Two nodes of one file that place the same mesh at the same place: the
// scene draws one, and says which, by the file's node names, not by the
// scene's object numbers (the scene has one object, the file two parts).
TEST(Meshes, CoincidingPartsOfAFileAreNamedByTheirNodes) {
    std::string dir = rgtest::outputDir("12_coinciding_nodes");
    std::string g = triangleGltf({0, 0, 0, 1, 0, 0, 0, 1, 0}, 3);
    g.replace(g.find(R"("nodes": [{"mesh": 0}])"), 22,
              R"("nodes": [{"mesh": 0, "name": "Leaf"}, {"mesh": 0, "name": "Leaf copy"}])");
    g.replace(g.find(R"("scenes": [{"nodes": [0]}])"), 26, R"("scenes": [{"nodes": [0, 1]}])");
    writeText(dir + "/twice.gltf", g);
    std::string scene = meshScene(dir, "twice.gltf");
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--scene", scene, "--width", "16", "--height", "16",
                                                  "--frames", "1", "--output", dir + "/twice.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("objects[0] (twice.gltf: node 1 \"Leaf copy\", primitive 0) coincides with objects[0] "
                            "(twice.gltf: node 0 \"Leaf\", primitive 0); only the first is drawn"),
              std::string::npos)
        << r.output;
}

// The any-hit shader's alpha test (glTF's alphaMode MASK): a leaf on a
// transparent card (meshes/leaf.glb) with a round hole at its centre, before
// a wall, lit from the upper right (assets/scenes/leaf.json). Checked against
// geometry, at pixels found by projecting the card and the light by hand
// (160x160, fov 40 degrees, camera at z = 4, card at z = 0, wall at z = -1.5,
// light at (2.5, 1.5, 6)), and against the same scene without the leaf:
// - through the hole the camera sees the wall as if the card were not there;
// - the hole's shadow on the wall is lit, the leaf's is dark;
// - the leaf itself is green; and the whole picture matches the reference.
TEST(AlphaTest, ALeafOnACardCutsOutItsShapeForCameraAndShadowRays) {
    std::string dir = rgtest::outputDir("12_alpha_test");
    std::string scene = meshDir() + "/../scenes/leaf.json";
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--reference", "--scene", scene,
                                                  "--width", "160", "--height", "160", "--frames", "1",
                                                  "--output", dir + "/leaf.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto report = rgtest::readJson(dir + "/leaf.json");
    EXPECT_EQ(report["alpha_test"], true);
    EXPECT_EQ(report["validation_messages"], 0);
    EXPECT_LE(report["error"]["frac_over_1_255"].get<double>(), 0.001);
    // the same scene without the leaf (its second object)
    auto json = nlohmann::json::parse(std::ifstream(scene));
    json["objects"].erase(1);
    writeText(dir + "/wall.json", json.dump());
    rgtest::RunResult bare = rgtest::run(RG_EXE_12, {"--headless", "--scene", dir + "/wall.json", "--width",
                                                     "160", "--height", "160", "--frames", "1", "--output",
                                                     dir + "/no_leaf.png"});
    ASSERT_EQ(bare.exitCode, 0) << bare.output;
    rgtest::Png leaf = rgtest::readPng(dir + "/leaf.png"), wall = rgtest::readPng(dir + "/no_leaf.png");
    auto same = [&](int x, int y) {
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(leaf.at(x, y)[c]) - int(wall.at(x, y)[c])) > 1) return false;
        return true;
    };
    EXPECT_TRUE(same(80, 80)) << "the hole at the card's centre";
    EXPECT_TRUE(same(55, 95)) << "the hole's shadow on the wall";
    const uint8_t* shadow = leaf.at(83, 117);  // the leaf's shadow on the wall
    EXPECT_LT(shadow[0], 0.7 * wall.at(83, 117)[0]);
    const uint8_t* green = leaf.at(110, 104);  // the leaf, off its vein
    EXPECT_GT(green[1], green[0] + 40);
    EXPECT_GT(green[1], green[2] + 40);
}

// The same rule's message for a `spheres` list (scene-format, rule 2): a
// sphere of the list is named by its place in the list's data.
TEST(Meshes, CoincidingSpheresOfAListAreNamedByTheirPlace) {
    std::string dir = rgtest::outputDir("12_coinciding_spheres");
    writeText(dir + "/list.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"m": {}},
        "objects": [{"type": "sphere", "material": "m", "center": [1, 0, 0], "radius": 0.5},
                    {"type": "spheres", "material": "m", "data": [0, 0, 0, 0.5, 2, 0, 0, 0.5, 1, 0, 0, 0.5]}]})");
    rgtest::RunResult r = rgtest::run(RG_EXE_05, {"--headless", "--scene", dir + "/list.json", "--width", "16",
                                                  "--height", "16", "--frames", "1", "--output", dir + "/out.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("objects[1] (sphere 2 of its data) coincides with objects[0]; only the first is drawn"),
              std::string::npos)
        << r.output;
}

// A mesh that names no material takes its format's default (glTF 2.0, 3.7.2.1:
// "a default material MUST be used": base colour 1, metallic 1, roughness 1;
// OBJ has none, a diffuse grey 0.8 stands in), and the scene says so once
// per file; a scene's material still wins. The glTF triangle here has no
// "materials" at all, as many exported models do for some of their meshes.
TEST(Meshes, AMeshWithoutAMaterialTakesItsFormatsDefault) {
    std::string dir = rgtest::outputDir("12_default_material");
    writeText(dir + "/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeText(dir + "/tri.gltf", triangleGltf({0, 0, 0, 1, 0, 0, 0, 1, 0}, 3));
    writeText(dir + "/bare.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "tri.obj"}, {"type": "mesh", "file": "tri.gltf"},
                    {"type": "mesh", "file": "tri.gltf", "transform": {"translate": [2, 0, 0]}}]})");
    rg::Scene scene = rg::loadScene(dir + "/bare.json");
    ASSERT_EQ(scene.objects.size(), 3u);
    const rg::Material& obj = scene.materials[scene.objects[0].material];
    EXPECT_EQ(obj.name, "tri.obj: RayGlass's default for OBJ");
    EXPECT_EQ(obj.kd, glm::dvec3(0.8));
    EXPECT_EQ(obj.reflectivity, 0.0);
    const rg::Material& gltf = scene.materials[scene.objects[1].material];
    EXPECT_EQ(gltf.name, "tri.gltf: glTF's default material");
    EXPECT_EQ(gltf.kd, glm::dvec3(0.0));     // metallic 1: no diffuse
    EXPECT_EQ(gltf.reflectivity, 1.0);       // a full mirror
    EXPECT_EQ(gltf.roughness, 1.0);          // as rough as can be
    EXPECT_EQ(scene.objects[2].material, scene.objects[1].material);  // read once
    // a chapter says so, once per file, and renders it
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene", dir + "/bare.json",
                                                  "--width", "32", "--height", "32", "--frames", "1",
                                                  "--output", dir + "/bare_out.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("objects[1]: note: 1 of tri.gltf's meshes name no material: they take glTF's "
                            "default material (base colour 1, metallic 1, roughness 1)"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("objects[2]: note"), std::string::npos) << r.output;
    // the scene's material wins, and then nothing is noted
    rgtest::RunResult own = rgtest::run(RG_EXE_12, {"--headless", "--scene", meshScene(dir, "tri.gltf"), "--width",
                                                    "32", "--height", "32", "--frames", "1", "--output",
                                                    dir + "/own.png"});
    ASSERT_EQ(own.exitCode, 0) << own.output;
    EXPECT_EQ(own.output.find("note:"), std::string::npos) << own.output;
}

// A mesh written far from its file's origin (page 12): the same glass ball
// as an OBJ with its vertices around (X, 0, -X), placed back by the scene's
// transform, must look like the ball written at the origin. The loader reads
// the file in double and recentres each mesh on its box before its vertices
// become floats (Mesh::origin); the floats would otherwise be spaced 0.06
// apart at 1e6 and the ball's facets would go astray.
TEST(Meshes, AMeshWrittenFarFromItsOriginLooksTheSame) {
    std::string dir = rgtest::outputDir("12_far_mesh");
    rg::Mesh ball = rg::icosphere(4);
    auto render = [&](double X) {
        std::string name = "ball_" + std::to_string(int(std::log10(std::max(X, 1.0))));
        std::string obj;
        char line[128];
        for (const glm::vec3& v : ball.vertices) {
            std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", double(v.x) + X, double(v.y),
                          double(v.z) - X);
            obj += line;
        }
        for (const glm::vec3& n : ball.normals) {
            std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
            obj += line;
        }
        for (size_t t = 0; t < ball.indices.size(); t += 3) {
            uint32_t a = ball.indices[t] + 1, b = ball.indices[t + 1] + 1, c = ball.indices[t + 2] + 1;
            obj += "f " + std::to_string(a) + "//" + std::to_string(a) + " " + std::to_string(b) + "//" +
                   std::to_string(b) + " " + std::to_string(c) + "//" + std::to_string(c) + "\n";
        }
        writeText(dir + "/" + name + ".obj", obj);
        char translate[96];
        std::snprintf(translate, sizeof translate, "[%.17g, 0, %.17g]", -X, X);
        writeText(dir + "/" + name + ".json",
                  R"({"camera": {"position": [0.4, 0.3, 3], "look_at": [0, 0, 0], "fov_y_deg": 40},
                      "sky": {"image": "sky.png"},
                      "materials": {"glass": {"ka": 0, "kd": 0, "ks": 0, "transmission": 1, "ior": 1.5}},
                      "objects": [{"type": "mesh", "file": ")" + name + R"(.obj", "material": "glass",
                                   "transform": {"translate": )" + translate + "}}]}");
        rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene",
                                                      dir + "/" + name + ".json", "--width", "160", "--height",
                                                      "90", "--frames", "1", "--output", dir + "/" + name + "_out.png"});
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return rgtest::readPng(dir + "/" + name + "_out.png");
    };
    rgtest::Png atOrigin = render(0);
    for (double X : {1e3, 1e4, 1e5, 1e6, 1e7}) {
        rgtest::Png far = render(X);
        ASSERT_EQ(far.rgb.size(), atOrigin.rgb.size());
        size_t off = 0;
        for (size_t i = 0; i < far.rgb.size(); i += 3) {
            int worst = 0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(far.rgb[i + c]) - int(atOrigin.rgb[i + c])));
            off += worst > 1;
        }
        EXPECT_LE(double(off) / (far.rgb.size() / 3), 0.001) << "written at " << X << ": " << off << " pixels differ";
    }
}

// glTF's thin-walled default (KHR_materials_volume): a transmissive material
// without a thicknessFactor above 0 is a surface with no volume behind it,
// a window pane modelled as one quad. Light crosses it unbent. Read off the
// picture: the sky is a ramp whose red / green says the direction a pixel's
// ray ends in (optics_image.h), and the pane, turned 40 degrees, reflects
// into the sky's black part; so through a thin pane every pixel reads the
// ramp where the same pixel reads it with no pane at all. The same quad as
// solid glass (thicknessFactor 1) bends the rays: the reading moves.
TEST(Meshes, AThinWalledPaneLetsLightThroughUnbent) {
    std::string dir = rgtest::outputDir("12_thin_walled");
    namespace optics = rgtest::optics;
    optics::writeRampSky(dir + "/sky.png", 256, 64, [](int x, int y) {
        // 45 degrees either side of straight ahead (-z), 22.5 degrees about the horizon
        return x >= 96 && x < 160 && y >= 24 && y < 40 ? (x - 96) * 4 : -1;
    });
    auto pane = [&](const std::string& name, const nlohmann::json& volume) {
        nlohmann::json gltf = nlohmann::json::parse(
            triangleGltf({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0}, 6));
        nlohmann::json extensions = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                     {"KHR_materials_ior", {{"ior", 1.5}}}};
        gltf["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior"};
        if (!volume.is_null()) {
            extensions["KHR_materials_volume"] = volume;
            gltf["extensionsUsed"].push_back("KHR_materials_volume");
        }
        gltf["materials"] = {{{"name", "pane"},
                              {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
                              {"extensions", extensions}}};
        gltf["meshes"][0]["primitives"][0]["material"] = 0;
        writeText(dir + "/" + name + ".gltf", gltf.dump());
        nlohmann::json scene = {
            {"camera", {{"position", {0, 0, 5}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", 20}}},
            {"sky", {{"image", "sky.png"}}}, {"ambient", 0}, {"materials", {{"unused", nlohmann::json::object()}}},
            // a scene has an object: a small ball behind the camera, seen by no ray of interest
            {"objects", {{{"type", "sphere"}, {"center", {0, 0, 50}}, {"radius", 0.1}, {"material", "unused"}}}}};
        if (name != "none")
            scene["objects"].push_back({{"type", "mesh"}, {"file", name + ".gltf"},
                                        {"transform", {{"rotate_deg", {0, 40, 0}}, {"scale", {1.5, 1.5, 1.5}}}}});
        std::ofstream(dir + "/" + name + "_scene.json") << scene.dump();
        return dir + "/" + name + "_scene.json";
    };
    std::string none = pane("none", nullptr), thin = pane("thin", nullptr),
                solid = pane("solid", {{"thicknessFactor", 1.0}});
    // What the loader makes of the two files.
    EXPECT_TRUE(rg::loadScene(thin).materials.back().thin);
    EXPECT_FALSE(rg::loadScene(solid).materials.back().thin);
    for (const char* exe : {RG_EXE_12, RG_EXE_13}) {
        std::string tag = std::filesystem::path(exe).filename().string();
        auto render = [&](const std::string& scene, const std::string& name) {
            return optics::renderOptics(exe, scene, 96, 96, dir + "/" + tag + "_" + name + ".pfm", {});
        };
        rg::FloatImage open = render(none, "none"), through = render(thin, "thin"), bent = render(solid, "solid");
        ASSERT_EQ(through.rgba.size(), open.rgba.size());
        // the thin-wall branches are compiled in only where a material is thin (kThinWalls)
        auto thinWalls = [&](const char* name) {
            return rgtest::readJson(dir + "/" + tag + "_" + name + ".json").value("thin_walls", false);
        };
        EXPECT_TRUE(thinWalls("thin")) << tag;
        EXPECT_FALSE(thinWalls("solid")) << tag;
        int behind = 0, moved = 0, bentAway = 0;
        double worst = 0;
        for (size_t i = 0; i < open.rgba.size(); i += 4) {
            double a = optics::rampPosition(&open.rgba[i]);
            if (a < 0) continue;
            // behind the pane: its two surfaces keep 1 - F of the light
            if (!(through.rgba[i + 1] < 0.99 * open.rgba[i + 1])) continue;
            ++behind;
            double b = optics::rampPosition(&through.rgba[i]), c = optics::rampPosition(&bent.rgba[i]);
            worst = std::max(worst, b < 0 ? 999.0 : std::abs(b - a));
            moved += b < 0 || std::abs(b - a) > 0.05;
            bentAway += c < 0 || std::abs(c - a) > 2;
        }
        EXPECT_GT(behind, 2000) << tag << ": the pane should cover much of the picture";
        EXPECT_EQ(moved, 0) << tag << ": through the thin pane a pixel's ray went elsewhere (worst "
                            << worst << " ramp codes)";
        EXPECT_GT(bentAway, behind / 2) << tag << ": solid glass should bend the rays";
    }
}

TEST(Meshes, ChaptersRefuseBadMeshesAndEarlierChaptersRefuseMeshes) {
    std::string dir = rgtest::outputDir("12_refusals");
    writeText(dir + "/range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    rgtest::RunResult bad = rgtest::run(RG_EXE_12, {"--headless", "--scene", meshScene(dir, "range.obj"), "--output",
                                                    dir + "/x.png"});
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("uses vertex 9, but there are 3 vertices"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir + "/x.png"));
    writeText(dir + "/nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n");
    rgtest::RunResult nan = rgtest::run(RG_EXE_12, {"--headless", "--scene", meshScene(dir, "nan.obj"), "--output",
                                                    dir + "/n.png"});
    EXPECT_EQ(nan.exitCode, 2) << nan.output;
    EXPECT_NE(nan.output.find("nan.obj: line 2: v nan 1 0: nan is not a finite number"), std::string::npos)
        << nan.output;
    EXPECT_FALSE(fs::exists(dir + "/n.png"));
    // Chapters 03-11 draw no meshes and say where they come.
    std::string scene = RG_SOURCE_DIR "/assets/scenes/meshes.json";
    for (const char* exe : {RG_EXE_03, RG_EXE_04, RG_EXE_05, RG_EXE_06, RG_EXE_10, RG_EXE_11}) {
        rgtest::RunResult r = rgtest::run(exe, {"--headless", "--scene", scene, "--output", dir + "/y.png"});
        EXPECT_EQ(r.exitCode, 2) << exe << ": " << r.output;
        EXPECT_NE(r.output.find("triangle meshes come in chapter 12; run 12_triangle_meshes"), std::string::npos)
            << r.output;
    }
}

// ---- glTF materials ---------------------------------------------------------

TEST(Meshes, GltfMaterialRoundTrip) {
    std::string dir = rgtest::outputDir("12_gltf_material");
    std::ifstream in(meshDir() + "/wine_glass.gltf");
    nlohmann::json j = nlohmann::json::parse(in);
    j["materials"][0] = {
        {"name", "tinted"},
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.5}}},
        {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.75}}},
                        {"KHR_materials_ior", {{"ior", 1.33}}},
                        {"KHR_materials_volume",  // chapter 13's absorption
                         {{"thicknessFactor", 0.1}, {"attenuationDistance", 0.5}, {"attenuationColor", {0.5, 0.25, 1}}}},
                        {"KHR_materials_dispersion", {{"dispersion", 0.3}}}}}};  // chapter 13: 20 / Abbe number
    fs::copy_file(meshDir() + "/wine_glass.bin", dir + "/wine_glass.bin", fs::copy_options::overwrite_existing);
    writeText(dir + "/tinted.gltf", j.dump());
    rg::MeshFile file = rg::loadMeshFile(dir + "/tinted.gltf");
    ASSERT_EQ(file.materials.size(), 1u);
    const rg::FileMaterial& f = file.materials[0];
    EXPECT_EQ(f.name, "tinted");
    EXPECT_EQ(f.baseColor, glm::dvec3(0.2, 0.4, 0.6));
    EXPECT_EQ(f.metallic, 0.25);
    EXPECT_EQ(f.roughness, 0.5);
    EXPECT_EQ(f.transmission, 0.75);
    EXPECT_EQ(f.ior, 1.33);
    EXPECT_EQ(f.attenuationDistance, 0.5);
    EXPECT_EQ(f.attenuationColor, glm::dvec3(0.5, 0.25, 1));
    EXPECT_EQ(f.dispersion, 0.3);
    EXPECT_EQ(f.thickness, 0.1);  // above 0: a volume, not a thin wall
    ASSERT_EQ(file.parts.size(), 1u);
    EXPECT_EQ(file.parts[0].material, 0);
    // Its mapping onto RayGlass's material (docs/scene-format.md).
    rg::Scene scene = rg::loadScene(meshScene(dir, "tinted.gltf", "\"glass\""));  // the scene's material overrides
    EXPECT_EQ(scene.materials[scene.objects[0].material].name, "glass");
    std::string noOverride = dir + "/own.json";
    writeText(noOverride, R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"unused": {}},
        "objects": [{"type": "mesh", "file": "tinted.gltf"}]})");
    scene = rg::loadScene(noOverride);
    const rg::Material& m = scene.materials[scene.objects[0].material];
    EXPECT_EQ(m.name, "tinted.gltf: tinted");
    EXPECT_NEAR(m.kd.g, 0.4 * 0.75 * 0.25, 1e-12);  // base (1 - metallic) (1 - transmission)
    EXPECT_NEAR(m.reflectivity, 0.25 * 0.25, 1e-12);
    EXPECT_EQ(m.transmission, 0.75);
    EXPECT_EQ(m.roughness, 0.5);  // glass is rough by its roughnessFactor (frosted: chapter 15)
    EXPECT_FALSE(m.thin);
    EXPECT_EQ(m.ior, 1.33);
    EXPECT_NEAR(m.f0, std::pow(0.33 / 2.33, 2), 1e-12);
    // Beer-Lambert: after 0.5, white keeps the attenuation colour.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::exp(-m.absorption[c] * 0.5), f.attenuationColor[c], 1e-12);
    EXPECT_EQ(m.absorption.b, 0.0);  // a channel of colour 1 is not absorbed
    // Dispersion, KHR_materials_dispersion's line: n_F - n_C = (n_d - 1) / V, V = 20 / 0.3.
    EXPECT_NEAR(rg::indexAt(m, 587.5618), 1.33, 1e-6);
    EXPECT_NEAR(rg::indexAt(m, 486.1327) - rg::indexAt(m, 656.2725), 0.33 / (20 / 0.3), 1e-5);
}

// ---- Textures -------------------------------------------------------------------

// A 2 x 2 image, as a viewer shows it: red, green on top; blue, white below.
const glm::dvec3 kQuadrants[2][2] = {{{1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 1, 1}}};
void writeQuadrantsPng(const std::string& path) {
    rg::FloatImage image{2, 2, std::vector<float>(16, 1.0f)};
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) image.rgba[4 * (2 * y + x) + c] = float(kQuadrants[y][x][c]);
    rg::writePng(path, image);
}

// A glTF square [-1, 1] x {0} x [-1, 1] facing up, texture coordinates from
// (lo, lo) at its -x -z corner to (hi, hi) at +x +z, the base colour
// texture quadrants.png through `sampler`.
void writeTexturedSquare(const std::string& dir, const std::string& name, float lo, float hi, const nlohmann::json& sampler) {
    Square floor{{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, {{lo, lo}, {lo, hi}, {hi, hi}, {hi, lo}}};
    writeSquareGltf(dir, name, floor, {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}},
                    {{"baseColorTexture", "quadrants.png"}}, sampler);
}

TEST(Textures, GltfBaseColourTextureIsReadAndDecoded) {
    rg::MeshFile file = rg::loadMeshFile(meshDir() + "/tiles.glb");
    ASSERT_EQ(file.textures.size(), 1u);
    const rg::Texture& t = file.textures[0];
    EXPECT_EQ(t.width, 64u);
    EXPECT_EQ(t.height, 64u);
    EXPECT_EQ(t.wrapU, rg::TextureWrap::Repeat);
    EXPECT_FALSE(t.nearest);
    ASSERT_EQ(file.materials.size(), 1u);
    EXPECT_EQ(file.materials[0].baseColorTexture, 0);
    ASSERT_EQ(file.meshes[0].texcoords.size(), 4u);
    EXPECT_EQ(file.meshes[0].texcoords[2], glm::vec2(10, 10));
    // make_meshes' tile: grout at the corner, then light top-left, dark top-right,
    // decoded from sRGB (the top row first, as the image is stored).
    EXPECT_NEAR(rg::texelValue(t, 0, 0, 0).r, rg::srgbToLinear(140 / 255.0), 1e-12);
    EXPECT_NEAR(rg::texelValue(t, 0, 8, 8).r, rg::srgbToLinear(222 / 255.0), 1e-12);
    EXPECT_NEAR(rg::texelValue(t, 0, 40, 8).b, rg::srgbToLinear(88 / 255.0), 1e-12);
    // The scene gives the material the texture; a scene material drops it.
    rg::Scene scene = rg::loadScene(RG_SOURCE_DIR "/assets/scenes/meshes.json");
    ASSERT_EQ(scene.textures.size(), 1u);
    int textured = 0;
    for (const rg::Material& m : scene.materials) textured += m.texture == 0;
    EXPECT_EQ(textured, 1);
}

TEST(Textures, ObjMapKdIsReadWithItsTextureCoordinatesFlipped) {
    std::string dir = rgtest::outputDir("12_obj_texture");
    writeQuadrantsPng(dir + "/quadrants.png");
    writeText(dir + "/square.mtl", "newmtl paint\nKd 1 1 1\nmap_Kd quadrants.png\n");
    writeText(dir + "/square.obj", "mtllib square.mtl\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl paint\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    rg::MeshFile file = rg::loadMeshFile(dir + "/square.obj");
    ASSERT_EQ(file.textures.size(), 1u);
    EXPECT_EQ(file.materials[0].baseColorTexture, 0);
    // the image's top-left texel: red
    EXPECT_EQ(rg::texelValue(file.textures[0], 0, 0, 0), glm::dvec4(1, 0, 0, 1));
    const rg::Mesh& m = file.meshes[0];
    ASSERT_EQ(m.texcoords.size(), 4u);
    // OBJ's (0, 0) is the image's bottom-left corner; glTF's (and RayGlass's) v points down.
    EXPECT_EQ(m.texcoords[0], glm::vec2(0, 1));
    EXPECT_EQ(m.texcoords[2], glm::vec2(1, 0));
    // One clear line for an image that is not one.
    writeText(dir + "/broken.png", "not a png");
    writeText(dir + "/broken.mtl", "newmtl paint\nmap_Kd broken.png\n");
    writeText(dir + "/broken.obj", "mtllib broken.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n");
    std::string message = inputError([&] { rg::loadMeshFile(dir + "/broken.obj"); });
    EXPECT_NE(message.find("map_Kd " + dir + "/broken.png: "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(Textures, ReferenceFiltersAndWrapsAsGltfSays) {
    std::vector<unsigned char> bytes;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 4; ++c) bytes.push_back(c == 3 ? 255 : 255 * kQuadrants[y][x][c]);
    rg::Texture t = rg::decodeTexture("t", bytes.data(), 2, 2);
    auto at = [&](double u, double v) { return rg::ReferenceRenderer::sampleTexture(t, {u, v}); };
    EXPECT_EQ(at(0.25, 0.25), glm::dvec3(1, 0, 0));  // texel centres: the texels themselves
    EXPECT_EQ(at(0.75, 0.75), glm::dvec3(1, 1, 1));
    EXPECT_EQ(at(0.5, 0.25), glm::dvec3(0.5, 0.5, 0));  // half way between red and green
    EXPECT_EQ(at(1.25, -0.75), at(0.25, 0.25));  // repeat
    t.wrapU = rg::TextureWrap::Clamp;
    EXPECT_EQ(at(-3, 0.25), glm::dvec3(1, 0, 0));  // the edge texel
    EXPECT_EQ(at(0.0, 0.25), glm::dvec3(1, 0, 0));  // no wrap-around blend at the edge
    t.wrapU = rg::TextureWrap::Mirror;
    EXPECT_EQ(at(1.25, 0.25), at(0.75, 0.25));  // the next copy mirrored
    EXPECT_EQ(at(-0.25, 0.25), at(0.25, 0.25));
    t.nearest = true;
    EXPECT_EQ(at(0.49, 0.26), glm::dvec3(1, 0, 0));
    EXPECT_EQ(at(0.51, 0.26), glm::dvec3(0, 1, 0));
}

// The GPU against the texture's own definition, then against the
// reference: three squares seen from above, lit by ambient light alone so
// that each pixel is its texture's value.
TEST(Textures, GpuShowsTheImageTheRightWayUpAndWrapsLikeTheReference) {
    std::string dir = rgtest::outputDir("12_textures");
    writeQuadrantsPng(dir + "/quadrants.png");
    writeTexturedSquare(dir, "plain", 0, 1, {{"magFilter", 9729}});
    writeTexturedSquare(dir, "wraps", -1, 2, {{"magFilter", 9729}, {"wrapS", 33648}, {"wrapT", 33071}});
    writeTexturedSquare(dir, "nearest", 0, 3, {{"magFilter", 9728}});
    writeText(dir + "/textures.json", R"({"camera": {"position": [0, 6, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_y_deg": 40},
        "sky": {"top": 0, "horizon": 0, "bottom": 0}, "ambient": 1,
        "objects": [
          {"type": "mesh", "file": "plain.gltf", "transform": {"translate": [-2.2, 0, 0]}},
          {"type": "mesh", "file": "wraps.gltf"},
          {"type": "mesh", "file": "nearest.gltf", "transform": {"translate": [2.2, 0, 0]}}]})");
    rgtest::expectMatchesReference(RG_EXE_12, dir + "/textures.json", "12_textures_reference");
    // The plain square shows the image as it is: red top-left, white bottom-right.
    rgtest::RunResult run = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene", dir + "/textures.json",
                                                    "--width", "320", "--height", "180", "--frames", "1", "--output",
                                                    dir + "/top_view.pfm"});
    ASSERT_EQ(run.exitCode, 0) << run.output;
    rg::FloatImage image = rg::readPfm(dir + "/top_view.pfm");
    ASSERT_EQ(image.width, 320u);
    for (int qy = 0; qy < 2; ++qy)
        for (int qx = 0; qx < 2; ++qx) {
            glm::dvec3 point(-2.2 - 0.5 + qx, 0, -0.5 + qy);  // the quadrant's centre on the square
            // Its pixel: where the camera ray toward it lands (the reference's camera).
            double tanHalf = std::tan(20 * kPi / 180), aspect = 320.0 / 180;
            double sx = point.x / 6 / (tanHalf * aspect), sy = -point.z / 6 / tanHalf;
            uint32_t px = uint32_t((sx + 1) / 2 * 320), py = uint32_t((1 - sy) / 2 * 180);
            const float* p = &image.rgba[4 * (size_t(py) * 320 + px)];
            for (int c = 0; c < 3; ++c)  // within half a pixel of the centre: at most 5 % blended with a neighbour
                EXPECT_NEAR(p[c], kQuadrants[qy][qx][c], 0.05) << "quadrant " << qx << "," << qy << " channel " << c;
        }
}

// ---- Watertight ---------------------------------------------------------------

// A scene holding one mesh at the identity, for the reference's own structures.
rg::Scene oneMesh(const std::string& file) {
    std::string dir = rgtest::outputDir("12_one_mesh_" + fs::path(file).stem().string());
    return rg::loadScene(meshScene(dir, file));
}

// 10^6 rays, each aimed exactly at a point of an edge or at a vertex of a
// closed mesh (reference/edge_rays.h): every one must hit (Woop et al.'s
// test shares each edge's function between its two triangles). From
// outside, each ray comes from the front of every face at that point, so
// its first hit is a front face; from the centre of these star-shaped
// meshes, each one leaves through a back face.
TEST(Watertight, ReferenceNeverMissesEdgesOrVertices) {
    for (const char* name : {"icosphere_3.obj", "lens.obj", "grid_box.obj"}) {
        rg::Scene scene = oneMesh(meshDir() + "/" + name);
        rg::ReferenceRenderer reference(scene);
        uint64_t missed[2] = {0, 0}, wrongSide[2] = {0, 0};
        for (const rg::EdgeRay& ray : rg::edgeRays(*scene.meshes[0], 1000000, 12)) {
            auto hit = rg::ReferenceRenderer::intersectMesh(reference.meshData(0), ray.origin,
                                                            ray.direction, 0, 1e300);
            if (hit.t < 0) ++missed[ray.outside];
            else if (hit.front != ray.outside) ++wrongSide[ray.outside];
        }
        EXPECT_EQ(missed[1], 0u) << name << ": rays from outside passed through";
        EXPECT_EQ(wrongSide[1], 0u) << name << ": a ray from outside met a back face first";
        EXPECT_EQ(missed[0], 0u) << name << ": rays from inside passed through";
        EXPECT_EQ(wrongSide[0], 0u) << name << ": a ray from inside met a front face";
    }
}

// The same kind of rays, in float, on the GPU (tools/leak_probe.cpp): with
// --triangles watertight (boxes and triangle.rint) none passes between two
// triangles; the driver's own test is only measured (the specification does
// not promise it: on lavapipe some pass, page 12).
TEST(Watertight, WatertightTestLetsNoRayThrough) {
    std::string dir = rgtest::outputDir("12_leak_probe");
    rgtest::RunResult r = rgtest::run(RG_LEAK_PROBE, {"--validation", "--rays", "200000", "--json",
                                                      dir + "/leaks.json"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::printf("%s", r.output.c_str());
    auto report = rgtest::readJson(dir + "/leaks.json");
    ASSERT_EQ(report["meshes"].size(), 3u);
    for (const auto& [name, mesh] : report["meshes"].items())
        for (const char* test : {"reference", "watertight"})
            for (const char* side : {"outside", "inside"}) {
                EXPECT_EQ(mesh[test][side]["rays"], 100000) << name << " " << test << " " << side;
                EXPECT_EQ(mesh[test][side]["through"], 0) << name << " " << test << " " << side;
            }
}

// The watertight test draws what the driver's draws (the same triangles,
// barycentrics and sides): the default scenes of chapters 12 (a lens, a
// prism, a slab and a wine glass at depth 6) and 13 (nested media), within
// 0.1 % of pixels, and both match the reference.
TEST(Watertight, BothTrianglesTestsDrawTheSamePicture) {
    std::string dir = rgtest::outputDir("12_triangle_tests");
    for (const char* exe : {RG_EXE_12, RG_EXE_13}) {
        std::string chapter = fs::path(exe).filename().string();
        for (const char* test : {"builtin", "watertight"}) {
            rgtest::RunResult r = rgtest::run(exe, {"--headless", "--validation", "--reference", "--width", "160",
                                                    "--height", "90", "--frames", "1", "--triangles", test,
                                                    "--output", dir + "/" + chapter + "_" + test + ".png"});
            ASSERT_EQ(r.exitCode, 0) << r.output;
            auto report = rgtest::readJson(dir + "/" + chapter + "_" + test + ".json");
            EXPECT_EQ(report["validation_messages"], 0);
            EXPECT_EQ(report["parameters"]["triangles"], test);
            EXPECT_LE(report["error"]["frac_over_1_255"].get<double>(), 0.001) << chapter << " " << test;
        }
        rgtest::Png a = rgtest::readPng(dir + "/" + chapter + "_builtin.png");
        rgtest::Png b = rgtest::readPng(dir + "/" + chapter + "_watertight.png");
        int differ = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > 1) {
                        ++differ;
                        break;
                    }
        EXPECT_LE(differ, a.width * a.height / 1000) << chapter;
        // page 12: on lavapipe, whose test leaks at no pixel of these scenes, none at all
        std::string device = rgtest::readJson(dir + "/" + chapter + "_builtin.json")["device"];
        if (device.find("llvmpipe") != std::string::npos) {
            EXPECT_EQ(differ, 0) << chapter;
        }
    }
}

// Both GPU triangle tests: the camera inside a closed, black icosphere under
// a white sky; a million camera rays (1000 x 1000, fan of 150 degrees) meet
// its 20,480 triangles, many within a float step of an edge or a vertex.
// A single sky pixel would be a leak. (Rays aimed at the edges themselves
// find the driver's leaks: WatertightTestLetsNoRayThrough.)
TEST(Watertight, GpuCameraInsideClosedMeshSeesNoSky) {
    std::string dir = rgtest::outputDir("12_leak");
    writeText(dir + "/camera_inside.json", R"({"camera": {"position": [0.01, 0.02, 0.03], "look_at": [0.3, 0.2, 1], "fov_y_deg": 150},
        "sky": {"top": 1, "horizon": 1, "bottom": 1}, "ambient": 0,
        "materials": {"black": {"ka": 0, "kd": 0, "ks": 0}},
        "objects": [{"type": "mesh", "file": ")" + meshDir() + R"(/icosphere_5.obj", "material": "black"}]})");
    for (const char* test : {"builtin", "watertight"}) {
        std::string out = dir + "/inside_" + test;
        rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene", dir + "/camera_inside.json",
                                                      "--width", "1000", "--height", "1000", "--frames", "1", "--depth",
                                                      "0", "--triangles", test, "--output", out + ".png"});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        rgtest::Png png = rgtest::readPng(out + ".png");
        uint64_t leaks = 0;
        for (int y = 0; y < png.height; ++y)
            for (int x = 0; x < png.width; ++x) leaks += png.at(x, y)[0] != 0;
        EXPECT_EQ(leaks, 0u) << test;
        EXPECT_EQ(rgtest::readJson(out + ".json")["validation_messages"], 0);
    }
}

// ---- Optics -------------------------------------------------------------------

// Snell's law in vector form, written here again: n faces the incoming ray.
bool refractRay(const glm::dvec3& d, const glm::dvec3& n, double eta, glm::dvec3& t) {
    double c = -glm::dot(n, d), k = 1 - eta * eta * (1 - c * c);
    if (k < 0) return false;
    t = glm::normalize(eta * d + (eta * c - std::sqrt(k)) * n);
    return true;
}

// Through a glass mesh: in at the first hit, out at the next; returns the
// direction leaving it (false if it does not get through).
bool throughGlass(const rg::ReferenceRenderer& r, glm::dvec3 o, glm::dvec3 d, double n, glm::dvec3& out,
                  glm::dvec3* exitPoint = nullptr, bool smooth = true) {
    rg::ReferenceHit in = r.trace(o, d, 0, 1e300);
    if (in.t < 0 || !in.frontFace) return false;
    glm::dvec3 p = o + in.t * d, t;
    if (!refractRay(d, smooth ? in.shading : in.normal, 1 / n, t)) return false;
    rg::ReferenceHit leave = r.trace(p + 1e-9 * t, t, 0, 1e300);
    if (leave.t < 0 || leave.frontFace) return false;
    glm::dvec3 q = p + 1e-9 * t + leave.t * t;
    if (!refractRay(t, -(smooth ? leave.shading : leave.normal), n, out)) return false;
    if (exitPoint) *exitPoint = q;
    return true;
}

// A 60-degree BK7 prism at minimum deviation: the ray crosses it parallel
// to its base, deviated by 2 asin(n sin(A / 2)) - A = 38.64 degrees; any
// other angle of incidence deviates it more.
TEST(Optics, PrismDeviatesByTheMinimumDeviationAngle) {
    rg::Scene scene = oneMesh(meshDir() + "/prism.obj");
    rg::ReferenceRenderer r(scene);
    const double n = 1.5168, A = 60 * kPi / 180;
    const double expected = (2 * std::asin(n * std::sin(A / 2)) - A) * 180 / kPi;
    ASSERT_NEAR(expected, 38.65, 0.02);
    // The prism's apex points along +z (tools/make_meshes.cpp); face 1 is
    // the one between the apex vertex and the next one. At minimum deviation
    // the ray inside runs parallel to the base, perpendicular to the apex's bisector.
    auto deviation = [&](double incidenceDeg) {
        const rg::Mesh& m = *scene.meshes[0];
        glm::dvec3 apex(m.vertices[0]), b(m.vertices[1]);
        glm::dvec3 mid = (apex + b) / 2.0 + glm::dvec3(0, 15, 0);  // on face 1, half way up
        glm::dvec3 faceNormal = glm::normalize(glm::cross(b - apex, glm::dvec3(0, 1, 0)));
        if (glm::dot(faceNormal, mid - glm::dvec3(0, 15, 0)) < 0) faceNormal = -faceNormal;
        double a = incidenceDeg * kPi / 180;
        glm::dvec3 up(0, 1, 0), side = glm::normalize(glm::cross(up, faceNormal));
        glm::dvec3 d = -(std::cos(a) * faceNormal) - std::sin(a) * side;  // toward the face, turned away from the apex
        if (glm::dot(d + faceNormal * glm::dot(-d, faceNormal), apex - mid) > 0) d = -(std::cos(a) * faceNormal) + std::sin(a) * side;
        glm::dvec3 out;
        if (!throughGlass(r, mid - 100.0 * d, d, n, out, nullptr, false)) return 999.0;
        return std::acos(std::clamp(glm::dot(d, out), -1.0, 1.0)) * 180 / kPi;
    };
    double incidence = std::asin(n * std::sin(A / 2)) * 180 / kPi;  // 49.32 degrees
    double atMinimum = deviation(incidence);
    std::printf("prism: deviation %.4f deg at incidence %.4f deg (optics: %.4f)\n", atMinimum, incidence, expected);
    EXPECT_NEAR(atMinimum, expected, 0.05);
    EXPECT_GT(deviation(incidence - 3), atMinimum);
    EXPECT_GT(deviation(incidence + 3), atMinimum);
}

// The biconvex lens (R = +-50 mm, 5 mm thick, n = 1.5168): thick-lens optics
// puts the focus of a paraxial beam 47.54 mm behind the rear vertex (back
// focal length) and gives an effective focal length of 49.21 mm; traced
// through the mesh with its interpolated normals, within 1 %.
TEST(Optics, LensFocusesWhereThickLensOpticsPutsIt) {
    rg::Scene scene = oneMesh(meshDir() + "/lens.obj");
    rg::ReferenceRenderer r(scene);
    const double n = 1.5168, R = 50, t = 5;
    double power = (n - 1) * (2 / R - (n - 1) * t / (n * R * R));
    double efl = 1 / power, bfl = efl * (1 - (n - 1) * t / (n * R));
    ASSERT_NEAR(efl, 49.21, 0.01);
    ASSERT_NEAR(bfl, 47.54, 0.01);
    for (double h : {0.5, 1.0, 2.0}) {  // heights in mm, off the axis (y) along x
        glm::dvec3 out, exit;
        ASSERT_TRUE(throughGlass(r, {h, -100, 0.3 * h}, {0, 1, 0}, n, out, &exit)) << h;
        // Where the ray meets the axis (x = 0, z = 0: its radial distance is 0).
        glm::dvec2 radial(exit.x, exit.z), dir(out.x, out.z);
        double s = -glm::dot(radial, dir) / glm::dot(dir, dir);
        double focus = exit.y + s * out.y - t / 2;  // from the rear vertex at y = t/2
        double slope = glm::length(dir) / out.y;
        double f = glm::length(glm::dvec2(h, 0.3 * h)) / slope;  // the ray's height over its angle
        std::printf("lens: ray at %.2f mm: back focal length %.3f mm (optics %.3f), effective %.3f mm (optics %.3f)\n",
                    glm::length(glm::dvec2(h, 0.3 * h)), focus, bfl, f, efl);
        EXPECT_NEAR(focus, bfl, 0.01 * bfl) << "height " << h;
        EXPECT_NEAR(f, efl, 0.01 * efl) << "height " << h;
    }
}

// ---- Optics from the image ------------------------------------------------------
//
// The two tests above follow single rays through the reference's hits. These
// read the same optics off chapter 12's own images (tests/optics_image.h).

nlohmann::json bk7() { return {{"ka", 0}, {"kd", 0}, {"ks", 0}, {"transmission", 1}, {"ior", 1.5168}}; }

// The lens's focal lengths from the magnification through it at three eye
// distances; at depth 2 (a ghost image blends in deeper).
TEST(Optics, LensFocalLengthsReadFromTheImage) {
    rgtest::optics::LensReading lens =
        rgtest::optics::lensFromImage(RG_EXE_12, rgtest::outputDir("12_lens_image"), meshDir(), bk7(), {});
    ASSERT_EQ(lens.ms.size(), 3u);
    std::printf("lens from the image: magnification %.5f %.5f %.5f at 10, 20, 30 mm; effective focal length %.3f mm "
                "(optics 49.213), back focal length %.3f mm (optics 47.536)\n", lens.ms[0], lens.ms[1], lens.ms[2],
                lens.efl, lens.bfl);
    EXPECT_NEAR(lens.efl, 49.213, 0.01 * 49.213);
    EXPECT_NEAR(lens.bfl, 47.536, 0.01 * 47.536);
    for (size_t i = 0; i < lens.ds.size(); ++i)
        EXPECT_NEAR(lens.ms[i], lens.slope * lens.ds[i] + lens.intercept, 1e-3) << "not a straight line";
}

// The smallest deviation over a fan through the prism must be the minimum
// deviation, 38.65 degrees for n = 1.5168.
TEST(Optics, PrismMinimumDeviationReadFromTheImage) {
    rgtest::optics::PrismReading prism =
        rgtest::optics::prismFromImage(RG_EXE_12, rgtest::outputDir("12_prism_image"), meshDir(), bk7(), {});
    const double n = 1.5168, expected = (2 * std::asin(n * std::sin(kPi / 6)) - kPi / 3) * 180 / kPi;
    std::printf("prism from the image: minimum deviation %.4f deg at column %d (optics %.4f)\n", prism.minimum,
                prism.column, expected);
    EXPECT_NEAR(prism.minimum, expected, 0.05);
}

// ---- Instancing and the fuzz pass ------------------------------------------

TEST(Meshes, OneFilePlacedAThousandTimesIsOneBlas) {
    std::string dir = rgtest::outputDir("12_instanced");
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene",
                                                  RG_SOURCE_DIR "/tests/mesh_scenes/instanced_1000.json", "--width",
                                                  "64", "--height", "36", "--frames", "1", "--output", dir + "/i.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/i.json");
    ASSERT_EQ(report["acceleration"]["meshes"].size(), 1u);
    const nlohmann::json& mesh = report["acceleration"]["meshes"][0];
    EXPECT_EQ(mesh["instances"], 1000);
    EXPECT_EQ(mesh["triangles"], 320);
    EXPECT_GT(mesh["blas_bytes"].get<double>(), 0);
    EXPECT_EQ(report["acceleration"]["tlas_instances"], 1001);  // and the floor
    EXPECT_TRUE(report.value("shading_normals", false));  // meshes: kMeshes
    EXPECT_EQ(report["validation_messages"], 0);
    // The report says what made the picture: the chapter's parameters, as run.
    EXPECT_EQ(report["parameters"]["depth"], 6);
    EXPECT_EQ(report["parameters"]["sphere-mesh"], 0);
    EXPECT_EQ(report["parameters"]["pattern"], "sobol");
}

// Mutated mesh files (bytes changed, cut short, numbers made huge or NaN):
// each loads or is refused with an InputError; nothing else may happen.
TEST(Meshes, FuzzedFilesLoadOrAreRefused) {
    std::string dir = rgtest::outputDir("12_fuzz");
    std::mt19937_64 rng(7);
    const char* tokens[] = {"nan", "inf", "-1", "1e39", "99999999999", "0", "f", "v", "/", "\"", "{", "]", ","};
    uint64_t loaded = 0, refused = 0;
    for (const char* name : {"icosphere_1.obj", "prism.obj", "wine_glass.gltf", "tiles.glb"}) {
        std::ifstream in(meshDir() + "/" + name, std::ios::binary);
        std::string original((std::istreambuf_iterator<char>(in)), {});
        std::string ext = fs::path(name).extension().string();
        for (int k = 0; k < 150; ++k) {
            std::string text = original;
            for (int edits = 1 + int(rng() % 4); edits > 0; --edits) {
                size_t at = rng() % text.size();
                switch (rng() % 4) {
                    case 0: text[at] = char(rng() % 128); break;
                    case 1: text.resize(at); break;
                    case 2: text.insert(at, tokens[rng() % std::size(tokens)]); break;
                    default: text.erase(at, rng() % 16); break;
                }
                if (text.empty()) text.push_back('x');
            }
            std::string path = dir + "/fuzz" + ext;
            writeText(path, text);
            if (ext == ".gltf") fs::copy_file(meshDir() + "/wine_glass.bin", dir + "/wine_glass.bin", fs::copy_options::skip_existing);
            try {
                rg::MeshFile f = rg::loadMeshFile(path);
                ++loaded;
            } catch (const rg::InputError& e) {
                ++refused;
                EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_GT(refused, 0u);
    EXPECT_GT(loaded + refused, 599u);
}

// Page 12's "what you should see" of the chapter's picture (meshes.json):
// through the wine glass's thin bowl the tiles behind stay nearly where
// they are, while its stem scrambles them, and the lens and the prism bend
// what is behind them past recognition. Read against the same scene without its
// glass (the floor and the mirror ball only): the Pearson correlation of
// the two pictures' luminance over a window of each object (positions from
// the scene, through its camera) is high where the view is kept, low where
// it is bent.
TEST(Chapter12, ThinBowlKeepsTheViewStemLensAndPrismScrambleIt) {
    std::string dir = rgtest::outputDir("12_page_picture");
    nlohmann::json scene = rgtest::readJson(RG_SOURCE_DIR "/assets/scenes/meshes.json");
    for (nlohmann::json& o : scene["objects"])
        if (o["type"] == "mesh") o["file"] = meshDir() + "/" + fs::path(std::string(o["file"])).filename().string();
    scene["sky"]["image"] = (fs::path(RG_EXE_12).parent_path() / "assets" / "sky.png").string();
    nlohmann::json bare = scene;
    bare["objects"] = nlohmann::json::array();
    for (const nlohmann::json& o : scene["objects"])  // the floor and the mirror ball
        if (o["type"] == "sphere" || std::string(o["file"]).find("tiles") != std::string::npos)
            bare["objects"].push_back(o);
    const int width = 320, height = 180;
    auto render = [&](const nlohmann::json& s, const std::string& name) {
        writeText(dir + "/" + name + "_scene.json", s.dump());
        // 8 frames: the tiles' rough reflections (chapter 11's) average out
        rgtest::RunResult r = rgtest::run(
            RG_EXE_12, {"--headless", "--validation", "--scene", dir + "/" + name + "_scene.json", "--width",
                        std::to_string(width), "--height", std::to_string(height), "--frames", "8", "--output",
                        dir + "/" + name + ".pfm"});
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return rg::readPfm(dir + "/" + name + ".pfm");
    };
    rg::FloatImage with = render(scene, "glass"), without = render(bare, "bare");
    rgtest::SceneCamera camera(scene, width, height);
    // the correlation over the pixels between two points' projections
    auto correlation = [&](glm::dvec3 a, glm::dvec3 b) {
        glm::dvec2 p = camera.project(a), q = camera.project(b);
        int x0 = int(std::ceil(std::min(p.x, q.x))), x1 = int(std::max(p.x, q.x));
        int y0 = int(std::ceil(std::min(p.y, q.y))), y1 = int(std::max(p.y, q.y));
        double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
        int n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x, ++n) {
                const float* u = &with.rgba[(size_t(y) * width + x) * 4];
                const float* v = &without.rgba[(size_t(y) * width + x) * 4];
                double l = (u[0] + u[1] + u[2]) / 3, m = (v[0] + v[1] + v[2]) / 3;
                sa += l, sb += m, saa += l * l, sbb += m * m, sab += l * m;
            }
        EXPECT_GT(n, 20) << "the window covers pixels";
        double cov = sab / n - sa / n * sb / n;
        return cov / std::sqrt(std::max(1e-12, (saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n)));
    };
    // the wine glass at (-1.25, 0, 0.1), 1/100 of its millimetres: bowl from y
    // 0.81 to 1.34 (radius 0.4 about y 1.2; the window keeps off its rim and
    // sides), stem 0.06-0.8 (radius 0.04); the lens at (0.05, 0.5, 0.4), 0.9
    // across; the prism at (1.3, 0, 0.2), 0.75 tall
    double bowl = correlation({-1.45, 0.9, 0.1}, {-1.05, 1.05, 0.1});
    double stem = correlation({-1.29, 0.15, 0.1}, {-1.21, 0.75, 0.1});
    double lens = correlation({-0.25, 0.3, 0.4}, {0.35, 0.7, 0.4});
    double prism = correlation({1.1, 0.15, 0.2}, {1.5, 0.6, 0.2});
    std::printf("correlation with the view without glass: bowl %.2f, stem %.2f, lens %.2f, prism %.2f\n", bowl,
                stem, lens, prism);
    EXPECT_GT(bowl, 0.5) << "through the thin bowl the tiles stay nearly where they are";
    EXPECT_LT(stem, 0.2) << "the stem scrambles them";
    EXPECT_LT(lens, 0.2) << "the lens bends them past recognition";
    EXPECT_LT(prism, 0.2) << "the prism bends them past recognition";
}

}  // namespace
