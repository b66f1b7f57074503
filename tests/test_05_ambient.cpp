// Chapter 05 against the CPU double-precision reference, on its default
// scene and on every hard case under tests/scenes/ (scales 1e-3 and 1e5, a
// light on a surface, a grazing light, tangent rays, overlapping spheres,
// the camera inside a sphere), with validation on and no NaN anywhere.
#include "harness.h"

#include <cctype>
#include <filesystem>

namespace {

TEST(Chapter05, DefaultSceneMatchesTheReference) {
    rgtest::expectMatchesReference(RG_EXE_05, "", "05_default");
}

class Chapter05HardCases : public ::testing::TestWithParam<std::string> {};

TEST_P(Chapter05HardCases, MatchesTheReference) {
    std::string stem = std::filesystem::path(GetParam()).stem().string();
    rgtest::expectMatchesReference(RG_EXE_05, GetParam(), "05_" + stem);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Chapter05HardCases, ::testing::ValuesIn(rgtest::hardCaseScenes()),
                         [](const auto& info) {  // test names allow letters, digits and '_'
                             std::string name = std::filesystem::path(info.param).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(Chapter05Windowed, RendersUnderXvfb) {
    rgtest::expectCleanWindowedRun(RG_EXE_05, "05_window", 10);
}

}  // namespace
