// Chapter 06's own experiment; the reference and hard-case tests of every
// shading chapter are in test_reference.cpp.
#include "harness.h"

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

TEST(Chapter06, NonPositiveEpsilonIsOneClearLine) {
    for (const char* bad : {"0", "-1e-3", "abc", "1e40"}) {
        rgtest::RunResult r = rgtest::run(RG_EXE_06, {"--headless", "--fixed-epsilon", bad});
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("--fixed-epsilon: must be a positive distance"), std::string::npos) << r.output;
    }
}

}  // namespace
