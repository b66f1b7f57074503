// Chapter 10's optics: seen through a glass ball, markers behind it appear
// inverted both ways, at the distance from the centre that the paraxial
// ball-lens formula predicts (effective focal length f = nR / (2(n - 1))
// from the centre), within 3 %.
#include "harness.h"

#include "core/display.h"
#include "core/image.h"
#include "reference/reference.h"
#include "scene/scene.h"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace {

struct Centroid {
    double dx = 0, dy = 0;  // pixels from the image centre, y down
    int pixels = 0;
};

Centroid find(const rgtest::Png& png, int channel) {
    Centroid c;
    double sx = 0, sy = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            const uint8_t* p = png.at(x, y);
            bool pure = p[channel] > 180 && p[(channel + 1) % 3] < 60 && p[(channel + 2) % 3] < 60;
            if (!pure) continue;
            sx += x + 0.5, sy += y + 0.5;
            ++c.pixels;
        }
    if (c.pixels) c.dx = sx / c.pixels - png.width / 2.0, c.dy = sy / c.pixels - png.height / 2.0;
    return c;
}

TEST(Chapter10, BallLensInvertsAndMagnifiesAsPredicted) {
    const std::string scenePath = RG_SOURCE_DIR "/tests/optics/ball_lens.json";
    std::ifstream file(scenePath);
    nlohmann::json scene = nlohmann::json::parse(file);
    const int size = 1000;
    std::string dir = rgtest::outputDir("10_ball_lens");
    rgtest::RunResult r = rgtest::run(RG_EXE_10, {"--headless", "--validation", "--scene", scenePath, "--width",
                                                  std::to_string(size), "--height", std::to_string(size), "--frames",
                                                  "1", "--output", dir + "/lens.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;

    // The paraxial prediction from the scene's own numbers.
    double n = scene["materials"]["glass"]["ior"], R = scene["objects"][0]["radius"];
    double D = scene["camera"]["position"][2], fov = scene["camera"]["fov_y_deg"];
    double L = -scene["objects"][2]["center"][2].get<double>();  // the markers' distance behind the centre
    double y = scene["objects"][2]["center"][1];                 // the red marker's height
    double f = n * R / (2 * (n - 1));                            // the ball lens's focal length, from the centre
    // A camera ray through height h at the centre plane leaves the lens at
    // angle h/D - h/f and reaches the marker plane at h (1 + L/D - L/f) = y.
    double alpha = y / (D * (1 + L / D - L / f));                // the camera ray's angle
    double predicted = std::tan(alpha) / std::tan(fov / 2 * 3.14159265358979323846 / 180) * size / 2;
    ASSERT_LT(predicted, 0) << "a real, inverted image";

    rgtest::Png png = rgtest::readPng(dir + "/lens.png");
    Centroid red = find(png, 0), green = find(png, 1), blue = find(png, 2);
    ASSERT_GT(red.pixels, 20);
    ASSERT_GT(green.pixels, 20);
    ASSERT_GT(blue.pixels, 20);
    // Above the axis in the world -> below the centre in the image (y down): up/down inverted.
    EXPECT_GT(red.dy, 0);
    EXPECT_LT(blue.dy, 0);
    // Right of the axis in the world -> left in the image: left/right inverted.
    EXPECT_LT(green.dx, 0);
    // Distances from the centre: within 3 % of the paraxial prediction.
    double tolerance = 0.03 * std::abs(predicted);
    EXPECT_NEAR(red.dy, -predicted, tolerance);
    EXPECT_NEAR(blue.dy, predicted, tolerance);
    EXPECT_NEAR(green.dx, predicted, tolerance);
    EXPECT_NEAR(red.dx, 0, 0.5);
    EXPECT_NEAR(green.dy, 0, 0.5);
}

// Tessellated spheres (--sphere-mesh) converge to the analytic one: the
// error against the analytic reference falls with the subdivision level.
TEST(Chapter10, TessellatedSpheresConvergeToTheAnalyticOne) {
    double previous = 1e9;
    for (int level : {1, 3, 5}) {
        std::string dir = rgtest::outputDir("10_mesh_" + std::to_string(level));
        rgtest::RunResult r = rgtest::run(RG_EXE_10, {"--headless", "--validation", "--reference", "--sphere-mesh",
                                                      std::to_string(level), "--scene",
                                                      RG_SOURCE_DIR "/assets/scenes/glass_sphere.json", "--width", "96",
                                                      "--height", "72", "--frames", "1", "--output", dir + "/m.png"});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        nlohmann::json report = rgtest::readJson(dir + "/m.json");
        double rmse = report["error"].value("rmse", 0.0);
        EXPECT_LT(rmse, previous) << "level " << level;
        EXPECT_GT(rmse, 1e-5) << "a mesh is not the sphere";
        EXPECT_EQ(report.value("validation_messages", 1), 0);
        // a sphere drawn as a mesh shades with its interpolated normals (kMeshes)
        EXPECT_TRUE(report.value("shading_normals", false));
        previous = rmse;
    }
    rgtest::RunResult bad = rgtest::run(RG_EXE_10, {"--headless", "--sphere-mesh", "8"});
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
}

// The full ray tree through the grouped layout (chapter 03): glass, mirrors
// and shadows against the CPU reference, on the default scene and on 1,000
// spheres.
TEST(Chapter10, GroupedLayoutMatchesTheReference) {
    rgtest::expectMatchesReference(RG_EXE_10, "", "10_grouped_default", {"--layout", "grouped"});
    nlohmann::json report = rgtest::expectMatchesReference(
        RG_EXE_10, RG_SOURCE_DIR "/tests/scenes/spheres_1000.json", "10_grouped_1000", {"--layout", "grouped"});
    EXPECT_EQ(report["acceleration"]["layout"], "grouped");
}

// Two launches (the trees past the first hit queued for a second launch)
// against one: the same image and the same rays, each against the CPU
// reference with validation on; on mirrors.json more pixels have a tree
// than the queue holds, so the rest are traced in the first launch; auto
// picks two launches exactly when few pixels had a tree.
TEST(Chapter10, TwoLaunchesMatchOneLaunch) {
    const std::vector<std::pair<std::string, std::string>> scenes = {
        {"default", ""},
        {"mirrors", RG_SOURCE_DIR "/assets/scenes/mirrors.json"},
        {"spheres_1000", RG_SOURCE_DIR "/tests/scenes/spheres_1000.json"},
        {"glass_grazing", RG_SOURCE_DIR "/tests/scenes/glass_grazing.json"},
    };
    for (const auto& [name, scene] : scenes) {
        SCOPED_TRACE(name);
        nlohmann::json one = rgtest::expectMatchesReference(RG_EXE_10, scene, "10_one_" + name, {"--launches", "one"});
        nlohmann::json two = rgtest::expectMatchesReference(RG_EXE_10, scene, "10_two_" + name, {"--launches", "two"});
        std::string dir = rgtest::outputDir("10_auto_" + name);  // 4 frames: from the third on, auto has a count
        std::vector<std::string> args = {"--headless", "--validation", "--width", "160", "--height", "90",
                                         "--frames", "4", "--launches", "auto", "--output", dir + "/out.png"};
        if (!scene.empty()) args.insert(args.end(), {"--scene", scene});
        EXPECT_EQ(rgtest::run(RG_EXE_10, args).exitCode, 0);
        nlohmann::json autoChoice = rgtest::readJson(dir + "/out.json");
        rgtest::expectCleanReport(autoChoice, "10_refraction", 160, 90);
        EXPECT_EQ(one["launches"], 1);
        EXPECT_EQ(two["launches"], 2);
        // no meshes: the hits' shading normal is compiled out (kMeshes)
        EXPECT_FALSE(one.value("shading_normals", true));
        EXPECT_EQ(one["rays_per_frame"], two["rays_per_frame"]);
        const nlohmann::json& trees = one["trees_past_first_hit"];
        uint32_t count = trees["trees"], pixels = trees["pixels"], capacity = trees["queue_capacity"];
        EXPECT_GT(count, 0u);
        EXPECT_EQ(two["trees_past_first_hit"]["trees"], std::min(count, capacity));  // the queue stops at its capacity
        if (name == "mirrors") {
            EXPECT_GT(count, capacity) << "the queue should overflow here";
        }
        EXPECT_EQ(autoChoice["launches"], count < 0.06 * pixels ? 2 : 1);  // two_launches.h: kTwoLaunchesBelow

        rgtest::Png a = rgtest::readPng(RG_TEST_OUTPUT_DIR "/10_one_" + name + "/out.png");
        rgtest::Png b = rgtest::readPng(RG_TEST_OUTPUT_DIR "/10_two_" + name + "/out.png");
        ASSERT_EQ(a.rgb.size(), b.rgb.size());
        int worst = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, std::abs(int(a.rgb[i]) - int(b.rgb[i])));
        EXPECT_LE(worst, 1) << "one and two launches trace the same rays in the same order";
    }
}

// Glass plates: spheres squashed by their transforms to 1e-5 of their width
// (tests/optics/thin_plates_1e-5.json; 1e-3 is a hard case of every
// chapter). Their hits' error bounds follow each axis through the transform
// and the intersection shader refines a hit seen from far in the sphere's
// own units (docs/06_diffuse.md), so a plate refracts like a pane: the GPU matches the
// reference in double. Except at a rim: there the plate is thinner than
// float can tell apart at its distance from the eye (at 5 units a refracted
// ray's offset is 16 * 2^-24 * 5, about 5e-6, hit_error.glsl: as thick as the
// plate a fraction of a pixel from its edge). Which pixels those are is
// geometry, found here in double: those whose 3x3 neighbours' rays do not
// all hit, or all miss, a plate.
TEST(Chapter10, ThinPlatesMatchTheReferenceAwayFromTheirRims) {
    const std::string scenePath = RG_SOURCE_DIR "/tests/optics/thin_plates_1e-5.json";
    const uint32_t width = 320, height = 180;
    rg::Scene scene = rg::toCameraSpace(rg::loadScene(scenePath));
    rg::ReferenceRenderer camera(scene);
    auto hitsPlate = [&](int x, int y) {
        glm::dvec3 o, d;
        camera.cameraRay(uint32_t(x), uint32_t(y), width, height, o, d);
        for (const rg::Object& obj : scene.objects) {
            if (obj.type != rg::ShapeType::Sphere) continue;
            if (rg::smallestStretch(obj.transform) > 1e-3 * rg::largestStretch(obj.transform)) continue;
            glm::dmat4 inv = glm::inverse(obj.transform);
            glm::dvec3 oo(inv * glm::dvec4(o, 1.0)), dd(inv * glm::dvec4(d, 0.0));
            double t0, t1;
            if (rg::referenceUnitSphere(oo, dd, t0, t1) && t1 > 0) return true;
        }
        return false;
    };
    std::vector<char> plate(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) plate[size_t(y) * width + x] = hitsPlate(int(x), int(y));
    auto rim = [&](uint32_t x, uint32_t y) {
        char first = plate[size_t(y) * width + x];
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int nx = int(x) + dx, ny = int(y) + dy;
                if (nx < 0 || ny < 0 || nx >= int(width) || ny >= int(height)) continue;
                if (plate[size_t(ny) * width + nx] != first) return true;
            }
        return false;
    };
    for (const char* exe : {RG_EXE_10, RG_EXE_13}) {
        std::string name = std::filesystem::path(exe).filename().string();
        std::string dir = rgtest::outputDir("10_thin_plates_" + name);
        rgtest::RunResult r = rgtest::run(exe, {"--headless", "--validation", "--reference", "--scene", scenePath,
                                                "--width", std::to_string(width), "--height",
                                                std::to_string(height), "--frames", "1", "--output", dir + "/out.png"});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        rg::FloatImage gpu = rg::readPfm(dir + "/out.pfm"), reference = rg::readPfm(dir + "/out_reference.pfm");
        ASSERT_EQ(gpu.width, width);
        ASSERT_EQ(reference.rgba.size(), gpu.rgba.size());
        size_t inside = 0, compared = 0, off = 0, rimOff = 0;
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) {
                size_t i = size_t(y) * width + x;
                int worst = 0;
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(int(rg::toDisplay8(gpu.rgba[4 * i + c])) -
                                                     int(rg::toDisplay8(reference.rgba[4 * i + c]))));
                if (rim(x, y)) {
                    rimOff += worst > 1;
                    continue;
                }
                ++compared;
                inside += plate[i];
                off += worst > 1;
            }
        std::printf("%s: %zu plate pixels, %zu of %zu off away from the rims, %zu off on them\n", name.c_str(), inside, off, compared, rimOff);
        EXPECT_GT(inside, 3000u) << "the plates should cover part of the picture";
        EXPECT_LE(double(off) / compared, 0.001) << name << ": " << off << " of " << compared
                                                 << " pixels off by more than 1/255 away from the rims ("
                                                 << rimOff << " on them)";
    }
}

}  // namespace

namespace {

// Page 10's "what you should see": glass_sphere.json's sphere shows "the
// sky behind it upside down and mirrored inside it". The sky's landmarks
// are the sun above, red on the right and blue on the left; inside the
// sphere's disc (projected from the scene's camera) the sun lies below the
// centre, red left of it and blue right of it.
TEST(Chapter10, TheGlassSphereShowsTheSkyUpsideDownAndMirrored) {
    std::string dir = rgtest::outputDir("10_sky_inverted");
    const int width = 320, height = 180;
    rgtest::RunResult r = rgtest::run(
        RG_EXE_10, {"--headless", "--validation", "--scene", RG_SOURCE_DIR "/assets/scenes/glass_sphere.json",
                    "--width", std::to_string(width), "--height", std::to_string(height), "--frames", "1",
                    "--output", dir + "/sphere.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    rgtest::Png png = rgtest::readPng(dir + "/sphere.png");
    // the unit sphere 4.2 in front of the eye, on the view axis, fov 40 degrees
    const double pi = 3.14159265358979323846;
    const double radius = std::tan(std::asin(1 / 4.2)) / std::tan(20 * pi / 180) * height / 2;
    double redX = 0, blueX = 0, sunY = 0;
    int reds = 0, blues = 0, suns = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double dx = x + 0.5 - width / 2.0, dy = y + 0.5 - height / 2.0;
            double d = std::hypot(dx, dy) / radius;
            const uint8_t* p = png.at(x, y);
            if (d < 0.85) {
                // a landmark's colour: one channel well above the other two
                if (p[0] > p[1] + 60 && p[0] > p[2] + 60) redX += dx, ++reds;
                if (p[2] > p[0] + 60 && p[2] > p[1] + 30) blueX += dx, ++blues;
                if (p[0] > 200 && p[1] > 170 && p[0] > p[2] + 60) sunY += dy, ++suns;  // yellow
            }
        }
    std::printf("inside the sphere: %d red pixels at mean x %+.1f, %d blue at %+.1f, %d of the sun at mean y %+.1f\n",
                reds, reds ? redX / reds : 0.0, blues, blues ? blueX / blues : 0.0, suns, suns ? sunY / suns : 0.0);
    ASSERT_GT(reds, 5);
    ASSERT_GT(blues, 5);
    ASSERT_GT(suns, 5);
    EXPECT_LT(redX / reds, 0) << "the red landmark (right in the sky) appears left, through the sphere";
    EXPECT_GT(blueX / blues, 0) << "the blue landmark (left in the sky) appears right";
    EXPECT_GT(sunY / suns, 0) << "the sun (up in the sky) appears below the centre (y down)";
}

}  // namespace
