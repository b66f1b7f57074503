// Chapter 09: every Fresnel mode matches the reference; the chapter prints
// Schlick's error table; a bad mode is rejected.
#include "harness.h"

namespace {

TEST(Chapter09, EveryFresnelModeMatchesTheReference) {
    for (const char* mode : {"schlick", "schlick-ior", "exact"})
        rgtest::expectMatchesReference(RG_EXE_09, RG_SOURCE_DIR "/assets/scenes/glass_sphere.json",
                                       std::string("09_") + mode, {"--fresnel", mode});
}

TEST(Chapter09, PrintsSchlicksErrorOverTheAngle) {
    std::string dir = rgtest::outputDir("09_table");
    rgtest::RunResult r = rgtest::run(RG_EXE_09, {"--headless", "--width", "16", "--height", "16", "--frames", "1",
                                                  "--output", dir + "/x.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("angle"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("89"), std::string::npos) << r.output;
}

TEST(Chapter09, UnknownModeIsRejected) {
    rgtest::RunResult r = rgtest::run(RG_EXE_09, {"--headless", "--fresnel", "fast"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--fresnel"), std::string::npos) << r.output;
}

}  // namespace
