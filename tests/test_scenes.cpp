// Bad scene files: one clear message naming the file and the key, exit code 2,
// for every chapter that reads scenes.
#include "harness.h"

#include "raytracing/rt_scene.h"
#include "scene/scene.h"

#include <fstream>

namespace {

struct BadScene {
    std::string name, json, key;
};

const char* kGood = R"({"camera": {"position": [0, 1, 5]}, "materials": {"m": {}},
  "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})";

std::vector<BadScene> badScenes() {
    return {
        {"malformed", R"({"camera": {)", "not valid JSON"},
        {"unknown_top_key", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}], "lihgts": []})", "lihgts"},
        {"unknown_material_key", R"({"camera": {}, "materials": {"m": {"shine": 3}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", "materials.m.shine"},
        {"negative_radius", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": -1, "material": "m"}]})", "objects[0].radius"},
        {"ior_below_1", R"({"camera": {}, "materials": {"m": {"ior": 0.9}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", "materials.m.ior"},
        {"nan_as_string", R"({"camera": {"fov_y_deg": "NaN"}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", "camera.fov_y_deg"},
        {"huge_number", R"({"camera": {"position": [0, 0, 1e999]}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", ""},
        {"missing_material", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "glass"}]})", "objects[0].material"},
        {"unknown_shape", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "cube", "material": "m"}]})", "objects[0].type"},
        {"parallel_quad", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "quad", "u": [1,0,0], "v": [2,0,0], "material": "m"}]})", "objects[0].v"},
        {"no_objects", R"({"camera": {}, "materials": {"m": {}}, "objects": []})", "objects"},
        {"duplicated_key", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "radius": 2, "material": "m"}]})", "radius\" appears twice"},
        {"sphere_list_not_quadruples", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": [0, 0, 0], "material": "m"}]})", "objects[0].data"},
        {"sphere_list_bad_radius", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": [0, 0, 0, 1, 2, 0, 0, -1], "material": "m"}]})", "objects[0].data[7]"},
        {"sphere_list_string", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": [0, "x", 0, 1], "material": "m"}]})", "objects[0].data[1]"},
        {"sphere_list_nested_array", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": [0, 0, 0, [1, 2]], "material": "m"}]})", "objects[0].data[3]: must be a number"},
        {"sphere_list_object", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": [0, 0, {"data": [1]}, 1], "material": "m"}]})", "objects[0].data[2]: must be a number"},
        {"sphere_list_not_array", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "spheres", "data": 4, "material": "m"}]})", "objects[0].data"},
        {"data_on_a_sphere", R"({"camera": {}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "data": [1, 2, 3, 4], "material": "m"}]})", "objects[0].data: unknown key"},
        {"missing_sky_image", R"({"camera": {}, "sky": {"image": "nope.png"}, "materials": {"m": {}}, "objects": [{"type": "sphere", "radius": 1, "material": "m"}]})", "sky.image"},
    };
}

class Scenes : public ::testing::TestWithParam<std::string> {};

TEST_P(Scenes, BadFilesExitWithCode2NamingFileAndKey) {
    std::string dir = rgtest::outputDir("scenes_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000));
    for (const auto& bad : badScenes()) {
        std::string path = dir + "/" + bad.name + ".json";
        std::ofstream(path) << bad.json;
        rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--scene", path, "--output", dir + "/x.png"});
        EXPECT_EQ(r.exitCode, 2) << bad.name << ": " << r.output;
        EXPECT_NE(r.output.find(path), std::string::npos) << bad.name << ": " << r.output;
        EXPECT_NE(r.output.find(bad.key), std::string::npos) << bad.name << ": " << r.output;
        EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
    }
    rgtest::RunResult missing = rgtest::run(GetParam(), {"--headless", "--scene", dir + "/none.json"});
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.output.find("--scene: " + dir + "/none.json: no such file"), std::string::npos) << missing.output;
}

TEST_P(Scenes, AFolderIsNotASceneFile) {
    // One folder per chapter: outputDir empties it, and the chapters run in parallel.
    std::string dir = rgtest::outputDir("scenes_folder_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000));
    rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--scene", dir, "--output", dir + "/x.png"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("is a folder, not a file"), std::string::npos) << r.output;
}

TEST_P(Scenes, AMinimalSceneRuns) {
    std::string dir = rgtest::outputDir("scenes_ok_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000));
    std::ofstream(dir + "/good.json") << kGood;
    rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--validation", "--scene", dir + "/good.json",
                                                   "--width", "32", "--height", "32", "--frames", "1", "--output",
                                                   dir + "/good_render.png"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
}

// The rule for coincident objects: the first listed is drawn, later copies
// are hidden (and the loader says so).
// The compact sphere list (for big scenes) reads as the same spheres as
// one object each, in its order.
TEST(SceneRules, SphereListEqualsSingleSpheres) {
    std::string dir = rgtest::outputDir("scenes_sphere_list");
    std::ofstream(dir + "/list.json") << R"({"camera": {}, "materials": {"a": {}, "b": {}}, "objects": [
        {"type": "spheres", "material": "b", "data": [1, 2, 3, 0.5, -4, 0, 2.5, 2]},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a"}]})";
    std::ofstream(dir + "/single.json") << R"({"camera": {}, "materials": {"a": {}, "b": {}}, "objects": [
        {"type": "sphere", "center": [1, 2, 3], "radius": 0.5, "material": "b"},
        {"type": "sphere", "center": [-4, 0, 2.5], "radius": 2, "material": "b"},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a"}]})";
    rg::Scene list = rg::loadScene(dir + "/list.json"), single = rg::loadScene(dir + "/single.json");
    ASSERT_EQ(list.objects.size(), 3u);
    ASSERT_EQ(single.objects.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(list.objects[i].type, rg::ShapeType::Sphere);
        EXPECT_EQ(list.objects[i].material, single.objects[i].material) << i;
        EXPECT_EQ(list.objects[i].center, single.objects[i].center) << i;
        EXPECT_EQ(list.objects[i].radius, single.objects[i].radius) << i;
        EXPECT_EQ(list.objects[i].transform, single.objects[i].transform) << i;
    }
    EXPECT_EQ(list.eyeTmin, single.eyeTmin);
}

TEST(SceneRules, CoincidentObjectsKeepTheFirst) {
    rg::Scene s = rg::loadScene(RG_SOURCE_DIR "/tests/scenes/coincident_spheres.json");
    ASSERT_EQ(s.objects.size(), 6u);
    EXPECT_TRUE(s.objects[5].hidden);
    for (size_t i = 0; i < 5; ++i) EXPECT_FALSE(s.objects[i].hidden) << i;
}

// Camera space: the eye at the origin, everything moved by the same vector
// in double.
TEST(SceneRules, CameraSpaceMovesEverythingByTheEye) {
    rg::Scene world = rg::loadScene(RG_SOURCE_DIR "/tests/scenes/far_1e6.json");
    rg::Scene near = rg::loadScene(RG_SOURCE_DIR "/assets/scenes/default.json");
    rg::Scene moved = rg::toCameraSpace(world);
    EXPECT_EQ(moved.camera.position, glm::dvec3(0));
    EXPECT_EQ(moved.origin, -world.camera.position);
    EXPECT_EQ(moved.eyeTmin, world.eyeTmin);  // the eye touches no surface here: 0 in both
    EXPECT_EQ(world.eyeTmin, 0.0);
    rg::Scene nearMoved = rg::toCameraSpace(near);
    ASSERT_EQ(moved.objects.size(), nearMoved.objects.size());
    for (size_t i = 0; i < moved.objects.size(); ++i)  // far and near scenes agree once moved
        EXPECT_NEAR(glm::length(moved.objects[i].center - nearMoved.objects[i].center), 0.0, 1e-9) << i;
    EXPECT_NEAR(glm::length(moved.lights[0].position - nearMoved.lights[0].position), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(moved.camera.lookAt - nearMoved.camera.lookAt), 0.0, 1e-9);
}

// The rule that compiles in the shaders' care for extreme numbers
// (rt_scene.h's needsCarefulNumerics), on scenes whose need is known from
// their geometry: a floor sphere's radius against the eye's height above
// it, lengths beyond 1e8 or below 1e-8, a shininess from 1e4 on.
rg::CarefulNumerics ruleFor(const std::string& name, const std::string& objects,
                            const std::string& material = "{}") {
    std::string dir = rgtest::outputDir("scenes_numerics_" + name);
    std::ofstream(dir + "/s.json") << R"({"camera": {"position": [3, 1, 5], "look_at": [3, 0, 0]},
        "lights": [{"position": [0, 5, 0]}], "materials": {"m": )" + material +
                                          R"(}, "objects": [)" + objects + "]}";
    return rg::needsCarefulNumerics(rg::toCameraSpace(rg::loadScene(dir + "/s.json")));
}

std::string floorSphere(double radius) {
    return R"({"type": "sphere", "center": [0, )" + std::to_string(-radius) +
           R"(, 0], "radius": )" + std::to_string(radius) + R"(, "material": "m"})";
}

TEST(SceneRules, CarefulNumericsWhereTheGeometryNeedsThem) {
    // the eye is 1 above the top of each floor sphere: careful past 1024
    EXPECT_FALSE(ruleFor("floor_500", floorSphere(500)).sizes);
    EXPECT_TRUE(ruleFor("floor_2000", floorSphere(2000)).sizes);
    EXPECT_TRUE(ruleFor("floor_1e5", floorSphere(1e5)).sizes);
    // a sky dome around the eye: a length past 1e8
    EXPECT_FALSE(ruleFor("dome_1e3", R"({"type": "sphere", "radius": 1e3, "material": "m"})").sizes);
    EXPECT_TRUE(ruleFor("dome_1e20", R"({"type": "sphere", "radius": 1e20, "material": "m"})").sizes);
    // a sphere far smaller than the scene's reach, a quad far larger
    std::string small = R"({"type": "sphere", "center": [0, 0, 0], "radius": )";
    EXPECT_FALSE(ruleFor("tiny_1e-6", small + R"(1e-6, "material": "m"})").sizes);
    EXPECT_TRUE(ruleFor("tiny_1e-9", small + R"(1e-9, "material": "m"})").sizes);
    EXPECT_TRUE(ruleFor("quad_1e9", R"({"type": "quad", "u": [1e9, 0, 0], "v": [0, 0, 1e9], "material": "m"})").sizes);
    // an ellipsoid 64 times longer than it is thin (its hits are refined, sphere.rint)
    std::string plate = R"({"type": "sphere", "radius": 1, "material": "m", "transform": {"translate": [0, 0, -5], )";
    EXPECT_FALSE(ruleFor("plate_1_64", plate + R"("scale": [1, 1, 0.0157]}})").sizes);
    EXPECT_TRUE(ruleFor("plate_1_65", plate + R"("scale": [1, 1, 0.0153]}})").sizes);
    EXPECT_TRUE(ruleFor("rod_1e3", plate + R"("scale": [1e-3, 1, 1e-3], "rotate_deg": [30, 40, 0]}})").sizes);
    // the shininess alone
    std::string ball = small + R"(1, "material": "m"})";
    EXPECT_FALSE(ruleFor("shininess_9999", ball, R"({"shininess": 9999})").shininess);
    EXPECT_TRUE(ruleFor("shininess_1e4", ball, R"({"shininess": 1e4})").shininess);
    EXPECT_FALSE(ruleFor("shininess_1e4", ball, R"({"shininess": 1e4})").sizes);
    // the hard cases that need it, and one far from the world's origin that
    // camera space makes ordinary
    auto rule = [](const std::string& scene) {
        return rg::needsCarefulNumerics(rg::toCameraSpace(rg::loadScene(RG_SOURCE_DIR "/tests/scenes/" + scene)));
    };
    EXPECT_TRUE(rule("ground_sphere_1e5.json").sizes);
    EXPECT_TRUE(rule("sky_dome_1e20.json").sizes);
    EXPECT_TRUE(rule("eye_on_sphere.json").sizes);  // the eye on a surface: no distance to it
    EXPECT_TRUE(rule("shininess_1e6.json").shininess);
    EXPECT_TRUE(rule("thin_plates_1e-3.json").sizes);
    rg::CarefulNumerics far = rule("far_1e6.json");
    EXPECT_FALSE(far.sizes || far.shininess);
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(SceneChapters, Scenes, ::testing::ValuesIn(std::vector<std::string>{RG_SCENE_CHAPTER_EXES}));
