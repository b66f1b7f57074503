// Chapter 12: mip levels and ray cones. The levels are checked against
// their definition (2x2 means in linear light), the level a hit reads
// against the geometry of the view (a pixel's footprint in texels, worked
// out here from the camera, not from the shaders' formula), and what mip
// levels are for against a supersampled picture: less aliasing.
#include "gltf_square.h"
#include "harness.h"

#include "core/display.h"
#include "core/image.h"
#include "reference/reference.h"
#include "scene/texture.h"

#include <stb_image_write.h>

#include <cmath>
#include <fstream>

namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A side x side PNG of black and white checks, each `check` texels wide.
void writeChecker(const std::string& path, int side, int check) {
    std::vector<unsigned char> rgb(size_t(side) * side * 3);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (int c = 0; c < 3; ++c) rgb[3 * (size_t(y) * side + x) + c] = ((x / check + y / check) % 2) * 255;
    ASSERT_NE(stbi_write_png(path.c_str(), side, side, 3, rgb.data(), side * 3), 0) << path;
}

}  // namespace

// Each level's texel is the mean of the 2x2 below it in linear light, then
// encoded as level 0 is: black and white make sRGB's 188 (linear 0.5), not
// 128; data textures stay linear (127.5 rounds to 128). Sides halve,
// rounding down, to 1x1.
TEST(MipLevels, AreMeansInLinearLight) {
    const unsigned char bw[16] = {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255};
    rg::Texture colour = rg::decodeTexture("bw", bw, 2, 2, rg::TexelData::Colour);
    ASSERT_EQ(colour.levels.size(), 2u);
    const uint8_t* top = &colour.rgba[colour.levels[1].offset];
    EXPECT_EQ(int(top[0]), int(std::lround(rg::linearToSrgb(0.5) * 255)));
    EXPECT_EQ(int(top[0]), 188);
    EXPECT_NEAR(rg::texelValue(colour, 1, 0, 0).r, 0.5, 0.003);
    rg::Texture data = rg::decodeTexture("bw", bw, 2, 2, rg::TexelData::Linear);
    EXPECT_EQ(int(data.rgba[data.levels[1].offset]), 128);
    // half-transparent texels average their alpha too
    const unsigned char clear[16] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 255, 255, 0, 0, 255};
    rg::Texture leaf = rg::decodeTexture("leaf", clear, 2, 2);
    EXPECT_FALSE(leaf.opaque);
    EXPECT_EQ(int(leaf.rgba[leaf.levels[1].offset + 3]), 128);
    std::vector<unsigned char> odd(5 * 3 * 4, 255);
    rg::Texture t = rg::decodeTexture("odd", odd.data(), 5, 3);
    ASSERT_EQ(t.levels.size(), 3u);
    EXPECT_EQ(glm::uvec2(t.levels[1].width, t.levels[1].height), glm::uvec2(2, 1));
    EXPECT_EQ(glm::uvec2(t.levels[2].width, t.levels[2].height), glm::uvec2(1, 1));
    EXPECT_EQ(t.rgba.size(), 4u * (15 + 2 + 1));
}

// A square of 256 x 256 one-texel checks, head-on. From distance d with a
// vertical field of view f and H rows, one pixel spans 2 d tan(f/2) / H of
// the square's 2 units, 128 texels a unit: 3 texels at d = 2.546 (45
// degrees, 90 rows). There every level above 0 is grey (each of its texels
// averages black and white), so with mip levels every pixel reads 0.5;
// without, each pixel centre lands on one texel: black or white (the
// aliasing). Checks two texels wide bound the level from above. From d / 6
// a pixel spans half a texel: magnified, both read
// level 0 and draw the checks alike.
TEST(RayCones, APixelSpanningThreeTexelsReadsTheirMean) {
    std::string dir = rgtest::outputDir("12_ray_cones");
    writeChecker(dir + "/checks.png", 256, 1);
    writeChecker(dir + "/checks2.png", 256, 2);
    for (const char* name : {"checks", "checks2"})
        writeSquareGltf(dir, name, wall(1), {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}},
                        {{"baseColorTexture", std::string(name) + ".png"}});
    const double tanHalf = std::tan(22.5 * 3.14159265358979 / 180), d = 3 * 90 / (2 * tanHalf * 128);
    auto scene = [&](const std::string& name, double distance, const std::string& file = "checks") {
        writeText(dir + "/" + name + ".json",
                  R"({"camera": {"position": [0, 0, )" + std::to_string(distance) +
                      R"(], "look_at": [0, 0, 0], "fov_y_deg": 45},
                      "sky": {"top": 0, "horizon": 0, "bottom": 0}, "ambient": 1,
                      "objects": [{"type": "mesh", "file": ")" + file + R"(.gltf"}]})");
        return dir + "/" + name + ".json";
    };
    // lit by ambient light alone, each pixel is k times the texture's value
    // (glTF's rough dielectric: ka = kd = its base colour times a constant)
    rgtest::Png on = render(scene("far", d), dir + "/far_on.png", {});
    rgtest::Png off = render(scene("far", d), dir + "/far_off.png", {"--mips", "off"});
    int lo = 255, hi = 0, pixels = 0;
    for (int y = 15; y < 75; ++y)
        for (int x = 50; x < 110; ++x) {
            ++pixels;
            lo = std::min(lo, int(on.at(x, y)[1])), hi = std::max(hi, int(on.at(x, y)[1]));
        }
    EXPECT_LE(hi - lo, 2) << "with mip levels every pixel should read the mean";
    // black and white in linear light: 0.5, shown as 188 (not 128)
    EXPECT_NEAR((lo + hi) / 2, rg::toDisplay8(0.5), 1);
    int aliased = 0;  // without: black or white, far from that mean
    for (int y = 15; y < 75; ++y)
        for (int x = 50; x < 110; ++x) aliased += std::abs(off.at(x, y)[1] - (lo + hi) / 2) > 40;
    EXPECT_GT(aliased, pixels / 2) << "of " << pixels << ": without mip levels the checks should alias";
    // Checks two texels wide: level 1 still has them (one texel wide), level
    // 2 is grey. At log2(3) = 1.58 the blend keeps 42 % of level 1: if the
    // cone chose level 2 or above (lod >= 2), the picture would be grey.
    rgtest::Png coarse = render(scene("far2", d, "checks2"), dir + "/far2_on.png", {});
    int coarseLo = 255, coarseHi = 0;
    for (int y = 15; y < 75; ++y)
        for (int x = 50; x < 110; ++x)
            coarseLo = std::min(coarseLo, int(coarse.at(x, y)[1])),
            coarseHi = std::max(coarseHi, int(coarse.at(x, y)[1]));
    EXPECT_GT(coarseHi - coarseLo, 8) << "two-texel checks: level 1 should still show (grey: <= 2)";
    rgtest::Png nearOn = render(scene("near", d / 6), dir + "/near_on.png", {});
    rgtest::Png nearOff = render(scene("near", d / 6), dir + "/near_off.png", {"--mips", "off"});
    int differ = 0;
    lo = 255, hi = 0;
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x) {
            differ += nearOn.at(x, y)[1] != nearOff.at(x, y)[1];
            lo = std::min(lo, int(nearOn.at(x, y)[1])), hi = std::max(hi, int(nearOn.at(x, y)[1]));
        }
    EXPECT_EQ(differ, 0) << "magnified, both should read level 0";
    // bilinear between texel centres: the checks show, softened
    EXPECT_GT(hi - lo, 30) << "magnified, the checks should show";
    nlohmann::json report = rgtest::readJson(dir + "/far_on.json");
    EXPECT_TRUE(report.value("ray_cones", false));
    EXPECT_EQ(report["textures"].value("levels", 0), 9);  // 256 .. 1
    EXPECT_FALSE(rgtest::readJson(dir + "/far_off.json").value("ray_cones", true));
}

// What mip levels are for, on page 12's far floor (assets/scenes/
// far_floor.json, its three pictures at 480x270) against the same view
// with 64 jittered rays a pixel at level 0 (the box-filtered picture a mip
// level stands for). What the page says one sees, as numbers: in the far
// floor's rows (the 35 below the horizon, row 104 of 270) level 0 shows
// moire (neighbouring pixels far apart), ray cones fade evenly (under a
// quarter of that), a little blurrier than 64 rays; and the error against
// the 64-ray picture falls (page 12 quotes both RMSEs; test_page_numbers.py
// checks them).
TEST(RayCones, MipLevelsTakeTheFarFloorTowardsItsSupersampledPicture) {
    std::string dir = rgtest::outputDir("12_far_floor");
    auto run = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = {"--headless", "--validation", "--scene",
                                         RG_SOURCE_DIR "/assets/scenes/far_floor.json", "--width", "480", "--height",
                                         "270", "--output", dir + "/" + name + ".pfm"};
        args.insert(args.end(), extra.begin(), extra.end());
        rgtest::RunResult r = rgtest::run(RG_EXE_12, args);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return rg::readPfm(dir + "/" + name + ".pfm");
    };
    rg::FloatImage truth = run("supersampled", {"--mips", "off", "--antialias", "on", "--frames", "64"});
    rg::FloatImage level0 = run("level0", {"--mips", "off"});
    rg::FloatImage mips = run("mips", {});
    ASSERT_EQ(mips.width, 480u);
    // the mean difference of horizontally neighbouring pixels (green) in the far rows
    auto ripple = [](const rg::FloatImage& image) {
        double sum = 0;
        int n = 0;
        for (uint32_t y = 105; y < 140; ++y)
            for (uint32_t x = 0; x + 1 < image.width; ++x, ++n)
                sum += std::abs(image.rgba[4 * (y * image.width + x + 1) + 1] - image.rgba[4 * (y * image.width + x) + 1]);
        return sum / n;
    };
    double moire = ripple(level0), even = ripple(mips), sharp = ripple(truth);
    std::printf("far rows, mean neighbour difference: level 0 %.4f, ray cones %.4f, 64 rays %.4f\n", moire, even, sharp);
    EXPECT_LT(even, 0.25 * moire) << "the far tiles should fade evenly, not ripple";
    EXPECT_LT(even, sharp) << "one isotropic level is blurrier than 64 rays";
    double without = rg::compareImages(level0, truth, nullptr).rmse, with = rg::compareImages(mips, truth, nullptr).rmse;
    std::printf("RMSE against 64 rays a pixel: level 0 %.4f, ray cones %.4f\n", without, with);
    EXPECT_LT(with, 0.7 * without);
}
