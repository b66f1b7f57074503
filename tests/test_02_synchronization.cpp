// Chapter 02: after N frames the image is the pattern at time (N-1)/60 s,
// scrolled by a known number of pixels; the windowed path runs under Xvfb;
// the --omit-barrier experiment is caught by synchronization validation.
#include "harness.h"

#include <cstdlib>

namespace {

constexpr int kChecker = 32;

void expectPatternAtFrame(const rgtest::Png& png, int lastFrame) {
    int shift = int(lastFrame / 60.0 * 240.0);
    for (int y : {0, 20, 33, png.height - 1})
        for (int x = 0; x < png.width; x += 7) {
            int sx = x + png.width * kChecker - shift % (png.width * kChecker);
            bool odd = ((sx / kChecker + y / kChecker) & 1) == 1;
            EXPECT_EQ(png.at(x, y)[2], rgtest::display8(odd ? 0.75 : 0.25)) << x << "," << y;
            EXPECT_NEAR(png.at(x, y)[0], rgtest::display8((x + 0.5) / png.width), 1);
        }
}

TEST(Chapter02, AnimatesDeterministicallyWithValidationClean) {
    std::string dir = rgtest::outputDir("02");
    for (int frames : {1, 5}) {
        std::string png = dir + "/02_" + std::to_string(frames) + ".png";
        rgtest::RunResult r = rgtest::run(RG_EXE_02, {"--headless", "--validation", "--width", "128", "--height",
                                                      "72", "--frames", std::to_string(frames), "--output", png});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        rgtest::Png image = rgtest::readPng(png);
        ASSERT_EQ(image.width, 128);
        ASSERT_EQ(image.height, 72);
        expectPatternAtFrame(image, frames - 1);  // frame 4: 16 pixels to the right
        nlohmann::json report = rgtest::readJson(dir + "/02_" + std::to_string(frames) + ".json");
        rgtest::expectCleanReport(report, "02_synchronization", 128, 72);
        EXPECT_EQ(report.value("frames", 0), frames);
        EXPECT_EQ(report.value("frames_in_flight", 0), 2);
    }
}

// Run by ctest under xvfb-run (see tests/CMakeLists.txt).
TEST(Chapter02Windowed, PresentsUnderXvfbWithValidationClean) {
    if (!rgtest::haveDisplay()) GTEST_SKIP() << "no DISPLAY: run through xvfb-run";
    std::string dir = rgtest::outputDir("02_window");
    rgtest::RunResult r = rgtest::run(RG_EXE_02, {"--validation", "--width", "160", "--height", "90", "--frames",
                                                  "30", "--output", dir + "/02.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/02.json");
    EXPECT_FALSE(report.value("headless", true));
    EXPECT_EQ(report.value("frames", 0), 30);
    EXPECT_EQ(report.value("validation_messages", -1), 0);
    expectPatternAtFrame(rgtest::readPng(dir + "/02.png"), 29);
}

TEST(Chapter02Windowed, OmittedBarrierIsReportedBySyncValidation) {
    if (!rgtest::haveDisplay()) GTEST_SKIP() << "no DISPLAY: run through xvfb-run";
    std::string dir = rgtest::outputDir("02_hazard");
    rgtest::RunResult r = rgtest::run(RG_EXE_02, {"--validation", "--omit-barrier", "--width", "64", "--height",
                                                  "64", "--frames", "3", "--output", dir + "/02.png"});
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("SYNC-HAZARD"), std::string::npos) << r.output;
}

}  // namespace
