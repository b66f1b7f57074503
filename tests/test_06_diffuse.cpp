// Chapter 06 against the CPU double-precision reference, on its default
// scene and on every hard case under tests/scenes/ (scales 1e-3 and 1e5, a
// light on a surface, a grazing light, tangent rays, overlapping spheres,
// the camera inside a sphere), with validation on and no NaN anywhere.
#include "harness.h"

#include <cctype>
#include <filesystem>

namespace {

TEST(Chapter06, DefaultSceneMatchesTheReference) {
    rgtest::expectMatchesReference(RG_EXE_06, "", "06_default");
}

class Chapter06HardCases : public ::testing::TestWithParam<std::string> {};

TEST_P(Chapter06HardCases, MatchesTheReference) {
    std::string stem = std::filesystem::path(GetParam()).stem().string();
    rgtest::expectMatchesReference(RG_EXE_06, GetParam(), "06_" + stem);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Chapter06HardCases, ::testing::ValuesIn(rgtest::hardCaseScenes()),
                         [](const auto& info) {  // test names allow letters, digits and '_'
                             std::string name = std::filesystem::path(info.param).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(Chapter06Windowed, RendersUnderXvfb) {
    rgtest::expectCleanWindowedRun(RG_EXE_06, "06_window", 10);
}

}  // namespace

namespace {

// The reference comparison is what catches acne and light leaks: a fixed
// epsilon of 1e-3 fails it at scene scales 1e-3 (leaks) and 1e5 (acne).
TEST(Chapter06, FixedEpsilonFailsWhereTheRobustOffsetPasses) {
    for (const char* scene : {"scaled_1e-3", "scaled_1e5"}) {
        std::string dir = rgtest::outputDir(std::string("06_fixed_") + scene);
        rgtest::RunResult r = rgtest::run(
            RG_EXE_06, {"--headless", "--reference", "--fixed-epsilon", "1e-3", "--width", "160", "--height", "90",
                        "--frames", "1", "--scene", std::string(RG_SOURCE_DIR "/tests/scenes/") + scene + ".json",
                        "--output", dir + "/out.png"});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        nlohmann::json report = rgtest::readJson(dir + "/out.json");
        EXPECT_GT(report["error"].value("frac_over_1_255", 0.0), 0.01) << scene;
    }
}

}  // namespace
