// Chapter 12: glTF's metal-roughness and normal textures. The texture
// values are tested against what glTF says they mean: a metal-roughness
// texel must act as the same factors would, and a normal texture must
// turn a flat mirror into the tilted mirror its normal describes. The
// painted panel (meshes/panel.glb) is then checked against the reference.
#include "gltf_square.h"
#include "harness.h"

#include "core/files.h"
#include "core/image.h"
#include "scene/mesh_file.h"
#include "scene/scene.h"

#include <stb_image_write.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;

std::string assetDir() { return (fs::path(RG_EXE_12).parent_path() / "assets").string(); }

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A 4 x 4 PNG of one colour, its bytes as given (data textures are not sRGB).
void writeFlatPng(const std::string& path, const glm::ivec3& bytes) {
    std::vector<unsigned char> rgb;
    for (int i = 0; i < 16; ++i) rgb.insert(rgb.end(), {(unsigned char)bytes.x, (unsigned char)bytes.y, (unsigned char)bytes.z});
    ASSERT_NE(stbi_write_png(path.c_str(), 4, 4, 3, rgb.data(), 12), 0) << path;
}

// Pixels whose channels differ by more than `codes`.
size_t pixelsApart(const rgtest::Png& a, const rgtest::Png& b, int codes) {
    size_t n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > codes) {
                    ++n;
                    break;
                }
    return n;
}

}  // namespace

TEST(MetalRoughness, TexturesAreReadAsLinearData) {
    std::string dir = rgtest::outputDir("12_mr_read");
    writeFlatPng(dir + "/mr.png", {255, 128, 64});
    writeFlatPng(dir + "/normal.png", {128, 128, 255});
    writeSquareGltf(dir, "square", wall(1), {{"normalTexture", {{"scale", 0.5}}}},
                    {{"metallicRoughnessTexture", "mr.png"}, {"normalTexture", "normal.png"}});
    rg::MeshFile file = rg::loadMeshFile(dir + "/square.gltf");
    ASSERT_EQ(file.materials.size(), 1u);
    const rg::FileMaterial& m = file.materials[0];
    ASSERT_GE(m.metallicRoughnessTexture, 0);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_EQ(m.normalScale, 0.5);
    // numbers, not colours: 128 is 128/255, not sRGB's 0.216
    EXPECT_EQ(glm::dvec3(rg::texelValue(file.textures[m.metallicRoughnessTexture], 0, 0, 0)),
              glm::dvec3(1.0, 128 / 255.0, 64 / 255.0));
    EXPECT_EQ(glm::dvec3(rg::texelValue(file.textures[m.normalTexture], 0, 0, 0)),
              glm::dvec3(128 / 255.0, 128 / 255.0, 1.0));
    // textures that name different coordinate sets: one line, naming both
    writeText(dir + "/two_sets.gltf", [&] {
        std::ifstream in(dir + "/square.gltf");
        nlohmann::json j = nlohmann::json::parse(in);
        j["materials"][0]["normalTexture"]["texCoord"] = 1;
        return j.dump();
    }());
    try {
        rg::loadMeshFile(dir + "/two_sets.gltf");
        ADD_FAILURE() << "two_sets.gltf was read";
    } catch (const rg::InputError& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("two_sets.gltf: material 0: its textures name different TEXCOORD sets"),
                  std::string::npos)
            << message;
    }
}

// Each texel of a uniform metal-roughness texture (factors 1) must draw the
// picture the same numbers draw as factors: the shader's per-hit mapping
// (raygen_common.glsl) against the host's (rules.cpp). A painted, rough
// dielectric (G 140, B 0) tests roughness; a polished metal (G 0, B 255)
// tests metalness: swapped channels would draw a grey diffuse square.
TEST(MetalRoughness, ATexelActsAsTheSameFactors) {
    std::string dir = rgtest::outputDir("12_mr_factors");
    struct Case {
        const char* name;
        glm::ivec3 texel;
    } cases[] = {{"paint", {255, 140, 0}}, {"metal", {255, 0, 255}}};
    std::string textured, factors;
    for (int i = 0; i < 2; ++i) {
        const Case& c = cases[i];
        writeFlatPng(dir + "/" + c.name + ".png", c.texel);
        nlohmann::json base = {{"baseColorFactor", {0.8, 0.3, 0.2, 1}}};
        nlohmann::json withTexture = {{"pbrMetallicRoughness", base}};
        withTexture["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
        withTexture["pbrMetallicRoughness"]["roughnessFactor"] = 1.0;
        writeSquareGltf(dir, std::string(c.name) + "_textured", wall(1), withTexture,
                        {{"metallicRoughnessTexture", std::string(c.name) + ".png"}});
        nlohmann::json asFactors = {{"pbrMetallicRoughness", base}};
        asFactors["pbrMetallicRoughness"]["metallicFactor"] = c.texel.z / 255.0;
        asFactors["pbrMetallicRoughness"]["roughnessFactor"] = c.texel.y / 255.0;
        writeSquareGltf(dir, std::string(c.name) + "_factors", wall(1), asFactors, {});
        std::string place = i == 0 ? R"("translate": [-1.1, 0, 0], "rotate_deg": [0, 20, 0])"
                                   : R"("translate": [1.1, 0, 0], "rotate_deg": [0, -20, 0])";
        textured += std::string(i ? ", " : "") + R"({"type": "mesh", "file": ")" + c.name +
                    R"(_textured.gltf", "transform": {)" + place + "}}";
        factors += std::string(i ? ", " : "") + R"({"type": "mesh", "file": ")" + c.name +
                   R"(_factors.gltf", "transform": {)" + place + "}}";
    }
    auto scene = [&](const std::string& name, const std::string& objects) {
        writeText(dir + "/" + name + ".json",
                  R"({"camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "fov_y_deg": 45},
                      "sky": {"image": ")" + assetDir() + R"(/sky.png"}, "ambient": 0.2,
                      "lights": [{"position": [-1, 2, 4], "intensity": 1}], "objects": [)" + objects + "]}");
        return dir + "/" + name + ".json";
    };
    rgtest::Png a = render(scene("textured", textured), dir + "/textured_image.png");
    rgtest::Png b = render(scene("factors", factors), dir + "/factors_image.png");
    ASSERT_EQ(a.width, 160);
    EXPECT_EQ(pixelsApart(a, b, 1), 0u);
    // and the two squares are what their numbers say: the paint shows its
    // base colour (0.8, 0.3, 0.2), the metal does not: it mirrors the sky's ground
    const uint8_t* paint = a.at(50, 45);
    EXPECT_GT(int(paint[0]) - int(paint[2]), 60) << "paint " << int(paint[0]) << "," << int(paint[2]);
    const uint8_t* metal = a.at(110, 45);
    EXPECT_LT(int(metal[0]) - int(metal[2]), 60) << "metal " << int(metal[0]) << "," << int(metal[2]);
}

// A flat mirror with a uniform normal texture must reflect as the mirror
// tilted to that normal does: the sky is at infinity, so only the
// direction of the normal matters. The expected normal comes from glTF's
// words (3.9.3), not from the shader: x along the texture's u, y toward the
// image's top, z out of the surface, x and y times the scale. The second
// case mirrors u (the tangent turns, the bitangent must not) and scales.
TEST(NormalTexture, AFlatMirrorReflectsAsTheTiltedMirror) {
    std::string dir = rgtest::outputDir("12_normal_tilt");
    const glm::ivec3 bytes(160, 100, 236);
    writeFlatPng(dir + "/tilt.png", bytes);
    glm::dvec3 texel = glm::dvec3(bytes) / 255.0 * 2.0 - 1.0;
    nlohmann::json mirror = {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}};
    struct Case {
        const char* name;
        bool mirrored;
        double scale;
    } cases[] = {{"plain", false, 1.0}, {"mirrored", true, 0.5}};
    for (const Case& c : cases) {
        nlohmann::json mapped = mirror;
        mapped["normalTexture"] = {{"scale", c.scale}};
        writeSquareGltf(dir, std::string(c.name) + "_mapped", wall(50, c.mirrored), mapped, {{"normalTexture", "tilt.png"}});
        // the wall's tangent frame: u along +x (or -x), the image's top +y, out +z
        glm::dvec3 n = glm::normalize(glm::dvec3((c.mirrored ? -1 : 1) * texel.x * c.scale, texel.y * c.scale, texel.z));
        // the wall turned so that its normal is n (Rodrigues, about z x n)
        glm::dvec3 axis = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), n));
        double angle = std::acos(n.z);
        Square tilted = wall(50);
        for (glm::vec3& p : tilted.corners) {
            glm::dvec3 v(p);
            v = v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) +
                axis * glm::dot(axis, v) * (1 - std::cos(angle));
            p = glm::vec3(v);
        }
        writeSquareGltf(dir, std::string(c.name) + "_tilted", tilted, mirror, {});
        auto scene = [&](const std::string& file) {
            std::string path = dir + "/" + file + ".json";
            writeText(path, R"({"camera": {"position": [0, 0.3, 2], "look_at": [0, 0, 0], "fov_y_deg": 40},
                "sky": {"image": ")" + assetDir() + R"(/sky.png"}, "ambient": 0,
                "objects": [{"type": "mesh", "file": ")" + file + R"(.gltf"}]})");
            return path;
        };
        rgtest::Png mappedImage = render(scene(std::string(c.name) + "_mapped"), dir + "/" + c.name + "_mapped_image.png");
        rgtest::Png tiltedImage = render(scene(std::string(c.name) + "_tilted"), dir + "/" + c.name + "_tilted_image.png");
        ASSERT_EQ(mappedImage.width, 160);
        // no more than 0.1 % of pixels by more than 1 code (sky texels' edges)
        EXPECT_LE(pixelsApart(mappedImage, tiltedImage, 1), 160u * 90 / 1000) << c.name;
    }
    // the tilt is there to be seen: the flat mirror without the texture differs
    writeSquareGltf(dir, "flat", wall(50), mirror, {});
    writeText(dir + "/flat.json", R"({"camera": {"position": [0, 0.3, 2], "look_at": [0, 0, 0], "fov_y_deg": 40},
        "sky": {"image": ")" + assetDir() + R"(/sky.png"}, "ambient": 0, "objects": [{"type": "mesh", "file": "flat.gltf"}]})");
    rgtest::Png flat = render(dir + "/flat.json", dir + "/flat_image.png");
    EXPECT_GT(pixelsApart(flat, rgtest::readPng(dir + "/plain_mapped_image.png"), 1), 160u * 90 / 2);
}

// The painted panel (assets/scenes/panel.json): base colour, metal-roughness
// and normal textures together, against the reference (32 frames of rough
// reflection in the brushed half).
TEST(MetalRoughness, PaintedPanelMatchesTheReference) {
    rgtest::expectMatchesReference(RG_EXE_12, assetDir() + "/scenes/panel.json", "12_panel_reference",
                                   {"--frames", "32"});
}

// What page 12 says of the panel, at 320 x 240 (its figure is 640 x 480):
// red paint; the top rivet lit on its upper left, shaded on its lower right
// (the light is at the upper left, the rivet only a normal texture); the
// yellow ball's edge sharp in the polished left half of the window and
// blurred in the brushed right half (along the row through the ball).
TEST(MetalRoughness, PanelShowsWhatItsPageSays) {
    std::string dir = rgtest::outputDir("12_panel_page");
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene", assetDir() + "/scenes/panel.json",
                                                  "--width", "320", "--height", "240", "--output", dir + "/panel.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    rgtest::Png png = rgtest::readPng(dir + "/panel.png");
    ASSERT_EQ(png.width, 320);
    const uint8_t* paint = png.at(80, 200);
    EXPECT_GT(paint[0], 3 * paint[1]);
    EXPECT_GT(paint[0], 3 * paint[2]);
    auto luminance = [&](int x, int y) { return 0.2126 * png.at(x, y)[0] + 0.7152 * png.at(x, y)[1] + 0.0722 * png.at(x, y)[2]; };
    EXPECT_GT(luminance(157, 33), 1.5 * luminance(163, 39));
    // the largest step in blue between neighbours along row 116
    auto largestStep = [&](int from, int to) {
        int step = 0;
        for (int x = from; x < to; ++x) step = std::max(step, std::abs(int(png.at(x + 1, 116)[2]) - int(png.at(x, 116)[2])));
        return step;
    };
    EXPECT_GE(largestStep(130, 158), 60);  // sharp
    EXPECT_LE(largestStep(162, 190), 15);  // blurred
}

// Textures are images of 4 bytes a texel (rt_textures.h): a 4096x4096 base
// colour texture with a 2048x2048 metal-roughness and normal texture, the
// sizes a scanned model brings (96 MiB here; as 16-byte floats in one
// storage buffer, 384 MiB, which lavapipe's 128 MiB could not hold), loads
// and renders with validation, and shows its four quadrants in place.
// Three large textures: 4 bytes a texel, and their mip levels a third more
// (4/3 in all: 1 + 1/4 + 1/16 + ...), where four floats a texel at full
// size (384 MiB) were more than lavapipe's storage buffers may hold.
TEST(Textures, LargeTexturesAreImagesOfFourBytesATexelAndTheirLevels) {
    std::string dir = rgtest::outputDir("12_large_textures");
    auto writePng = [&](const std::string& name, int side, auto colourAt) {
        std::vector<unsigned char> rgb(size_t(side) * side * 3);
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                glm::ivec3 c = colourAt(x * 2 / side, y * 2 / side);
                for (int k = 0; k < 3; ++k) rgb[3 * (size_t(y) * side + x) + k] = (unsigned char)c[k];
            }
        ASSERT_NE(stbi_write_png((dir + "/" + name).c_str(), side, side, 3, rgb.data(), side * 3), 0);
    };
    const glm::ivec3 quadrants[2][2] = {{{255, 0, 0}, {0, 255, 0}}, {{0, 0, 255}, {255, 255, 255}}};
    writePng("colour.png", 4096, [&](int qx, int qy) { return quadrants[qy][qx]; });
    writePng("mr.png", 2048, [](int, int) { return glm::ivec3(255, 255, 0); });  // rough, not metal
    writePng("normal.png", 2048, [](int, int) { return glm::ivec3(128, 128, 255); });
    writeSquareGltf(dir, "big", wall(1), {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}}}},
                    {{"baseColorTexture", "colour.png"}, {"metallicRoughnessTexture", "mr.png"},
                     {"normalTexture", "normal.png"}});
    writeText(dir + "/big.json", R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_y_deg": 45},
        "sky": {"top": 0, "horizon": 0, "bottom": 0}, "ambient": 1, "objects": [{"type": "mesh", "file": "big.gltf"}]})");
    rgtest::RunResult r = rgtest::run(RG_EXE_12, {"--headless", "--validation", "--scene", dir + "/big.json", "--width",
                                                  "160", "--height", "90", "--frames", "1", "--output",
                                                  dir + "/big_image.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/big_image.json");
    EXPECT_EQ(report.value("validation_messages", -1), 0);
    EXPECT_EQ(report["textures"].value("texels", 0), 4096 * 4096 + 2 * 2048 * 2048);
    EXPECT_EQ(report["textures"].value("levels", 0), 13);  // 4096 .. 1
    EXPECT_NEAR(report["textures"].value("bytes_per_texel", 99.0), 4 * 4 / 3.0, 0.05);
    // lit by ambient light alone, each quadrant is its colour (0.7 of it:
    // glTF's rough dielectric maps to kd = base colour, ka = kd, ambient 1)
    rgtest::Png png = rgtest::readPng(dir + "/big_image.png");
    for (int qy = 0; qy < 2; ++qy)
        for (int qx = 0; qx < 2; ++qx) {
            // the quadrant's centre: (-0.5 or 0.5, 0.5 or -0.5) on the wall, seen from 3 away
            double tanHalf = std::tan(22.5 * 3.14159265358979 / 180), aspect = 160.0 / 90;
            int px = int((1 + (qx ? 0.5 : -0.5) / 3 / (tanHalf * aspect)) / 2 * 160);
            int py = int((1 - (qy ? -0.5 : 0.5) / 3 / tanHalf) / 2 * 90);
            const uint8_t* p = png.at(px, py);
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(p[c] > 128, quadrants[qy][qx][c] > 128) << "quadrant " << qx << "," << qy << " channel " << c;
        }
}
