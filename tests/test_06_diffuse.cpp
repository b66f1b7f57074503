// Chapter 06's own experiment; the reference and hard-case tests of every
// shading chapter are in test_reference.cpp.
#include "core/image.h"
#include "harness.h"
#include "reference/reference.h"

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

// --exposure (the overlay's View section) scales what is written, nothing
// else: one stop doubles every pixel exactly, also where frames accumulate
// (chapter 11 stores the exposed mean and reads it back), and the reference
// scales the same way.
TEST(Exposure, OneStopDoublesEveryPixel) {
    for (const char* exe : {RG_EXE_06, RG_EXE_11}) {
        std::string dir = rgtest::outputDir(std::string("exposure_") + (exe == std::string(RG_EXE_06) ? "06" : "11"));
        for (const char* ev : {"0", "1"}) {
            rgtest::RunResult r = rgtest::run(exe, {"--headless", "--validation", "--width", "96", "--height", "54",
                                                    "--frames", "3", "--exposure", ev,
                                                    "--output", dir + "/ev" + ev + ".png"});
            ASSERT_EQ(r.exitCode, 0) << r.output;
        }
        rg::FloatImage a = rg::readPfm(dir + "/ev0.pfm"), b = rg::readPfm(dir + "/ev1.pfm");
        ASSERT_EQ(a.rgba.size(), b.rgba.size());
        size_t differ = 0;
        double lit = 0;
        for (size_t i = 0; i < a.rgba.size(); ++i) {
            if (i % 4 == 3) continue;  // alpha
            differ += b.rgba[i] != 2 * a.rgba[i];
            lit += a.rgba[i];
        }
        EXPECT_EQ(differ, 0u) << exe;
        EXPECT_GT(lit, 0.1 * double(a.rgba.size())) << exe << ": a picture, not black";
    }
    nlohmann::json report = rgtest::expectMatchesReference(RG_EXE_06, "", "exposure_06_reference", {"--exposure", "1"});
    EXPECT_EQ(report["parameters"]["exposure"], 1.0);
}

TEST(Exposure, OutOfRangeIsOneClearLine) {
    rgtest::RunResult r = rgtest::run(RG_EXE_06, {"--headless", "--exposure", "11"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--exposure"), std::string::npos) << r.output;
}

}  // namespace
