// Metamorphic tests of the numerics (chapter 06's offsets, the sphere
// intersection, shadow rays, the specular power): pairs of scenes that
// physics says must look the same, rendered by the chapters and compared
// pixel by pixel. The CPU reference cannot judge these, because it follows
// the same rules; here the judge is geometry:
//   - an object that no ray meets changes no pixel;
//   - a sphere far larger than the view looks like a plane where the two
//     differ by less than a pixel;
//   - a thin and a thick flat glass plate show the same view (parallel
//     faces only shift the rays sideways, here by far less than a pixel);
//   - a light inside a closed opaque object lights nothing outside it;
//   - a scene and the same scene scaled by 1e-3 or 1e3 look the same;
//   - and without the care the rule compiles in, the hard cases fail.
// Each holds when at most 0.1 % of the pixels differ by more than 1/255.
#include "harness.h"

#include <cmath>
#include <glm/glm.hpp>
#include <fstream>
#include <functional>

namespace {
using nlohmann::json;

constexpr int kWidth = 200, kHeight = 112;

// The tutorial's scene without the parts that are not exact in every
// chapter: no moving object, no rough material.
json baseScene() {
    std::ifstream file(RG_SOURCE_DIR "/assets/scenes/default.json");
    json s = json::parse(file);
    for (json& o : s["objects"]) o.erase("moving");
    for (auto& [name, m] : s["materials"].items()) m.erase("roughness");
    return s;
}

json sphere(double x, double y, double z, double r, const std::string& material) {
    return {{"type", "sphere"}, {"center", {x, y, z}}, {"radius", r}, {"material", material}};
}

rgtest::Png render(const std::string& exe, const json& scene, const std::string& name,
                   const std::vector<std::string>& extraArgs = {}) {
    std::string dir = rgtest::outputDir("meta_" + name);
    std::ofstream(dir + "/scene.json") << scene.dump(1);
    std::vector<std::string> args = {"--headless", "--validation", "--frames", "1", "--width",
                                     std::to_string(kWidth), "--height", std::to_string(kHeight),
                                     "--scene", dir + "/scene.json", "--output", dir + "/out.png"};
    args.insert(args.end(), extraArgs.begin(), extraArgs.end());
    rgtest::RunResult r = rgtest::run(exe, args);
    EXPECT_EQ(r.exitCode, 0) << name << ": " << r.output;
    return rgtest::readPng(dir + "/out.png");
}

// The share of pixels whose display value differs by more than 1/255 in any channel.
double differing(const rgtest::Png& a, const rgtest::Png& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.empty()) return 1.0;
    size_t count = 0;
    for (size_t i = 0; i < a.rgb.size(); i += 3)
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(a.rgb[i + c]) - int(b.rgb[i + c])) > 1) {
                ++count;
                break;
            }
    return double(count) / (a.width * a.height);
}

const std::vector<std::pair<std::string, std::string>> kChapters = {
    {"06", RG_EXE_06}, {"08", RG_EXE_08}, {"10", RG_EXE_10}};

void expectSame(const json& a, const json& b, const std::string& name,
                const std::vector<std::pair<std::string, std::string>>& chapters = kChapters) {
    for (const auto& [nn, exe] : chapters) {
        double share = differing(render(exe, a, name + "_" + nn + "_a"), render(exe, b, name + "_" + nn + "_b"));
        EXPECT_LE(share, 0.001) << name << ", chapter " << nn << ": " << 100 * share << " % of pixels differ";
    }
}

// Every length in the scene times k (camera, lights, objects): the same picture.
json scaled(json s, double k) {
    auto scale3 = [k](json& v) {
        for (json& x : v) x = x.get<double>() * k;
    };
    scale3(s["camera"]["position"]);
    scale3(s["camera"]["look_at"]);
    for (json& l : s["lights"]) scale3(l["position"]);
    for (json& o : s["objects"]) {
        scale3(o["center"]);
        if (o.contains("radius")) o["radius"] = o["radius"].get<double>() * k;
        if (o.contains("u")) scale3(o["u"]);
        if (o.contains("v")) scale3(o["v"]);
    }
    return s;
}

TEST(Metamorphic, AnObjectNoRayMeetsChangesNothing) {
    json base = baseScene();
    // Two large spheres far below the floor, and a radius-10 sphere below a
    // millimetre-sized copy of the scene. That no
    // ray meets them is checked first: the CPU reference, whose rays start
    // within 1e-15 of exact, draws the same picture with and without them.
    struct Case {
        std::string name;
        json scene, extra;
    };
    std::vector<Case> cases = {
        {"huge", base, sphere(0, -500, 0, 400, "red")},
        {"below", base, sphere(0, -2000, 0, 100, "blue")},
        {"millimetre", scaled(base, 1e-3), sphere(0, -100, 0, 10, "red")},
    };
    for (Case& c : cases) {
        json with = c.scene;
        with["objects"].push_back(c.extra);
        std::string name = "unmet_" + c.name;
        for (const auto& [nn, exe] : kChapters) {
            std::string a = rgtest::outputDir("meta_" + name + "_ref_" + nn + "_a"),
                        b = rgtest::outputDir("meta_" + name + "_ref_" + nn + "_b");
            std::ofstream(a + "/scene.json") << c.scene.dump(1);
            std::ofstream(b + "/scene.json") << with.dump(1);
            for (const std::string& dir : {a, b})
                rgtest::run(exe, {"--headless", "--frames", "1", "--width", std::to_string(kWidth), "--height",
                                  std::to_string(kHeight), "--scene", dir + "/scene.json", "--reference", "--output",
                                  dir + "/out.png"});
            ASSERT_EQ(differing(rgtest::readPng(a + "/out_reference.png"), rgtest::readPng(b + "/out_reference.png")),
                      0.0)
                << name << ": the reference sees the extra object in chapter " << nn;
        }
        expectSame(c.scene, with, name);
    }
}

TEST(Metamorphic, AHugeSphereLooksLikeAPlane) {
    // The floor as a quad and as the top of a sphere of radius R (the
    // classic "big sphere as the floor"), seen from above: within the view
    // the sphere is at most 6 units from its top, so it departs from the
    // plane by under 6^2 / 2R, less than a thousandth of a pixel. Direct
    // light and shadows only (chapters 06, 07): a mirror's rim reflects the
    // floor far away, where a sphere and a plane really differ
    // (tests/scenes/ground_sphere_1e5.json checks those chapters against
    // the reference instead).
    json plane = baseScene();
    plane["camera"] = {{"position", {0, 3.5, 4.5}}, {"look_at", {0, 0.3, 0}}, {"up", {0, 1, 0}}, {"fov_y_deg", 45}};
    plane["objects"][0]["u"] = {40, 0, 0};
    plane["objects"][0]["v"] = {0, 0, -40};
    for (double radius : {1e4, 1e5, 1e6}) {
        json ball = plane;
        ball["objects"][0] = sphere(0, -radius, 0, radius, "floor");
        expectSame(plane, ball, "ground_" + std::to_string(int(std::log10(radius))),
                   {{"06", RG_EXE_06}, {"07", RG_EXE_07}});
    }
}

// The other side of the rule (rt_scene.h's needsCarefulNumerics): where it
// compiles in the shaders' care for extreme numbers, that care is what makes
// the pictures right. Forced off (--numerics fast) the floor sphere no
// longer looks like the plane, and the sky dome of radius 1e20 and the
// shininess of 1e6 leave their reference (which here computes in double,
// not by the rule under test).
TEST(Metamorphic, WithoutTheCareTheHardCasesFail) {
    json plane = baseScene();
    plane["camera"] = {{"position", {0, 3.5, 4.5}}, {"look_at", {0, 0.3, 0}}, {"up", {0, 1, 0}}, {"fov_y_deg", 45}};
    plane["objects"][0]["u"] = {40, 0, 0};
    plane["objects"][0]["v"] = {0, 0, -40};
    json ball = plane;
    ball["objects"][0] = sphere(0, -1e5, 0, 1e5, "floor");
    double share = differing(render(RG_EXE_06, plane, "fast_plane"),
                             render(RG_EXE_06, ball, "fast_ground_5", {"--numerics", "fast"}));
    EXPECT_GT(share, 0.01) << 100 * share << " % of pixels differ";
    struct Case {
        std::string exe, scene, careful;
    };
    for (const Case& c : {Case{RG_EXE_06, "ground_sphere_1e5", "sizes"}, Case{RG_EXE_06, "sky_dome_1e20", "sizes"},
                          Case{RG_EXE_07, "shininess_1e6", "shininess"}}) {
        std::string dir = rgtest::outputDir("meta_fast_" + c.scene);
        for (std::string numerics : {"auto", "fast"}) {
            rgtest::RunResult r =
                rgtest::run(c.exe, {"--headless", "--validation", "--reference", "--frames", "1", "--width", "160",
                                    "--height", "90", "--scene", RG_SOURCE_DIR "/tests/scenes/" + c.scene + ".json",
                                    "--numerics", numerics, "--output", dir + "/" + numerics + ".png"});
            ASSERT_EQ(r.exitCode, 0) << r.output;
            json report = rgtest::readJson(dir + "/" + numerics + ".json");
            double off = report["error"].value("frac_over_1_255", 0.0);
            if (numerics == "auto") {  // the rule chose the care; the match itself is HardCases's
                EXPECT_EQ(report["numerics"].value(c.careful, ""), "careful") << c.scene;
            } else {
                EXPECT_EQ(report["numerics"].value(c.careful, ""), "fast") << c.scene;
                EXPECT_GT(off, 0.003) << c.scene << ": " << 100 * off << " % of pixels off";
            }
        }
    }
}

TEST(Metamorphic, ThinAndThickGlassPlatesShowTheSameView) {
    // A flat glass plate between the camera and the scene: two quads, the
    // upper facing up (u x v), the lower facing down, so that a ray going
    // down enters through the front of one and leaves through the back of
    // the other. The camera looks straight down through it with a narrow
    // view, so rays cross it within 10 degrees of the normal and come out
    // shifted sideways by under 6 % of its thickness: 6e-5 for 1e-3, a
    // third of a percent of a pixel here.
    auto withPlate = [](double thickness) {
        json s = baseScene();
        // Without the mirror and the glass sphere: their rims turn the
        // plate's sub-pixel shift into a visible one, as any curved mirror
        // or lens would.
        s["objects"].erase(3);
        s["objects"].erase(2);
        s["camera"] = {{"position", {0, 6, 0.3}}, {"look_at", {0, 0, 0.3}}, {"up", {0, 0, -1}}, {"fov_y_deg", 20}};
        double top = 4;
        s["objects"].push_back(
            {{"type", "quad"}, {"center", {0, top, 0.3}}, {"u", {3, 0, 0}}, {"v", {0, 0, -3}}, {"material", "glass"}});
        s["objects"].push_back({{"type", "quad"},
                                {"center", {0, top - thickness, 0.3}},
                                {"u", {3, 0, 0}},
                                {"v", {0, 0, 3}},  // u x v points down: its front faces the floor
                                {"material", "glass"}});
        return s;
    };
    json thick = withPlate(1e-3);
    for (double thin : {2e-5, 1e-4})
        expectSame(thick, withPlate(thin), "plate_" + std::to_string(int(-std::log10(thin) * 10)),
                   {{"10", RG_EXE_10}});
}

TEST(Metamorphic, ALightInsideAClosedObjectLightsNothingOutside) {
    // The first light enclosed by a small opaque sphere: the picture must be
    // the one without that light (the sphere itself is drawn in both).
    json base = baseScene();
    glm::dvec3 light(base["lights"][0]["position"][0], base["lights"][0]["position"][1],
                     base["lights"][0]["position"][2]);
    for (double radius : {1e-4, 1e-2, 0.3}) {
        json enclosed = base;
        enclosed["objects"].push_back(sphere(light.x, light.y, light.z, radius, "red"));
        json without = enclosed;
        without["lights"].erase(0);
        expectSame(enclosed, without, "enclosed_" + std::to_string(int(-std::log10(radius))),
                   {{"06", RG_EXE_06}, {"07", RG_EXE_07}});
    }
}

TEST(Metamorphic, AScaledSceneLooksTheSame) {
    json base = baseScene();
    for (double k : {1e-3, 1e3}) expectSame(base, scaled(base, k), "scaled_" + std::to_string(int(std::log10(k))));
}

}  // namespace
