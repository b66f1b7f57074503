// Chapter 04 against the CPU double-precision reference: at most 0.1% of the
// pixels may differ by more than 1/255 in display value; every pixel traced
// exactly one ray; no NaN; the sky's landmarks are where they belong. The
// same far from the world's origin (camera-relative rendering space), and
// with the eye exactly on a sphere (the rule for hits at the eye).
#include "harness.h"

#include "core/image.h"
#include "reference/reference.h"

#include <cmath>
#include <fstream>

namespace {

TEST(Chapter04, MatchesTheReference) {
    const int w = 240, h = 136;
    std::string dir = rgtest::outputDir("04");
    rgtest::RunResult r = rgtest::run(RG_EXE_04, {"--headless", "--validation", "--reference", "--width",
                                                  std::to_string(w), "--height", std::to_string(h), "--frames", "3",
                                                  "--output", dir + "/04.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/04.json");
    rgtest::expectCleanReport(report, "04_raygen_miss", w, h);
    ASSERT_TRUE(report.contains("error")) << report.dump();
    EXPECT_LE(report["error"].value("frac_over_1_255", 1.0), 0.001);
    EXPECT_LE(report["error"].value("rmse", 1.0), 1e-3);
    EXPECT_EQ(report["error"].value("non_finite_pixels", 1), 0);
    EXPECT_EQ(report.value("non_finite_values", 1), 0);
    EXPECT_EQ(report.value("rays_per_frame", 0), w * h);  // one camera ray per pixel, counted
    EXPECT_GT(report.value("mrays_per_s", 0.0), 0.0);

    // The reference and heat map are written beside the image.
    rgtest::Png reference = rgtest::readPng(dir + "/04_reference.png");
    EXPECT_EQ(reference.width, w);
    rgtest::Png heat = rgtest::readPng(dir + "/04_error.png");
    EXPECT_EQ(heat.width, w);

    // The default camera looks down -z: the sky's blue landmark (-x) is in
    // the top-left, the red one (+x) in the top-right.
    rgtest::Png png = rgtest::readPng(dir + "/04.png");
    const uint8_t* left = png.at(w / 40, h / 8);
    const uint8_t* right = png.at(w - 1 - w / 40, h / 8);
    EXPECT_GT(left[2], left[0] + 60) << "blue landmark on the left";
    EXPECT_GT(right[0], right[2] + 60) << "red landmark on the right";
    // The floor's normal is +y: (0.5, 1, 0.5) in the bottom rows.
    const uint8_t* floor = png.at(w / 2, h - 2);
    EXPECT_NEAR(floor[0], rgtest::display8(0.5), 2);
    EXPECT_NEAR(floor[1], rgtest::display8(1.0), 2);
}

// The default scene translated by (1e4, 0, -1e4) ... (1e6, 0, -1e6), and the
// eye on the mirror sphere's top: against the reference like any scene.
TEST(Chapter04, FarFromTheOriginAndEyeOnASurfaceMatchTheReference) {
    for (const char* scene : {"far_1e4", "far_1e5", "far_1e6", "eye_on_sphere", "spheres_1000", "transformed_spheres"})
        rgtest::expectMatchesReference(RG_EXE_04, RG_SOURCE_DIR "/tests/scenes/" + std::string(scene) + ".json",
                                       std::string("04_") + scene);
}

// Renders chapter 04 twice at 160x90, with each run's own extra arguments,
// and compares the two pictures.
rg::ImageError compareRuns(const std::string& name, const std::vector<std::string>& a,
                           const std::vector<std::string>& b) {
    std::string dir = rgtest::outputDir(name);
    for (const auto& [tag, extra] : {std::pair{"a", a}, std::pair{"b", b}}) {
        std::vector<std::string> args = {"--headless", "--validation", "--width", "160", "--height", "90",
                                         "--frames", "1", "--output", dir + "/" + tag + ".png"};
        args.insert(args.end(), extra.begin(), extra.end());
        rgtest::RunResult r = rgtest::run(RG_EXE_04, args);
        EXPECT_EQ(r.exitCode, 0) << r.output;
    }
    return rg::compareImages(rg::readPfm(dir + "/a.pfm"), rg::readPfm(dir + "/b.pfm"), nullptr);
}

// --antialias: 8 frames through new points of each pixel against the
// reference's mean over the same points; the default headless run is the
// pixel centre's, as --antialias off.
TEST(Chapter04, AntialiasedMatchesTheReferenceAndOffIsTheDefault) {
    nlohmann::json report = rgtest::expectMatchesReference(RG_EXE_04, "", "04_antialias",
                                                           {"--antialias", "on", "--frames", "8"});
    EXPECT_EQ(report["parameters"].value("antialias", ""), "on");
    rg::ImageError same = compareRuns("04_antialias_off", {}, {"--antialias", "off"});
    EXPECT_EQ(same.maxAbs, 0.0);
    rg::ImageError jittered = compareRuns("04_antialias_on", {}, {"--antialias", "on"});
    EXPECT_GT(jittered.fracOver1_255, 0.01);  // frame 0's points are not the centres
}

// Independently of the reference: moving the whole scene by 1e6 must not
// change the picture (it did, in 10 % of the pixels, in world-space floats).
TEST(Chapter04, TranslationDoesNotChangeThePicture) {
    rg::ImageError e = compareRuns("04_translation", {}, {"--scene", RG_SOURCE_DIR "/tests/scenes/far_1e6.json"});
    EXPECT_LE(e.fracOver1_255, 0.001);
    EXPECT_LT(e.rmse, 1e-4);
}

// The order of the TLAS's instances changes the tree, never the picture:
// 1,000 spheres in median-split order and in the file's random order.
TEST(Chapter04, InstanceOrderDoesNotChangeThePicture) {
    const std::string scene = RG_SOURCE_DIR "/tests/scenes/spheres_1000.json";
    rg::ImageError e = compareRuns("04_order", {"--scene", scene}, {"--scene", scene, "--file-order"});
    EXPECT_EQ(e.fracOver1_255, 0.0);
    EXPECT_LT(e.rmse, 1e-6);
}

// Chapter 03's two layouts, one instance per sphere and one BLAS of boxes
// for all static spheres (gl_PrimitiveID picks the sphere), trace the same
// spheres: the picture does not change, and the report names the layout
// (grouped is the default; --layout instances the other).
TEST(Chapter04, GroupedLayoutDoesNotChangeThePicture) {
    for (std::string scene : {std::string(), std::string(RG_SOURCE_DIR "/tests/scenes/spheres_1000.json")}) {
        std::vector<std::string> a = {"--layout", "instances"}, b = {"--layout", "grouped"};
        if (!scene.empty())
            for (auto* args : {&a, &b}) args->insert(args->end(), {"--scene", scene});
        std::string name = scene.empty() ? "04_layout_default" : "04_layout_1000";
        rg::ImageError e = compareRuns(name, a, b);
        EXPECT_LE(e.fracOver1_255, 0.001) << name;
        EXPECT_LT(e.rmse, 1e-4) << name;
        std::string dir = RG_TEST_OUTPUT_DIR "/" + name;  // compareRuns wrote there
        nlohmann::json instances = rgtest::readJson(dir + "/a.json"), grouped = rgtest::readJson(dir + "/b.json");
        EXPECT_EQ(instances["acceleration"]["layout"], "instances");
        EXPECT_EQ(grouped["acceleration"]["layout"], "grouped");
        EXPECT_LT(grouped["acceleration"]["tlas_instances"], instances["acceleration"]["tlas_instances"]) << name;
        EXPECT_EQ(grouped["rays_per_frame"], instances["rays_per_frame"]) << name;
    }
}

// Antialiasing against geometry, not the reference: a square tilted by 20
// degrees, facing the camera, on a black sky. Chapter 04 colours it by its
// normal (0, 0, 1), so a pixel's blue is the share of it the square covers:
// the exact area of the projected square clipped to the pixel. One ray
// through the centre gets 0 or 1 on every edge pixel; 64 frames of jittered
// rays must come close to the true coverage.
double polygonArea(const std::vector<glm::dvec2>& p) {
    double a = 0;
    for (size_t i = 0; i < p.size(); ++i) a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
    return 0.5 * std::abs(a);
}

// The convex polygon `p` clipped to the box [x0, x1] x [y0, y1] (Sutherland-Hodgman).
std::vector<glm::dvec2> clipToBox(std::vector<glm::dvec2> p, double x0, double y0, double x1, double y1) {
    auto clip = [&](auto inside, auto cross) {
        std::vector<glm::dvec2> out;
        for (size_t i = 0; i < p.size(); ++i) {
            glm::dvec2 a = p[i], b = p[(i + 1) % p.size()];
            if (inside(a)) out.push_back(a);
            if (inside(a) != inside(b)) out.push_back(cross(a, b));
        }
        p = out;
    };
    auto atX = [](double x) { return [x](glm::dvec2 a, glm::dvec2 b) { return a + (b - a) * ((x - a.x) / (b.x - a.x)); }; };
    auto atY = [](double y) { return [y](glm::dvec2 a, glm::dvec2 b) { return a + (b - a) * ((y - a.y) / (b.y - a.y)); }; };
    clip([&](glm::dvec2 a) { return a.x >= x0; }, atX(x0));
    clip([&](glm::dvec2 a) { return a.x <= x1; }, atX(x1));
    clip([&](glm::dvec2 a) { return a.y >= y0; }, atY(y0));
    clip([&](glm::dvec2 a) { return a.y <= y1; }, atY(y1));
    return p;
}

TEST(Chapter04, AntialiasedEdgesCoverWhatTheGeometrySays) {
    const int w = 160, h = 90;
    const double distance = 5, fovY = 45, angle = glm::radians(20.0), half = 1.2;
    std::string dir = rgtest::outputDir("04_antialias_coverage");
    glm::dvec2 u(std::cos(angle), std::sin(angle)), v(-std::sin(angle), std::cos(angle));
    nlohmann::json scene = {
        {"camera", {{"position", {0, 0, distance}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", fovY}}},
        {"sky", {{"top", {0, 0, 0}}, {"horizon", {0, 0, 0}}, {"bottom", {0, 0, 0}}}},
        {"materials", {{"m", nlohmann::json::object()}}},
        {"objects", {{{"type", "quad"}, {"material", "m"}, {"center", {0, 0, 0}},
                      {"u", {half * u.x, half * u.y, 0}}, {"v", {half * v.x, half * v.y, 0}}}}}};
    std::ofstream(dir + "/square.json") << scene.dump(1);
    // The square's corners in pixels: x right, y down, the image plane at 1.
    double tanHalf = std::tan(glm::radians(fovY) / 2), aspect = double(w) / h;
    std::vector<glm::dvec2> square;
    for (glm::dvec2 c : {half * (u + v), half * (v - u), -half * (u + v), half * (u - v)})
        square.push_back({(c.x / distance / (tanHalf * aspect) + 1) / 2 * w, (1 - c.y / distance / tanHalf) / 2 * h});
    std::vector<double> coverage(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) coverage[size_t(y) * w + x] = polygonArea(clipToBox(square, x, y, x + 1, y + 1));

    // RMSE of blue against the coverage over the edge pixels (0 < coverage < 1).
    auto edgeError = [&](const std::string& tag, const std::vector<std::string>& extra) {
        std::vector<std::string> args = {"--headless", "--validation", "--scene", dir + "/square.json", "--width",
                                         std::to_string(w), "--height", std::to_string(h), "--output",
                                         dir + "/" + tag + ".png"};
        args.insert(args.end(), extra.begin(), extra.end());
        rgtest::RunResult r = rgtest::run(RG_EXE_04, args);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(rgtest::readJson(dir + "/" + tag + ".json").value("validation_messages", 1), 0);
        rg::FloatImage image = rg::readPfm(dir + "/" + tag + ".pfm");
        double sumSq = 0;
        int edges = 0;
        for (size_t i = 0; i < coverage.size(); ++i) {
            double blue = image.rgba[4 * i + 2];
            if (coverage[i] <= 1e-9 || coverage[i] >= 1 - 1e-9) {
                EXPECT_NEAR(blue, coverage[i] > 0.5 ? 1.0 : 0.0, 1e-5) << tag << " pixel " << i;  // inside or out
                continue;
            }
            sumSq += (blue - coverage[i]) * (blue - coverage[i]);
            ++edges;
        }
        EXPECT_GT(edges, 2 * (w + h) / 4) << "the square's edges cross this many pixels";
        return std::sqrt(sumSq / std::max(1, edges));
    };
    double centre = edgeError("centre", {"--frames", "1"});
    double four = edgeError("aa4", {"--antialias", "on", "--frames", "4"});
    double many = edgeError("aa64", {"--antialias", "on", "--frames", "64"});
    std::printf("edge RMSE against the true coverage: centre %.4f, 4 frames %.4f, 64 frames %.4f\n", centre, four, many);
    EXPECT_GT(centre, 0.2);  // about 1/sqrt(12): a step where the coverage is a ramp
    EXPECT_LT(four, 0.6 * centre);
    EXPECT_LT(many, 0.1 * centre);
    EXPECT_LT(many, 0.3 * four);
}

TEST(Chapter04Windowed, TracesAndPresentsUnderXvfb) {
    rgtest::expectCleanWindowedRun(RG_EXE_04, "04_window", 20);
}

}  // namespace
