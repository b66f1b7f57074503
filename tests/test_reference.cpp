// Compiled once per shading chapter (05-12; tests/CMakeLists.txt sets
// RG_THIS_EXE and RG_THIS_NAME): the chapter against the CPU double-precision
// reference on its default scene and on every hard case under tests/scenes/
// (scales 1e-3 and 1e5, the scene moved 1e4-1e6 from the origin, a light on
// a surface, a grazing light, tangent rays, overlapping and coincident
// spheres, the eye on a sphere, a camera inside a sphere or inside glass
// (where total internal reflection happens), glass at grazing incidence,
// touching glass spheres, a long glass ellipsoid, the depth limit, 1,000
// spheres), with validation on and no NaN anywhere; chapter 12 also on the
// mesh scenes under tests/mesh_scenes/; antialiased (--antialias); and its
// window under Xvfb.
#include "harness.h"

#include <cctype>
#include <filesystem>

namespace {

// Chapter 11's default scene has a rough surface: Monte Carlo noise, judged
// by test_11_rough.cpp against a converged reference instead.
#ifndef RG_NOISY_DEFAULT_SCENE
TEST(Reference, DefaultSceneMatches) {
    rgtest::expectMatchesReference(RG_THIS_EXE, "", RG_THIS_NAME "_default");
}
#endif

// --antialias: 8 frames of rays through new points in each pixel, against
// the reference's mean over the same points. (Chapter 11: a scene without a
// rough surface, so that only the pixel is integrated.)
TEST(Antialias, MatchesTheReferenceOverTheSamePointsOfEachPixel) {
#ifdef RG_NOISY_DEFAULT_SCENE
    std::string scene = RG_SOURCE_DIR "/tests/scenes/far_1e4.json";
#else
    std::string scene;
#endif
    nlohmann::json report = rgtest::expectMatchesReference(RG_THIS_EXE, scene, RG_THIS_NAME "_antialias",
                                                           {"--antialias", "on", "--frames", "8"});
    EXPECT_EQ(report["parameters"].value("antialias", ""), "on");
}

class HardCases : public ::testing::TestWithParam<std::string> {};

TEST_P(HardCases, MatchReference) {
    std::string stem = std::filesystem::path(GetParam()).stem().string();
    rgtest::expectMatchesReference(RG_THIS_EXE, GetParam(), RG_THIS_NAME "_" + stem);
}

INSTANTIATE_TEST_SUITE_P(Scenes, HardCases, ::testing::ValuesIn(rgtest::hardCaseScenes()),
                         [](const auto& info) {  // test names allow letters, digits and '_'
                             std::string name = std::filesystem::path(info.param).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

#ifdef RG_MESH_SCENES
// Chapter 12 on: the mesh hard cases (thin shells, a mesh inside a sphere,
// edges seen edge-on, one mesh placed 1,000 times).
INSTANTIATE_TEST_SUITE_P(MeshScenes, HardCases, ::testing::ValuesIn(rgtest::meshScenes()),
                         [](const auto& info) { return std::filesystem::path(info.param).stem().string(); });
#endif

TEST(Windowed, RendersUnderXvfb) {
    rgtest::expectCleanWindowedRun(RG_THIS_EXE, RG_THIS_NAME "_window", 10);
}

}  // namespace
