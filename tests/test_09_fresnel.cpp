// Chapter 09: every Fresnel mode matches the reference; the chapter prints
// Schlick's error table; a bad mode is rejected; a glint on glass carries
// the Fresnel share of the light (chapters 09-12); the sphere reflects more
// toward its rim (page 09).
#include "harness.h"
#include "fresnel_equations.h"

#include <cmath>
#include <fstream>
#include <glm/glm.hpp>

#include "core/image.h"

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

// A highlight is the light's own reflection, so on clear glass it carries
// the share F that glass reflects: against the same highlight on an opaque
// surface (which keeps all of it), the ratio is F at the glint's angle, by
// the Fresnel equations. The light is put where a unit sphere's point at
// angle phi from the view axis mirrors it into the eye, once near normal
// incidence and once at about 70 degrees. The brightest pixel must lie
// where that point projects. (The old rule gave the glint 1 - F in chapter
// 09 and nothing from chapter 10 on.)
TEST(Chapter09, AGlintOnGlassIsTheFresnelShareOfTheLight) {
    const glm::dvec3 eye(0, 0, 6);
    const int width = 240, height = 240;
    const double fov = 30, ior = 1.5, pi = 3.14159265358979323846;
    std::string dir = rgtest::outputDir("09_glint");
    for (double phi : {5.0, 60.0}) {
        glm::dvec3 p(std::sin(phi * pi / 180), 0, std::cos(phi * pi / 180));  // on the sphere: p = n
        glm::dvec3 v = glm::normalize(eye - p), light = p + 6.0 * (2 * glm::dot(p, v) * p - v);
        auto sceneFile = [&](const std::string& name, double transmission) {
            nlohmann::json scene = {
                {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", fov}}},
                {"sky", {{"top", 0}, {"horizon", 0}, {"bottom", 0}}},
                {"ambient", 0},
                {"lights", {{{"position", {light.x, light.y, light.z}}, {"intensity", 1}}}},
                {"materials", {{"m", {{"ka", 0}, {"kd", 0}, {"ks", 1}, {"shininess", 4000},
                                      {"transmission", transmission}, {"ior", ior}}}}},
                {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
            std::string path = dir + "/" + name + "_scene.json";
            std::ofstream(path) << scene.dump(2);
            return path;
        };
        std::string glass = sceneFile("glass", 1), opaque = sceneFile("opaque", 0);
        // Where p projects: the camera looks down -z, y up; pixel rows go down.
        double tanHalf = std::tan(fov / 2 * pi / 180);
        double px = (p.x / (eye.z - p.z) / tanHalf + 1) / 2 * width, py = (1 - p.y / (eye.z - p.z) / tanHalf) / 2 * height;
        for (const char* exe : {RG_EXE_09, RG_EXE_10, RG_EXE_11, RG_EXE_12}) {
            SCOPED_TRACE(std::string(exe) + " phi " + std::to_string(phi));
            auto render = [&](const std::string& scene, const std::string& name) {
                std::string out = dir + "/" + name + ".pfm";
                rgtest::RunResult r = rgtest::run(exe, {"--headless", "--validation", "--scene", scene, "--fresnel",
                                                        "exact", "--depth", "0", "--width", std::to_string(width),
                                                        "--height", std::to_string(height), "--frames", "1",
                                                        "--output", out});
                EXPECT_EQ(r.exitCode, 0) << r.output;
                return rg::readPfm(out);
            };
            rg::FloatImage g = render(glass, "glass"), o = render(opaque, "opaque");
            ASSERT_EQ(o.rgba.size(), size_t(width) * height * 4);
            ASSERT_EQ(g.rgba.size(), o.rgba.size());
            size_t best = 0;
            for (size_t i = 0; i < o.rgba.size(); i += 4)
                if (o.rgba[i] > o.rgba[best]) best = i;
            int x = int(best / 4 % width), y = int(best / 4 / width);
            EXPECT_NEAR(x + 0.5, px, 1.5);
            EXPECT_NEAR(y + 0.5, py, 1.5);
            ASSERT_GT(o.rgba[best], 0.5) << "the glint's peak";
            // The cosine of incidence at that pixel's own point of the sphere.
            glm::dvec3 d = glm::normalize(glm::dvec3(((x + 0.5) / width * 2 - 1) * tanHalf,
                                                     (1 - (y + 0.5) / height * 2) * tanHalf, -1));
            double b = glm::dot(eye, d), t = -b - std::sqrt(b * b - glm::dot(eye, eye) + 1);
            double cosI = -glm::dot(glm::normalize(eye + t * d), d);
            double F = rgtest::fresnelEquations(cosI, 1.0, ior);
            EXPECT_NEAR(g.rgba[best] / o.rgba[best], F, 0.01 * F) << "F " << F << " at cos " << cosI;
        }
    }
}

}  // namespace

namespace {

// Page 09's "what you should see": the glass sphere of glass_sphere.json
// "reflects faintly at its centre and strongly toward its rim". What it
// reflects is the picture with the reflected rays (--depth 1) less the
// picture without them (--depth 0); its mean over a ring near the sphere's
// outline must be at least twice its mean over the central disc, where
// F is 4 %.
TEST(Chapter09, TheSphereReflectsFaintlyAtItsCentreAndStronglyTowardItsRim) {
    std::string dir = rgtest::outputDir("09_rim");
    const int width = 320, height = 180;
    auto render = [&](const char* depth) {
        std::string png = dir + "/depth" + depth + ".png";
        rgtest::RunResult r = rgtest::run(
            RG_EXE_09, {"--headless", "--validation", "--scene", RG_SOURCE_DIR "/assets/scenes/glass_sphere.json",
                        "--fresnel", "exact", "--depth", depth, "--width", std::to_string(width), "--height",
                        std::to_string(height), "--frames", "1", "--output", png});
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return rg::readPfm(dir + "/depth" + depth + ".pfm");
    };
    rg::FloatImage with = render("1"), without = render("0");
    // the unit sphere 4.2 in front of the eye, on the view axis, fov 40 degrees
    const double pi = 3.14159265358979323846;
    const double radius = std::tan(std::asin(1 / 4.2)) / std::tan(20 * pi / 180) * height / 2;
    double centre = 0, ring = 0;
    int inCentre = 0, inRing = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double r = std::hypot(x + 0.5 - width / 2.0, y + 0.5 - height / 2.0) / radius;
            size_t i = (size_t(y) * width + x) * 4;
            double reflected = 0;
            for (int c = 0; c < 3; ++c) reflected += (with.rgba[i + c] - without.rgba[i + c]) / 3;
            if (r < 0.3) centre += reflected, ++inCentre;
            if (r > 0.85 && r < 0.97) ring += reflected, ++inRing;
        }
    centre /= inCentre, ring /= inRing;
    std::printf("reflected light: centre %.4f, near the rim %.4f (%.1f times)\n", centre, ring, ring / centre);
    EXPECT_GT(centre, 0.0);
    EXPECT_GT(ring, 2 * centre) << "the rim reflects more than the centre";
}

}  // namespace
