// Chapter 01 headless on lavapipe with validation: the PNG shows exactly the
// pattern that pattern.comp defines, and the report is complete and clean.
#include "harness.h"

namespace {

TEST(Chapter01, WritesThePatternWithValidationClean) {
    const int w = 96, h = 64, checker = 32;
    std::string dir = rgtest::outputDir("01");
    rgtest::RunResult r = rgtest::run(RG_EXE_01, {"--headless", "--validation", "--width", std::to_string(w),
                                                  "--height", std::to_string(h), "--frames", "2", "--output",
                                                  dir + "/01.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("shaderGroupHandleSize"), std::string::npos) << "ray tracing properties printed";

    rgtest::Png png = rgtest::readPng(dir + "/01.png");
    ASSERT_EQ(png.width, w);
    ASSERT_EQ(png.height, h);
    // Red = u, green = v at pixel centres; blue alternates 0.25 / 0.75 per square.
    for (int y : {0, 1, 31, 32, 40, h - 1})
        for (int x : {0, 5, 31, 32, 63, 64, w - 1}) {
            bool odd = ((x / checker + y / checker) & 1) == 1;
            const uint8_t* p = png.at(x, y);
            EXPECT_NEAR(p[0], rgtest::display8((x + 0.5) / w), 1) << x << "," << y;
            EXPECT_NEAR(p[1], rgtest::display8((y + 0.5) / h), 1) << x << "," << y;
            EXPECT_EQ(p[2], rgtest::display8(odd ? 0.75 : 0.25)) << x << "," << y;
        }
    rgtest::expectCleanReport(rgtest::readJson(dir + "/01.json"), "01_vulkan_setup", w, h);
}

}  // namespace
