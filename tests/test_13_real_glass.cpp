// Chapter 13, real glass, checked against optics (the CPU reference shares
// the media rule, so these tests use the laws themselves, written here in
// double): glass in the same glass is no surface; an air bubble in glass
// reflects totally past the critical angle; a slab transmits Fresnel at
// both faces times Beer-Lambert; with nothing nested chapter 13 is chapter
// 10; and the scene keys of media are checked. Dispersion: a prism and a
// lens measured at the Fraunhofer lines against SCHOTT's N-BK7 indices,
// white light through a slab stays white, and the prism scene against its
// reference after the same frames.
#include "harness.h"
#include "fresnel_equations.h"
#include "optics_image.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>

#include "core/display.h"
#include "core/image.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

using rgtest::fresnelEquations;

std::string writeScene(const std::string& dir, const std::string& name, const nlohmann::json& scene) {
    std::string path = dir + "/" + name + "_scene.json";
    std::ofstream(path) << scene.dump(1);
    return path;
}

rg::FloatImage render(const char* exe, const std::string& scene, const std::string& out, int width, int height,
                      std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"--headless", "--validation", "--scene", scene, "--width", std::to_string(width),
                                     "--height", std::to_string(height), "--output", out};
    args.insert(args.end(), extra.begin(), extra.end());
    if (std::find(extra.begin(), extra.end(), "--frames") == extra.end()) args.insert(args.end(), {"--frames", "1"});
    rgtest::RunResult r = rgtest::run(exe, args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return rg::readPfm(out);
}

// Pixels whose display value differs by more than 1/255, as a share.
double shareOff(const rg::FloatImage& a, const rg::FloatImage& b) {
    EXPECT_EQ(a.rgba.size(), b.rgba.size());
    if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return 1;
    size_t off = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c)
            if (std::abs(rgtest::display8(a.rgba[i + c]) - rgtest::display8(b.rgba[i + c])) > 1) {
                ++off;
                break;
            }
    return double(off) / double(a.rgba.size() / 4);
}

// The camera ray through pixel (x, y)'s centre (docs/04_raygen_miss.md's camera).
glm::dvec3 cameraDirection(const glm::dvec3& eye, const glm::dvec3& lookAt, double fovDeg, int x, int y, int width,
                           int height) {
    glm::dvec3 forward = glm::normalize(lookAt - eye), right = glm::normalize(glm::cross(forward, {0, 1, 0}));
    glm::dvec3 up = glm::cross(right, forward);
    double tanHalf = std::tan(fovDeg / 2 * kPi / 180), aspect = double(width) / height;
    return glm::normalize(forward + ((x + 0.5) / width * 2 - 1) * tanHalf * aspect * right +
                          (1 - (y + 0.5) / height * 2) * tanHalf * up);
}

nlohmann::json glass(double ior, nlohmann::json extra = nlohmann::json::object()) {
    nlohmann::json m = {{"ka", 0}, {"kd", 0}, {"ks", 0.8}, {"shininess", 200}, {"transmission", 1}, {"ior", ior}};
    m.update(extra);
    return m;
}

// Glass inside the same glass has no surface between them: adding it
// changes no pixel (chapter 10, which puts air outside each, shows a ball).
// Several sizes and placements, the same material and an equal one.
TEST(Media, GlassInTheSameGlassIsNoSurface) {
    std::string dir = rgtest::outputDir("13_same_glass");
    nlohmann::json base = {
        {"camera", {{"position", {0, 0.4, 4}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", 40}}},
        {"ambient", 0.1},
        {"lights", {{{"position", {-3, 4, 4}}, {"intensity", 0.8}}}},
        {"materials", {{"bk7", glass(1.5168)}, {"bk7_too", glass(1.5168)},
                       {"floor", {{"kd", {0.6, 0.5, 0.4}}}}}},
        {"objects", {{{"type", "quad"}, {"center", {0, -1.01, 0}}, {"u", {4, 0, 0}}, {"v", {0, 0, 4}}, {"material", "floor"}},
                     {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "bk7"}}}}};
    std::string single = writeScene(dir, "single", base);
    rg::FloatImage one13 = render(RG_EXE_13, single, dir + "/single13.pfm", 160, 120);
    rg::FloatImage one10 = render(RG_EXE_12, single, dir + "/single10.pfm", 160, 120, {"--fresnel", "exact", "--depth", "8"});
    struct Inner { glm::dvec3 centre; double radius; const char* material; };
    for (const Inner& inner : {Inner{{0, 0, 0}, 0.5, "bk7"}, Inner{{0.3, 0.2, 0.1}, 0.4, "bk7_too"},
                               Inner{{-0.4, -0.3, 0.3}, 0.3, "bk7"}}) {
        SCOPED_TRACE("inner ball r " + std::to_string(inner.radius) + " of " + inner.material);
        nlohmann::json nested = base;
        nested["objects"].push_back({{"type", "sphere"}, {"center", {inner.centre.x, inner.centre.y, inner.centre.z}},
                                     {"radius", inner.radius}, {"material", inner.material}});
        std::string path = writeScene(dir, "nested", nested);
        EXPECT_EQ(shareOff(render(RG_EXE_13, path, dir + "/nested13.pfm", 160, 120), one13), 0.0);
        // Chapter 10's rule (in chapter 12, which takes the same scenes) sees a ball.
        EXPECT_GT(shareOff(render(RG_EXE_12, path, dir + "/nested10.pfm", 160, 120, {"--fresnel", "exact", "--depth", "8"}),
                           one10),
                  0.01);
    }
}

// From inside glass (n = 1.5168) onto an air bubble: below the critical
// angle asin(1 / n) = 41.25 degrees part of the light leaves into the air,
// above it all is reflected. The eye is in the glass (camera.medium), the
// sky is white and the depth limit 1, so a pixel holds exactly what the
// bubble reflects: F of its angle of incidence, which the test finds from
// the pixel's ray and the sphere alone.
TEST(Media, ABubbleInGlassReflectsTotallyPastTheCriticalAngle) {
    std::string dir = rgtest::outputDir("13_bubble");
    const double n = 1.5168, r = 1;
    const glm::dvec3 eye(0, 0, 5), centre(0, 0, 0);
    const int width = 320, height = 320;
    const double fov = 30;
    nlohmann::json scene = {
        {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", fov}, {"medium", "bk7"}}},
        {"sky", {{"top", 1}, {"horizon", 1}, {"bottom", 1}}},
        {"ambient", 0},
        {"materials", {{"bk7", glass(n)}, {"air", glass(1.0, {{"priority", 1}})}}},
        {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", r}, {"material", "air"}}}}};
    rg::FloatImage image = render(RG_EXE_13, writeScene(dir, "bubble", scene), dir + "/bubble.pfm", width, height,
                                  {"--depth", "1"});
    ASSERT_EQ(image.rgba.size(), size_t(width) * height * 4);
    double critical = std::asin(1 / n) * 180 / kPi;
    EXPECT_NEAR(critical, 41.25, 0.005);
    int below = 0, above = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            glm::dvec3 d = cameraDirection(eye, {0, 0, 0}, fov, x, y, width, height);
            glm::dvec3 f = eye - centre;
            double b = glm::length(f - glm::dot(f, d) * d);  // the ray's distance from the centre
            if (b >= r) continue;
            double incidence = std::asin(b / r) * 180 / kPi;
            float value = image.rgba[4 * (size_t(y) * width + x)];
            if (std::abs(incidence - 41.0) < 0.1) {  // leaves: F < 1, as Fresnel says
                double F = fresnelEquations(std::cos(incidence * kPi / 180), n, 1.0);
                EXPECT_NEAR(value, F, 0.01 * F) << "at " << incidence << " degrees";
                EXPECT_LT(value, 0.8);
                ++below;
            } else if (std::abs(incidence - 41.5) < 0.1) {  // totally reflected
                EXPECT_NEAR(value, 1.0, 1e-3) << "at " << incidence << " degrees";
                ++above;
            }
        }
    EXPECT_GT(below, 20);
    EXPECT_GT(above, 20);
}

// The nearer root t > 1e-9 of |o + t d - c| = r, or -1.
double hitSphere(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& c, double r) {
    glm::dvec3 f = o - c;
    double b = glm::dot(f, d), q = glm::dot(f, f) - r * r, disc = b * b - q;
    if (disc < 0) return -1;
    double s = std::sqrt(disc), t0 = -b - s, t1 = -b + s;
    return t0 > 1e-9 ? t0 : t1 > 1e-9 ? t1 : -1;
}

// Snell's law for unit d and a unit normal n facing it, from n1 into n2;
// false under total internal reflection.
bool refracted(const glm::dvec3& d, const glm::dvec3& n, double n1, double n2, glm::dvec3& t) {
    double eta = n1 / n2, c = -glm::dot(n, d), k = 1 - eta * eta * (1 - c * c);
    if (k < 0) return false;
    t = eta * d + (eta * c - std::sqrt(k)) * n;
    return true;
}

// A glass ball with an air bubble, seen from outside: its ring. Rays that
// refract into the ball and meet the bubble past the critical angle are
// reflected whole, so the bubble shows a bright ring round a darker disc
// where most light enters the air. The sky is white, the material has no
// ambient, diffuse or highlight, and the depth limit is 3, so a pixel that
// sees the bubble holds exactly F0 + (1 - F0) Rb (1 - F2): the ball's
// reflection of the sky, plus the light the bubble reflects (Rb) that then
// leaves the ball (1 - F2); the light that enters the bubble needs a fourth
// surface to get out. The test traces each pixel's ray itself, in double,
// with the bubble off the ball's centre, and must find the ring where its
// own trace puts it.
TEST(Media, ABubbleShowsItsRingWhereAnIndependentTracePutsIt) {
    std::string dir = rgtest::outputDir("13_bubble_ring");
    const double n = 1.5168, R = 1, r = 0.45;
    const glm::dvec3 eye(0.3, 0.2, 4), ball(0, 0, 0), bubble(0.15, -0.1, 0.1);
    const int size = 160;
    const double fov = 32;
    nlohmann::json scene = {
        {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", fov}}},
        {"sky", {{"top", 1}, {"horizon", 1}, {"bottom", 1}}},
        {"ambient", 0},
        {"materials", {{"bk7", glass(n, {{"ks", 0}})}, {"air", glass(1.0, {{"ks", 0}, {"priority", 1}})}}},
        {"objects", {{{"type", "sphere"}, {"center", {ball.x, ball.y, ball.z}}, {"radius", R}, {"material", "bk7"}},
                     {{"type", "sphere"}, {"center", {bubble.x, bubble.y, bubble.z}}, {"radius", r}, {"material", "air"}}}}};
    rg::FloatImage image = render(RG_EXE_13, writeScene(dir, "ring", scene), dir + "/ring.pfm", size, size,
                                  {"--depth", "3"});
    ASSERT_EQ(image.rgba.size(), size_t(size) * size * 4);
    const double critical = std::asin(1 / n);
    int ring = 0, disc = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            glm::dvec3 d = cameraDirection(eye, {0, 0, 0}, fov, x, y, size, size);
            double t0 = hitSphere(eye, d, ball, R);
            if (t0 < 0) continue;
            glm::dvec3 p0 = eye + t0 * d, n0 = glm::normalize(p0 - ball), d1;
            if (!refracted(d, n0, 1, n, d1)) continue;
            d1 = glm::normalize(d1);
            double t1 = hitSphere(p0, d1, bubble, r);
            if (t1 < 0) continue;  // misses the bubble
            glm::dvec3 p1 = p0 + t1 * d1, n1 = glm::normalize(p1 - bubble);
            double cos1 = -glm::dot(n1, d1), incidence = std::acos(cos1);
            if (std::abs(incidence - critical) < 0.004 || cos1 < 0.05) continue;  // too steep to compare
            glm::dvec3 d2 = d1 + 2 * cos1 * n1;  // reflected, on into the glass
            double t2 = hitSphere(p1, d2, ball, R);
            if (t2 < 0) continue;
            glm::dvec3 n2 = glm::normalize(p1 + t2 * d2 - ball);
            double F0 = fresnelEquations(-glm::dot(n0, d), 1, n), Rb = fresnelEquations(cos1, n, 1);
            double F2 = fresnelEquations(glm::dot(n2, d2), n, 1);
            double expected = F0 + (1 - F0) * Rb * (1 - F2);
            float value = image.rgba[4 * (size_t(y) * size + x)];
            EXPECT_NEAR(value, expected, 0.005 * expected + 1e-4) << "pixel " << x << "," << y;
            if (incidence > critical) {
                ++ring;
                EXPECT_GT(value, 0.5) << "the ring at pixel " << x << "," << y;
            } else if (incidence < critical - 0.05) {  // Fresnel climbs steeply in the last 3 degrees
                ++disc;
                EXPECT_LT(value, 0.5) << "inside the ring at pixel " << x << "," << y;
            }
        }
    std::printf("bubble: %d pixels of the ring, %d inside it\n", ring, disc);
    EXPECT_GT(ring, 300);
    EXPECT_GT(disc, 300);
}

// A flat box of vertices in world space, wound counter-clockwise from outside.
std::string slabObj(const glm::dvec3& centre, const glm::dvec3& normal, double halfWidth, double thickness) {
    glm::dvec3 t1 = glm::normalize(glm::cross(normal, {1, 0, 0})), t2 = glm::cross(normal, t1);
    std::string obj;
    auto vertex = [&](const glm::dvec3& v) { obj += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n"; };
    glm::dvec3 axes[3] = {halfWidth * t1, halfWidth * t2, thickness / 2 * normal};
    for (int c = 0; c < 8; ++c)
        vertex(centre + (c & 1 ? 1.0 : -1.0) * axes[0] + (c & 2 ? 1.0 : -1.0) * axes[1] + (c & 4 ? 1.0 : -1.0) * axes[2]);
    std::vector<glm::dvec3> corners;
    for (int c = 0; c < 8; ++c)
        corners.push_back(centre + (c & 1 ? 1.0 : -1.0) * axes[0] + (c & 2 ? 1.0 : -1.0) * axes[1] + (c & 4 ? 1.0 : -1.0) * axes[2]);
    int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (auto& f : faces) {
        glm::dvec3 mid = (corners[f[0]] + corners[f[2]]) / 2.0;
        bool outward = glm::dot(glm::cross(corners[f[1]] - corners[f[0]], corners[f[2]] - corners[f[0]]), mid - centre) > 0;
        int a = f[0] + 1, b = f[1] + 1, c = f[2] + 1, d = f[3] + 1;
        if (!outward) std::swap(b, d);
        obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
        obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
    return obj;
}

// A tinted glass slab seen at an angle transmits (1 - F) at the face it
// enters, (1 - F) at the face it leaves, and exp(-sigma L) on the way,
// L = thickness / cos(refraction angle): per channel, within 0.5 %, for
// two thicknesses and two angles. The sky is black above the horizon and
// -y below, so a reflection adds nothing and the transmitted ray (parallel
// to the camera ray) brings -d.y; --depth 2 ends the path before a second
// internal reflection could come out.
TEST(Media, ASlabTransmitsFresnelAtBothFacesAndBeerLambert) {
    std::string dir = rgtest::outputDir("13_slab");
    const double n = 1.5168;
    const glm::dvec3 color(0.9, 0.5, 0.2);
    const double distance = 0.3;
    const glm::dvec3 eye(0, 3, 3), lookAt(0, 0, 0);
    const int width = 64, height = 64;
    const double fov = 20;
    for (double thickness : {0.1, 0.4})
        for (double tilt : {0.0, 35.0}) {
            SCOPED_TRACE("thickness " + std::to_string(thickness) + ", tilt " + std::to_string(tilt));
            glm::dvec3 view = glm::normalize(eye - lookAt), side(1, 0, 0);
            double a = tilt * kPi / 180;
            glm::dvec3 normal = glm::normalize(std::cos(a) * view + std::sin(a) * side);
            std::ofstream(dir + "/slab.obj") << slabObj(lookAt, normal, 1.5, thickness);
            nlohmann::json scene = {
                {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {lookAt.x, lookAt.y, lookAt.z}}, {"fov_y_deg", fov}}},
                {"sky", {{"top", 0}, {"horizon", 0}, {"bottom", 1}}},
                {"ambient", 0},
                {"materials", {{"tinted", glass(n, {{"attenuation_color", {color.r, color.g, color.b}},
                                                    {"attenuation_distance", distance}})}}},
                {"objects", {{{"type", "mesh"}, {"file", "slab.obj"}, {"material", "tinted"}}}}};
            rg::FloatImage image = render(RG_EXE_13, writeScene(dir, "slab", scene), dir + "/slab.pfm", width, height,
                                          {"--depth", "2"});
            ASSERT_EQ(image.rgba.size(), size_t(width) * height * 4);
            for (int y = 24; y < 40; y += 5)
                for (int x = 24; x < 40; x += 5) {
                    glm::dvec3 d = cameraDirection(eye, lookAt, fov, x, y, width, height);
                    double cosI = -glm::dot(d, normal), sinT = std::sqrt(1 - cosI * cosI) / n;
                    double cosT = std::sqrt(1 - sinT * sinT);
                    double F1 = fresnelEquations(cosI, 1.0, n), F2 = fresnelEquations(cosT, n, 1.0);
                    for (int c = 0; c < 3; ++c) {
                        double sigma = -std::log(color[c]) / distance;
                        double expected = (1 - F1) * (1 - F2) * std::exp(-sigma * thickness / cosT) * -d.y;
                        EXPECT_NEAR(image.rgba[4 * (size_t(y) * width + x) + c], expected, 0.005 * expected)
                            << "pixel " << x << "," << y << " channel " << c;
                    }
                }
        }
}

// With no medium inside another and none absorbing, chapter 13 is chapter
// 10 with exact Fresnel: its default glass scene and the thesis's scene.
TEST(Media, WithNothingNestedItIsChapter10) {
    std::string dir = rgtest::outputDir("13_as_10");
    for (const char* name : {"glass_sphere", "default"}) {
        SCOPED_TRACE(name);
        std::string scene = std::string(RG_SOURCE_DIR "/assets/scenes/") + name + ".json";
        rg::FloatImage a = render(RG_EXE_13, scene, dir + "/13.pfm", 160, 90, {"--depth", "6"});
        rg::FloatImage b = render(RG_EXE_10, scene, dir + "/10.pfm", 160, 90, {"--depth", "6", "--fresnel", "exact"});
        EXPECT_LE(shareOff(a, b), 0.001);
    }
}

// Bad media keys: one line naming the key, exit 2, no output written.
TEST(Media, BadMediumKeysAreOneClearLine) {
    std::string dir = rgtest::outputDir("13_bad_keys");
    struct Case { nlohmann::json material; nlohmann::json camera; std::string says; };
    nlohmann::json plainCamera = {{"position", {0, 0, 5}}, {"look_at", {0, 0, 0}}};
    nlohmann::json inOpaque = plainCamera;
    inOpaque["medium"] = "m";
    nlohmann::json inNothing = plainCamera;
    inNothing["medium"] = "nothing";
    for (const Case& c : {Case{glass(1.5, {{"attenuation_color", {1, 0.5, 0.5}}}), plainCamera,
                               "materials.m.attenuation_distance: missing"},
                          Case{glass(1.5, {{"attenuation_color", {1, 0, 0.5}}, {"attenuation_distance", 1}}), plainCamera,
                               "materials.m.attenuation_color"},
                          Case{glass(1.5, {{"priority", 1.5}}), plainCamera, "materials.m.priority: must be a whole number"},
                          Case{{{"kd", 0.5}}, inOpaque, "camera.medium: must name a material that transmits"},
                          Case{glass(1.5), inNothing, "camera.medium: no material named \"nothing\""}}) {
        nlohmann::json scene = {{"camera", c.camera},
                                {"materials", {{"m", c.material}}},
                                {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
        rgtest::RunResult r = rgtest::run(RG_EXE_13, {"--headless", "--scene", writeScene(dir, "bad", scene), "--output",
                                                      dir + "/x.png"});
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(std::ifstream(dir + "/x.png").good());
    }
}

// ---- Dispersion -------------------------------------------------------------------

std::string meshDir() { return (std::filesystem::path(RG_EXE_13).parent_path() / "assets" / "meshes").string(); }

// N-BK7 at the Fraunhofer lines F, d and C, as SCHOTT's datasheet tabulates
// them (measured indices, not the Sellmeier fit the renderer uses).
struct Line { const char* name; double nm, n; };
const Line kLines[3] = {{"F", 486.1327, 1.52238}, {"d", 587.5618, 1.51680}, {"C", 656.2725, 1.51432}};
constexpr double kAbbe = (1.51680 - 1) / (1.52238 - 1.51432);  // 64.2

double minimumDeviation(double n) { return (2 * std::asin(n * std::sin(kPi / 6)) - kPi / 3) * 180 / kPi; }

// The 60-degree prism read off chapter 13's image at one wavelength at a
// time (--wavelength), of N-BK7 by name (Sellmeier) and by its Abbe number
// (glTF's KHR_materials_dispersion): each line deviates as its index says,
// and F spreads from C by 0.709 degrees.
TEST(Dispersion, APrismDeviatesEachLineAsItsIndexSays) {
    nlohmann::json named = {{"ka", 0}, {"kd", 0}, {"ks", 0}, {"transmission", 1}, {"dispersion", "bk7"}};
    nlohmann::json abbe = {{"ka", 0}, {"kd", 0}, {"ks", 0}, {"transmission", 1}, {"ior", 1.5168},
                           {"dispersion", 20 / kAbbe}};
    for (const auto& [what, material] : {std::pair("named", named), std::pair("abbe", abbe)}) {
        double deviation[3];
        for (int i = 0; i < 3; ++i) {
            SCOPED_TRACE(std::string(what) + " " + kLines[i].name);
            std::string dir = rgtest::outputDir(std::string("13_prism_") + what + "_" + kLines[i].name);
            deviation[i] = rgtest::optics::prismFromImage(RG_EXE_13, dir, meshDir(), material,
                                                          {"--wavelength", std::to_string(kLines[i].nm)})
                               .minimum;
            std::printf("prism (%s) at %s, %.4f nm: minimum deviation %.4f deg (optics %.4f)\n", what, kLines[i].name,
                        kLines[i].nm, deviation[i], minimumDeviation(kLines[i].n));
            EXPECT_NEAR(deviation[i], minimumDeviation(kLines[i].n), 0.01);
        }
        double spread = deviation[0] - deviation[2], expected = minimumDeviation(1.52238) - minimumDeviation(1.51432);
        std::printf("prism (%s): F - C spread %.4f deg (optics %.4f)\n", what, spread, expected);
        EXPECT_NEAR(spread, expected, 0.005);
    }
}

// Chapter 12's biconvex lens of N-BK7 (R = +-50 mm, 5 mm thick) at F and
// C: blue comes to focus closer. Thick-lens optics: 1/f = (n - 1) (2/R -
// (n - 1) t / (n R^2)), the back focal length f (1 - (n - 1) t / (n R)).
TEST(Dispersion, ALensFocusesBlueCloserThanRedByTheLensmakersFormula) {
    nlohmann::json named = {{"ka", 0}, {"kd", 0}, {"ks", 0}, {"transmission", 1}, {"dispersion", "bk7"}};
    auto backFocus = [](double n) {
        const double R = 50, t = 5;
        double f = 1 / ((n - 1) * (2 / R - (n - 1) * t / (n * R * R)));
        return f * (1 - (n - 1) * t / (n * R));
    };
    double bfl[2];
    for (int i : {0, 2}) {
        SCOPED_TRACE(kLines[i].name);
        rgtest::optics::LensReading lens = rgtest::optics::lensFromImage(
            RG_EXE_13, rgtest::outputDir(std::string("13_lens_") + kLines[i].name), meshDir(), named,
            {"--wavelength", std::to_string(kLines[i].nm)});
        bfl[i / 2] = lens.bfl;
        std::printf("lens at %s: back focal length %.4f mm (optics %.4f)\n", kLines[i].name, lens.bfl,
                    backFocus(kLines[i].n));
    }
    double shift = bfl[1] - bfl[0], expected = backFocus(1.51432) - backFocus(1.52238);
    std::printf("lens: red focuses %.4f mm beyond blue (optics %.4f)\n", shift, expected);
    EXPECT_NEAR(shift, expected, 0.02 * expected);
}

// White light through a flat slab of dispersive glass stays white. Under
// a white sky all round, whatever a clear slab does not transmit it
// reflects (R + T = 1 at every face), so each wavelength's paths bring 1,
// whatever its index; at depth 8 what is cut off is below 1e-6. Then each
// pixel is the mean of the wavelengths' weights, which must be 1 in every
// channel: a wrong scale for a channel, or wavelengths drawn unevenly over
// the range, tints it. 1024 frames; within 0.05 %.
TEST(Dispersion, WhiteLightThroughASlabStaysWhite) {
    std::string dir = rgtest::outputDir("13_white_slab");
    const glm::dvec3 eye(0, 0, 3), lookAt(0, 0, 0), normal = glm::normalize(glm::dvec3(0.6, 0, 0.8));
    std::ofstream(dir + "/slab.obj") << slabObj(lookAt, normal, 1.5, 0.3);
    nlohmann::json scene = {
        {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", 5}}},
        {"sky", {{"top", 1}, {"horizon", 1}, {"bottom", 1}}},
        {"ambient", 0},
        {"materials", {{"bk7", {{"ka", 0}, {"kd", 0}, {"ks", 0}, {"transmission", 1}, {"dispersion", "bk7"}}}}},
        {"objects", {{{"type", "mesh"}, {"file", "slab.obj"}, {"material", "bk7"}}}}};
    const int size = 8;
    rg::FloatImage image = render(RG_EXE_13, writeScene(dir, "slab", scene), dir + "/slab.pfm", size, size,
                                  {"--depth", "8", "--frames", "1024"});
    ASSERT_EQ(image.rgba.size(), size_t(size) * size * 4);
    std::printf("white slab: pixel 0 %.6f %.6f %.6f\n", image.rgba[0], image.rgba[1], image.rgba[2]);
    for (int i = 0; i < size * size; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.rgba[4 * i + c], 1.0, 5e-4) << "pixel " << i << " channel " << c;
}

// The prism scene against its CPU reference, which integrates over the
// very wavelengths the frames drew.
TEST(Dispersion, ThePrismSceneMatchesItsReference) {
    std::string dir = rgtest::outputDir("13_prism_reference");
    rgtest::RunResult r = rgtest::run(RG_EXE_13, {"--headless", "--validation", "--reference", "--scene",
                                                  RG_SOURCE_DIR "/assets/scenes/prism.json", "--width", "160",
                                                  "--height", "90", "--frames", "16", "--output", dir + "/p.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/p.json");
    rgtest::expectCleanReport(report, "13_real_glass", 160, 90);
    EXPECT_LE(report["error"].value("frac_over_1_255", 1.0), 0.001);
    EXPECT_LE(report["error"].value("rmse", 1.0), 1e-4);
}

// Bad dispersion: one line naming the key (or the option), exit 2, no output.
TEST(Dispersion, BadDispersionIsOneClearLine) {
    std::string dir = rgtest::outputDir("13_bad_dispersion");
    struct Case { nlohmann::json material; std::vector<std::string> args; std::string says; };
    nlohmann::json plain = glass(1.5);
    nlohmann::json flint = {{"transmission", 1}, {"dispersion", "flint"}};
    nlohmann::json both = {{"transmission", 1}, {"dispersion", "bk7"}, {"ior", 1.6}};
    nlohmann::json negative = glass(1.5, {{"dispersion", -1}});
    for (const Case& c : {Case{flint, {}, "materials.m.dispersion: no glass named \"flint\""},
                          Case{both, {}, "materials.m.ior: a named glass's dispersion sets the index"},
                          Case{negative, {}, "materials.m.dispersion"},
                          Case{plain, {"--wavelength", "200"}, "--wavelength: must be 0 or 380-780 nm"}}) {
        nlohmann::json scene = {{"camera", {{"position", {0, 0, 5}}, {"look_at", {0, 0, 0}}}},
                                {"materials", {{"m", c.material}}},
                                {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
        std::vector<std::string> args = {"--headless", "--scene", writeScene(dir, "bad", scene), "--output", dir + "/x.png"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        rgtest::RunResult r = rgtest::run(RG_EXE_13, args);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_FALSE(std::ifstream(dir + "/x.png").good());
    }
}

}  // namespace

// Page 13's "what you should see" of the glass of water: the ice cube,
// under the waterline, almost vanishes (ice 1.309 in water 1.333: F at
// normal incidence 8e-5), where chapter 10's rule (chapter 12, air outside
// every glass) shows it dark and sharp. Each rule's picture against the same
// scene without the ice: the change over the glass of water below the
// waterline (projected from the scene's camera) is small with nested media
// and several times larger with air outside every object.
TEST(Media, TheIceCubeAlmostVanishesUnderWater) {
    std::string dir = rgtest::outputDir("13_ice");
    const int W = 160, H = 90;
    nlohmann::json scene = rgtest::readJson(RG_SOURCE_DIR "/assets/scenes/real_glass.json");
    std::string assets = (std::filesystem::path(RG_EXE_13).parent_path() / "assets").string();
    for (nlohmann::json& o : scene["objects"])
        if (o["type"] == "mesh") o["file"] = assets + "/" + std::string(o["file"]);
    if (scene["sky"].contains("image")) scene["sky"]["image"] = assets + "/" + std::string(scene["sky"]["image"]);
    nlohmann::json noIce = scene;
    noIce["objects"] = nlohmann::json::array();
    for (const nlohmann::json& o : scene["objects"])
        if (o.value("material", "") != "ice") noIce["objects"].push_back(o);
    ASSERT_EQ(noIce["objects"].size() + 1, scene["objects"].size());
    auto pictureOf = [&](const char* exe, const nlohmann::json& s, const std::string& name,
                         std::vector<std::string> extra) {
        return render(exe, writeScene(dir, name, s), dir + "/" + name + ".pfm", W, H, extra);
    };
    const std::vector<std::string> chapter10Rule = {"--depth", "8", "--fresnel", "exact"};
    rg::FloatImage nested = pictureOf(RG_EXE_13, scene, "nested", {}),
                   nestedNoIce = pictureOf(RG_EXE_13, noIce, "nested_no_ice", {}),
                   air = pictureOf(RG_EXE_12, scene, "air", chapter10Rule),
                   airNoIce = pictureOf(RG_EXE_12, noIce, "air_no_ice", chapter10Rule);
    // the glass of water (60 mm across, 90 tall, at (-0.5, 0, 0.6), 1/100 of its
    // millimetres) below the waterline (y 0.6), seen from the front: the
    // ice's light, refracted by the water and the glass, lands inside it
    rgtest::SceneCamera camera(scene, W, H);
    glm::dvec2 a = camera.project({-0.8, 0.1, 0.9}), b = camera.project({-0.2, 0.58, 0.9});
    // how much darker the ice makes it: the light it takes away, over the
    // light without it (under water it takes almost none; with chapter 10's
    // rule it shows dark)
    auto change = [&](const rg::FloatImage& with, const rg::FloatImage& without) {
        double sum = 0, base = 0;
        int n = 0;
        for (int y = int(std::ceil(b.y)); y < int(a.y); ++y)
            for (int x = int(std::ceil(a.x)); x < int(b.x); ++x, ++n)
                for (int c = 0; c < 3; ++c) {
                    size_t i = (size_t(y) * W + x) * 4 + c;
                    sum += without.rgba[i] - with.rgba[i], base += without.rgba[i];
                }
        EXPECT_GT(n, 20) << "the window covers pixels";
        return sum / std::max(base, 1e-9);
    };
    double withMedia = change(nested, nestedNoIce), withAir = change(air, airNoIce);
    std::printf("the ice changes the glass of water below the waterline by %.3f of its light (nested media), "
                "%.3f (air outside every object)\n", withMedia, withAir);
    EXPECT_LT(withMedia, 0.05) << "under water the ice almost vanishes";
    EXPECT_GT(withAir, 3 * withMedia) << "with chapter 10's rule it does not";
}

// Page 13's "what you should see" of the two amber balls: one glass, one
// twice the other's size, so the larger is redder (Beer-Lambert: each
// channel keeps exp(-sigma d), and the attenuation colour (0.85, 0.45,
// 0.12) takes green and blue faster than red). Each ball's disc is
// projected from the scene file's camera here, and the linear mean of the
// pixels within 0.7 of its radius is read off the chapter's own picture.
// (Not darker overall: the larger ball shows more of the bright floor and
// sky through its upper half.)
TEST(Media, TheLargerAmberBallIsRedder) {
    std::string dir = rgtest::outputDir("13_amber");
    const int W = 320, H = 180;
    rgtest::RunResult r = rgtest::run(RG_EXE_13, {"--headless", "--validation", "--width", std::to_string(W), "--height",
                                                  std::to_string(H), "--output", dir + "/real_glass.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    rgtest::Png png = rgtest::readPng(dir + "/real_glass.png");
    // assets/scenes/real_glass.json's camera and amber balls
    const glm::dvec3 eye(0.25, 0.95, 3.2), target(0.3, 0.38, 0);
    const double tanHalf = std::tan(20 * 3.14159265358979 / 180), aspect = double(W) / H;
    glm::dvec3 forward = glm::normalize(target - eye), right = glm::normalize(glm::cross(forward, {0, 1, 0})),
               up = glm::cross(right, forward);
    auto meanOf = [&](glm::dvec3 centre, double radius) {
        glm::dvec3 d = centre - eye;
        double z = glm::dot(d, forward);
        double px = (1 + glm::dot(d, right) / z / (tanHalf * aspect)) / 2 * W;
        double py = (1 - glm::dot(d, up) / z / tanHalf) / 2 * H;
        double pr = 0.7 * radius / glm::length(d) / tanHalf * H / 2;
        glm::dvec3 sum(0);
        int n = 0;
        for (int y = int(py - pr); y <= int(py + pr); ++y)
            for (int x = int(px - pr); x <= int(px + pr); ++x)
                if (std::hypot(x + 0.5 - px, y + 0.5 - py) < pr) {
                    ++n;
                    for (int c = 0; c < 3; ++c) sum[c] += rg::srgbToLinear(png.at(x, y)[c] / 255.0);
                }
        return sum / double(n);
    };
    glm::dvec3 small = meanOf({0.95, 0.202, 0.7}, 0.2), large = meanOf({1.35, 0.402, -0.3}, 0.4);
    EXPECT_GT(small.r, small.g) << "the small ball should be amber too";
    EXPECT_GT(small.g, small.b);
    EXPECT_GT(large.r / large.g, 1.3 * small.r / small.g) << "the larger ball should be redder";
    EXPECT_LT(large.b / large.r, small.b / small.r) << "and keep less blue against its red";
}
