// What pages 05-08 say their pictures show ("What you should see"), read off
// the pictures of the default scene (assets/scenes/default.json) at 320x180.
// Positions come from the scene: each sphere's centre and radius, the
// lights, projected through the scene's camera. Each check compares two
// chapters' pictures, so that it reads what the page's chapter adds.
#include "harness.h"

#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 320, kHeight = 180;

struct Picture {
    rg::FloatImage image;
    glm::dvec3 at(int x, int y) const {
        const float* p = &image.rgba[(size_t(y) * image.width + x) * 4];
        return {p[0], p[1], p[2]};
    }
    double luminance(int x, int y) const {
        glm::dvec3 c = at(x, y);
        return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
};

// The chapter's picture of its default scene, or of `scene` where given.
Picture render(const char* exe, const std::string& name, const nlohmann::json& scene = nullptr) {
    std::string dir = rgtest::outputDir("page_pictures_" + name), stem = dir + "/" + name;
    std::vector<std::string> args = {"--headless", "--validation", "--width", std::to_string(kWidth),
                                     "--height", std::to_string(kHeight), "--output", stem + ".png"};
    if (!scene.is_null()) {
        std::ofstream(dir + "/scene.json") << scene.dump();
        args.insert(args.end(), {"--scene", dir + "/scene.json"});
    }
    rgtest::RunResult r = rgtest::run(exe, args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return {rg::readPfm(stem + ".pfm")};
}

// The default scene, its camera, and where its spheres land in the picture.
struct Scene {
    nlohmann::json json = rgtest::readJson(RG_SOURCE_DIR "/assets/scenes/default.json");
    rgtest::SceneCamera camera{json, kWidth, kHeight};
    struct Disc {
        glm::dvec3 centre;
        double radius;
        glm::dvec2 pixel;  // the centre's projection
        double pixels;     // the radius, in pixels
    };
    Disc sphere(const std::string& material) const {
        for (const nlohmann::json& o : json["objects"])
            if (o["type"] == "sphere" && o["material"] == material) {
                Disc d{rgtest::vec3(o["center"]), double(o["radius"]), {}, 0};
                d.pixel = camera.project(d.centre);
                d.pixels = camera.pixelsAcross(d.centre, d.radius);
                return d;
            }
        ADD_FAILURE() << "no sphere of " << material;
        return {};
    }
    // the pixels within `fraction` of a disc's radius
    template <class F> void inside(const Disc& d, double fraction, F f) const {
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                if (std::hypot(x + 0.5 - d.pixel.x, y + 0.5 - d.pixel.y) < fraction * d.pixels) f(x, y);
    }
};

// Page 05: "flat, dim silhouettes in each material's colour, no shading at
// all, the sky unchanged" (from chapter 04's).
TEST(PagePictures, Page05FlatDimSilhouettesAndTheSkyUnchanged) {
    Scene s;
    Picture ambient = render(RG_EXE_05, "05"), sky = render(RG_EXE_04, "04");
    Scene::Disc red = s.sphere("red");
    glm::dvec3 lo(1e9), hi(-1e9);
    s.inside(red, 0.8, [&](int x, int y) {
        lo = glm::min(lo, ambient.at(x, y));
        hi = glm::max(hi, ambient.at(x, y));
    });
    std::printf("page 05: the red sphere from (%.4f %.4f %.4f) to (%.4f %.4f %.4f)\n", lo.r, lo.g, lo.b, hi.r,
                hi.g, hi.b);
    EXPECT_LT(hi.r - lo.r, 1e-4) << "flat: no shading";
    EXPECT_GT(lo.r, 4 * hi.g) << "in its material's colour (red)";
    EXPECT_LT(hi.r, 0.25) << "dim";
    // the top rows are sky in both
    double most = 0;
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < kWidth; ++x)
            most = std::max(most, glm::length(ambient.at(x, y) - sky.at(x, y)));
    EXPECT_LT(most, 1e-5) << "the sky unchanged";
}

// Page 06: "spheres lit from two lights, darker away from them, with two
// shadows each on the floor". The red sphere's light leans toward the
// lights; where a sphere's shadow from one light is in view (the line from
// the light through the centre meets the floor in the picture, with no
// sphere in front), the floor there is darker than the same floor without
// the spheres.
TEST(PagePictures, Page06LitSidesAndShadows) {
    Scene s;
    Picture diffuse = render(RG_EXE_06, "06");
    nlohmann::json floorOnly = s.json;
    floorOnly["objects"] = nlohmann::json::array({s.json["objects"][0]});  // the floor (a quad)
    floorOnly["sky"]["image"] = (std::filesystem::path(RG_EXE_06).parent_path() / "assets" / "sky.png").string();
    Picture bare = render(RG_EXE_06, "06_floor", floorOnly);
    Scene::Disc red = s.sphere("red");
    glm::dvec2 lean(0);
    double total = 0;
    s.inside(red, 0.9, [&](int x, int y) {
        double l = diffuse.luminance(x, y);
        lean += l * (glm::dvec2(x + 0.5, y + 0.5) - red.pixel), total += l;
    });
    lean /= total;
    glm::dvec2 towardLight(0);
    for (const nlohmann::json& light : s.json["lights"]) {
        glm::dvec3 l = rgtest::vec3(light["position"]);
        double weight = double(light["intensity"][0]) / glm::dot(l - red.centre, l - red.centre);
        towardLight += weight * glm::normalize(s.camera.project(l) - red.pixel);
    }
    std::printf("page 06: the red sphere's light leans (%.1f, %.1f) px, the lights lie toward (%.2f, %.2f)\n",
                lean.x, lean.y, towardLight.x, towardLight.y);
    EXPECT_GT(glm::dot(lean, glm::normalize(towardLight)), 0.1 * red.pixels) << "darker away from the lights";
    int shadows = 0;
    for (const char* material : {"red", "mirror", "glass", "blue"}) {
        Scene::Disc d = s.sphere(material);
        for (const nlohmann::json& light : s.json["lights"]) {
            glm::dvec3 l = rgtest::vec3(light["position"]);
            glm::dvec3 floor = l + (d.centre - l) * (l.y / (l.y - d.centre.y));  // the shadow's centre
            glm::dvec2 p = s.camera.project(floor);
            bool inView = p.x >= 2 && p.y >= 2 && p.x < kWidth - 2 && p.y < kHeight - 2;
            for (const char* other : {"red", "mirror", "glass", "blue"}) {  // a sphere in front hides it
                Scene::Disc o = s.sphere(other);
                if (std::hypot(p.x - o.pixel.x, p.y - o.pixel.y) < o.pixels + 2) inView = false;
            }
            if (!inView) continue;
            double in = diffuse.luminance(int(p.x), int(p.y)), out = bare.luminance(int(p.x), int(p.y));
            std::printf("page 06: %s's shadow from the light at (%g, %g, %g): %.3f, the floor without spheres %.3f\n", material,
                        l.x, l.y, l.z, in, out);
            EXPECT_LT(in, 0.95 * out) << material << "'s shadow (no shadow: equal)";
            ++shadows;
        }
    }
    EXPECT_GE(shadows, 2) << "shadows in view (the others lie behind their spheres)";
}

// Page 07: "small bright highlights on the spheres, where the half vector
// meets the normal": chapter 07 against chapter 06 on the red sphere.
// Brighter at the point whose normal is the first (brighter) light's half
// vector, the same far from both lights' such points, the brighter patch
// small.
TEST(PagePictures, Page07HighlightWhereTheHalfVectorMeetsTheNormal) {
    Scene s;
    Picture specular = render(RG_EXE_07, "07"), diffuse = render(RG_EXE_06, "06_for_07");
    Scene::Disc red = s.sphere("red");
    glm::dvec3 eye = s.camera.eye;
    // each light's highlight: the point whose normal is its own half vector
    std::vector<glm::dvec2> highlights;
    for (const nlohmann::json& l : s.json["lights"]) {
        glm::dvec3 light = rgtest::vec3(l["position"]), n = glm::normalize(eye - red.centre);
        for (int i = 0; i < 20; ++i) {
            glm::dvec3 p = red.centre + red.radius * n;
            n = glm::normalize(glm::normalize(light - p) + glm::normalize(eye - p));
        }
        highlights.push_back(s.camera.project(red.centre + red.radius * n));
    }
    glm::dvec2 h = highlights[0];  // the brighter light's
    double added = specular.luminance(int(h.x), int(h.y)) - diffuse.luminance(int(h.x), int(h.y));
    int brighter = 0, all = 0;
    double farthest = 0;
    s.inside(red, 0.9, [&](int x, int y) {
        double d = specular.luminance(x, y) - diffuse.luminance(x, y);
        ++all;
        if (d > 0.05) ++brighter;
        bool far = true;
        for (glm::dvec2 k : highlights) far = far && std::hypot(x - k.x, y - k.y) > 0.8 * red.pixels;
        if (far) farthest = std::max(farthest, d);
    });
    std::printf("page 07: the highlight adds %.3f at (%.0f, %.0f); %d of %d pixels gain over 0.05; %.4f at most "
                "far from it\n", added, h.x, h.y, brighter, all, farthest);
    EXPECT_GT(added, 0.1) << "a bright highlight where the half vector meets the normal";
    EXPECT_LT(brighter, all / 5) << "a small one";
    EXPECT_LT(farthest, 0.01) << "nothing added far from it";
}

// Page 08: "the large sphere now a mirror that shows the floor, the other
// spheres and the sky": chapter 08 against chapter 07 inside the mirror
// sphere's disc. Its upper part shows the sky (bright, blue above red), its
// lower part the floor, and reds of the red sphere appear in it.
TEST(PagePictures, Page08TheMirrorShowsTheFloorTheSpheresAndTheSky) {
    Scene s;
    Picture mirror = render(RG_EXE_08, "08"), flat = render(RG_EXE_07, "07_for_08");
    Scene::Disc m = s.sphere("mirror");
    double skyNow = 0, skyBefore = 0, blueAboveRed = 0;
    int top = 0, reds = 0, redsBefore = 0;
    s.inside(m, 0.95, [&](int x, int y) {
        auto red = [](glm::dvec3 c) { return c.r > 0.08 && c.r > 3 * c.g && c.r > 3 * c.b; };
        reds += red(mirror.at(x, y)), redsBefore += red(flat.at(x, y));
        if (y + 0.5 < m.pixel.y - 0.6 * m.pixels) {  // the cap above
            skyNow += mirror.luminance(x, y), skyBefore += flat.luminance(x, y), ++top;
            blueAboveRed += mirror.at(x, y).b - mirror.at(x, y).r;
        }
    });
    std::printf("page 08: the mirror's cap %.3f (chapter 07: %.3f), blue - red %.3f; red pixels in it %d "
                "(chapter 07: %d)\n", skyNow / top, skyBefore / top, blueAboveRed / top, reds, redsBefore);
    ASSERT_GT(top, 10);
    EXPECT_GT(skyNow, 3 * skyBefore) << "the sky in its upper part";
    EXPECT_GT(blueAboveRed, 0) << "the sky's blue";
    EXPECT_GT(reds, 10) << "the red sphere in it";
    EXPECT_EQ(redsBefore, 0) << "chapter 07's grey sphere shows none";
}

}  // namespace
